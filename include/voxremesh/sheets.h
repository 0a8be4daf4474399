// Sheets: the clean, manifold, consistently oriented pieces a part is split into before it is
// written into a volume, with the curves extraction must keep (boundary loops, feature lines,
// feature points, junction curves).
//
// Definitions (buildSheets, buildAllSheets):
// - Faces. Every shell of the part is one face, except shells without a surface: a shell whose
//   corners, after dropping a corner equal to the one before it (cyclically), are fewer than three
//   or still name a node twice (a line, a point, or a quad folded onto itself like a-b-a-c). Those
//   belong to no sheet. A quad with one repeated corner (a-a-b-c) is the triangle a-b-c.
// - Splitting. An edge of the part is manifold when exactly two faces use it, non-manifold when
//   three or more do. A sheet is a maximal set of faces connected across manifold edges that are
//   not cuts (below); sheets are ordered by their first face, faces by their order in the model.
// - Folds. A manifold edge whose faces' normals (in a consistent orientation) differ by more than
//   120 degrees is a fold: its two sides open at less than 60 degrees (a trailing edge, a hem)
//   and lie closer to each other than to the fold, too close for one volume to hold both. The
//   part's faces are coloured by the side of the nearest fold (walking between face centroids
//   across inner edges that are not folds; along a chain of folds one side is the same side all
//   along), and the inner edges between faces of different colours are the fold cuts: the folds
//   themselves and a line where the two sides' regions meet (along a wing's leading edge). Each
//   side becomes a sheet of its own, meeting the other at junction curves along the cuts, so that
//   each gets its own volume.
// - Seams inside a sheet. A seam with another part (edges whose nodes both parts' shells use)
//   that runs through the inside of the part, over edges with two of its faces (a stiffener
//   standing on a line of a panel), is a cut: the panel is split along it, so that the seam lies
//   on the boundaries of the sheets that meet there and every sheet's mesh carries its nodes.
//   Where such a seam ends inside the part, away from its boundary and from other curves, it is
//   extended along the part's edges, each turning less than 45 degrees from the seam's last
//   edge, to the first node on the boundary, another curve or a fold cut; an end that reaches
//   none is not extended. The part's own T-junctions (a fin of the part standing on a line of
//   its panel) are extended the same way where they end inside the panel (the fin's free edge
//   being the only other curve there): the panel's volume mesh has nodes only on its sheets'
//   boundaries, so a line ending inside one sheet would get none and the fin would come loose.
// - Cuts. Fold cuts, seams inside a sheet and their extensions are the part's cuts. findSheetCuts
// finds them on a whole
//   deck; SheetSettings::sheetCuts hands them to buildSheets on a piece of it, so that both parts
//   of a seam see the same cuts.
// - Orientation. Each sheet is oriented by a breadth-first walk from its first face across its
//   manifold edges, flipping faces so that the two faces of every manifold edge run along it in
//   opposite directions. Then the orientation that more of the original faces had is kept (on a
//   tie, the first face's). A flipped face lists its corners in reverse order starting from the
//   same first corner (a-b-c-d becomes a-d-c-b) and has faceFlipped set. When the walk meets a
//   face it already oriented the other way across a manifold edge, the sheet is not orientable
//   (Moebius-like): buildSheets throws InputError naming the part, that shell and the edge.
// - Non-manifold edges inside a sheet. A sheet can hold several faces of one non-manifold edge
//   when they are connected around it (a plate with a fin welded along part of its middle). Of
//   those, the pair that runs along the edge in opposite directions and is the most nearly flat is
//   joined (the edge is inside the sheet); the others are cut apart along the edge: the sheet gets
//   a separate point per side of the cut, so pointNodeIds can then name a node more than once
//   (the faces around a node that are joined across edges share one point). Where that is still
//   not enough (faces of a cut joined around both its ends), the faces of the cut edge that are
//   not joined across it get points of their own at its ends. Nodes are otherwise not split, also
//   not where two fans of faces touch at a single node (that does not affect orientation, and the
//   boundary loops pass such a node once per fan). The result is that every edge of a sheet's
//   points has one face (boundary) or two faces running along it in opposite directions.
// - Points. The points of a sheet are the nodes its faces use, numbered by first use in face
//   order (corners in the face's oriented order).
// - Boundary loops. The sheet's boundary edges (one face) chained into closed loops that run the
//   way the faces run along them: with the face on the left seen from the normal, so an outer
//   contour runs counter-clockwise and a hole clockwise. At a point with more than two boundary
//   edges the loops are paired by walking around the point through the faces (as the deck report
//   does, model::boundaryChains). A loop starts at its lowest sheet edge.
// - Normals and dihedral angles. A triangle's normal is (p1 - p0) x (p2 - p0); a quad's is the
//   cross product of its diagonals, (p2 - p0) x (p3 - p1), the area-weighted average of its four
//   corner triangles' normals (less sensitive to warping than a single corner triangle). The
//   dihedral angle of an inner edge is the angle between the oriented normals of its two faces:
//   0 where the sheet is flat, 90 at a right-angled bend. Faces with a zero normal make no feature.
// - Feature lines. Inner edges whose dihedral angle exceeds featureAngleDeg, chained into
//   polylines that stop at points where feature edges end or branch (one or three and more
//   feature edges) and at boundary points. A ring of feature edges with a single stop on it starts
//   and ends at that point (an open polyline repeating it); a ring without any stop is closed.
//   Open polylines come first, walked from their stops in ascending point order, then closed
//   ones, each starting at the lower point of its lowest sheet edge (so are junction curves).
// - Feature points. Ascending, without repeats: the ends of open feature polylines (ends and
//   branch points of feature lines, and where they meet the boundary), and the points where a
//   boundary loop or a feature polyline turns by more than cornerAngleDeg (the angle between the
//   incoming and the outgoing segment; a point next to a zero-length segment is no corner); and
//   apexes: inner points off feature lines where the sheet comes to a point (a cone's tip, a
//   nose), whose faces' corner angles add up to less than 360 degrees by more than those of a
//   cone whose normals turn by featureAngleDeg across its tip, 360 x (1 - cos(featureAngleDeg /
//   2)) (27.4 degrees at 45).
// - Junction curves. Sheet edges whose part edge is non-manifold (where this sheet met other
//   sheets of the part, or itself) or a cut, and sheet edges whose two nodes are both used by
//   shells of one same other part (a seam where parts share nodes). Chained into polylines that
//   stop where junction edges end or branch; without any stop, closed. A single node shared with
//   another part (a spot connection) is no curve and is not reported. The seam rule looks at nodes
//   only: an edge joining two seam nodes across a corner of the seam (a triangle cutting the
//   corner) counts too.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "voxremesh/fe_model.h"

