// idealCorners: the best-fitting square or equilateral triangle of a face (ideal_shape.h).
#include "optimize/ideal_shape.h"

#include <cmath>

namespace voxremesh::opt {

using namespace geom;  // NOLINT: the vector operators

std::array<Vec3, 4> idealCorners(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face,
                                 double edgeLength) {
  const int n = cornerCount(face);
  std::array<Vec3, 4> p{};
  Vec3 centroid{0.0, 0.0, 0.0};
  for (int k = 0; k < n; ++k) {
    p[static_cast<std::size_t>(k)] = mesh.points[face[static_cast<std::size_t>(k)]];
    centroid = centroid + p[static_cast<std::size_t>(k)];
  }
  centroid = centroid * (1.0 / n);
  const Vec3 normal = n == 4 ? cross(p[2] - p[0], p[3] - p[1]) : cross(p[1] - p[0], p[2] - p[0]);
  const double normalLength = norm(normal);
  if (!(normalLength > 0.0)) return p;
  const Vec3 z = normal * (1.0 / normalLength);
  // An in-plane basis: u along the first corner's offset (any in-plane vector would do).
  Vec3 u = p[0] - centroid;
  u = u - z * dot(u, z);
  if (!(norm(u) > 0.0)) return p;
  u = normalized(u);
  const Vec3 w = cross(z, u);
  // Regular polygon corners s_k at angles phase + k * 2 pi / n (counter-clockwise about z), radius
  // r; the best rotation theta maximises sum s_k(theta) . q_k, q_k the projected corners.
  const double pi = 3.14159265358979323846;
  const double step = 2.0 * pi / n;
  const double radius = edgeLength / (2.0 * std::sin(pi / n));
  double c = 0.0, s = 0.0;
  for (int k = 0; k < n; ++k) {
    const Vec3 q = p[static_cast<std::size_t>(k)] - centroid;
    const double x = dot(q, u), y = dot(q, w);
    const double angle = k * step;
    // s_k(theta) = r (cos(angle + theta), sin(angle + theta)); d/dtheta of the sum vanishes at
    // theta = atan2(sum (y cos a - x sin a), sum (x cos a + y sin a)).
    c += x * std::cos(angle) + y * std::sin(angle);
    s += y * std::cos(angle) - x * std::sin(angle);
  }
  const double theta = std::atan2(s, c);
  std::array<Vec3, 4> result = p;
  for (int k = 0; k < n; ++k) {
    const double angle = k * step + theta;
    result[static_cast<std::size_t>(k)] =
        centroid + u * (radius * std::cos(angle)) + w * (radius * std::sin(angle));
  }
  return result;
}

}  // namespace voxremesh::opt
