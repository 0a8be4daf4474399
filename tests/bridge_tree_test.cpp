// The bridges of a keyhole strip read from the dual loop's walk round its loops
// (src/extract/bridge_tree.h): the walk of an Euler tour gives back its tree; noise and loops
// the walk misses do not break it.
#include <gtest/gtest.h>

#include <algorithm>

#include "extract/bridge_tree.h"

namespace voxremesh::extract {
namespace {

using Pairs = std::vector<std::pair<std::size_t, std::size_t>>;

Pairs sorted(Pairs pairs) {
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

/// A walk that stays `run` vertices at each loop of `tour`.
std::vector<int> walk(const std::vector<int>& tour, int run) {
  std::vector<int> labels;
  for (const int loop : tour) labels.insert(labels.end(), std::size_t(run), loop);
  return labels;
}

TEST(BridgePairs, AStarOfHolesRoundTheOuterContour) {
  // The outer contour 0 with holes 1 and 2 by it: the walk goes 0 1 0 2 (0 again at the start).
  // Holes 1 and 2 lie closer to each other than to 0 does not matter: the walk says 0-1 and 0-2.
  EXPECT_EQ(sorted(bridgePairs(walk({0, 1, 0, 2}, 5), 3)), (Pairs{{0, 1}, {0, 2}}));
}

TEST(BridgePairs, ARowOfHolesIsAChain) {
  // Holes 0 1 2 3 in a row: the walk round them goes 0 1 2 3 2 1.
  EXPECT_EQ(sorted(bridgePairs(walk({0, 1, 2, 3, 2, 1}, 4), 4)), (Pairs{{0, 1}, {1, 2}, {2, 3}}));
}

TEST(BridgePairs, SingleVerticesBetweenOneLoopAreNoise) {
  // The bracket at 6 mm: a vertex closest to the lower hole (2) amid those of the top hole (1).
  std::vector<int> labels = walk({0, 2, 0}, 6);
  for (const int label : {1, 2, 1, 1, 1}) labels.push_back(label);
  for (int k = 0; k < 6; ++k) labels.push_back(0);
  EXPECT_EQ(sorted(bridgePairs(labels, 3)), (Pairs{{0, 1}, {0, 2}}));
}

TEST(BridgePairs, LoopsTheWalkMissesAreLeftToTheCaller) {
  // Loop 2 has no vertex (and -1 marks vertices near none of the loops): one pair only.
  std::vector<int> labels = walk({0, 1}, 3);
  labels.insert(labels.begin() + 2, -1);
  EXPECT_EQ(bridgePairs(labels, 3), (Pairs{{0, 1}}));
  EXPECT_TRUE(bridgePairs({}, 2).empty());
  EXPECT_TRUE(bridgePairs(walk({0}, 4), 1).empty());
}

}  // namespace
}  // namespace voxremesh::extract
