// How the searches of the optimisation run in parallel and still give the same mesh for any
// thread count: work items that do not see each other's changes are grouped in classes; the items
// of a class are processed in parallel, the classes one after another.
#pragma once

#include <cstdint>
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

}  // namespace voxremesh::opt
