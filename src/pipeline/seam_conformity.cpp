// hangingPoints: nodes one side of a seam has and the other lacks (remesh_part.h).
#include <algorithm>
#include <vector>

#include "geometry/vec3.h"
#include "pipeline/remesh_part.h"
#include "voxremesh/quality.h"

namespace voxremesh::pipeline {

std::size_t hangingPoints(const QuadMesh& a, const QuadMesh& b, double tolerance) {
  using namespace geom;  // NOLINT: the vector operators
  const auto edgesA = edgesSharedBy(a, 1, 1), edgesB = edgesSharedBy(b, 1, 1);
  std::vector<CornerIndex> points;
  for (const auto& [first, second] : edgesA) {
    points.push_back(first);
    points.push_back(second);
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  std::size_t hanging = 0;
  for (const CornerIndex p : points) {
    const Vec3& x = a.points[p];
    for (const auto& edge : edgesB) {
      const Vec3 &u = b.points[edge.first], along = b.points[edge.second] - u;
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
