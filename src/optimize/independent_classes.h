// How the searches of the optimisation run in parallel and still give the same mesh for any
// thread count: work items that do not see each other's changes are grouped in classes; the items
// of a class are processed in parallel, the classes one after another.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "voxremesh/quad_mesh.h"

namespace voxremesh::opt {

/// The points a work item reads and those it changes (any order, repeats allowed).
struct PointAccess {
  std::vector<CornerIndex> reads;
  std::vector<CornerIndex> writes;
};

/// Splits items 0 .. items.size() - 1 into classes of items none of which changes a point another
/// reads or changes, greedily in item order: an item goes to the first class with no such
/// conflict. Classes list their items ascending and depend only on `items`.
/// @param items       per item, the points it reads and changes
/// @param pointCount  the number of points; every point named is below it
/// Throws std::out_of_range for a point at or above pointCount.
std::vector<std::vector<std::uint32_t>> independentClasses(const std::vector<PointAccess>& items,
                                                           std::size_t pointCount);

/// The work loop of the optimisation's searches: items class by class (independentClasses). As
/// a class comes up, ready(i) picks its items to run (asked for each, in item order, before any
/// of them runs); then startClass(); then tryItem(i) of the items picked, in parallel; then
/// apply(i, result) of each, alone and in item order. The result does not depend on the thread
/// count when tryItem reads only the points its item reads (changing only those it changes)
/// and what apply and startClass set.
/// @param items       per item, the points it reads and changes
/// @param pointCount  the number of points; every point named is below it
/// Throws what independentClasses and the callbacks throw.
template <class Ready, class StartClass, class Try, class Apply>
void runInClasses(const std::vector<PointAccess>& items, std::size_t pointCount, const Ready& ready,
                  const StartClass& startClass, const Try& tryItem, const Apply& apply) {
  using Result = decltype(tryItem(std::uint32_t{}));
  struct Slot {
    Result value{};  // a struct, so that a bool result is not packed into vector<bool>
  };
  for (const std::vector<std::uint32_t>& inClass : independentClasses(items, pointCount)) {
    std::vector<std::uint32_t> members;
    for (const std::uint32_t i : inClass)
      if (ready(i)) members.push_back(i);
    startClass();
    std::vector<Slot> results(members.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, members.size(), 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t m = r.begin(); m < r.end(); ++m)
                          results[m].value = tryItem(members[m]);
                      });
    for (std::size_t m = 0; m < members.size(); ++m) apply(members[m], std::move(results[m].value));
  }
}

}  // namespace voxremesh::opt
