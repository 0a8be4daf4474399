// Wall-clock timing the benchmarks under tools/ share.
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>

namespace voxremesh::bench {

/// Seconds elapsed since `start` (steady clock).
inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Seconds one call of f takes.
inline double seconds(const std::function<void()>& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return secondsSince(start);
}

/// The shortest time of `repeat` calls of f (infinity when repeat <= 0).
inline double best(int repeat, const std::function<void()>& f) {
  double t = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeat; ++r) t = std::min(t, seconds(f));
  return t;
}

}  // namespace voxremesh::bench
