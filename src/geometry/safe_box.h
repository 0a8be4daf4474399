// Axis-aligned boxes for the closest-point hierarchies: grown by a few units in the last place so
// that a closest point computed in floating point (which may round a little outside the exact
// primitive) still lies inside its primitive's box, and the squared distance from a point to a box
// never exceeds the computed squared distance to anything inside it (a safe lower bound to prune
// with: pruning never changes an answer).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/vec3.h"

namespace voxremesh::geom {

/// An axis-aligned box [lo, hi].
struct Box {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()};

  /// Grows the box to hold point q.
  void add(const Vec3& q) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], q[k]);
      hi[k] = std::max(hi[k], q[k]);
    }
  }
  /// Grows the box to hold box b.
  void add(const Box& b) {
    add(b.lo);
    add(b.hi);
  }
};

/// `box` grown on each axis by 16 units in the last place of its largest coordinate magnitude
/// there (plus the smallest normal double): more than the rounding error of the closest points
/// on segments and triangles whose corners span the box. Precondition: finite coordinates.
inline Box safeBox(const Box& box) {
  constexpr double kGrowth = 16.0 * std::numeric_limits<double>::epsilon();
  Box out;
  for (int k = 0; k < 3; ++k) {
    const double margin = kGrowth * std::max(std::abs(box.lo[k]), std::abs(box.hi[k])) +
                          std::numeric_limits<double>::min();
    out.lo[k] = box.lo[k] - margin;
    out.hi[k] = box.hi[k] + margin;
  }
  return out;
}

/// The squared distance from p to the box [lo, hi], summed over the axes in the order of
/// geom::dot, so that it is at most the computed dot(p - q, p - q) of any q in the box (rounding is
/// monotonic). NaN coordinates of p count as inside.
inline double boxDistance2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = p[k] < lo[k] ? lo[k] - p[k] : (p[k] > hi[k] ? p[k] - hi[k] : 0.0);
    d2 += d * d;
  }
  return d2;
}
/// boxDistance2 of p and box.
inline double boxDistance2(const Vec3& p, const Box& box) {
  return boxDistance2(p, box.lo, box.hi);
}

}  // namespace voxremesh::geom
