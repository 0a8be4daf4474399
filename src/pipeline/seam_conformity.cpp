// hangingPoints: nodes one side of a seam has and the other lacks (remesh_part.h).
#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "geometry/vec3.h"
#include "pipeline/remesh_part.h"
#include "voxremesh/quality.h"

namespace voxremesh::pipeline {

std::size_t hangingPoints(const QuadMesh& a, const QuadMesh& b, double tolerance) {
  using namespace geom;                             // NOLINT: the vector operators
  std::vector<std::pair<double, CornerIndex>> byX;  // a's points by their x
  for (CornerIndex p = 0; p < a.points.size(); ++p) byX.emplace_back(a.points[p][0], p);
  std::sort(byX.begin(), byX.end());
  std::vector<std::uint8_t> hanging(a.points.size(), 0);
  for (const auto& [first, second] : edgesSharedBy(b, 1, std::numeric_limits<std::size_t>::max())) {
    const Vec3 &u = b.points[first], &v = b.points[second], along = v - u;
    const double length = norm(along);
    if (!(length > 0.0)) continue;
    const double margin = tolerance / length;
    auto it = std::lower_bound(byX.begin(), byX.end(),
                               std::make_pair(std::min(u[0], v[0]) - tolerance, CornerIndex(0)));
    for (; it != byX.end() && it->first <= std::max(u[0], v[0]) + tolerance; ++it) {
      const Vec3& x = a.points[it->second];
      if (hanging[it->second]) continue;
      const double t = dot(x - u, along) / (length * length);
      if (t > margin && t < 1.0 - margin && distance(u + along * t, x) < tolerance)
        hanging[it->second] = 1;
    }
  }
  return std::size_t(std::count(hanging.begin(), hanging.end(), 1));
}

}  // namespace voxremesh::pipeline
