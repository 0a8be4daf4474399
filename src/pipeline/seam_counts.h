// Node counts of junction curves that face each other across a narrow sheet (interval
// assignment): where a narrow sheet's patch is four-sided (narrow_sheet.h, mapped_patch.h) and
// two opposite sides are each made of whole junction curves, both sides get the same number of
// pieces, so that the patch is a grid of rows and columns instead of a row with trapezoids and
// triangles where the counts differ; so do the two long sides of a three-sided patch (a strip
// running into a tip), and in an L-shaped patch the two sides along each direction together with
// the side across from them (with a station where the cut from its reflex corner meets that
// side, so that the L is two grids). Curves are tied through every patch that has them on opposite
// sides, over the whole deck (the parts on both sides of a seam see the same curve). Where both
// sides are as many curves whose joints face each other, each curve gets the count of the one
// across it; else the side with fewer pieces gets more on its curve with the longest pieces until
// the totals match, and a single curve facing several gets stations, nodes facing their joints,
// each stretch with the count of the curve across (where the side across runs on past the
// patch's corner, the curves beyond the single curve's end count with the stretch next to it,
// spread over more stretches while their lengths differ past the Jacobian ratio's square root). Then a curve between rungs of different
// lengths (a tapering strip) gets as many pieces as keep its rows' trapezoids within the
// Jacobian ratio, and a side of a four-sided patch whose pieces are longer than the aspect limit
// times the pieces across it (two or more across; for the sides across a strip, its longest
// rung counts: a rib web taller in its middle than at its ends) gets that many more, pass after
// pass with the pairs matched again, until no side asks for more; so do the long sides of a
// three-sided patch whose base has more pieces than its tip's angle can fan into triangles within
// their smallest angle: as many as its base, evenly (not shrinking toward the tip), so that its
// rows grow by one piece each from a triangle at the tip. And where a narrow sheet narrows
// into a sharp corner, the junction curves along the two sides of that wedge get pieces shrinking
// toward it (junction_nodes.h), on every part that has them. Internal to src/pipeline.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "voxremesh/pipeline.h"

namespace voxremesh::pipeline {

/// An edge between two nodes, by their IDs, lower first (both parts of a seam see it alike).
using NodeEdge = std::pair<Id, Id>;

/// Hash of a NodeEdge.
struct NodeEdgeHash {
  std::size_t operator()(const NodeEdge& edge) const noexcept {
    return std::hash<Id>()(edge.first) * 1000003u ^ std::hash<Id>()(edge.second);
  }
};

/// Per junction curve, keyed by its lowest edge (curveKey), the count of pieces it must have.
using SeamCounts = std::unordered_map<NodeEdge, long, NodeEdgeHash>;

/// The key of an open junction curve of a sheet: its lowest edge by node IDs.
/// Precondition: the curve has at least two points.
NodeEdge curveKey(const Sheet& sheet, const Polyline& curve);

/// Where a junction curve's nodes must stand (Polyline::stations): the points, in the curve's
/// order from its point with node ID `firstNode`, and the pieces of each stretch between them.
struct SeamStations {
  Id firstNode = 0;
  std::vector<std::array<double, 3>> points;
  std::vector<long> pieces;  ///< points.size() + 1 entries
};

/// How the deck's junction curves are sampled beyond their spacing.
struct SeamSampling {
  /// Per curve that must get more pieces than its spacing gives it, that count (see the top of
  /// the file); curves not listed keep their sampling.
  SeamCounts counts;
  /// Per sharp corner of a narrow sheet and side of its wedge, keyed by the corner's node ID and
  /// the ID of the next node along that side, the ratio of the pieces shrinking toward the corner
  /// on the junction curve running along that side (wedgeRatio; the smallest any sheet asks).
  /// Curves that only end there (along another sheet's side) keep even pieces.
  std::unordered_map<NodeEdge, double, NodeEdgeHash> grading;
  /// Per curve facing a side of several whole curves across a narrow sheet's four-sided patch,
  /// the points of it closest to their joints and the count of the curve across each stretch,
  /// so that its nodes line up with theirs instead of spreading evenly over it.
  std::map<NodeEdge, SeamStations> stations;
};

/// The growth ratio of the pieces of a junction curve toward a corner of `cornerDeg` degrees
/// narrower than a quad's smallest angle (where rows narrow into a wedge): the rungs across the
/// wedge then keep consecutive lengths within that ratio. It keeps each trapezoid of the row
/// halfway (geometrically) between a rectangle and the limits: its parallel sides' ratio (its
/// Jacobian ratio at the corners) at sqrt(minJacobianRatio), its length along at most
/// sqrt(maxAspectRatio) times its width. Returns 0 (no grading) for a corner at or above
/// minQuadAngleDeg. Precondition: valid criteria (checkQualitySettings).
double wedgeRatio(double cornerDeg, const QualitySettings& criteria);

/// The sampling of the deck's junction curves (SeamSampling, see the top of the file).
/// @param models          per plan, the part's shells and its neighbours' (as remeshDeck builds
///                        them)
/// @param junctionSpacing per plan, the spacing its junction curves get (PartSurroundings)
/// @param skip            per plan, 1 for parts not remeshed
/// @param seamSpacing     seamNodeSpacing of the same plans
/// @param hardPoints      per plan, the part's hard points (its curves are cut there, as
///                        placeHardPoints cuts them in the part's remesh)
/// @param keptParts       parts that keep their elements (ascending IDs): not sampled, and the
///                        curves along them keep their points (markKeptSeams), as in the
///                        remesh of their neighbours
/// A part whose sheets cannot be built adds nothing. Deterministic: the result does not depend
/// on the order or thread count.
SeamSampling seamSampling(const std::vector<FeModel>& models, const std::vector<PartPlan>& plans,
                          const std::vector<double>& junctionSpacing,
                          const std::vector<std::uint8_t>& skip,
                          const std::unordered_map<Id, double>& seamSpacing,
                          const std::vector<std::unordered_set<Id>>& hardPoints,
                          const std::vector<Id>& keptParts, const RemeshSettings& settings);

/// Sets Polyline::nodeCount of the open junction curves of `sheets` that `sampling` counts, their
/// Polyline::stations, and Polyline::grading at the curve points it grades.
void setSeamSampling(std::vector<Sheet>& sheets, const SeamSampling& sampling);

}  // namespace voxremesh::pipeline
