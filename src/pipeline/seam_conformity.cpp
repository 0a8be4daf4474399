// hangingPoints: nodes one side of a seam has and the other lacks (remesh_part.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "pipeline/remesh_part.h"

namespace voxremesh::pipeline {

namespace {

/// The boundary edges of a mesh (edges of one face), as point index pairs.
std::vector<std::array<CornerIndex, 2>> boundaryEdges(const QuadMesh& mesh) {
  std::map<std::array<CornerIndex, 2>, int> count;
  for (const auto& face : mesh.faces) {
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k) {
      const CornerIndex a = face[std::size_t(k)], b = face[std::size_t((k + 1) % n)];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<std::array<CornerIndex, 2>> edges;
  for (const auto& [edge, faces] : count)
    if (faces == 1) edges.push_back(edge);
  return edges;
}

}  // namespace

std::size_t hangingPoints(const QuadMesh& a, const QuadMesh& b, double tolerance) {
  const std::vector<std::array<CornerIndex, 2>> edgesA = boundaryEdges(a),
                                                edgesB = boundaryEdges(b);
  std::vector<CornerIndex> points;
  for (const auto& edge : edgesA) points.insert(points.end(), edge.begin(), edge.end());
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  std::size_t hanging = 0;
  for (const CornerIndex p : points) {
    const auto& x = a.points[p];
    for (const auto& edge : edgesB) {
      const auto &u = b.points[edge[0]], &v = b.points[edge[1]];
      double uv = 0.0, ux = 0.0;
      for (int k = 0; k < 3; ++k)
        uv += (v[k] - u[k]) * (v[k] - u[k]), ux += (x[k] - u[k]) * (v[k] - u[k]);
      if (!(uv > 0.0)) continue;
      const double t = ux / uv, margin = tolerance / std::sqrt(uv);
      if (t <= margin || t >= 1.0 - margin) continue;
      double d = 0.0;
      for (int k = 0; k < 3; ++k) d += std::pow(u[k] + t * (v[k] - u[k]) - x[k], 2);
      if (d < tolerance * tolerance) {
        ++hanging;
        break;
      }
    }
  }
  return hanging;
}

}  // namespace voxremesh::pipeline
