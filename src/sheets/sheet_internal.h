// Internal steps of buildSheets (include/voxremesh/sheets.h), one file each:
//   sheet_model.cpp        what is computed once per model (corners, parts, nodes shared by parts)
//   sheet_orientation.cpp  components across manifold edges and their consistent orientation
//   sheet_folds.cpp        the edges where sheets are split at folds; all cuts of a model
//   sheet_extensions.cpp   cuts along seams inside a sheet, extended from their ends
//   sheet_splitting.cpp    the sheets' faces and points (joining or cutting at non-manifold edges)
//   sheet_boundary.cpp     boundary loops
//   sheet_features.cpp     feature lines and feature points
//   sheet_junctions.cpp    junction curves
//   sheet_polylines.cpp    chaining sheet edges into polylines (features, junctions)
//   build_sheets.cpp       the public functions
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "model/shell_edges.h"
#include "voxremesh/fe_model.h"
#include "voxremesh/sheets.h"

namespace voxremesh::sheets {

using model::Index;
using model::kNoIndex;
using model::ShellCorners;
using model::ShellEdges;

using Vec3 = std::array<double, 3>;

/// The normal of a face with `count` corners at p[0..count-1], not normalised: (p1 - p0) x
/// (p2 - p0) for a triangle, the cross product of the diagonals (p2 - p0) x (p3 - p1) for a quad.
inline Vec3 faceNormal(const std::array<Vec3, 4>& p, unsigned count) {
  const Vec3 u = count == 3 ? Vec3{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]}
                            : Vec3{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
  const Vec3 v = count == 3 ? Vec3{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]}
                            : Vec3{p[3][0] - p[1][0], p[3][1] - p[1][1], p[3][2] - p[1][2]};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

/// The angle between two vectors in degrees (0..180); 0 when either is zero or not finite.
inline double angleDeg(const Vec3& a, const Vec3& b) {
  const double cross =
      std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
  const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  if (!(cross > 0.0 || dot > 0.0 || dot < 0.0)) return 0.0;  // a zero vector, or NaN
  const double angle = std::atan2(cross, dot) * (180.0 / 3.14159265358979323846);
  return std::isfinite(angle) ? angle : 0.0;
}

/// What buildSheets needs of the whole model, computed once.
struct ModelContext {
  const FeModel& model;
  std::vector<ShellCorners> corners;   ///< per model shell: node indices as the model lists them
  std::vector<Id> partIds;             ///< parts with shells, in output order
  std::vector<std::string> partNames;  ///< per entry of partIds: the name ("" when undefined)
  std::vector<std::vector<Index>> partShells;  ///< per entry of partIds: model shell indices
  /// Nodes used by shells of several parts: the part entries (indices into partIds, ascending) of
  /// node v are sharedParts[sharedBegin[v] .. sharedBegin[v + 1]); empty for other nodes. Both
  /// vectors are empty when no node is shared.
  std::vector<Index> sharedBegin;
  std::vector<Index> sharedParts;
  std::vector<Index> shellEntry;  ///< per model shell: its part entry
  /// The shells using node v (model node index) are shellsAt[shellsBegin[v] .. shellsBegin[v+1]).
  std::vector<Index> shellsBegin;
  std::vector<Index> shellsAt;
  /// Inner edges where a part's faces are split at an acute fold (see "Folds" in sheets.h): model
  /// node index pairs, lower first, ascending.
  std::vector<std::array<Index, 2>> sheetCuts;

  /// The edge between nodes u and v (model node indices) is a cut (a fold's or a seam's).
  bool isCut(Index u, Index v) const;

  /// Nodes u and v (model node indices) lie on a seam with a part entry other than `part`: a shell
  /// of such a part has the edge u-v, or shells of such parts have edges from u towards v and from
  /// v towards u (within 15 degrees: the seam's two sides have different nodes along it). Two
  /// nodes another part uses on lines that cross u-v (a frame standing on two rings of a skin) are
  /// not a seam.
  bool sharedWithOtherPart(Index u, Index v, Index part) const;

