// Quads across the necks of a keyhole strip (boundary_strip.h): where a bridge joins two original
// loops that run side by side, the strip's outer row comes back along itself, and the zip, which
// only joins the outer row to the dual loop, would fan faces over the neck from both sides.
#pragma once

#include <openvdb/math/Vec3.h>

#include <array>
#include <cstddef>
#include <map>
#include <vector>

namespace voxremesh::extract {

/// The ladders across the necks: their quads, the nodes they add and those they take from the zip.
/// Node indices below outer.size() are outer row nodes, the others points[index - outer.size()].
struct NeckLadders {
  std::vector<std::array<std::size_t, 4>> quads;  ///< oriented like the mesh
  std::vector<openvdb::math::Vec3d> points;       ///< new nodes inside the rungs (on the chord)
  std::vector<char> carved;  ///< per outer node: inside a ladder, not in the zip's row any more
  /// Per outer node that ends a ladder's last rung on the row's side before the neck: the rung's
  /// inner nodes, in row order, which the zip's row takes after it.
  std::map<std::size_t, std::vector<std::size_t>> rowInserts;
};

/// Grows a ladder of quads out of every bridge of the outer row, on both sides of it. A bridge
/// runs from outer node p to q = p + pieces (the nodes between are its inner nodes); rung k joins
/// nodes p - k and q + k, cut into `pieces` by nodes on its chord, while its length is within 0.6
/// x `spacing` of pieces x spacing (at most 1.6 x spacing for one piece), every quad it closes
/// with rung k - 1 is convex and holds no dual vertex, and no dual vertex comes within 0.3 x
/// `spacing` of it (there the dual mesh fills the neck itself). The nodes of all but the last
/// rung (the bridge's included) are carved out of the zip's row; the last rung becomes the row's
/// step across the neck. Node 0 (where the zip starts) and nodes of another bridge are not taken.
/// @param outer         the outer row (closed, in order)
/// @param bridgeEnd     per outer node j: 0, or the number of pieces of the bridge from j to j +
///                      pieces
/// @param inner         the dual loop's vertices
/// @param innerNormals  a surface normal per dual vertex, oriented like the mesh (need not be unit)
/// @param spacing       the strip's node spacing, > 0
NeckLadders neckLadders(const std::vector<openvdb::math::Vec3d>& outer,
                        const std::vector<std::size_t>& bridgeEnd,
                        const std::vector<openvdb::math::Vec3d>& inner,
                        const std::vector<openvdb::math::Vec3d>& innerNormals, double spacing);

}  // namespace voxremesh::extract
