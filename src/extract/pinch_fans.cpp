// removePinchedFans: one fan of faces around every vertex (pinch_fans.h).
#include "extract/pinch_fans.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace voxremesh::extract {

namespace {

/// The faces around each point, ascending (compressed rows).
struct PointFaces {
  std::vector<std::uint32_t> start, faces;
  explicit PointFaces(const QuadMesh& mesh) : start(mesh.points.size() + 1, 0) {
    for (const auto& face : mesh.faces)
      for (int k = 0; k < cornerCount(face); ++k) ++start[face[std::size_t(k)] + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    faces.resize(start.back());
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
      for (int k = 0; k < cornerCount(mesh.faces[f]); ++k)
        faces[next[mesh.faces[f][std::size_t(k)]]++] = f;
  }
};

/// The two neighbours of `v` in `face` (the corners before and after it).
std::array<CornerIndex, 2> neighboursIn(const std::array<CornerIndex, 4>& face, CornerIndex v) {
  const int n = cornerCount(face);
  int k = 0;
  while (face[std::size_t(k)] != v) ++k;
  return {face[std::size_t((k + n - 1) % n)], face[std::size_t((k + 1) % n)]};
}

/// Per face around v (in `around` order), the index of its fan: faces sharing an edge at v are
/// in one fan. Fans are numbered by their first face.
std::vector<std::size_t> fansAround(const QuadMesh& mesh, CornerIndex v,
                                    const std::vector<std::uint32_t>& around) {
  std::vector<std::size_t> fan(around.size());
  std::iota(fan.begin(), fan.end(), 0);
  auto find = [&](std::size_t i) {
    while (fan[i] != i) i = fan[i] = fan[fan[i]];
    return i;
  };
  for (std::size_t i = 0; i < around.size(); ++i)
    for (std::size_t j = i + 1; j < around.size(); ++j) {
      const auto a = neighboursIn(mesh.faces[around[i]], v);
      const auto b = neighboursIn(mesh.faces[around[j]], v);
      if (a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]) {
        const std::size_t ri = find(i), rj = find(j);
        fan[std::max(ri, rj)] = std::min(ri, rj);
      }
    }
  for (std::size_t i = 0; i < around.size(); ++i) fan[i] = find(i);
  return fan;
}

}  // namespace

std::size_t removePinchedFans(QuadMesh& mesh, std::vector<CornerIndex> vertices) {
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < cornerCount(mesh.faces[f]); ++k)
      if (mesh.faces[f][std::size_t(k)] >= mesh.points.size())
        throw std::invalid_argument("removePinchedFans: face " + std::to_string(f) +
                                    " names a missing point");
  std::size_t removed = 0;
  while (!vertices.empty()) {
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    const PointFaces pointFaces(mesh);
    std::vector<char> drop(mesh.faces.size(), 0);
    std::vector<CornerIndex> next;  // the corners of dropped faces, looked at in the next round
    for (const CornerIndex v : vertices) {
      if (v >= mesh.points.size()) continue;
      std::vector<std::uint32_t> around;
      for (std::uint32_t i = pointFaces.start[v]; i < pointFaces.start[v + 1]; ++i)
        if (!drop[pointFaces.faces[i]]) around.push_back(pointFaces.faces[i]);
      if (around.size() < 2) continue;
      const std::vector<std::size_t> fan = fansAround(mesh, v, around);
      std::vector<std::size_t> size(around.size(), 0);
      for (const std::size_t r : fan) ++size[r];
      // The largest fan; fans are numbered by their first (lowest) face, so the first largest
      // found has the lowest face.
      std::size_t keep = fan[0];
      for (std::size_t r = 0; r < around.size(); ++r)
        if (size[r] > size[keep]) keep = r;
      for (std::size_t i = 0; i < around.size(); ++i) {
        if (fan[i] == keep) continue;
        drop[around[i]] = 1;
        const auto& face = mesh.faces[around[i]];
        next.insert(next.end(), face.begin(), face.begin() + cornerCount(face));
      }
    }
    std::size_t kept = 0;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      if (!drop[f]) mesh.faces[kept++] = mesh.faces[f];
    removed += mesh.faces.size() - kept;
    mesh.faces.resize(kept);
    vertices = std::move(next);
  }
  return removed;
}

std::vector<CornerIndex> endsOfOverfullEdges(const QuadMesh& mesh) {
  // Points with equal coordinates count as one (the lowest index), as after the weld.
  std::vector<CornerIndex> order(mesh.points.size()), representative(mesh.points.size());
  std::iota(order.begin(), order.end(), CornerIndex(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](CornerIndex a, CornerIndex b) { return mesh.points[a] < mesh.points[b]; });
  for (std::size_t k = 0; k < order.size(); ++k)
    representative[order[k]] = k > 0 && mesh.points[order[k]] == mesh.points[order[k - 1]]
                                   ? representative[order[k - 1]]
                                   : order[k];
  std::vector<std::pair<CornerIndex, CornerIndex>> edges;
  for (const auto& face : mesh.faces) {
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k) {
      const CornerIndex a = representative[face[std::size_t(k)]];
      const CornerIndex b = representative[face[std::size_t((k + 1) % n)]];
      if (a == b) continue;
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<CornerIndex> ends;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i > 2) ends.push_back(edges[i].first), ends.push_back(edges[i].second);
    i = j;
  }
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  return ends;
}

}  // namespace voxremesh::extract
