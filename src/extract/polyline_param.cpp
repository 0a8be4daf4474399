// Arc-length parametrisation of a polyline (see polyline_param.h).
#include "extract/polyline_param.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/chord_limit.h"

namespace voxremesh::extract {

using openvdb::math::Vec3d;

PolylineParam::PolylineParam(const std::vector<std::array<double, 3>>& points, bool closed)
    : closed_(closed && points.size() > 2) {
  points_.reserve(points.size());
  for (const auto& p : points) points_.emplace_back(p[0], p[1], p[2]);
  boxMin_ = boxMax_ = points_.front();
  for (const Vec3d& p : points_) {
    boxMin_ = minComponent(boxMin_, p);
    boxMax_ = maxComponent(boxMax_, p);
  }
  arc_.assign(points_.size() + 1, 0.0);
  for (std::size_t i = 1; i < points_.size(); ++i)
    arc_[i] = arc_[i - 1] + (points_[i] - points_[i - 1]).length();
  const double closing = closed_ ? (points_.front() - points_.back()).length() : 0.0;
  arc_[points_.size()] = arc_[points_.size() - 1] + closing;
}

std::size_t PolylineParam::segmentAt(double s) const {
  std::size_t lo = 0, hi = points_.size();
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    (arc_[mid] <= s ? lo : hi) = mid;
  }
  return lo;
}

double PolylineParam::closestParam(const Vec3d& p, double& distance) const {
  const std::size_t n = points_.size();
  const std::size_t segments = closed_ ? n : n - 1;
  double best = std::numeric_limits<double>::infinity();
  double bestParam = 0.0;
  if (segments == 0) {
    distance = (p - points_[0]).length();
    return 0.0;
  }
  for (std::size_t i = 0; i < segments; ++i) {
    const Vec3d& a = points_[i];
    const Vec3d& b = points_[(i + 1) % n];
    const Vec3d ab = b - a;
    const double len2 = ab.lengthSqr();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double d2 = (a + ab * t - p).lengthSqr();
    if (d2 < best) {
      best = d2;
      bestParam = arc_[i] + t * (arc_[i + 1] - arc_[i]);
    }
  }
  distance = std::sqrt(best);
  return bestParam;
}

Vec3d PolylineParam::pointAt(double s) const {
  const double total = length();
  if (closed_ && total > 0.0) {
    s = std::fmod(s, total);
    if (s < 0.0) s += total;
  } else {
    s = std::clamp(s, 0.0, total);
  }
  const std::size_t n = points_.size();
  // The segment i with arc_[i] <= s <= arc_[i + 1].
  auto it = std::upper_bound(arc_.begin(), arc_.end(), s);
  std::size_t i = it == arc_.begin() ? 0 : std::size_t(it - arc_.begin()) - 1;
  if (i >= n - (closed_ ? 0 : 1)) return closed_ ? points_[0] : points_[n - 1];
  const double span = arc_[i + 1] - arc_[i];
  const double t = span > 0.0 ? (s - arc_[i]) / span : 0.0;
  return points_[i] + (points_[(i + 1) % n] - points_[i]) * t;
}

double PolylineParam::boxDistance(const Vec3d& p) const {
  const Vec3d below = maxComponent(boxMin_ - p, Vec3d(0.0));
  const Vec3d above = maxComponent(p - boxMax_, Vec3d(0.0));
  return (below + above).length();
}

void addFarVertices(const PolylineParam& line, double s0, double s1, double tolerance,
                    std::vector<double>& out, double sagittaShare) {
  const double length = line.length();
  const Vec3d a = line.pointAt(s0), b = line.pointAt(s1);
  double worst = geom::chordLimit(tolerance, sagittaShare, (b - a).length());
  double worstParam = -1.0;
  const std::size_t n = line.pointCount();
  for (std::size_t i = 0; i < n; ++i) {
    for (double wrap : {0.0, length}) {
      const double v = line.vertexParam(i) + wrap;
      if (v <= s0 || v >= s1) continue;
      const Vec3d ab = b - a, p = line.point(i);
      const double len2 = ab.lengthSqr();
      const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      const double d = (a + ab * t - p).length();
      if (d > worst) worst = d, worstParam = v;
    }
  }
  if (worstParam < 0.0) return;
  addFarVertices(line, s0, worstParam, tolerance, out, sagittaShare);
  out.push_back(worstParam);
  addFarVertices(line, worstParam, s1, tolerance, out, sagittaShare);
}

}  // namespace voxremesh::extract
