// Topology checks of a QuadMesh (see mesh_topology.h).
#include "support/mesh_topology.h"

#include <numeric>
#include <vector>

#include "model/shell_edges.h"

namespace voxremesh::test {

namespace {

std::size_t find(std::vector<std::size_t>& parent, std::size_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

MeshTopology meshTopology(const QuadMesh& mesh) {
  std::vector<model::ShellCorners> corners(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    corners[f].count = static_cast<std::uint8_t>(cornerCount(mesh.faces[f]));
    for (int c = 0; c < corners[f].count; ++c)
      corners[f].node[std::size_t(c)] = mesh.faces[f][std::size_t(c)];
  }
  const model::ShellEdges adjacency(corners);
  MeshTopology result;
  result.edges = adjacency.edgeCount();
  result.boundaryEdges = adjacency.boundaryEdges().size();
  result.nonManifoldEdges = adjacency.nonManifoldEdges().size();
  result.inconsistentEdges = adjacency.inconsistentEdges().size();
  for (const model::BoundaryChain& chain : model::boundaryChains(adjacency))
    result.boundaryLoops += chain.closed ? 1 : 0;

  // Faces joined across edges: components; faces around a vertex joined across its edges: fans.
  std::vector<std::size_t> component(mesh.faces.size());
  std::iota(component.begin(), component.end(), std::size_t{0});
  std::vector<std::vector<std::size_t>> facesOfPoint(mesh.points.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int c = 0; c < corners[f].count; ++c)
      facesOfPoint[corners[f].node[std::size_t(c)]].push_back(f);
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e) {
    const auto incidences = adjacency.incidences(model::Index(e));
    for (std::size_t i = 1; i < incidences.size(); ++i) {
      const std::size_t a = find(component, incidences[0].shell);
      const std::size_t b = find(component, incidences[i].shell);
      if (a != b) component[std::max(a, b)] = std::min(a, b);
    }
  }
  std::size_t usedPoints = 0;
  for (std::size_t p = 0; p < mesh.points.size(); ++p) {
    const std::vector<std::size_t>& faces = facesOfPoint[p];
    if (faces.empty()) {
      ++result.unusedPoints;
      continue;
    }
    ++usedPoints;
    // Fans: faces around p joined when they share an edge at p.
    std::vector<std::size_t> fan(faces.size());
    std::iota(fan.begin(), fan.end(), std::size_t{0});
    for (std::size_t i = 0; i < faces.size(); ++i) {
      for (unsigned side = 0; side < 4; ++side) {
        const model::Index e = adjacency.shellEdge(model::Index(faces[i]), side);
        if (e == model::kNoIndex) continue;
        const auto& edge = adjacency.edge(e);
        if (edge.a != p && edge.b != p) continue;
        for (const auto& incidence : adjacency.incidences(e)) {
          for (std::size_t j = 0; j < faces.size(); ++j) {
            if (faces[j] != incidence.shell) continue;
            const std::size_t a = find(fan, i), b = find(fan, j);
            if (a != b) fan[std::max(a, b)] = std::min(a, b);
          }
        }
      }
    }
    std::size_t fans = 0;
    for (std::size_t i = 0; i < faces.size(); ++i) fans += find(fan, i) == i ? 1 : 0;
    if (fans > 1) ++result.nonManifoldVertices;
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) result.components += find(component, f) == f;
  result.eulerCharacteristic = int(usedPoints) - int(result.edges) + int(mesh.faces.size());
  return result;
}

}  // namespace voxremesh::test
