// The boundary strip of the extraction stage (paper Fig. 7): the dual mesh stops short of the
// original boundary loops; this closes the gap with a strip of quads (triangles only where no
// quad fits, strip_zip.h) whose outer nodes lie on the original loops.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "extract/junction_nodes.h"
#include "voxremesh/quad_mesh.h"

namespace voxremesh::extract {

/// Counts of rebuildBoundaryStrip.
struct StripStats {
  std::uint64_t quads = 0;
  std::uint64_t triangles = 0;
  std::uint64_t removedFaces = 0;     ///< faces of stray dual pieces removed (see below)
  std::uint64_t pinchedFaces = 0;     ///< faces removed at pinched vertices (pinch_fans.h)
  std::uint64_t filledQuads = 0;      ///< quads closing gaps inside the dual mesh
  std::uint64_t filledTriangles = 0;  ///< triangles closing gaps inside the dual mesh
  std::uint64_t junctionNodes = 0;    ///< nodes placed where the junction curves prescribe
  /// The nodes placed inside bridges (Free points on the straight bridge, for the caller to lay
  /// on the surface; each bridge node is there twice, once per visit, with the same coordinates).
  std::vector<std::uint32_t> bridgeNodes;
  /// Quads of the ladders across keyhole necks (neck_ladder.h; counted in `quads` too), and the
  /// Free nodes inside their rungs (on the chord, for the caller to lay on the surface).
  std::uint64_t ladderQuads = 0;
  std::vector<std::uint32_t> ladderNodes;
};

/// Rebuilds the boundary of `mesh` up to the original boundary loops.
/// Every boundary loop of the dual mesh is matched to the original loop most of its vertices are
/// closest to; each original loop takes the matched dual loop with the most vertices. Dual
/// pieces (connected components) with a boundary none of whose loops was taken are stray
/// (surface left inside a small hole) and removed. Between a taken dual loop D and its loop O the
/// strip gets nodes on O: its corners, and between consecutive corners nodes evenly spaced about
/// `spacing` apart (at least four on a loop, and one more where the count around the strip would
/// be odd); then the faces between D and those nodes are the cheapest sequence of quads (across
/// the strip, or fanning two edges of one side to a point of the other) and, only where no quad
/// fits, triangles (strip_zip.h). New nodes on O get role Boundary (curve: the loop's index in
/// mesh.curves) or Corner.
/// @param mesh        the dual mesh: edge-manifold, faces oriented (boundary loops run with the
///                    mesh on their left, as the original loops do)
/// @param loopCurves  the indices into mesh.curves of the original boundary loops (closed)
/// @param corners     feature points; those equal to a vertex of a loop are its corners
/// @param junctions   the nodes of the junction curves: on loop edges that are junction edges
///                    these are the strip's nodes there, with the exact prescribed coordinates, and
///                    get role Junction; no corner or extra node is added there
/// @param spacing     the distance between nodes on the loops (the voxel size), > 0
/// @param tolerance   where the chord between two strip nodes misses a vertex of the loop by
///                    more than this, the vertex becomes a node too (with a triangle)
/// @param reach       a dual vertex votes only for original loops closer than this (the dual mesh
///                    stops within a few voxels of the boundary; farther vertices belong to gaps)
/// A boundary loop of a kept piece that no original loop takes is a gap inside the surface and is
/// closed by a fan of quads. Where one dual loop takes several original loops (the dual mesh could
/// not pass between two holes, or a hole and the outer contour), they are joined by bridges at
/// their closest points, so the strip spans the narrow neck between them; a bridge longer than
/// 1.5 x `spacing` gets Free nodes along it about `spacing` apart (StripStats::bridgeNodes), the
/// same on both of its visits, so that the weld makes them points inside the surface.
/// Throws std::runtime_error naming the loop (index and a point of it) when an original loop has
/// no dual loop to join.
StripStats rebuildBoundaryStrip(QuadMesh& mesh, const std::vector<std::uint32_t>& loopCurves,
                                const std::vector<std::array<double, 3>>& corners,
                                const JunctionNodes& junctions, double spacing, double tolerance,
                                double reach);

}  // namespace voxremesh::extract
