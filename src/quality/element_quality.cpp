// The per-element metrics of quality.h (definitions there).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "geometry/vec3.h"
#include "voxremesh/quality.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// The angle in degrees between two lines, folded to 0..90.
double lineAngleDeg(const Vec3& a, const Vec3& b) {
  const double angle = angleDeg(a, b);
  return angle > 90.0 ? 180.0 - angle : angle;
}

/// Angle between the normals of triangles (a,b,c) and (a,c,d); 0 when one has no area.
double splitAngleDeg(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 n1 = cross(b - a, c - a), n2 = cross(c - a, d - a);
  if (norm(n1) == 0.0 || norm(n2) == 0.0) return 0.0;
  return angleDeg(n1, n2);
}

/// Fills the edge-based metrics shared by quads and triangles: aspect ratio, interior angles
/// (reflex-corrected against `normal`), longest edge.
void edgeMetrics(const std::array<Vec3, 4>& p, int n, const Vec3& normal, ElementQuality& q,
                 double& longest) {
  double shortest = kInfinity;
  longest = 0.0;
  q.minAngleDeg = kInfinity;
  q.maxAngleDeg = -kInfinity;
  for (int i = 0; i < n; ++i) {
    const Vec3& prev = p[static_cast<std::size_t>((i + n - 1) % n)];
    const Vec3& here = p[static_cast<std::size_t>(i)];
    const Vec3& next = p[static_cast<std::size_t>((i + 1) % n)];
    const double length = norm(next - here);
    shortest = std::min(shortest, length);
    longest = std::max(longest, length);
    double angle = angleDeg(prev - here, next - here);
    if (dot(cross(here - prev, next - here), normal) < 0.0) angle = 360.0 - angle;
    q.minAngleDeg = std::min(q.minAngleDeg, angle);
    q.maxAngleDeg = std::max(q.maxAngleDeg, angle);
  }
  q.aspectRatio = shortest > 0.0 ? longest / shortest : kInfinity;
}

ElementQuality triangleQuality(const std::array<Vec3, 4>& p) {
  ElementQuality q;
  const Vec3 normal = cross(p[1] - p[0], p[2] - p[0]);
  double longest = 0.0;
  edgeMetrics(p, 3, normal, q, longest);
  // Skew: per corner, the median against the line joining the adjacent midsides.
  double smallest = 90.0;
  for (std::size_t i = 0; i < 3; ++i) {
    const Vec3& a = p[i];
    const Vec3& b = p[(i + 1) % 3];
    const Vec3& c = p[(i + 2) % 3];
    const Vec3 median = (b + c) * 0.5 - a;
    const Vec3 midline = (c + a) * 0.5 - (a + b) * 0.5;
    smallest = std::min(smallest, lineAngleDeg(median, midline));
  }
  q.skewDeg = 90.0 - smallest;
  const Vec3 unit = normalized(normal);
  double minSine = kInfinity;
  for (std::size_t i = 0; i < 3; ++i) {
    const Vec3 u = p[(i + 1) % 3] - p[i], v = p[(i + 2) % 3] - p[i];
    const double lengths = norm(u) * norm(v);
    minSine = std::min(minSine, lengths > 0.0 ? dot(cross(u, v), unit) / lengths : 0.0);
  }
  q.scaledJacobian = minSine * 2.0 / std::sqrt(3.0);
  q.jacobianRatio = 1.0;
  const double area = 0.5 * norm(normal);
  q.minLength = longest > 0.0 ? 2.0 * area / longest : 0.0;
  return q;
}

ElementQuality quadQuality(const std::array<Vec3, 4>& p) {
  ElementQuality q;
  const Vec3 diagonalNormal = cross(p[2] - p[0], p[3] - p[1]);
  double longest = 0.0;
  edgeMetrics(p, 4, diagonalNormal, q, longest);
  q.warpingDeg =
      std::max(splitAngleDeg(p[0], p[1], p[2], p[3]), splitAngleDeg(p[1], p[2], p[3], p[0]));

  const Vec3 m01 = (p[0] + p[1]) * 0.5, m12 = (p[1] + p[2]) * 0.5;
  const Vec3 m23 = (p[2] + p[3]) * 0.5, m30 = (p[3] + p[0]) * 0.5;
  q.skewDeg = 90.0 - lineAngleDeg(m12 - m30, m23 - m01);

  // Corner Jacobians on the plane of the averaged corner normals.
  std::array<Vec3, 4> cornerNormal;
  Vec3 sum{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < 4; ++i) {
    cornerNormal[i] = cross(p[i] - p[(i + 3) % 4], p[(i + 1) % 4] - p[i]);
    sum = sum + cornerNormal[i];
  }
  const Vec3 n = normalized(sum);
  double minJ = kInfinity, maxJ = -kInfinity, minScaled = kInfinity;
  for (std::size_t i = 0; i < 4; ++i) {
    const double j = dot(cornerNormal[i], n);
    minJ = std::min(minJ, j);
    maxJ = std::max(maxJ, j);
    const double lengths = norm(p[i] - p[(i + 3) % 4]) * norm(p[(i + 1) % 4] - p[i]);
    minScaled = std::min(minScaled, lengths > 0.0 ? j / lengths : 0.0);
  }
  q.jacobianRatio = maxJ > 0.0 ? minJ / maxJ : -1.0;
  // The same at the 2 x 2 Gauss points of the bilinear map.
  const double g = 1.0 / std::sqrt(3.0);
  double minG = kInfinity, maxG = -kInfinity;
  for (const double xi : {-g, g})
    for (const double eta : {-g, g}) {
      const Vec3 dXi = ((p[1] - p[0]) * (1.0 - eta) + (p[2] - p[3]) * (1.0 + eta)) * 0.25;
      const Vec3 dEta = ((p[3] - p[0]) * (1.0 - xi) + (p[2] - p[1]) * (1.0 + xi)) * 0.25;
      const double j = dot(cross(dXi, dEta), n);
      minG = std::min(minG, j);
      maxG = std::max(maxG, j);
    }
  q.jacobianRatioGauss = maxG > 0.0 ? minG / maxG : -1.0;
  q.scaledJacobian = minScaled;

  // Taper: signed corner-triangle areas along the element normal against half the quad area.
  const double area = 0.5 * norm(diagonalNormal);
  const Vec3 unit = normalized(diagonalNormal);
  double minCorner = kInfinity;
  for (std::size_t i = 0; i < 4; ++i)
    minCorner = std::min(minCorner, 0.5 * dot(cornerNormal[i], unit));
  q.taper = area > 0.0 ? 1.0 - minCorner / (0.5 * area) : 1.0;
  q.minLength = longest > 0.0 ? area / longest : 0.0;
  return q;
}

}  // namespace

ElementQuality elementQuality(const std::array<std::array<double, 3>, 4>& p, int corners) {
  if (corners == 3) return triangleQuality(p);
  if (corners == 4) return quadQuality(p);
  throw std::invalid_argument("an element has 3 or 4 corners, not " + std::to_string(corners));
}

}  // namespace voxremesh
