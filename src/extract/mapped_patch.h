// A structured grid of quads over a four-sided patch of a narrow sheet (narrow_sheet.h): where the
// patch's boundary turns sharply at exactly four nodes, the patch is mapped onto a rectangle and
// meshed as rows and columns of quads, with nodes inside where the patch is more than one element
// wide (transfinite interpolation between its four sides, laid on the surface).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "extract/polyline_param.h"
#include "voxremesh/quad_mesh.h"
#include "voxremesh/reference_surface.h"

namespace voxremesh::extract {

/// A node on a patch's loop: its arc length, position and role (Corner, Junction or Boundary).
struct LoopNode {
  double param = 0.0;
  std::array<double, 3> point{};
  PointRole role = PointRole::Boundary;
  /// The stretch to the next node runs along a junction curve between two of its nodes: no node
  /// may be put into it (the neighbour across the junction has none there).
  bool fixedAfter = false;
};

/// The grid of mappedPatch: the loop's nodes (a side may have been spaced again), the nodes
/// inside, and the quads (indices: loop nodes first, then inner nodes), oriented like the loop.
struct MappedPatch {
  std::vector<LoopNode> loop;
  std::vector<std::array<double, 3>> inner;
  std::vector<std::array<std::uint32_t, 4>> quads;
};

/// The surface normal at a point (need not be unit).
using NormalAt = std::function<std::array<double, 3>(const std::array<double, 3>&)>;

/// The indices of the points where a closed loop (in order, not repeated) turns by more than 45
/// degrees: the corners mappedPatch and midpointPatch see.
std::vector<std::size_t> loopCorners(const std::vector<std::array<double, 3>>& loop);

/// The corners of a closed loop (loopCorners) where it turns against its own sense of rotation
/// (about the normal of its vector area, Newell's): the reflex corners of a patch, such as the
/// inner corner of an L.
std::vector<std::size_t> reflexCorners(const std::vector<std::array<double, 3>>& loop);

/// Meshes a patch as a grid when its loop turns by more than 45 degrees at exactly four of its
/// nodes, and opposite sides have as many pieces, or can get as many: a side whose inner nodes all
/// have role Boundary and that has no fixed stretch (LoopNode::fixedAfter) is spaced again evenly
/// with the count of the side opposite (junction nodes are never moved or added). Inner nodes are
/// interpolated from the four sides and laid on the surface.
/// @param loop       the patch's loop (closed)
/// @param nodes      the nodes on it, ascending arc length, at least 4
/// @param reference  the surface the inner nodes are laid on
/// @param normalAt   the surface normal at a point, which every quad must agree with
/// @param tolerance  largest distance of a quad's centre and edge midpoints from the surface
/// @param sagittaShare  where positive, the quads together keep the area of the surface they span
///                   as edges within this share of their length from a curved surface would
///                   (8/3 sagittaShare^2); a crease across the patch costs only the quads on it
/// @return the grid, or nothing when the patch is not four-sided, opposite counts cannot be
///         matched, a quad is not convex or leaves the surface, or the quads lose area
std::optional<MappedPatch> mappedPatch(const PolylineParam& loop,
                                       const std::vector<LoopNode>& nodes,
                                       const ReferenceSurface& reference, const NormalAt& normalAt,
                                       double tolerance, double sagittaShare);

/// Meshes a patch whose loop turns by more than 45 degrees at three or more of its nodes (its
/// corners) as one grid round each corner, all meeting at a node at its centre (midpoint
/// subdivision): each side is split at a node, and the split points are joined to the centre by
/// rows of nodes laid on the surface, so that the grid round a corner has as many pieces on its
/// opposite sides: side k split m_k pieces from its start with m_{k+2} = n_k - m_k (n_k: its
/// pieces), for three sides m_k = (n_k + n_{k+1} - n_{k+2}) / 2. The loop's nodes are kept.
/// @param nodes      the nodes on the patch's loop, ascending arc length
/// @param reference  the surface the inner nodes are laid on
/// @param normalAt   the surface normal at a point, which every quad must agree with
/// @param tolerance  largest distance of a quad's centre and edge midpoints from the surface
/// @param sagittaShare  where positive, the quads together keep the area of the surface they span
///                   as edges within this share of their length from a curved surface would
///                   (8/3 sagittaShare^2); a crease across the patch costs only the quads on it
/// @return the grids (MappedPatch::loop is `nodes`), or nothing when the patch has fewer than
///         three corners, no split point lies strictly inside every side (a side as long as the
///         others together, an odd count of pieces; four sides with different counts on
///         opposite sides), a quad is not convex or leaves the surface, or the quads lose area
std::optional<MappedPatch> midpointPatch(const std::vector<LoopNode>& nodes,
                                         const ReferenceSurface& reference,
                                         const NormalAt& normalAt, double tolerance,
                                         double sagittaShare);

/// Meshes an L-shaped patch (a loop of nodes with six corners, one of them reflex: reflexCorners)
/// as two grids: the patch is cut from its reflex corner straight across, continuing one of the
/// two sides meeting there, to the node of the side it meets that leaves both pieces four-sided
/// with as many pieces on opposite sides (the counts round an L allow that where its two sides
/// along each direction add up to the side across from them). Of the two cuts, the shorter that
/// works. The loop's nodes are kept (MappedPatch::loop is `nodes`), the cut's are inner nodes.
/// @param nodes      the nodes on the patch's loop, ascending arc length
/// @param reference  the surface the inner nodes are laid on
/// @param normalAt   the surface normal at a point, which every quad must agree with
/// @param tolerance  largest distance of a quad's centre and edge midpoints from the surface
/// @param sagittaShare  as for mappedPatch
/// @return the grids, or nothing when the patch is no L, neither cut leaves matching counts, or a
///         quad is not convex, leaves the surface or the quads lose area
std::optional<MappedPatch> lShapedPatch(const std::vector<LoopNode>& nodes,
                                        const ReferenceSurface& reference, const NormalAt& normalAt,
                                        double tolerance, double sagittaShare);

/// The rows of mappedRing: both loops' nodes (a loop may have been spaced again), the nodes inside
/// (row after row), and the quads (indices: the first loop's nodes, the second's, then the inner
/// nodes), oriented like the surface.
struct MappedRing {
  std::array<std::vector<LoopNode>, 2> loops;
  std::vector<std::array<double, 3>> inner;
  std::vector<std::array<std::uint32_t, 4>> quads;
};

/// Meshes a ring patch (a band round a hole, or a tube between its two ends) as rows of quads
/// swept from one loop to the other: both loops get as many nodes (a loop without prescribed
/// nodes or fixed stretches is spaced again evenly with the other's count); node i of the first is
/// paired with a node of the second, in the direction and with the offset that make the pairs
/// shortest in total; each pair's chord is cut into as many pieces as the mean pair is long in
/// `spacing`s (at least one), laid on the surface.
/// @param loops      the two loops (closed)
/// @param nodes      the nodes on each, ascending arc length, at least 3 each
/// @param spacing    the element length wanted across the rows (> 0)
/// @param reference  the surface the inner nodes are laid on
/// @param normalAt   the surface normal at a point, which every quad must agree with
/// @param tolerance  largest distance of a quad's centre and edge midpoints from the surface
/// @param sagittaShare  where positive, the quads together keep the area of the surface they span
///                   as edges within this share of their length from a curved surface would
///                   (8/3 sagittaShare^2); a crease across the patch costs only the quads on it
/// @return the rows, or nothing when the counts cannot be matched, a quad is not convex or
///         leaves the surface, or the quads lose area
std::optional<MappedRing> mappedRing(const std::array<PolylineParam, 2>& loops,
                                     std::array<std::vector<LoopNode>, 2> nodes, double spacing,
                                     const ReferenceSurface& reference, const NormalAt& normalAt,
                                     double tolerance, double sagittaShare);

}  // namespace voxremesh::extract
