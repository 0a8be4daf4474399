// Narrow sheets meshed from their boundary alone (DESIGN.md, "Sizing resolves the part": a narrow
// strip is better meshed with rows along it than with small elements everywhere).
//
// A sheet narrower than a few voxels leaves the volume's dual mesh too little room: the strip
// between the dual mesh and the boundary cannot be zipped, or pieces and loops are lost. Such a
// sheet is cut into patches along the junction curves that run through it (sheet_patches.h);
// each patch, a disk or a ring, gets nodes on its boundary loops:
// - its corners; on junction stretches (edges of junction curves) the nodes the junction curves
//   prescribe (junction_nodes.h), with their exact coordinates, so that the neighbouring sheet or
//   part gets the same ones;
// - on free stretches, first the points facing nodes already placed across the patch (where the
//   loop runs against the node's stretch), then nodes evenly spaced about `spacing` apart, then
//   loop points farther than `tolerance` (or `sagittaShare` of its length) from the chord between
//   two nodes (Douglas-Peucker), and one more node where the count would be odd.
// Faces: a disk whose loop turns sharply at exactly four nodes becomes a grid (mapped_patch.h,
// nodes inside where it is more than one element wide); an L (six corners, one reflex), two grids
// either side of a cut from its reflex corner, and one that turns sharply at three or more, a grid
// round each corner meeting at its centre, where they do better than a row; any other
// disk, and a ring joined into one polygon by a bridge between its loops, gets one row of quads
// across (polygon_quads.h), chords allowed where points sampled along them lie within
// `tolerance` of the sheet, faces agreeing with the sheet's normals and chosen by the quality
// criteria. The patches are joined at their shared junction nodes. The mesh is of the same kind
// as an extracted one: nodes with role Corner, Junction or Boundary on their loop's curve, grid
// nodes inside Free.
#pragma once

#include <stdexcept>

#include "extract/junction_nodes.h"
#include "voxremesh/quad_mesh.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"
#include "voxremesh/sheets.h"

namespace voxremesh::extract {

/// Why a sheet cannot be meshed from its boundary: a patch neither a disk nor a ring, a junction
/// curve ending inside it, or no mesh of its boundary nodes near enough to it.
class NarrowSheetRefusal : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Settings of meshNarrowSheet.
struct NarrowSheetSettings {
  double spacing = 0.0;    ///< distance of the nodes along free stretches of the loop, > 0
  double tolerance = 0.0;  ///< largest distance of a face's chords from the sheet, > 0
  double maxChord = 0.0;   ///< the longest edge across the sheet, > 0
  /// The largest distance of an edge of a row across the sheet from it as a share of the edge's
  /// length (a sagitta; below `tolerance` on short edges), so that rows across a sheet curved
  /// across keep its area; grids keep as much of the area over all their quads (mapped_patch.h);
  /// 0: `tolerance` alone.
  double sagittaShare = 0.0;
  /// Nodes on free stretches facing junction nodes across may lie as close to the nodes next to
  /// them as the pieces next to the node they face are short (a wedge's junction nodes close
  /// toward its wide end), not only a share of the spacing away.
  bool followShortPieces = false;
  /// The quality limits the faces of a row are chosen by (polygon_quads.h); targetSize unused.
  QualitySettings criteria;
};

/// Meshes a narrow sheet from its boundary nodes (see the top of the file).
/// @param sheet      the sheet (buildSheets): boundary loops running with the sheet on their left
/// @param surface    sheetSurface of the sheet (its faces, oriented as the sheet)
/// @param reference  the closest-point structure built from `surface`
/// @param junctions  the nodes of the junction curves (those of the sheet's part)
/// @param settings   see NarrowSheetSettings
/// @return the mesh, oriented as the sheet, part sheet.part
/// Throws std::invalid_argument for settings not > 0; NarrowSheetRefusal (with the reason) when a
/// patch is neither a disk nor a ring, a junction curve ends inside the sheet, a row across would
/// have more than 400 boundary nodes, no mesh of the nodes stays on the sheet, or a node of the
/// sheet's junction curves is no node of its mesh (a curve across a patch that does not cut it).
QuadMesh meshNarrowSheet(const Sheet& sheet, const QuadMesh& surface,
                         const ReferenceSurface& reference, const JunctionNodes& junctions,
                         const NarrowSheetSettings& settings);

}  // namespace voxremesh::extract
