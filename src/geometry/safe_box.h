// Axis-aligned boxes for the closest-point hierarchies: grown by a few units in the last place so
// that a closest point computed in floating point (which may round a little outside the exact
// primitive) still lies inside its primitive's box, and the squared distance from a point to a box
// never exceeds the computed squared distance to anything inside it (a safe lower bound to prune
// with: pruning never changes an answer).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

/// The squared distance from p to the box [lo, hi]: per axis d = max(lo - p, p - hi, 0), summed
/// as (dx^2 + dy^2) + dz^2 in the order of geom::dot, so that it is at most the computed
/// dot(p - q, p - q) of any q in the box (rounding is monotonic). With SSE2, x and y in one
/// register (the same values). A NaN coordinate of p may give any value (nothing is pruned while
/// the best distance is infinite, and a NaN query has no finite distance).
inline double boxDistance2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
#if defined(__SSE2__)
  const __m128d pxy = _mm_loadu_pd(p.data());
  const __m128d below = _mm_sub_pd(_mm_loadu_pd(lo.data()), pxy);
  const __m128d above = _mm_sub_pd(pxy, _mm_loadu_pd(hi.data()));
  const __m128d dxy = _mm_max_pd(_mm_max_pd(below, above), _mm_setzero_pd());
  const __m128d squares = _mm_mul_pd(dxy, dxy);
  const __m128d pz = _mm_load_sd(&p[2]);
  const __m128d dz = _mm_max_sd(
      _mm_max_sd(_mm_sub_sd(_mm_load_sd(&lo[2]), pz), _mm_sub_sd(pz, _mm_load_sd(&hi[2]))),
      _mm_setzero_pd());
  const __m128d sum = _mm_add_sd(squares, _mm_unpackhi_pd(squares, squares));
  return _mm_cvtsd_f64(_mm_add_sd(sum, _mm_mul_sd(dz, dz)));
#else
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::max(std::max(lo[k] - p[k], p[k] - hi[k]), 0.0);
    d2 += d * d;
  }
  return d2;
#endif
}
/// boxDistance2 of p and box.
inline double boxDistance2(const Vec3& p, const Box& box) {
  return boxDistance2(p, box.lo, box.hi);
}

}  // namespace voxremesh::geom
