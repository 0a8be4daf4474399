// ChannelWidth: the grid of curve segments and the largest empty ball through a point
// (channel_width.h).
#include "quality/channel_width.h"

#include <algorithm>
#include <cmath>

#include "geometry/plane_basis.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"
#include "voxremesh/sheets.h"

namespace voxremesh::quality {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// A segment longer than this many half cells is not put in the grid but checked every query.
constexpr double kMaxSegmentSamples = 4096.0;
/// Directions the pattern search tries around its centre.
constexpr int kDirections = 12;
/// The search stops when its step falls below this share of the cap.
constexpr double kStepTolerance = 1e-3;
constexpr int kMaxSearchSteps = 200;

}  // namespace

ChannelWidth::ChannelWidth(const std::vector<MeshCurve>& curves, double cap)
    : cap_(cap), cell_(0.5 * cap) {
  for (const MeshCurve& curve : curves) {
    const std::size_t n = curve.points.size();
    if (n == 1) segments_.push_back({curve.points[0], curve.points[0]});
    const std::size_t count = curve.closed && n > 2 ? n : (n > 0 ? n - 1 : 0);
    for (std::size_t i = 0; i < count; ++i)
      segments_.push_back({curve.points[i], curve.points[(i + 1) % n]});
  }
  // A segment on two curves (a seam between two sheets) once: it bounds the channel alike.
  for (auto& [a, b] : segments_)
    if (b < a) std::swap(a, b);
  std::sort(segments_.begin(), segments_.end());
  segments_.erase(std::unique(segments_.begin(), segments_.end()), segments_.end());
  // Cells no larger than the median segment: queries near short elements (reaching about their
  // length) then look at few segments, even where the cap is many elements wide.
  if (!segments_.empty()) {
    std::vector<double> lengths;
    for (const auto& [a, b] : segments_) lengths.push_back(distance(a, b));
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    const double median = lengths[lengths.size() / 2];
    if (median > 0.0) cell_ = std::min(cell_, median);
  }
  for (std::uint32_t s = 0; s < segments_.size(); ++s) {
    const auto& [a, b] = segments_[s];
    const double samples = std::ceil(distance(a, b) / (0.5 * cell_));
    if (!(samples <= kMaxSegmentSamples)) {  // also NaN coordinates
      longSegments_.push_back(s);
      continue;
    }
    const int n = std::max(1, static_cast<int>(samples));
    for (int k = 0; k <= n; ++k) cells_.push_back({cellKey(a + (b - a) * (double(k) / n)), s});
  }
  std::sort(cells_.begin(), cells_.end());
  cells_.erase(std::unique(cells_.begin(), cells_.end()), cells_.end());
}

std::uint64_t ChannelWidth::cellKey(std::int64_t i, std::int64_t j, std::int64_t k) const {
  // Cells far apart may share a key: that only adds segments to a query, never loses one.
  const auto wrap = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & 0x1fffffu; };
  return wrap(i) << 42 | wrap(j) << 21 | wrap(k);
}

std::int64_t ChannelWidth::cellIndex(double coordinate) const {
  return static_cast<std::int64_t>(std::clamp(std::floor(coordinate / cell_), -1e15, 1e15));
}

std::uint64_t ChannelWidth::cellKey(const Vec3& p) const {
  return cellKey(cellIndex(p[0]), cellIndex(p[1]), cellIndex(p[2]));
}

std::vector<std::uint32_t> ChannelWidth::segmentsNear(const Vec3& p, double reach) const {
  std::vector<std::uint32_t> near(longSegments_);
  // A segment point within reach has a grid sample within a quarter cell of it.
  const double margin = reach + 0.25 * cell_;
  std::array<std::int64_t, 3> lo{}, hi{};
  for (std::size_t d = 0; d < 3; ++d) {
    lo[d] = cellIndex(p[d] - margin);
    hi[d] = cellIndex(p[d] + margin);
  }
  for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
    for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
      for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
        const std::uint64_t key = cellKey(i, j, k);
        auto it = std::lower_bound(cells_.begin(), cells_.end(), std::make_pair(key, 0u));
        for (; it != cells_.end() && it->first == key; ++it) near.push_back(it->second);
      }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  return near;
}

double ChannelWidth::clearance(const Vec3& p, const std::vector<std::uint32_t>& near) const {
  double best = 0.5 * cap_;
  for (std::uint32_t s : near) {
    const auto& [a, b] = segments_[s];
    best = std::min(best, distance(p, closestPointOnSegment(p, a, b)));
  }
  return best;
}

double ChannelWidth::at(const Vec3& point, const Vec3& normal) const {
  return at(point, normal, cap_);
}

double ChannelWidth::at(const Vec3& point, const Vec3& normal, double cap) const {
  cap = std::min(cap, cap_);
  const double reach = 0.5 * cap;
  // Every centre tried lies within `reach` of the point, so its nearest segments within reach
  // lie within twice that.
  const std::vector<std::uint32_t> near = segmentsNear(point, 2.0 * reach);
  double radius = clearance(point, near);
  if (!(radius < reach)) return cap;
  // The plane the centre moves in: normal to `normal` (any plane when it is zero).
  const auto [u, v] = planeBasis(norm(normal) > 0.0 ? normalized(normal) : Vec3{0.0, 0.0, 1.0});
  Vec3 centre = point;
  double step = std::max(radius, kStepTolerance * cap);
  for (int s = 0; s < kMaxSearchSteps && step >= kStepTolerance * cap; ++s) {
    Vec3 bestCentre = centre;
    double bestRadius = radius;
    for (int k = 0; k < kDirections; ++k) {
      const double angle = 2.0 * M_PI * k / kDirections;
      const Vec3 c = centre + (u * std::cos(angle) + v * std::sin(angle)) * step;
      const double r = clearance(c, near);
      if (r > bestRadius && distance(c, point) <= r) {
        bestRadius = r;
        bestCentre = c;
      }
    }
    if (bestRadius > radius) {
      centre = bestCentre;
      radius = bestRadius;
      if (!(radius < reach)) return cap;
      step = std::min(2.0 * step, reach);
    } else {
      step *= 0.5;
    }
  }
  return std::min(cap, 2.0 * radius);
}

}  // namespace voxremesh::quality

namespace voxremesh {

std::vector<MeshCurve> channelCurves(const std::vector<Sheet>& sheets) {
  std::vector<MeshCurve> curves;
  for (const Sheet& sheet : sheets) {
    const auto add = [&](const std::vector<Polyline>& lines, PointRole role) {
      for (const Polyline& line : lines) {
        MeshCurve curve;
        curve.closed = line.closed;
        curve.role = role;
        curve.points.reserve(line.points.size());
        for (PointIndex p : line.points) curve.points.push_back(sheet.points.at(p));
        curves.push_back(std::move(curve));
      }
    };
    add(sheet.boundaryLoops, PointRole::Boundary);
    add(sheet.featureLines, PointRole::Feature);
    add(sheet.junctionCurves, PointRole::Junction);
  }
  return curves;
}

}  // namespace voxremesh
