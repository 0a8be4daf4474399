// topologyCounts: components and boundary loops of a mesh; edgesSharedBy: its edges by how many
// faces share them (quality.h).
#include <algorithm>
#include <utility>
#include <vector>

#include "geometry/disjoint_sets.h"
#include "voxremesh/quality.h"

namespace voxremesh {

namespace {

/// The number of distinct sets among the flagged points.
std::size_t setsAmong(DisjointSets& sets, const std::vector<bool>& flagged) {
  std::vector<std::size_t> roots;
  for (std::size_t p = 0; p < flagged.size(); ++p)
    if (flagged[p]) roots.push_back(sets.find(p));
  std::sort(roots.begin(), roots.end());
  return static_cast<std::size_t>(std::unique(roots.begin(), roots.end()) - roots.begin());
}

/// Every face's edges, each as its two point indices (lower first), sorted: an edge appears once
/// per face using it.
std::vector<std::pair<CornerIndex, CornerIndex>> sortedFaceEdges(const QuadMesh& mesh) {
  std::vector<std::pair<CornerIndex, CornerIndex>> edges;
  for (const auto& face : mesh.faces) {
    const int corners = cornerCount(face);
    for (int k = 0; k < corners; ++k) {
      const CornerIndex a = face[std::size_t(k)], b = face[std::size_t((k + 1) % corners)];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

}  // namespace

std::vector<std::pair<CornerIndex, CornerIndex>> edgesSharedBy(const QuadMesh& mesh,
                                                               std::size_t minFaces,
                                                               std::size_t maxFaces) {
  const std::vector<std::pair<CornerIndex, CornerIndex>> edges = sortedFaceEdges(mesh);
  std::vector<std::pair<CornerIndex, CornerIndex>> shared;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i >= minFaces && j - i <= maxFaces) shared.push_back(edges[i]);
    i = j;
  }
  return shared;
}

TopologyCounts topologyCounts(const QuadMesh& mesh) {
  const std::size_t n = mesh.points.size();
  DisjointSets pieces(n), loops(n);
  std::vector<bool> used(n, false), onBoundary(n, false);
  for (const auto& face : mesh.faces) {
    const int corners = cornerCount(face);
    for (int k = 0; k < corners; ++k) {
      const CornerIndex a = face[std::size_t(k)], b = face[std::size_t((k + 1) % corners)];
      used[a] = true;
      pieces.join(a, b);
    }
  }
  for (const auto& [a, b] : edgesSharedBy(mesh, 1, 1)) {
    loops.join(a, b);
    onBoundary[a] = onBoundary[b] = true;
  }
  return {setsAmong(pieces, used), setsAmong(loops, onBoundary)};
}

}  // namespace voxremesh
