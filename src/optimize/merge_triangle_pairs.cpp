// mergeTrianglePairs: two triangles across an edge become a quad where that quad passes the
// element criteria.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "optimize/mesh_topology.h"
#include "optimize/steps.h"
#include "voxremesh/errors.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

namespace {

/// The quad two triangles sharing edge (a, b) make: triangle 1 runs a -> b -> c, triangle 2
/// b -> a -> d; the quad is b -> c -> a -> d. Returns false when they do not fit that way.
bool pairQuad(const std::array<CornerIndex, 4>& t1, const std::array<CornerIndex, 4>& t2,
              std::array<CornerIndex, 4>& quad) {
  for (std::size_t i = 0; i < 3; ++i) {
    const CornerIndex a = t1[i], b = t1[(i + 1) % 3], c = t1[(i + 2) % 3];
    for (std::size_t j = 0; j < 3; ++j) {
      if (t2[j] != b || t2[(j + 1) % 3] != a) continue;
      const CornerIndex d = t2[(j + 2) % 3];
      if (d == c) return false;
      quad = {b, c, a, d};
      return true;
    }
  }
  return false;
}

}  // namespace

std::size_t mergeTrianglePairs(QuadMesh& mesh, const QualitySettings& settings,
                               opt::MeshCache& cache) {
  checkQualitySettings(settings);
  if (!(settings.targetSize > 0.0))
    throw std::invalid_argument("mergeTrianglePairs: settings.targetSize must be > 0");
  opt::checkMesh(mesh);
  const opt::Topology& topology = cache.topology(mesh);
  // Candidates: (score, first triangle, second triangle, quad).
  std::vector<std::tuple<double, std::uint32_t, std::uint32_t, std::array<CornerIndex, 4>>> pairs;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (cornerCount(mesh.faces[f]) != 3) continue;
    for (std::size_t k = 0; k < 3; ++k) {
      const CornerIndex a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
      if (topology.edgeFaces(a, b) != 2) continue;  // boundary or non-manifold edge
      // The other face of edge (a, b); each pair is taken from its lower triangle.
      std::uint32_t other = kNoCorner;
      for (const std::uint32_t* g = topology.facesBegin(a); g != topology.facesEnd(a); ++g) {
        const auto& face = mesh.faces[*g];
        if (*g != f && std::find(face.begin(), face.end(), b) != face.end()) other = *g;
      }
      if (other == kNoCorner || other < f || cornerCount(mesh.faces[other]) != 3) continue;
      const auto f1 = static_cast<std::uint32_t>(f), f2 = other;
      std::array<CornerIndex, 4> quad{};
      if (!pairQuad(mesh.faces[f1], mesh.faces[f2], quad)) continue;
      // The new quad's diagonal (c, d) must not be an edge already.
      if (topology.edgeFaces(quad[1], quad[3]) != 0) continue;
      std::array<std::array<double, 3>, 4> p;
      for (std::size_t c = 0; c < 4; ++c) p[c] = mesh.points[quad[c]];
      const ElementQuality q = elementQuality(p, 4);
      if (elementFailures(q, 4, settings) != 0) continue;
      const double score = std::max(std::abs(q.minAngleDeg - 90.0), std::abs(q.maxAngleDeg - 90.0));
      pairs.emplace_back(score, f1, f2, quad);
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const auto& x, const auto& y) {
    return std::tie(std::get<0>(x), std::get<1>(x), std::get<2>(x)) <
           std::tie(std::get<0>(y), std::get<1>(y), std::get<2>(y));
  });
  std::vector<std::uint8_t> used(mesh.faces.size(), 0), deleted(mesh.faces.size(), 0);
  std::size_t merged = 0;
  for (const auto& [score, f1, f2, quad] : pairs) {
    if (used[f1] || used[f2]) continue;
    used[f1] = used[f2] = 1;
    mesh.faces[f1] = quad;
    deleted[f2] = 1;
    ++merged;
  }
  opt::eraseFaces(mesh, deleted);
  return merged;
}

std::size_t mergeTrianglePairs(QuadMesh& mesh, const QualitySettings& settings) {
  opt::MeshCache cache(settings);
  return mergeTrianglePairs(mesh, settings, cache);
}

}  // namespace voxremesh
