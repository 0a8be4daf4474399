// bridgePairs: the bridges of a keyhole strip, from the dual loop's walk round its loops.
#include "extract/bridge_tree.h"

#include <algorithm>
#include <map>
#include <numeric>

namespace voxremesh::extract {

std::vector<std::pair<std::size_t, std::size_t>> bridgePairs(const std::vector<int>& labels,
                                                             std::size_t loopCount) {
  std::vector<int> walk;
  for (const int label : labels)
    if (label >= 0 && std::size_t(label) < loopCount) walk.push_back(label);
  // A single vertex between two of one loop (cyclically) is that loop's.
  for (bool changed = walk.size() >= 3; changed;) {
    changed = false;
    const std::size_t n = walk.size();
    for (std::size_t i = 0; i < n; ++i) {
      const int before = walk[(i + n - 1) % n], after = walk[(i + 1) % n];
      if (walk[i] != before && before == after) walk[i] = before, changed = true;
    }
  }
  // The steps between loops, counted per pair, in the order first seen.
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> count, firstSeen;
  for (std::size_t i = 0; i < walk.size(); ++i) {
    const int a = walk[i], b = walk[(i + 1) % walk.size()];
    if (a == b) continue;
    const std::pair<std::size_t, std::size_t> pair{std::size_t(std::min(a, b)),
                                                   std::size_t(std::max(a, b))};
    ++count[pair];
    firstSeen.emplace(pair, i);
  }
  std::vector<std::pair<std::size_t, std::size_t>> candidates;
  for (const auto& [pair, n] : count) candidates.push_back(pair);
  std::sort(candidates.begin(), candidates.end(), [&](const auto& p, const auto& q) {
    if (count[p] != count[q]) return count[p] > count[q];
    return firstSeen[p] < firstSeen[q];
  });
  // Kruskal: a pair is taken when it joins two trees of the forest.
  std::vector<std::size_t> parent(loopCount);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::size_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (const auto& [a, b] : candidates) {
    const std::size_t ra = find(a), rb = find(b);
    if (ra == rb) continue;
    parent[ra] = rb;
    pairs.emplace_back(a, b);
  }
  return pairs;
}

}  // namespace voxremesh::extract
