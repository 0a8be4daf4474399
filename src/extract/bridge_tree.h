// Which original loops a keyhole strip joins by bridges: read from the order in which the dual
// loop passes them (boundary_strip.h).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace voxremesh::extract {

/// Where one dual loop takes several original loops (the dual mesh could not pass between them),
/// it runs round all of them as round a tree of loops joined by bridges, passing each bridge twice
/// (an Euler tour): the loops its vertices lie closest to follow each other as a walk along that
/// tree. This reads the tree back: the walk's steps from one loop to another, after single
/// vertices between two of the same loop are taken as that loop (noise), are the candidate
/// bridges; a spanning forest of them is chosen, the pairs stepped between most often first (ties:
/// the first seen).
/// @param labels     per dual vertex, in loop order, the loop it lies closest to (0 .. loopCount -
///                   1), or -1 for none of them
/// @param loopCount  the number of loops the dual loop takes
/// @return pairs (a, b), a < b, at most loopCount - 1, each joining two trees of the forest; fewer
///         when the walk does not reach every loop (the caller joins the rest otherwise)
std::vector<std::pair<std::size_t, std::size_t>> bridgePairs(const std::vector<int>& labels,
                                                             std::size_t loopCount);

}  // namespace voxremesh::extract
