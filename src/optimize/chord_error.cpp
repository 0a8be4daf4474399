// chordError (chord_error.h).
#include "optimize/chord_error.h"

#include <algorithm>

#include "geometry/vec3.h"

namespace voxremesh::opt {

using namespace geom;  // NOLINT: the vector operators

double chordError(const QuadMesh& mesh, const std::vector<std::array<CornerIndex, 4>>& faces,
                  const ReferenceSurface& original) {
  double largest = 0.0;
  // The queries lie close together: each starts from the answer before it (the same answers).
  std::uint32_t hint = kNoCorner;
  const auto distanceAt = [&](const Vec3& p) {
    const SurfaceHit hit = original.closestPoint(p, hint);
    hint = hit.face;
    return hit.distance;
  };
  for (const auto& face : faces) {
    const int n = cornerCount(face);
    Vec3 centre{0.0, 0.0, 0.0};
    for (int k = 0; k < n; ++k) {
      const Vec3& p = mesh.points[face[std::size_t(k)]];
      const Vec3& q = mesh.points[face[std::size_t((k + 1) % n)]];
      centre = centre + p * (1.0 / n);
      largest = std::max(largest, distanceAt((p + q) * 0.5));
    }
    largest = std::max(largest, distanceAt(centre));
  }
  return largest;
}

}  // namespace voxremesh::opt