namespace voxremesh {

/// Index of a point in Sheet::points.
using PointIndex = std::uint32_t;

/// Marks the unused fourth corner of a triangle in Sheet::faces.
constexpr PointIndex kNoPoint = std::numeric_limits<PointIndex>::max();

/// A polyline through sheet points; closed polylines do not repeat their first point.
struct Polyline {
  std::vector<PointIndex> points;
  bool closed = false;
  /// Junction curves only: every point stays a node and none is added between them (the seam to
  /// a part that keeps its elements).
  bool keepPoints = false;
  /// Junction curves only: the distance between the nodes placed along it, when the sheets on
  /// either side ask for less than the extraction's spacing (seamNodeSpacing); 0: the extraction's.
  double nodeSpacing = 0.0;
  /// Junction curves only: the number of pieces its nodes cut it into, where it must match the
  /// side across a narrow sheet's four-sided patch (seamSampling); 0: from the spacing.
  long nodeCount = 0;
  /// Junction curves only: points of the curve (indices into `points`) toward which its pieces
  /// shrink (sharp corners of a sheet, where a row narrows into a wedge; seamSampling), each
  /// with the largest ratio between the distances of two consecutive nodes from it; empty: even
  /// pieces.
  std::vector<std::pair<std::size_t, double>> grading{};
  /// Junction curves only: points on the curve, in its order, where nodes must stand because the
  /// curves across a narrow sheet's four-sided patch end there (seamSampling); the curve is then
  /// cut into stationPieces[k] pieces between station k - 1 (or its start) and station k (or its
  /// end), stations.size() + 1 entries. Empty: none.
  std::vector<std::array<double, 3>> stations{};
  std::vector<long> stationPieces{};
};

/// One manifold, consistently oriented sheet (with boundary) of a part.
struct Sheet {
  Id part = 0;
  std::vector<std::array<double, 3>> points;  ///< positions
  std::vector<Id> pointNodeIds;               ///< the model node ID of each point
  /// Corners in a consistent orientation; a triangle has faces[f][3] == kNoPoint.
  std::vector<std::array<PointIndex, 4>> faces;
  std::vector<Id> faceShellIds;         ///< the model shell ID of each face
  std::vector<bool> faceFlipped;        ///< the face's corner order is reversed from the model's
  std::vector<Polyline> boundaryLoops;  ///< closed, following the boundary
  std::vector<Polyline> featureLines;   ///< chains of edges whose dihedral angle exceeds the limit
  std::vector<PointIndex> featurePoints;  ///< corners of feature lines and of boundary loops
  /// Curves along which this sheet met another sheet or part (non-manifold edges of the part, or
  /// nodes shared with another part), to be meshed conformingly on both sides.
  std::vector<Polyline> junctionCurves;
};

/// Thresholds for feature detection.
struct SheetSettings {
  /// An edge is a feature when its dihedral angle exceeds this. 45 degrees: a sharp edge stays
  /// sharp, while a bend meshed with two or more rows (each edge near 30 to 45 degrees) is left to
  /// the projection on the original surface; feature lines there break into short pieces whose
  /// ends are fixed points (on the bracket at 4.5 mm: 4.4 % of the elements failing with 30,
  /// 2.1 % with 45; the wheel 9.0 % and 8.0 %).
  double featureAngleDeg = 45.0;
  double cornerAngleDeg = 30.0;  ///< a boundary or feature-line point is a corner when the curve
                                 ///< turns by more than this there
  /// The cuts (node ID pairs, findSheetCuts) of the whole deck the model given to buildSheets
  /// was taken from, so that a part's sheets and their seams do not depend on how much of the
  /// deck around it that model holds; null: found on the model given.
  std::shared_ptr<const std::vector<std::array<Id, 2>>> sheetCuts;
};

/// The edges where the sheets of `model`'s parts are cut: at folds and along seams inside a sheet
/// (see "Cuts" at the top of the file): node ID pairs,
/// lower first, ascending; parts in parallel, deterministic. A part that cannot be oriented has
/// none.
/// @param model  the model; preconditions as for buildSheets
/// Throws std::invalid_argument as buildSheets does for a model that breaks its preconditions.
std::vector<std::array<Id, 2>> findSheetCuts(const FeModel& model);

/// Splits the shells of one part into sheets and finds their curves (see the definitions at the
/// top of the file).
/// @param model     the model; node IDs unique, every shell naming existing nodes (as readDeck
///                  ensures)
/// @param part      the part ID; a part without shells gives no sheets
/// @param settings  feature and corner thresholds
/// @return the part's sheets, ordered by their first face; deterministic
/// Throws SettingError when an angle of `settings` is not within 0..180 degrees; InputError (file
/// empty, line 0) naming the part, a shell and an edge when a sheet is not orientable;
/// std::invalid_argument when a precondition on the model does not hold (naming the shell and
/// node).
std::vector<Sheet> buildSheets(const FeModel& model, Id part, const SheetSettings& settings = {});

/// Builds the sheets of every part with shells: the model's parts in their order, then parts that
/// shells name but the model does not define, by ascending ID; within a part as buildSheets.
/// Parts are processed in parallel; the result does not depend on the number of threads.
/// @param model     the model; preconditions as for buildSheets
/// @param settings  feature and corner thresholds
/// Throws as buildSheets; when several parts fail, the error of the first failing part in the
/// output order is thrown.
std::vector<Sheet> buildAllSheets(const FeModel& model, const SheetSettings& settings = {});

}  // namespace voxremesh
