#include "assembly/nearest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace voxremesh::assembly {

NearestPoint::NearestPoint(const std::vector<std::array<double, 3>>& points) : points_(points) {
  if (points.empty()) return;
  std::array<double, 3> lo = points[0], hi = points[0];
  for (const auto& p : points)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  origin_ = lo;
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  // About one point per cell for a surface-like set: cell ~ extent / sqrt(n), capped in count.
  const double n = static_cast<double>(points.size());
  cell_ = extent > 0 ? extent / std::max(1.0, std::sqrt(n)) : 1.0;
  for (int a = 0; a < 3; ++a) {
    const double cells = std::floor((hi[a] - lo[a]) / cell_) + 1;
    dims_[a] = static_cast<std::int64_t>(std::min(cells, 4096.0));
  }
  cellStart_.assign(static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]) + 1, 0);
  std::vector<std::uint32_t> cellOfPoint(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto c = cellOf(points[i]);
    cellOfPoint[i] = static_cast<std::uint32_t>(cellIndex(c[0], c[1], c[2]));
    ++cellStart_[cellOfPoint[i] + 1];
  }
  for (std::size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
  order_.resize(points.size());
  std::vector<std::uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
  for (std::size_t i = 0; i < points.size(); ++i)
    order_[fill[cellOfPoint[i]]++] = static_cast<std::uint32_t>(i);
}

std::array<std::int64_t, 3> NearestPoint::cellOf(const std::array<double, 3>& p) const {
  std::array<std::int64_t, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const double t = std::floor((p[a] - origin_[a]) / cell_);
    c[a] = std::clamp<std::int64_t>(
        static_cast<std::int64_t>(std::clamp(t, -1.0, static_cast<double>(dims_[a]))), 0,
        dims_[a] - 1);
  }
  return c;
}

std::size_t NearestPoint::cellIndex(std::int64_t i, std::int64_t j, std::int64_t k) const {
  return static_cast<std::size_t>((k * dims_[1] + j) * dims_[0] + i);
}

std::size_t NearestPoint::nearest(const std::array<double, 3>& q, double* distance) const {
  std::size_t best = std::numeric_limits<std::size_t>::max();
  double bestSq = std::numeric_limits<double>::infinity();
  if (points_.empty()) return best;
  const auto center = cellOf(q);
  // Distance from q to the box of the cells within `ring` of center bounds what a larger ring
  // can add: stop once the nearest found is closer than the part of the grid not yet searched.
  const std::int64_t maxRing = std::max({dims_[0], dims_[1], dims_[2]});
  for (std::int64_t ring = 0; ring <= maxRing; ++ring) {
    for (std::int64_t k = center[2] - ring; k <= center[2] + ring; ++k) {
      if (k < 0 || k >= dims_[2]) continue;
      for (std::int64_t j = center[1] - ring; j <= center[1] + ring; ++j) {
        if (j < 0 || j >= dims_[1]) continue;
        for (std::int64_t i = center[0] - ring; i <= center[0] + ring; ++i) {
          if (i < 0 || i >= dims_[0]) continue;
          const bool shell = std::abs(i - center[0]) == ring || std::abs(j - center[1]) == ring ||
                             std::abs(k - center[2]) == ring;
          if (!shell) continue;
          const std::size_t c = cellIndex(i, j, k);
          for (std::uint32_t s = cellStart_[c]; s < cellStart_[c + 1]; ++s) {
            const std::size_t p = order_[s];
            const auto& x = points_[p];
            const double d = (x[0] - q[0]) * (x[0] - q[0]) + (x[1] - q[1]) * (x[1] - q[1]) +
                             (x[2] - q[2]) * (x[2] - q[2]);
            if (d < bestSq || (d == bestSq && p < best)) {
              bestSq = d;
              best = p;
            }
          }
        }
      }
    }
    // Every point not yet visited lies outside the searched cube of cells; the nearest such
    // point is at least the distance from q to that cube's faces.
    double margin = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      const double lo = origin_[a] + static_cast<double>(center[a] - ring) * cell_;
      const double hi = origin_[a] + static_cast<double>(center[a] + ring + 1) * cell_;
      if (center[a] - ring > 0) margin = std::min(margin, q[a] - lo);
      if (center[a] + ring + 1 < dims_[a]) margin = std::min(margin, hi - q[a]);
    }
    if (best != std::numeric_limits<std::size_t>::max() &&
        (margin == std::numeric_limits<double>::infinity() || margin * margin > bestSq))
      break;
    if (margin == std::numeric_limits<double>::infinity()) break;
  }
  if (distance) *distance = std::sqrt(bestSq);
  return best;
}

}  // namespace voxremesh::assembly
