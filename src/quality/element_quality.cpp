// The per-element metrics of quality.h (definitions there).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "geometry/vec3.h"
#include "quality/windowed_quality.h"
#include "voxremesh/quality.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// How far inside a window's key an angle's key must lie to be taken as inside it: about 1e-7
/// degrees, far above the rounding of keys and of atan2 (about 1e-13 degrees).
constexpr double kKeyMargin = 1e-9;

/// The angle between two vectors a, b as angleDeg's operands s = |a x b| and c = a . b: ordered by
/// a pseudo-angle, turned into degrees (atan2, the costly part) only for the angle that is kept.
struct Angle {
  double s = 0.0, c = 0.0;

  Angle() = default;
  Angle(const Vec3& a, const Vec3& b) : s(norm(cross(a, b))), c(dot(a, b)) {}
  Angle(double sine, double cosine) : s(sine), c(cosine) {}

  /// The value of angleDeg(a, b).
  double degrees() const { return s == 0.0 && c == 0.0 ? 0.0 : std::atan2(s, c) * kDegrees; }
  /// The angle folded to 0..90 (lineAngleDeg).
  double lineDegrees() const {
    const double angle = degrees();
    return angle > 90.0 ? 180.0 - angle : angle;
  }
  /// A key that increases with the angle, 0..2 for 0..180 degrees (0 when s = c = 0, as
  /// degrees()); NaN when s or c is not finite or their sum overflows.
  double key() const {
    const double sum = s + std::abs(c);
    if (!std::isfinite(sum)) return std::numeric_limits<double>::quiet_NaN();
    if (sum == 0.0) return 0.0;
    return c >= 0.0 ? s / sum : 2.0 - s / sum;
  }
  /// The key of the angle folded to 0..90, 0..1.
  double lineKey() const { return Angle(s, std::abs(c)).key(); }

 private:
  static constexpr double kDegrees = 57.29577951308232;  // as angleDeg
};

/// Angle between the normals of triangles (a,b,c) and (a,c,d); 0 when one has no area.
Angle splitAngle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 n1 = cross(b - a, c - a), n2 = cross(c - a, d - a);
  if (dot(n1, n1) == 0.0 || dot(n2, n2) == 0.0) return {};  // as norm == 0, without the root
  return {n1, n2};
}

/// The edges e_i = p_{i+1} - p_i of an element, their lengths and the corner normals
/// c_i = e_{i-1} x e_i, shared by the metrics.
struct Edges {
  std::array<Vec3, 4> edge, cornerNormal;
  std::array<double, 4> length{};

  Edges(const std::array<Vec3, 4>& p, int n) {
    const auto count = static_cast<std::size_t>(n);
    for (std::size_t i = 0; i < count; ++i) {
      edge[i] = p[(i + 1) % count] - p[i];
      length[i] = norm(edge[i]);
    }
    for (std::size_t i = 0; i < count; ++i)
      cornerNormal[i] = cross(edge[(i + count - 1) % count], edge[i]);
  }
};

/// Fills the edge-based metrics shared by quads and triangles: aspect ratio, interior angles
/// (reflex-corrected against `normal`), longest edge.
void edgeMetrics(const Edges& edges, int n, const Vec3& normal, const AngleWindow* window,
                 ElementQuality& q, double& longest) {
  const auto count = static_cast<std::size_t>(n);
  double shortest = kInfinity;
  longest = 0.0;
  std::array<Angle, 4> angle;
  std::array<bool, 4> reflex{};
  std::array<double, 4> key{};
  bool finite = true;
  for (std::size_t i = 0; i < count; ++i) {
    shortest = std::min(shortest, edges.length[i]);
    longest = std::max(longest, edges.length[i]);
    // The angle between -e_{i-1} and e_i; concave where c_i points against the normal.
    angle[i] = Angle(norm(edges.cornerNormal[i]),
                     -dot(edges.edge[(i + count - 1) % count], edges.edge[i]));
    reflex[i] = dot(edges.cornerNormal[i], normal) < 0.0;
    key[i] = reflex[i] ? 4.0 - angle[i].key() : angle[i].key();  // reflex: 2..4
    finite = finite && std::isfinite(key[i]);
  }
  auto degrees = [&](std::size_t i) {
    const double value = angle[i].degrees();
    return reflex[i] ? 360.0 - value : value;
  };
  if (finite) {
    // Only the smallest and the largest angle are converted (the first of equal ones).
    std::size_t smallest = 0, largest = 0;
    for (std::size_t i = 1; i < count; ++i) {
      if (key[i] < key[smallest]) smallest = i;
      if (key[i] > key[largest]) largest = i;
    }
    q.minAngleDeg = window && key[smallest] >= window->minAngleKey + kKeyMargin
                        ? window->minAngleDeg
                        : degrees(smallest);
    q.maxAngleDeg = window && key[largest] <= window->maxAngleKey - kKeyMargin ? window->maxAngleDeg
                                                                               : degrees(largest);
  } else {
    // Not finite: every angle, NaN ones left out by std::min/max.
    q.minAngleDeg = kInfinity;
    q.maxAngleDeg = -kInfinity;
    for (std::size_t i = 0; i < count; ++i) {
      q.minAngleDeg = std::min(q.minAngleDeg, degrees(i));
      q.maxAngleDeg = std::max(q.maxAngleDeg, degrees(i));
    }
  }
  q.aspectRatio = shortest > 0.0 ? longest / shortest : kInfinity;
}

