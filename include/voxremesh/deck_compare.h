// A physics check of a remesh: what a deck and its remeshed version carry, side by side, and what
// was lost on the way (DESIGN.md, "Connections survive").
//
// Compared, per part and for the deck:
// - shells and shell area per part; a part whose shells are gone, or whose area changed by more
//   than kAreaTolerance, is a loss (mass follows area: thickness and material cards are the same);
// - shared nodes per pair of parts (deckSeams) and T-junction edges; a pair that shared nodes and
//   shares none is a loss;
// - hard points (hardPointNodes of the first deck): a node missing, or moved by more than 1e-6 x
//   the diagonal of the first deck's nodes, is a loss;
// - node sets (member lists: LS-DYNA *SET_NODE, Nastran SET1/SPC1, Abaqus *NSET), matched by
//   keyword and order: members, repeated members and the area of the shells all of whose nodes
//   are members; a set emptied or with more repeated members than before is a loss;
// - per-node data (records: *INITIAL_VELOCITY_NODE), per keyword and part: the share of the
//   part's shell nodes that carry a record; a part fully covered before and not after, or covered
//   before and not at all after, is a loss;
// - the pressure load (Nastran PLOAD4) as the total force: the sum over loaded shells of the
//   corner-mean pressure x area x unit normal; a change of its vector by more than kLoadTolerance
//   of its length is a loss;
// - references of the second deck naming a node or shell it does not have (dangling): a loss.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "voxremesh/fe_model.h"

namespace voxremesh {

/// A part's area may change by this share of its area before it counts as lost.
inline constexpr double kAreaTolerance = 0.01;
/// The largest distance of a mesh's chord (an edge, a node-to-node piece of a curve) from the
/// surface or curve it stands for, as a share of the chord's length: an arc cut by chords of
/// sagitta s and length c is 8/3 (s/c)^2 longer than they are, so this share (the square root of
/// 3/16 kAreaTolerance) keeps a curved surface's area within half the area limit.
inline constexpr double kChordSagittaShare = 0.0433;
static_assert(kChordSagittaShare * kChordSagittaShare > 0.99 * 3.0 / 16.0 * kAreaTolerance &&
                  kChordSagittaShare * kChordSagittaShare < 1.01 * 3.0 / 16.0 * kAreaTolerance,
              "kChordSagittaShare follows kAreaTolerance");
/// The total pressure force may change by this share of its length before it counts as lost.
inline constexpr double kLoadTolerance = 0.01;

/// One part in both decks.
struct PartComparison {
  Id part = 0;
  std::size_t shellsBefore = 0, shellsAfter = 0;
  double areaBefore = 0.0, areaAfter = 0.0;
};

/// One pair of parts that share nodes in either deck.
struct SeamComparison {
  Id first = 0, second = 0;  ///< first < second
  std::size_t before = 0, after = 0;
};

/// One node set in both decks.
struct SetComparison {
  std::string keyword;   ///< as the deck names it
  std::size_t line = 0;  ///< line of its first member in its block of the first deck
  std::size_t membersBefore = 0, membersAfter = 0;    ///< distinct nodes
  std::size_t repeatedBefore = 0, repeatedAfter = 0;  ///< entries naming a node again
  double areaBefore = 0.0, areaAfter = 0.0;           ///< shells with every node a member
};

/// Per-node data of one keyword on one part's shell nodes.
struct CoverageComparison {
  std::string keyword;
  Id part = 0;
  std::size_t nodesBefore = 0, coveredBefore = 0;
  std::size_t nodesAfter = 0, coveredAfter = 0;
};

/// A reference of the second deck to a node or shell it does not have.
struct DanglingReference {
  std::string keyword;
  std::size_t line = 0;  ///< line within its block
  Id id = 0;
  bool element = false;  ///< a shell ID (else a node ID)
};

/// Everything compareDecks measured, and the losses in words.
struct DeckComparison {
  std::vector<PartComparison> parts;  ///< ascending part ID
  std::vector<SeamComparison> seams;  ///< ascending pair
  std::size_t tJunctionEdgesBefore = 0, tJunctionEdgesAfter = 0;
  std::size_t hangingNodesBefore = 0, hangingNodesAfter = 0;  ///< DeckSeams::hangingNodes
  std::size_t hardPoints = 0, hardPointsMissing = 0, hardPointsMoved = 0;
  double largestHardPointMove = 0.0;
  std::vector<SetComparison> sets;
  std::vector<CoverageComparison> coverage;
  std::size_t loadCardsBefore = 0, loadCardsAfter = 0;
  std::array<double, 3> forceBefore{}, forceAfter{};  ///< total pressure force
  std::vector<DanglingReference> dangling;
  std::vector<std::string> losses;  ///< one sentence per loss; empty when nothing was lost
};

/// Compares a deck with its remeshed version (see the top of the file).
/// @param before  the deck as it was (readDeck)
/// @param after   the remeshed deck (readDeck of remeshDeck's output), same format
/// @return the comparison; deterministic
/// Throws std::runtime_error when a deck has two nodes with one ID.
DeckComparison compareDecks(const FeModel& before, const FeModel& after);

/// The comparison as tables (parts, seams, sets, coverage, load) and the list of losses.
std::string formatComparisonTable(const DeckComparison& comparison);

/// The comparison as a JSON object.
std::string formatComparisonJson(const DeckComparison& comparison);

}  // namespace voxremesh