  /// True when junction curves must end at node v (model node index), whichever part or sheet
  /// they are found from: the model's seam edges at v (edges of three or more shells, of shells
  /// of two or more parts, or cuts) are not exactly two, or the two are edges of different
  /// sets of parts or of different numbers of shells (a sheet of one of the parts ends at v, as
  /// where a T's stem ends on one side of it). Every part meeting at v then cuts its curves there,
  /// so that both sides of a seam sample the same pieces between the same ends.
  bool seamStop(Index v) const;
};

/// Builds the context of `model`, without cuts. Throws std::invalid_argument as
/// model::shellCorners does.
ModelContext makeModelContext(const FeModel& model);

/// Sets the context's cuts: settings.sheetCuts (those whose nodes the model has) when given, else
/// those found on the model itself (findSheetCuts).
void setSheetCuts(ModelContext& context, const SheetSettings& settings);

/// The cuts of every part of the context's model (see "Cuts" in sheets.h), found with the
/// context's own cuts ignored: model node index pairs, lower first, ascending.
std::vector<std::array<Index, 2>> findSheetCuts(const ModelContext& context);

/// The faces of one part: the shells with a surface, with part-local node numbers and adjacency.
struct PartMesh {
  Id part = 0;
  Index partEntry = 0;                ///< index into ModelContext::partIds
  std::string label;                  ///< "part 7" or "part 7 (name)", for messages
  std::vector<Index> shells;          ///< per position: the model shell index (ascending)
  std::vector<Index> nodes;           ///< per local node: the model node index
  std::vector<ShellCorners> corners;  ///< per position: distinct local node indices, model order
  ShellEdges edges;                   ///< adjacency of `corners`, all positions
};

/// Collects the faces of part entry `partEntry` (see the definitions in sheets.h: shells without
/// a surface are left out; repeated neighbouring corners are dropped).
/// @param localOf scratch: one entry per model node, all kNoIndex; left so on return
PartMesh makePartMesh(const ModelContext& context, Index partEntry, std::vector<Index>& localOf);

/// The consistent orientation of the components of a part.
struct Orientation {
  std::vector<Index> component;       ///< per position: its component, numbered by first position
  std::vector<std::uint8_t> flipped;  ///< per position: 1 where the face's corners are reversed
  Index componentCount = 0;
};

/// The cuts of one part (partFoldCuts and partInnerSeamCuts, see "Cuts" in sheets.h), found with
/// the context's own cuts ignored; none for a part that cannot be oriented (its buildSheets
/// reports that). Model node index pairs, lower first, ascending.
std::vector<std::array<Index, 2>> partCuts(const ModelContext& context, const PartMesh& part);

/// The fold cuts of one part (see "Folds" in sheets.h): model node index pairs, lower first,
/// ascending. Throws InputError as orientComponents does.
std::vector<std::array<Index, 2>> partFoldCuts(const ModelContext& context, const PartMesh& part);

/// The cuts along the seams inside the part (see "Seams inside a sheet" in sheets.h): its manifold
/// edges whose nodes another part shares, and from each end of such a seam inside the part the
/// edges turning less than 45 degrees from the seam's last edge to the first node on the
/// boundary, another curve or one of `cuts` (sorted model node index pairs; an end that reaches
/// none is not extended). Model node index pairs, lower first, ascending.
std::vector<std::array<Index, 2>> partInnerSeamCuts(const ModelContext& context,
                                                    const PartMesh& part,
                                                    const std::vector<std::array<Index, 2>>& cuts);

/// Splits the faces into components across manifold edges that are not cuts of the context
/// and orients each consistently, keeping the majority orientation. Throws InputError naming the
/// part, a shell and an edge when a component is not orientable.
Orientation orientComponents(const ModelContext& context, const PartMesh& part);

/// One sheet with the topology its curves are found from.
struct SheetDraft {
  Sheet sheet;
  std::vector<Index> positions;       ///< per face: its position in the part
  std::vector<ShellCorners> corners;  ///< per face: point indices in the sheet's orientation
  ShellEdges edges;                   ///< adjacency of `corners`
  std::vector<Index> partEdge;        ///< per sheet edge: the edge of the part it lies on
};

/// Builds the sheets of a part: faces, points, shell IDs and flips; non-manifold edges joined or
/// cut (see sheets.h). Curves are left empty.
std::vector<SheetDraft> splitSheets(const ModelContext& context, const PartMesh& part,
                                    const Orientation& orientation);

/// Fills draft.sheet.boundaryLoops.
void findBoundaryLoops(SheetDraft& draft);

/// Fills draft.sheet.featureLines and draft.sheet.featurePoints (boundary loops must be filled).
/// Preconditions: the angles of `settings` are valid (checked by the public functions).
void findFeatures(SheetDraft& draft, const SheetSettings& settings);

/// Fills draft.sheet.junctionCurves.
void findJunctions(SheetDraft& draft, const ModelContext& context, const PartMesh& part);

/// Chains the sheet edges `chosen` (ascending sheet edge indices of `edges`) into polylines that
/// stop at points where a chosen edge ends or branches and at points with stop[p] != 0 (stop may
/// be empty). Open polylines come first, walked from their stops in ascending point order (the
/// edges at a stop in ascending order); then closed ones, each starting at the lower point of its
/// lowest edge and walking along that edge.
std::vector<Polyline> chainEdges(const ShellEdges& edges, const std::vector<Index>& chosen,
                                 std::size_t pointCount, const std::vector<std::uint8_t>& stop);

/// The points of `polylines` where the polyline turns by more than `cornerAngleDeg` (every point
/// of a closed polyline, the inner points of an open one), appended to `result` (unsorted).
void appendCorners(const std::vector<Polyline>& polylines,
                   const std::vector<std::array<double, 3>>& points, double cornerAngleDeg,
                   std::vector<PointIndex>& result);

}  // namespace voxremesh::sheets