ElementQuality triangleQuality(const std::array<Vec3, 4>& p, const AngleWindow* window) {
  ElementQuality q;
  const Edges edges(p, 3);
  const Vec3 normal = cross(p[1] - p[0], p[2] - p[0]);
  double longest = 0.0;
  edgeMetrics(edges, 3, normal, window, q, longest);
  // Skew: per corner, the median against the line joining the adjacent midsides.
  std::array<Angle, 3> line;
  std::array<double, 3> key{};
  for (std::size_t i = 0; i < 3; ++i) {
    const Vec3& a = p[i];
    const Vec3& b = p[(i + 1) % 3];
    const Vec3& c = p[(i + 2) % 3];
    const Vec3 median = (b + c) * 0.5 - a;
    const Vec3 midline = (c + a) * 0.5 - (a + b) * 0.5;
    line[i] = Angle(median, midline);
    key[i] = line[i].lineKey();
  }
  double smallest = 90.0;
  if (std::isfinite(key[0]) && std::isfinite(key[1]) && std::isfinite(key[2])) {
    const std::size_t i = key[1] < key[0] ? (key[2] < key[1] ? 2 : 1) : (key[2] < key[0] ? 2 : 0);
    smallest = window && key[i] >= window->minLineKey + kKeyMargin
                   ? 90.0 - window->maxSkewDeg
                   : std::min(smallest, line[i].lineDegrees());
  } else {
    for (const Angle& angle : line) smallest = std::min(smallest, angle.lineDegrees());
  }
  q.skewDeg = 90.0 - smallest;
  const Vec3 unit = normalized(normal);
  double minSine = kInfinity;
  for (std::size_t i = 0; i < 3; ++i) {
    // The corner's edges u = e_i and v = -e_{i-1}: u x v = c_i.
    const double lengths = edges.length[i] * edges.length[(i + 2) % 3];
    minSine = std::min(minSine, lengths > 0.0 ? dot(edges.cornerNormal[i], unit) / lengths : 0.0);
  }
  q.scaledJacobian = minSine * 2.0 / std::sqrt(3.0);
  q.jacobianRatio = 1.0;
  const double area = 0.5 * norm(normal);
  q.minLength = longest > 0.0 ? 2.0 * area / longest : 0.0;
  return q;
}

