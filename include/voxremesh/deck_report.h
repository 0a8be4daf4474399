// The mesh report an engineer checks before remeshing: per part and for the whole model, the
// counts, sizes and topology findings of the shell mesh.
//
// Definitions (every count below is of one row: the shells of one part, or all shells for the
// total):
// - nodes: distinct nodes the row's shells use.
// - quads, trias: shells with 4 and 3 nodes.
// - bounding box: of the row's nodes.
// - edge length min / median / max: over the element sides, i.e. the 3 or 4 sides of every shell
//   (a side shared by two shells counts once per shell), as element-size checks count them; this
//   gives the median 4.46 mm that ../shared/data/README.md states for bracket.k. The median of an
//   even number of sides is the mean of the two middle ones.
// - edges: unique undirected edges (node pairs) of the row's shells.
// - boundary edges: edges used by exactly one shell of the row. An edge where two parts meet is a
//   boundary edge of each part, but not of the total.
// - non-manifold edges: edges used by three or more shells of the row (T-junctions).
// - inconsistent edges: edges on which two shells of the row run in the same direction, i.e. the
//   shells' normals disagree across the edge. Every non-manifold edge is among them (three shells
//   cannot alternate between two directions), so inconsistent - non-manifold is the number of
//   two-shell edges with flipped normals (wheel.k: 980 = 168 non-manifold + 812 flipped).
// - boundary loops: closed chains of boundary edges (an outer contour, a hole); open boundary
//   chains: chains that end, which happens only where boundary edges meet non-manifold edges (or
//   a shell names a node twice). At a node with more than two boundary edges (shells touching at
//   one node) each fan of shells around the node keeps its own contour; boundaryChains in
//   src/model/shell_edges.h states the exact pairing.
// - duplicate nodes: nodes within the tolerance of a node with a different ID (coincident but not
//   merged), counted as a merge would remove them: a group of k mutually coincident nodes
//   (transitively) counts k - 1. Found on a uniform grid of cells (sort-based spatial hashing),
//   not by comparing all pairs.
// - free elements: shells that share no node with any other shell of the row.
// - degenerate elements: shells whose area is at most tolerance x their longest side (their height
//   is below the tolerance), which includes all zero-area shells. The area of a triangle is half
//   the norm of the cross product of two sides; of a quad half the norm of the cross product of
//   its diagonals (the area the solver integrates; zero for a symmetric bow-tie quad).
// - unused nodes (model only): nodes of the model no shell uses. They may belong to other elements
//   (SPH particles, beams, solids, masses) or keywords (constraints, sets) and are kept.
// Totals count edges model-wide: an edge shared by two parts is one edge.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "voxremesh/fe_model.h"

namespace voxremesh {

/// Settings of reportDeck.
struct ReportSettings {
  /// Distance within which two nodes count as coincident (model units); also the height under
  /// which an element is degenerate. Unset: 1e-6 x the diagonal of the bounding box of all nodes
  /// used by shells. Zero: only exactly equal coordinates coincide.
  std::optional<double> tolerance;
  /// How many examples (IDs) each finding lists.
  std::size_t maxExamples = 10;
};

/// An axis-aligned box; empty when it encloses no node (min > max).
struct BoundingBox {
  std::array<double, 3> min{0.0, 0.0, 0.0};
  std::array<double, 3> max{-1.0, -1.0, -1.0};
  /// The box holds no point.
  bool empty() const { return min[0] > max[0]; }
  /// Length of the diagonal; 0 for an empty box.
  double diagonal() const;
};

/// Minimum, median and maximum of a set of lengths; count 0 when there are none (then all 0).
struct LengthStats {
  std::size_t count = 0;
  double min = 0.0;
  double median = 0.0;
  double max = 0.0;
};

/// Counts, sizes and topology of one set of shells (see the definitions at the top of the file).
struct MeshStats {
  std::size_t nodes = 0;
  std::size_t quads = 0;
  std::size_t trias = 0;
  BoundingBox box;
  LengthStats edgeLength;
  std::size_t edges = 0;
  std::size_t boundaryEdges = 0;
  std::size_t boundaryLoops = 0;
  std::size_t openBoundaryChains = 0;
  std::size_t nonManifoldEdges = 0;
  std::size_t inconsistentEdges = 0;
  std::size_t duplicateNodes = 0;
  std::size_t freeElements = 0;
  std::size_t degenerateElements = 0;

  /// quads + trias.
  std::size_t shells() const { return quads + trias; }
};

/// One part's row.
struct PartReport {
  Id id = 0;
  std::string name;
  bool defined = true;  ///< the model defines the part (false: only its shells name it)
  MeshStats stats;
};

/// An edge given as an example of a finding: its node IDs (ascending) and the IDs of its shells.
struct EdgeExample {
  std::array<Id, 2> nodes{};
  std::vector<Id> shells;
};

/// Two coincident nodes given as an example: their IDs and distance.
struct NodePairExample {
  std::array<Id, 2> nodes{};
  double distance = 0.0;
};

/// Examples of the model-wide findings, at most ReportSettings::maxExamples each, in model order.
struct ReportExamples {
  std::vector<EdgeExample> nonManifoldEdges;
  std::vector<EdgeExample> inconsistentEdges;  ///< two-shell edges only (non-manifold ones above)
  std::vector<NodePairExample> duplicateNodes;
  std::vector<Id> unusedNodes;
  std::vector<Id> freeElements;
  std::vector<Id> degenerateElements;
};

/// The report of a whole deck.
struct DeckReport {
  /// One row per part: the model's parts in their order, then parts that shells name but the model
  /// does not define, by ascending ID.
  std::vector<PartReport> parts;
  MeshStats total;             ///< all shells; edges counted model-wide
  std::size_t modelNodes = 0;  ///< all nodes of the model
  std::size_t unusedNodes = 0;
  double tolerance = 0.0;  ///< the coincidence tolerance used
  ReportExamples examples;
};

/// Computes the report of `model`'s shells: per part and in total.
/// Preconditions: node IDs are unique and every shell names existing nodes (as readDeck ensures).
/// Throws SettingError for a negative or non-finite tolerance, or one so large that the nodes
/// within it are too many to compare (over 10^8 comparisons); std::invalid_argument when a
/// precondition does not hold (naming the shell and node).
DeckReport reportDeck(const FeModel& model, const ReportSettings& settings = {});

/// Renders the report as text tables (sizes, bounding boxes, topology; one row per part plus a
/// total row) followed by the findings with examples.
std::string formatReportTable(const DeckReport& report);

/// Renders the report as JSON: an object with keys in a fixed order, numbers with full precision
/// (shortest round-trip form), strings escaped (invalid UTF-8 bytes as Latin-1).
std::string formatReportJson(const DeckReport& report);

}  // namespace voxremesh
