// The search engine's loop (src/optimize/search_engine.h) on a row of numbers: an item raises its
// number to its right neighbour's. The tests check which items are tried in which round: a try
// in vain is not made again while its points are unchanged, an item waits for the next round when
// an earlier class changed its points (or sees the change, by its rules), and the rounds stop
// when one changes nothing.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "optimize/search_engine.h"

namespace {

using voxremesh::CornerIndex;
using voxremesh::opt::PointAccess;
using voxremesh::opt::RoundRules;
using voxremesh::opt::runEngineRounds;
using voxremesh::opt::VainTries;

/// Item i reads numbers i and i + 1 and raises number i to number i + 1 when it is lower.
/// Neighbouring items conflict, so the even items form one class and the odd ones the next.
struct RaiseToTheRight {
  struct Item {
    CornerIndex key;
    PointAccess access;
    std::vector<CornerIndex> depends;
  };
  std::vector<int> numbers;
  int round = 0;
  std::vector<std::pair<int, CornerIndex>> tries;  ///< (round, item), in the order applied

  std::vector<Item> items(int r) {
    round = r;
    std::vector<Item> items;
    for (CornerIndex i = 0; i + 1 < numbers.size(); ++i)
      items.push_back({i, {{i, i + 1}, {i}}, {i, i + 1}});
    return items;
  }
  void startClass() {}
  bool tryItem(const Item& item) const { return numbers[item.key] < numbers[item.key + 1]; }
  std::vector<CornerIndex> apply(const Item& item, bool raise) {
    tries.emplace_back(round, item.key);
    if (!raise) return {};
    numbers[item.key] = numbers[item.key + 1];
    return {item.key};
  }
  void endRound(std::size_t /*changed*/) {}
};

using Tries = std::vector<std::pair<int, CornerIndex>>;

TEST(SearchEngine, AnItemWaitsForTheNextRoundWhereAnEarlierClassChangedItsPoints) {
  RaiseToTheRight kind{{0, 0, 0, 5}, 0, {}};
  EXPECT_EQ(runEngineRounds(10, 4, RoundRules{true, true}, kind), 3u);
  EXPECT_EQ(kind.numbers, (std::vector<int>{5, 5, 5, 5}));
  // Round 0: item 2 raises its number; item 1 (next class) waits. Round 1: item 0, tried in vain
  // with its numbers unchanged, is dropped; 1 raises, 2 is tried in vain. Round 2: 0 raises (its
  // neighbour changed), 1 finds nothing, 2 is dropped. Round 3: only 0 is tried, in vain.
  EXPECT_EQ(kind.tries, (Tries{{0, 0}, {0, 2}, {1, 1}, {1, 2}, {2, 0}, {2, 1}, {3, 0}}));
}

TEST(SearchEngine, AnItemSeesTheChangesOfEarlierClassesWhenItsRulesSaySo) {
  RaiseToTheRight kind{{0, 0, 0, 5}, 0, {}};
  EXPECT_EQ(runEngineRounds(10, 4, RoundRules{false, false}, kind), 3u);
  EXPECT_EQ(kind.numbers, (std::vector<int>{5, 5, 5, 5}));
  // Round 0: item 1 sees item 2's raise and raises too. Round 1: item 0 raises; 2 and 1 find
  // nothing. Round 2: 2 and 1, in vain with their numbers unchanged, are skipped; 0 finds nothing.
  EXPECT_EQ(kind.tries, (Tries{{0, 0}, {0, 2}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {2, 0}}));
}

TEST(SearchEngine, StopsAfterTheRoundsAskedFor) {
  RaiseToTheRight kind{{0, 0, 0, 5}, 0, {}};
  EXPECT_EQ(runEngineRounds(1, 4, RoundRules{true, true}, kind), 1u);
  EXPECT_EQ(kind.numbers, (std::vector<int>{0, 0, 5, 5}));
  EXPECT_EQ(runEngineRounds(0, 4, RoundRules{true, true}, kind), 0u);
}

TEST(VainTries, ATryInVainHoldsUntilAPointItDependsOnChanges) {
  VainTries<CornerIndex> byPoint(4);
  const std::vector<CornerIndex> points{1, 2};
  EXPECT_FALSE(byPoint.unchangedSinceVain(7, points));  // never tried
  byPoint.noteVain(7, 3);
  byPoint.noteChanged(0, 4);  // not a point it depends on
  EXPECT_TRUE(byPoint.unchangedSinceVain(7, points));
  byPoint.noteChanged(2, 3);  // changed at the stamp of the try: it may have come after it
  EXPECT_FALSE(byPoint.unchangedSinceVain(7, points));
  VainTries<std::vector<CornerIndex>> byFace(4);
  byFace.noteVain({1, 2, 3}, 5);
  EXPECT_EQ(byFace.vainAt({1, 2, 3}), 5u);
  EXPECT_EQ(byFace.vainAt({1, 2}), 0u);
}

}  // namespace