ElementQuality quadQuality(const std::array<Vec3, 4>& p, const AngleWindow* window,
                           bool gaussJacobian) {
  ElementQuality q;
  const Edges edges(p, 4);
  const Vec3 diagonalNormal = cross(p[2] - p[0], p[3] - p[1]);
  double longest = 0.0;
  edgeMetrics(edges, 4, diagonalNormal, window, q, longest);
  const Angle split02 = splitAngle(p[0], p[1], p[2], p[3]);
  const Angle split13 = splitAngle(p[1], p[2], p[3], p[0]);
  const double key02 = split02.key(), key13 = split13.key();
  if (!std::isfinite(key02) || !std::isfinite(key13))
    q.warpingDeg = std::max(split02.degrees(), split13.degrees());
  else if (window && std::max(key02, key13) <= window->maxWarpingKey - kKeyMargin)
    q.warpingDeg = window->maxWarpingDeg;
  else
    q.warpingDeg = (key02 < key13 ? split13 : split02).degrees();

  const Vec3 m01 = (p[0] + p[1]) * 0.5, m12 = (p[1] + p[2]) * 0.5;
  const Vec3 m23 = (p[2] + p[3]) * 0.5, m30 = (p[3] + p[0]) * 0.5;
  const Angle midLines(m12 - m30, m23 - m01);
  const double midLinesKey = midLines.lineKey();
  q.skewDeg = window && std::isfinite(midLinesKey) && midLinesKey >= window->minLineKey + kKeyMargin
                  ? window->maxSkewDeg
                  : 90.0 - midLines.lineDegrees();

  // Corner Jacobians on the plane of the averaged corner normals.
  const std::array<Vec3, 4>& cornerNormal = edges.cornerNormal;
  Vec3 sum{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < 4; ++i) sum = sum + cornerNormal[i];
  const Vec3 n = normalized(sum);
  double minJ = kInfinity, maxJ = -kInfinity, minScaled = kInfinity;
  for (std::size_t i = 0; i < 4; ++i) {
    const double j = dot(cornerNormal[i], n);
    minJ = std::min(minJ, j);
    maxJ = std::max(maxJ, j);
    const double lengths = edges.length[(i + 3) % 4] * edges.length[i];
    minScaled = std::min(minScaled, lengths > 0.0 ? j / lengths : 0.0);
  }
  q.jacobianRatio = maxJ > 0.0 ? minJ / maxJ : -1.0;
  // The same at the 2 x 2 Gauss points of the bilinear map.
  if (gaussJacobian) {
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
  }
  q.scaledJacobian = minScaled;

  // Taper: signed corner-triangle areas along the element normal against half the quad area.
  const double diagonalLength = norm(diagonalNormal);
  const double area = 0.5 * diagonalLength;
  const Vec3 unit =
      diagonalLength > 0.0 ? diagonalNormal * (1.0 / diagonalLength) : Vec3{0.0, 0.0, 0.0};
  double minCorner = kInfinity;
  for (std::size_t i = 0; i < 4; ++i)
    minCorner = std::min(minCorner, 0.5 * dot(cornerNormal[i], unit));
  q.taper = area > 0.0 ? 1.0 - minCorner / (0.5 * area) : 1.0;
  q.minLength = longest > 0.0 ? area / longest : 0.0;
  return q;
}

}  // namespace

ElementQuality elementQuality(const std::array<std::array<double, 3>, 4>& p, int corners) {
  if (corners == 3) return triangleQuality(p, nullptr);
  if (corners == 4) return quadQuality(p, nullptr, true);
  throw std::invalid_argument("an element has 3 or 4 corners, not " + std::to_string(corners));
}

AngleWindow makeAngleWindow(double minAngleDeg, double maxAngleDeg, double maxWarpingDeg,
                            double maxSkewDeg) {
  constexpr double kRadians = 0.017453292519943295;
  // A bound outside 0..180 degrees (odd settings) gets a key no angle passes: nothing is skipped.
  auto key = [&](double degrees, double outside) {
    if (!(degrees >= 0.0 && degrees <= 180.0)) return outside;
    return Angle(std::sin(degrees * kRadians), std::cos(degrees * kRadians)).key();
  };
  AngleWindow w;
  w.minAngleDeg = minAngleDeg;
  w.maxAngleDeg = maxAngleDeg;
  w.maxWarpingDeg = maxWarpingDeg;
  w.maxSkewDeg = maxSkewDeg;
  w.minAngleKey = key(minAngleDeg, kInfinity);
  w.maxAngleKey = key(maxAngleDeg, -kInfinity);
  w.maxWarpingKey = key(maxWarpingDeg, -kInfinity);
  w.minLineKey = key(90.0 - maxSkewDeg, kInfinity);
  return w;
}

ElementQuality elementQualityWithin(const std::array<std::array<double, 3>, 4>& p, int corners,
                                    const AngleWindow& window, bool gaussJacobian) {
  if (corners == 3) return triangleQuality(p, &window);
  if (corners == 4) return quadQuality(p, &window, gaussJacobian);
  throw std::invalid_argument("an element has 3 or 4 corners, not " + std::to_string(corners));
}

}  // namespace voxremesh
