// The classes the optimisation's parallel searches run in (src/optimize/independent_classes.h):
// no item of a class changes a point another item of it reads or changes, the items go to the
// first class they fit in item order, and readers of a common point share a class.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <vector>

#include "optimize/independent_classes.h"

namespace {

using voxremesh::CornerIndex;
using voxremesh::opt::independentClasses;
using voxremesh::opt::PointAccess;

TEST(IndependentClasses, ReadersShareAClassAndAWriterWaitsForTheNext) {
  // Items 0 and 1 only read point 5: one class. Item 2 changes point 5: the next class. Item 3
  // changes point 7, which nobody else touches: the first class.
  const std::vector<PointAccess> items{{{5, 6}, {6}}, {{5, 4}, {4}}, {{5}, {5}}, {{7}, {7}}};
  const auto classes = independentClasses(items, 8);
  ASSERT_EQ(classes.size(), 2u);
  EXPECT_EQ(classes[0], (std::vector<std::uint32_t>{0, 1, 3}));
  EXPECT_EQ(classes[1], (std::vector<std::uint32_t>{2}));
  EXPECT_THROW(independentClasses({{{8}, {}}}, 8), std::out_of_range);
}

TEST(IndependentClasses, NoItemOfAClassSeesAnotherOnesChangesOnRandomAccessLists) {
  // Random items over 60 points: every pair in one class is free of write conflicts, and each
  // item sits in the first class it fits (it conflicts with an item of every class before).
  std::mt19937 random(7);
  std::uniform_int_distribution<CornerIndex> point(0, 59);
  std::vector<PointAccess> items(200);
  for (PointAccess& item : items) {
    for (int k = 0; k < 6; ++k) item.reads.push_back(point(random));
    item.writes.push_back(item.reads[0]);
  }
  const auto conflict = [&](std::uint32_t a, std::uint32_t b) {
    const auto touches = [](const std::vector<CornerIndex>& list, CornerIndex v) {
      return std::find(list.begin(), list.end(), v) != list.end();
    };
    for (const CornerIndex v : items[a].writes)
      if (touches(items[b].reads, v) || touches(items[b].writes, v)) return true;
    for (const CornerIndex v : items[b].writes)
      if (touches(items[a].reads, v)) return true;
    return false;
  };
  const auto classes = independentClasses(items, 60);
  std::size_t count = 0;
  for (std::size_t k = 0; k < classes.size(); ++k) {
    count += classes[k].size();
    for (std::size_t i = 0; i < classes[k].size(); ++i) {
      for (std::size_t j = i + 1; j < classes[k].size(); ++j)
        EXPECT_FALSE(conflict(classes[k][i], classes[k][j])) << k;
      for (std::size_t before = 0; before < k; ++before) {
        bool fitsNowhereBefore = false;
        for (const std::uint32_t other : classes[before])
          fitsNowhereBefore =
              fitsNowhereBefore || (other < classes[k][i] && conflict(other, classes[k][i]));
        EXPECT_TRUE(fitsNowhereBefore) << "item " << classes[k][i] << " class " << before;
      }
    }
  }
  EXPECT_EQ(count, items.size());
}

TEST(RunInClasses, RunsTheReadyItemsClassByClassAndAppliesTheirResultsInItemOrder) {
  // Item i reads points i and i + 1 and changes point i: neighbours conflict, so the even items
  // make one class and the odd ones the next. Item 4 is not ready. Each try writes its point (in
  // parallel) and reads its neighbour, which no item of its class changes.
  constexpr std::size_t kItems = 9;
  std::vector<PointAccess> items;
  for (CornerIndex i = 0; i < kItems; ++i) items.push_back({{i, i + 1}, {i}});
  std::vector<int> points(kItems + 1, 1);
  std::vector<std::uint32_t> applied;
  int classes = 0;
  voxremesh::opt::runInClasses(
      items, points.size(), [](std::uint32_t i) { return i != 4; }, [&] { ++classes; },
      [&](std::uint32_t i) {
        points[i] += points[i + 1];
        return points[i] > 2;  // a bool result: one per item, none packed with another
      },
      [&](std::uint32_t i, bool raised) {
        EXPECT_EQ(raised, i % 2 == 1 && i + 1 != 4 && i + 1 < kItems) << i;
        applied.push_back(i);
      });
  EXPECT_EQ(classes, 2);
  EXPECT_EQ(applied, (std::vector<std::uint32_t>{0, 2, 6, 8, 1, 3, 5, 7}));
  // The even items added their odd neighbour's 1; the odd ones then their even neighbour's 2, but
  // 1 from point 4, whose item did not run. The last point no item changes.
  EXPECT_EQ(points, (std::vector<int>{2, 3, 2, 2, 1, 3, 2, 3, 2, 1}));
}

}  // namespace
