// The faces of the boundary strip between two closed rows of points: the dual mesh's boundary
// loop (inner) and the nodes placed on the original boundary loop (outer). A shortest-path
// search over the pairs (inner i, outer j) chooses, step by step, a quad across the strip (both
// rows advance), a quad fanning two edges of one row to a point of the other (the 2:1 transition
// that fills the notch of a staircase, or turns a convex corner of the boundary), or a triangle
// where no quad fits, minimising the summed shape cost of the faces.
#pragma once

#include <openvdb/math/Vec3.h>

#include <array>
#include <cstdint>
#include <vector>

namespace voxremesh::extract {

/// A face of the strip: corner k is inner row point `index[k]` when `outer[k]` is 0, else outer
/// row point `index[k]`; corners = 3 or 4. Ordered like the dual mesh's faces (the strip lies
/// to the right of the inner row's direction).
struct StripFace {
  std::array<std::uint32_t, 4> index{};
  std::array<bool, 4> outer{};
  int corners = 4;
};

/// Zips the two rows from the pair (inner 0, outer 0) once around back to it.
/// @param inner         the inner row, in loop order (the mesh on its left)
/// @param innerNormals  a surface normal at each inner point (need not be unit)
/// @param outer         the outer row, the same direction
/// @param bandCentre    per inner point, the outer index it lies across from (non-decreasing);
///                      the search keeps within `band` of it
/// @param band          half width of the search band in outer points
/// Preconditions: both rows have at least two points; bandCentre has inner.size() entries.
std::vector<StripFace> zipStrip(const std::vector<openvdb::math::Vec3d>& inner,
                                const std::vector<openvdb::math::Vec3d>& innerNormals,
                                const std::vector<openvdb::math::Vec3d>& outer,
                                const std::vector<std::size_t>& bandCentre, std::size_t band);

}  // namespace voxremesh::extract
