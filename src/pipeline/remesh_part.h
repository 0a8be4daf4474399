// One part of remeshDeck: its sheets, the voxel size that resolves them, the attempts at finer
// voxels and the acceptance of each attempt's mesh (pipeline.h). Internal to src/pipeline.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "extract/junction_nodes.h"
#include "pipeline/seam_counts.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"

namespace voxremesh::pipeline {

/// A number with 4 significant digits, as the part reasons write them.
std::string formatNumber(double value);

/// Checks a part's new mesh against the part's original shells (DESIGN.md, "Acceptance of a
/// remeshed part"): assessQuality with its elements judged at `size` and the distance limit at
/// `askedSize` (distance sampled inside faces, folds, degenerate corners, failing share), the
/// faces in `foldedAgainstOriginal` (one flag per face of `mesh`, or empty) counted as folded
/// too, and the components and boundary loops of both.
/// @param mesh       the part's new mesh, faces naming existing points
/// @param original   the part's original shells as a mesh
/// @param size       the element size the mesh is judged against: the voxel used (> 0)
/// @param askedSize  the part's target size, which the distance limit scales with (> 0)
/// @param settings   the limits; targetSize and distanceSize are replaced
/// @param channels   channelCurves of the part's original sheets: the minimum length of an
///                   element in a channel narrower than `size` is judged against its width
/// Throws SettingError for bad settings.
PartAcceptance acceptPartMesh(const QuadMesh& mesh, const QuadMesh& original,
                              const std::vector<std::uint8_t>& foldedAgainstOriginal, double size,
                              double askedSize, const QualitySettings& settings,
                              const std::vector<MeshCurve>& channels);

/// What a kept part writes back, judged as a new mesh of it would be: acceptPartMesh of its
/// original shells against themselves at its target size, its sheets' curves bounding the
/// channels (none when its sheets cannot be built). Throws SettingError for bad settings.
PartAcceptance keptPartQuality(const FeModel& model, const PartPlan& plan,
                               const RemeshSettings& settings);

/// Makes a part's unmerged coincident nodes one: in the shells of `part`, every node within
/// `tolerance` (in each coordinate) of a node with a smaller ID is replaced by that node, so that
/// a slit between doubled rows of nodes (a tube meshed round with its seam row doubled) is no
/// boundary. Only nodes that no other shell of `model` uses take part: seams with other parts
/// keep their nodes. Deterministic. Returns how many nodes the part no longer uses.
/// Preconditions: the shells name nodes of the model; tolerance > 0.
std::size_t mergeCoincidentNodes(FeModel& model, Id part, double tolerance);

/// Points of mesh `a` that lie inside an edge of mesh `b` (closer to it than `tolerance`, away
/// from its ends): nodes one side has and the other lacks where two parts' new meshes meet, along
/// a seam, where one stands on the other (a T-junction) or where they share an area (layers on
/// the same nodes). Preconditions: faces name existing points; tolerance > 0.
std::size_t hangingPoints(const QuadMesh& a, const QuadMesh& b, double tolerance);

/// The faces of a sheet as a mesh (oriented as the sheet), the surface its new mesh is projected
/// on and checked against.
QuadMesh sheetSurface(const Sheet& sheet);

/// Per face of `mesh` (extracted from a sheet, oriented like it), 1 when its normal points
/// against (more than 120 degrees from) the normal of the sheet's face closest to its centroid.
/// @param surface    sheetSurface of the sheet
/// @param reference  the closest-point structure built from `surface`
std::vector<std::uint8_t> foldedAgainstSheet(const QuadMesh& mesh, const QuadMesh& surface,
                                             const ReferenceSurface& reference);

/// The width of a sheet as a strip: 2 x area / boundary length (infinite without boundary).
double sheetWidth(const Sheet& sheet);

/// The width of a sheet as the rectangle of its area and boundary length: the shorter side (for
/// a long strip about sheetWidth; for a compact sheet, a square or a triangle, up to twice it),
/// the quarter of the boundary length where no rectangle has them (a round sheet).
double stripWidth(const Sheet& sheet);

/// Called with the stage a part enters ("volume", "extract", "optimize").
using StageCallback = std::function<void(const char* stage)>;

using Point3 = std::array<double, 3>;

/// The spacing extraction places a part's junction nodes at: the one the settings ask for
/// (ExtractSettings::junctionSpacing), else `junctionSpacing` (PartSurroundings::junctionSpacing).
double extractJunctionSpacing(const RemeshSettings& settings, double junctionSpacing);

/// The nodes of a sheet's junction curves as extraction places them (extract.cpp): at `spacing`
/// (> 0) or each curve's own spacing or count, chords within a fifth of the spacing.
extract::JunctionNodes sheetJunctionNodes(const Sheet& sheet, double spacing);

/// What a part's remesh must respect of the deck around it.
struct PartSurroundings {
  double junctionSpacing = 0.0;  ///< the node spacing on the part's junction curves (> 0)
  /// Parts (ascending IDs) that keep their elements: the seams along them keep their nodes.
  std::vector<Id> keptParts;
  /// Nodes of the part that other keywords use as points (hardPointNodes): the new mesh has a
  /// node at each, at its exact coordinates.
  std::unordered_set<Id> hardPoints;
  /// Per seam node, the spacing the sheets through it ask for (seamNodeSpacing); a junction curve
  /// whose nodes ask for less than junctionSpacing gets that (setSeamSpacing). Null: none.
  const std::unordered_map<Id, double>* seamSpacing = nullptr;
  /// The counts and grading of the deck's junction curves (seamSampling, setSeamSampling).
  /// Null: none.
  const SeamSampling* seamSampling = nullptr;
};

/// Marks the junction curves of `sheets` that run along a part of `keptParts` (ascending IDs): a
/// curve with an edge whose two nodes are both used by the shells of one kept part in `model`.
/// Every point of such a curve stays a node and none is added (Polyline::keepPoints), so that the
/// seam keeps the kept part's nodes.
void markKeptSeams(std::vector<Sheet>& sheets, const FeModel& model,
                   const std::vector<Id>& keptParts);

/// Puts the hard points (sheet points whose node ID is in `hardPoints`) where extraction keeps
/// them: one on a boundary loop, feature line or junction curve becomes a feature point (a fixed
/// corner) and cuts the junction curves through it (so both sides of a seam place a node there).
/// @return per sheet, the positions of its other hard points (inside it), for snapHardPoints
std::vector<std::vector<Point3>> placeHardPoints(std::vector<Sheet>& sheets,
                                                 const std::unordered_set<Id>& hardPoints);

/// For each of `points` in turn, moves the nearest point of `mesh` that is free (role Free, not
/// moved already) and at most `reach` away exactly onto it and fixes it there (role Corner), so
/// that the optimisation keeps it.
/// @return how many of `points` found a partner
std::size_t snapHardPoints(QuadMesh& mesh, const std::vector<Point3>& points, double reach);

/// Each of `points` that is not a point of `mesh` yet and lies inside one of its faces (within
/// `reach` of the face's plane, on the inner side of every edge) becomes a fixed point (role
/// Corner) of it: the face is replaced by the fan of triangles from its edges to the point, in its
/// orientation (the optimisation may merge them into quads again). A point on an edge instead
/// (within `reach` of it, away from its ends) splits the edge: each face along it becomes the
/// fan from its other edges.
/// @return how many of `points` were inserted
std::size_t insertHardPoints(QuadMesh& mesh, const std::vector<Point3>& points, double reach);

/// How many of `points` are not points of `mesh`: no point of it within `tolerance` in every
/// coordinate (0: bit-identical coordinates).
std::size_t missingPoints(const QuadMesh& mesh, const std::vector<Point3>& points,
                          double tolerance = 0.0);

/// Remeshes one part: its sheets; a voxel of the plan's target size, reduced where a sheet is
/// narrower than settings.narrowFeatureVoxels voxels; up to 1 + settings.retries attempts, each
/// at half the voxel of the one before (never below settings.finestVoxelShare x target size),
/// until a mesh passes acceptPartMesh. Never throws for the part's own failures: they end as
/// status Kept with the reason (std::bad_alloc and a refused memory budget end the attempts).
/// @param model            the part's shells and the shells sharing nodes with them; no two
///                         shells of the part on the same nodes (remeshDeck holds duplicates)
/// @param plan             the part
/// @param surroundings     junction spacing, kept neighbours and hard points
/// @param mesh             receives the accepted mesh (cleared when the part is kept)
RemeshedPart remeshPart(const FeModel& model, const PartPlan& plan, const RemeshSettings& settings,
                        const PartSurroundings& surroundings, QuadMesh& mesh,
                        const StageCallback& stage);

}  // namespace voxremesh::pipeline
