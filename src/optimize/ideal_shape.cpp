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
  // Regular polygon corners s_k at angles a_k + theta, a_k = k * 2 pi / n (counter-clockwise
  // about z), radius r; the best rotation theta maximises sum s_k(theta) . q_k (q_k the projected
  // corners): (cos theta, sin theta) is the unit vector of (sum x cos a + y sin a,
  // sum y cos a - x sin a).
  static const double kCos4[4] = {1.0, 0.0, -1.0, 0.0}, kSin4[4] = {0.0, 1.0, 0.0, -1.0};
  static const double kCos3[3] = {1.0, -0.5, -0.5};
  static const double kSin3[3] = {0.0, 0.8660254037844386, -0.8660254037844386};
  const double* cosA = n == 4 ? kCos4 : kCos3;
  const double* sinA = n == 4 ? kSin4 : kSin3;
  // Circumradius: edge / (2 sin(pi / n)), sin(pi / 4) = 1 / sqrt 2, sin(pi / 3) = sqrt 3 / 2.
  const double radius = n == 4 ? edgeLength * 0.7071067811865476 : edgeLength * 0.5773502691896258;
  double c = 0.0, s = 0.0;
  for (int k = 0; k < n; ++k) {
    const Vec3 q = p[static_cast<std::size_t>(k)] - centroid;
    const double x = dot(q, u), y = dot(q, w);
    c += x * cosA[k] + y * sinA[k];
    s += y * cosA[k] - x * sinA[k];
  }
  const double length = std::hypot(c, s);
  const double cosT = length > 0.0 ? c / length : 1.0, sinT = length > 0.0 ? s / length : 0.0;
  std::array<Vec3, 4> result = p;
  for (int k = 0; k < n; ++k) {
    const double cosK = cosA[k] * cosT - sinA[k] * sinT, sinK = sinA[k] * cosT + cosA[k] * sinT;
    result[static_cast<std::size_t>(k)] = centroid + u * (radius * cosK) + w * (radius * sinK);
  }
  return result;
}

}  // namespace voxremesh::opt
