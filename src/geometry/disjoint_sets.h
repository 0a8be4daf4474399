// DisjointSets: union-find over indices 0..n-1, with path halving. The lower index of two joined
// roots stays the root, so a set's root is its lowest member and does not depend on join order.
#pragma once

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace voxremesh {

class DisjointSets {
 public:
  /// n singleton sets.
  explicit DisjointSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), std::size_t(0));
  }

  /// The root of x's set (its lowest member). Precondition: x < n.
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }

  /// Merges the sets of a and b. Precondition: a, b < n.
  void join(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace voxremesh
