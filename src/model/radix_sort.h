// Stable least-significant-digit radix sort of (key, value) pairs, for the sort-based adjacency
// and proximity searches (deterministic, linear time, no hashing).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace voxremesh::model {

/// Sorts `keys` ascending and applies the same permutation to `values`; equal keys keep their
/// input order. Every key must be at most `maxKey` (only the digits it needs are sorted).
/// Preconditions: keys.size() == values.size() < 2^32.
inline void radixSortPairs(std::vector<std::uint64_t>& keys, std::vector<std::uint32_t>& values,
                           std::uint64_t maxKey) {
  const std::size_t n = keys.size();
  if (n < 512) {
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t x, std::uint32_t y) { return keys[x] < keys[y]; });
    std::vector<std::uint64_t> sortedKeys(n);
    std::vector<std::uint32_t> sortedValues(n);
    for (std::size_t i = 0; i < n; ++i) {
      sortedKeys[i] = keys[order[i]];
      sortedValues[i] = values[order[i]];
    }
    keys.swap(sortedKeys);
    values.swap(sortedValues);
    return;
  }
  constexpr int kBits = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kBits;
  int bits = 0;
  while (bits < 64 && (maxKey >> bits) != 0) ++bits;
  std::vector<std::uint64_t> keyBuffer(n);
  std::vector<std::uint32_t> valueBuffer(n);
  std::vector<std::size_t> count(kBuckets);
  for (int shift = 0; shift < bits; shift += kBits) {
    std::fill(count.begin(), count.end(), 0);
    for (const std::uint64_t key : keys) ++count[(key >> shift) & (kBuckets - 1)];
    if (*std::max_element(count.begin(), count.end()) == n) continue;  // one digit: no change
    std::size_t sum = 0;
    for (std::size_t& c : count) {
      const std::size_t here = c;
      c = sum;
      sum += here;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t slot = count[(keys[i] >> shift) & (kBuckets - 1)]++;
      keyBuffer[slot] = keys[i];
      valueBuffer[slot] = values[i];
    }
    keys.swap(keyBuffer);
    values.swap(valueBuffer);
  }
}

}  // namespace voxremesh::model
