// hangingPoints: nodes one side of a seam has and the other lacks (remesh_part.h).
#include <algorithm>
#include <array>
#include <map>
#include <vector>

#include "geometry/vec3.h"
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
  using namespace geom;  // NOLINT: the vector operators
  const std::vector<std::array<CornerIndex, 2>> edgesA = boundaryEdges(a),
                                                edgesB = boundaryEdges(b);
  std::vector<CornerIndex> points;
  for (const auto& edge : edgesA) points.insert(points.end(), edge.begin(), edge.end());
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  std::size_t hanging = 0;
  for (const CornerIndex p : points) {
    const Vec3& x = a.points[p];
    for (const auto& edge : edgesB) {
      const Vec3 &u = b.points[edge[0]], along = b.points[edge[1]] - u;
      const double length = norm(along);
      if (!(length > 0.0)) continue;
      const double t = dot(x - u, along) / (length * length), margin = tolerance / length;
      if (t > margin && t < 1.0 - margin && distance(u + along * t, x) < tolerance) {
        ++hanging;
        break;
      }
    }
  }
  return hanging;
}

}  // namespace voxremesh::pipeline
