// collapseRhombicQuads: collapse the low-degree diagonal of quads whose corners all have odd
// degree (paper Sect. 5.2).
#include <vector>

#include "optimize/mesh_topology.h"
#include "optimize/steps.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

namespace {

/// The diagonal (k, k + 2) of a rhombic quad to collapse, or -1 when the quad is not rhombic.
int rhombicDiagonal(const QuadMesh& mesh, const opt::Topology& t,
                    const std::array<CornerIndex, 4>& face) {
  if (cornerCount(face) != 4) return -1;
  std::array<std::size_t, 4> degree{};
  for (std::size_t k = 0; k < 4; ++k) {
    const CornerIndex v = face[k];
    if (opt::roleOf(mesh, v) != PointRole::Free || t.boundary[v]) return -1;
    degree[k] = t.degree(v);
    if (degree[k] % 2 == 0) return -1;
  }
  const std::size_t sum02 = degree[0] + degree[2], sum13 = degree[1] + degree[3];
  if (sum02 < sum13 && degree[1] > 3 && degree[3] > 3) return 0;
  if (sum13 < sum02 && degree[0] > 3 && degree[2] > 3) return 1;
  return -1;
}

}  // namespace

std::size_t collapseRhombicQuads(QuadMesh& mesh, const ReferenceSurface* surface,
                                 opt::MeshCache& cache) {
  opt::checkMesh(mesh);
  std::size_t collapsed = 0;
  for (;;) {
    const opt::Topology& topology = cache.topology(mesh);
    std::vector<std::uint8_t> locked(mesh.points.size(), 0), deleted(mesh.faces.size(), 0);
    std::size_t round = 0;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      if (deleted[f]) continue;
      const auto face = mesh.faces[f];
      const int k = rhombicDiagonal(mesh, topology, face);
      if (k < 0) continue;
      const CornerIndex u = face[static_cast<std::size_t>(k)];
      const CornerIndex v = face[static_cast<std::size_t>(k + 2)];
      if (!opt::tryMerge(mesh, topology, u, v, locked, deleted, surface)) continue;
      ++round;
    }
    if (round == 0) break;
    collapsed += round;
    opt::eraseFaces(mesh, deleted);
  }
  eraseUnusedPoints(mesh);
  return collapsed;
}

std::size_t collapseRhombicQuads(QuadMesh& mesh, const ReferenceSurface* surface) {
  opt::MeshCache cache;
  return collapseRhombicQuads(mesh, surface, cache);
}

}  // namespace voxremesh
