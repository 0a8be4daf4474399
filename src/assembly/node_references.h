// Finding the node references in the verbatim blocks of a deck, per format, so that deck assembly
// can rewrite those that name removed nodes (see include/voxremesh/deck_assembly.h for the
// keywords understood and the scan of the others). Internal to src/assembly.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

#include "voxremesh/fe_model.h"

namespace voxremesh::assembly {

/// How a reference can be treated.
enum class ReferenceKind {
  Field,    ///< one node ID in one field: can be rewritten in place
  Range,    ///< a range of IDs (generate, THRU) covering the node: cannot be rewritten
  Suspect,  ///< an equal integer in a keyword not understood field by field: reported only
};

/// What a reference means, which says what takes the place of a removed node.
enum class NodeRole {
  Point,   ///< a point (a weld, a load, a history node): the nearest new node takes it
  Member,  ///< a member of a node list (a set): the new nodes of the list's region join it
  Record,  ///< the key of a per-node data line (an initial velocity): the line is repeated for
           ///< the new nodes of the region, each taking the data of the nearest old member
};

/// Where a field stands in a block's text.
struct BlockField {
  std::size_t offset = 0;  ///< in the block's text
  std::size_t length = 0;
  std::size_t width = 0;  ///< fixed field width (0: a free-format token)
};

/// One reference to a node of the watched set in a verbatim block.
struct NodeReference {
  std::size_t block = 0;   ///< index into FeModel::blocks
  std::size_t offset = 0;  ///< where the replaced span starts in the block's text
  std::size_t length = 0;  ///< length of the replaced span
  std::size_t width = 0;   ///< fixed field width to right-align into (0: free format token)
  std::size_t line = 0;    ///< 1-based line within the block
  Id node = 0;
  ReferenceKind kind = ReferenceKind::Field;
  std::string keyword;  ///< as the deck names it ("*SET_NODE_LIST", "SPC1", "*NSET")
  std::string reason;   ///< for Range and Suspect (and Field spans that cannot be rewritten)
  NodeRole role = NodeRole::Point;
  // Member and Record references: the list or data lines they belong to.
  std::size_t group = 0;     ///< the offset of the card or keyword in the block
  std::size_t listLast = 0;  ///< Member: an offset within the list's last line
  std::size_t perLine = 0;   ///< Member: IDs per added line
  std::string linePrefix;    ///< Member: what an added line starts with (a continuation field)
  bool blankAllowed = true;  ///< Member: a field left over may be blank (else it repeats a member)
  /// Record: offsets within the first and last line of the record (a card with continuation
  /// lines); both 0: the reference's line.
  std::size_t recordFirst = 0, recordLast = 0;
  /// Record: fields of the record whose values scale with the share of a new element it covers
  /// (a pressure); empty when none does, or when one cannot be rewritten in place.
  std::vector<BlockField> scaledFields;
};

/// A replacement in a block's text: `length` characters at `offset` become `text`.
struct TextEdit {
  std::size_t offset = 0, length = 0;
  std::string text;
};

/// Finds the references to nodes of `watched` in the verbatim blocks of `model` (its
/// sourceFormat selects the syntax; surface formats have none). Deterministic, in block order and
/// text order.
std::vector<NodeReference> findNodeReferences(const FeModel& model,
                                              const std::unordered_set<Id>& watched);

/// Finds the references to the shell elements of `watched` in the verbatim blocks of `model`:
/// Nastran PLOAD4 cards (a Record each, spanning its continuation lines; a PLOAD4 THRU range is
/// left as it is); LS-DYNA shell sets (*SET_SHELL..., Members of their card's list, GENERATE
/// ranges as Range), *DATABASE_HISTORY_SHELL (Members), *LOAD_SHELL_ELEMENT and
/// *DATABASE_HISTORY_SHELL_ID (Records); Abaqus *ELSET lists (Members, GENERATE as
/// Range) and *DLOAD lines naming an element (Records). Deterministic, in block order and text
/// order.
std::vector<NodeReference> findElementReferences(const FeModel& model,
                                                 const std::unordered_set<Id>& watched);

/// A pressure on shell elements (a Nastran PLOAD4 card): the elements first..last (one element
/// without THRU) and the pressures at their corners (a blank P2..P4 is P1).
struct ElementPressure {
  std::int64_t first = 0, last = 0;
  std::array<double, 4> pressure{};
  std::size_t block = 0;  ///< index into FeModel::blocks
  std::size_t line = 0;   ///< 1-based line of the card within the block
};

/// The pressures the verbatim blocks of a Nastran model put on elements (PLOAD4 cards that can be
/// read field by field), in block and text order; none for other formats.
std::vector<ElementPressure> findElementPressures(const FeModel& model);

/// The largest element ID named by the verbatim element keywords of the model (first field of
/// the data lines of LS-DYNA *ELEMENT_..., Nastran element and rigid element cards, Abaqus
/// *ELEMENT data lines), or 0.
Id maxVerbatimElementId(const FeModel& model);

/// Text of `id` to put into the span of `reference`: right-aligned in the field width, or the
/// plain number for a free-format token. Returns false when it does not fit the width.
bool referenceText(const NodeReference& reference, Id id, std::string& text);

}  // namespace voxremesh::assembly
