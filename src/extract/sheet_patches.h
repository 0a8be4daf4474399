// The patches of a narrow sheet (narrow_sheet.h): the sheet cut along its junction curves that
// run through its inside (where another part or sheet meets it along a line inside, e.g. a web on
// the middle of a spar cap), so that each patch is meshed from its own boundary and the nodes on
// the cut are those the junction curve prescribes, on both sides.
#pragma once

#include <vector>

#include "voxremesh/sheets.h"

namespace voxremesh::extract {

/// A patch: its faces (indices into Sheet::faces) and its boundary loops (sheet points, running
/// with the patch on their left): one for a disk, two for a ring (a band or a tube).
struct SheetPatch {
  std::vector<std::size_t> faces;
  std::vector<std::vector<PointIndex>> loops;
  /// A ring's rung: the points of the one cut running through it from a point of its first loop
  /// to a point of its second (a web standing across a band), in that order; else empty.
  std::vector<PointIndex> rung;
};

/// Cuts a sheet into patches along its inner junction edges: junction-curve edges with a face on
/// both sides, rungs from one boundary loop to another too (a web standing on a strip's rung gets
/// the rung's junction nodes on both patches' loops); and, when asked, along all edges of its
/// feature lines (a box or a cup becomes its walls and its cap). A ring crossed by one cut from
/// one of its loops to the other stays a ring with that cut as its rung.
/// @param sheet           a sheet (buildSheets): manifold, consistently oriented
/// @param atFeatureLines  cut along the feature lines too
/// @return the patches in the order of their first face
/// Throws NarrowSheetRefusal when a patch is neither a disk (one boundary loop, Euler
/// characteristic 1) nor a ring (two loops, Euler characteristic 0), or a cut ends inside a
/// patch (other than a ring's rung).
std::vector<SheetPatch> sheetPatches(const Sheet& sheet, bool atFeatureLines = false);

}  // namespace voxremesh::extract
