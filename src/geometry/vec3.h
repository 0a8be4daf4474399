// Small double-precision vector helpers on std::array<double, 3>, the point type of QuadMesh, for
// the quality, reference-surface and optimisation kernels.
#pragma once

#include <array>
#include <cmath>

namespace voxremesh::geom {

using Vec3 = std::array<double, 3>;

inline Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 operator*(const Vec3& a, double s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}
inline double distance(const Vec3& a, const Vec3& b) {
  return norm(a - b);
}
/// a / |a|, or the zero vector for a zero vector.
inline Vec3 normalized(const Vec3& a) {
  const double l = norm(a);
  return l > 0.0 ? a * (1.0 / l) : Vec3{0.0, 0.0, 0.0};
}
/// The normal of an element, not normalised (twice its area along the normal): a triangle's
/// (p1 - p0) x (p2 - p0), a quad's the cross product of its diagonals (p2 - p0) x (p3 - p1), the
/// area-weighted mean of its corner normals. p3 is not read for a triangle.
inline Vec3 elementNormal(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3,
                          bool triangle) {
  return triangle ? cross(p1 - p0, p2 - p0) : cross(p2 - p0, p3 - p1);
}
/// The angle between a and b in degrees (0 when either is zero).
inline double angleDeg(const Vec3& a, const Vec3& b) {
  const double s = norm(cross(a, b)), c = dot(a, b);
  if (s == 0.0 && c == 0.0) return 0.0;
  return std::atan2(s, c) * 57.29577951308232;
}

}  // namespace voxremesh::geom
