// Node and shell references in LS-DYNA keyword blocks (the keywords listed in deck_assembly.h).
#include <array>
#include <cstdint>

#include "assembly/reference_scanners.h"
#include "io/lsdyna_cards.h"
#include "io/text_scan.h"

namespace voxremesh::assembly {

namespace {

namespace lsdyna = io::lsdyna;
using lsdyna::CardFormat;

/// A keyword read field by field: cards to skip at the start of the block, then data cards with
/// the given standard-format widths whose fields in nodeMask hold node (or element) IDs (or, for
/// ranges, pairs of first and last IDs), and what those references mean (NodeRole).
struct KeywordSpec {
  std::string_view name;
  std::uint8_t leadingCards;
  std::uint8_t count;
  std::array<std::uint8_t, lsdyna::kMaxFields> widths;
  std::uint16_t nodeMask;
  bool ranges = false;
  NodeRole role = NodeRole::Point;
};

constexpr std::array<std::uint8_t, lsdyna::kMaxFields> k10x8{10, 10, 10, 10, 10, 10, 10, 10};
constexpr std::array<std::uint8_t, lsdyna::kMaxFields> k8x10{8, 8, 8, 8, 8, 8, 8, 8, 8, 8};

constexpr KeywordSpec kKeywords[] = {
    {"*SET_NODE", 1, 8, k10x8, 0xFF, false, NodeRole::Member},
    {"*SET_NODE_LIST", 1, 8, k10x8, 0xFF, false, NodeRole::Member},
    {"*SET_NODE_TITLE", 2, 8, k10x8, 0xFF, false, NodeRole::Member},
    {"*SET_NODE_LIST_TITLE", 2, 8, k10x8, 0xFF, false, NodeRole::Member},
    {"*SET_NODE_LIST_GENERATE", 1, 8, k10x8, 0xFF, true},
    {"*SET_NODE_LIST_GENERATE_TITLE", 2, 8, k10x8, 0xFF, true},
    {"*DATABASE_HISTORY_NODE", 0, 8, k10x8, 0xFF},
    {"*DATABASE_HISTORY_NODE_ID", 0, 1, k10x8, 0x1},
    {"*CONSTRAINED_SPOTWELD", 0, 8, k10x8, 0x3},
    {"*CONSTRAINED_NODAL_RIGID_BODY", 0, 7, k10x8, 0x8},
    {"*CONSTRAINED_EXTRA_NODES_NODE", 0, 2, k10x8, 0x2},
    {"*BOUNDARY_SPC_NODE", 0, 8, k10x8, 0x1},
    {"*BOUNDARY_PRESCRIBED_MOTION_NODE", 0, 8, k10x8, 0x1},
    {"*INITIAL_VELOCITY_NODE", 0, 7, k10x8, 0x1, false, NodeRole::Record},
    {"*LOAD_NODE_POINT", 0, 8, k10x8, 0xE1},
    {"*ELEMENT_MASS", 0, 4, {8, 8, 16, 8}, 0x2},
    {"*ELEMENT_BEAM", 0, 10, k8x10, 0x1C},
    {"*ELEMENT_DISCRETE", 0, 8, {8, 8, 8, 8, 8, 16, 8, 16}, 0xC},
    {"*ELEMENT_SPH", 0, 3, {8, 8, 16}, 0x1},
};

/// Keywords read field by field whose fields name shell elements: shell sets and history lists
/// (their members cover a region), pressures on shells and history shells with a heading (a
/// record repeated for the new shells).
constexpr KeywordSpec kElementKeywords[] = {
    {"*SET_SHELL", 1, 8, k10x8, 0xFF, false, NodeRole::Member},
    {"*SET_SHELL_LIST", 1, 8, k10x8, 0xFF, false, NodeRole::Member},
    {"*SET_SHELL_TITLE", 2, 8, k10x8, 0xFF, false, NodeRole::Member},
    {"*SET_SHELL_LIST_TITLE", 2, 8, k10x8, 0xFF, false, NodeRole::Member},
    {"*SET_SHELL_LIST_GENERATE", 1, 8, k10x8, 0xFF, true},
    {"*SET_SHELL_LIST_GENERATE_TITLE", 2, 8, k10x8, 0xFF, true},
    {"*LOAD_SHELL_ELEMENT", 0, 4, k10x8, 0x1, false, NodeRole::Record},
    {"*DATABASE_HISTORY_SHELL", 0, 8, k10x8, 0xFF, false, NodeRole::Member},
    {"*DATABASE_HISTORY_SHELL_ID", 0, 1, k10x8, 0x1, false, NodeRole::Record},
};

/// Keywords not read field by field whose data may still name nodes: element, constraint,
/// boundary, load, initial-condition, node-set, segment-set and history keywords and any keyword
/// with "_NODE" in its name, except those whose option says they name sets, parts or contacts
/// instead (a name ending in _SET or holding _SET_, rigid-part motions, *CONTACT_...,
/// *CONSTRAINED_RIGID_BODIES, *SET_SEGMENT_GENERAL and _ADD).
bool mayNameNodes(std::string_view name) {
  std::string_view base = name;
  for (std::string_view suffix : {std::string_view("_TITLE"), std::string_view("_ID")})
    if (base.size() > suffix.size() && base.substr(base.size() - suffix.size()) == suffix)
      base.remove_suffix(suffix.size());
  const auto endsWith = [&](std::string_view suffix) {
    return base.size() >= suffix.size() && base.substr(base.size() - suffix.size()) == suffix;
  };
  if (endsWith("_SET") || base.find("_SET_") != std::string_view::npos || endsWith("_RIGID") ||
      base.substr(0, 8) == "*CONTACT" || base.substr(0, 26) == "*CONSTRAINED_RIGID_BODIES" ||
      endsWith("_GENERAL") || endsWith("_ADD"))
    return false;
  static constexpr std::string_view kPrefixes[] = {
      "*ELEMENT_", "*CONSTRAINED_", "*BOUNDARY_",   "*LOAD_",
      "*INITIAL_", "*SET_NODE",     "*SET_SEGMENT", "*DATABASE_HISTORY_"};
  for (std::string_view prefix : kPrefixes)
    if (name.substr(0, prefix.size()) == prefix) return true;
  return name.find("_NODE") != std::string_view::npos;
}

template <std::size_t N>
const KeywordSpec* findSpec(const KeywordSpec (&table)[N], std::string_view name) {
  for (const KeywordSpec& spec : table)
    if (spec.name == name) return &spec;
  return nullptr;
}

/// The layout of a spec's data card in a card format (I10: fields under 10 become 10; long:
/// under 20 become 20).
lsdyna::Layout layoutOf(const KeywordSpec& spec, CardFormat format) {
  lsdyna::Layout layout;
  layout.count = spec.count;
  for (std::size_t i = 0; i < spec.count; ++i) {
    std::uint8_t width = spec.widths[i];
    if (format == CardFormat::I10 && width < 10) width = 10;
    if (format == CardFormat::Long && width < 20) width = 20;
    layout.widths[i] = width;
    layout.kinds[i] = lsdyna::FieldKind::Int;
    layout.names[i] = "";
  }
  return layout;
}

/// A field of a data line: where it is in the line, and the width to rewrite it in (0: token).
struct FieldSpan {
  std::string_view text;  ///< the field as split (a view into the line)
  std::size_t begin = 0, end = 0;
  std::size_t width = 0;
};

/// Splits a data line into the fields of `layout`: free format when it has a comma, else fixed
/// columns, and blank-separated tokens when a node field of the fixed reading does not parse (as
/// lsdyna::parseCard reads a line).
std::array<FieldSpan, lsdyna::kMaxFields> splitLine(std::string_view line,
                                                    const lsdyna::Layout& layout,
                                                    std::uint16_t nodeMask) {
  std::array<std::string_view, lsdyna::kMaxFields> views{};
  std::array<FieldSpan, lsdyna::kMaxFields> spans{};
  const auto fromViews = [&](bool fixed) {
    std::size_t column = 0;
    for (std::size_t i = 0; i < layout.count; ++i) {
      FieldSpan& span = spans[i];
      span.text = views[i];
      if (fixed) {
        span.begin = std::min(column, line.size());
        span.end = std::min(column + layout.widths[i], line.size());
        span.width = layout.widths[i];
        column += layout.widths[i];
      } else {
        span.begin = views[i].empty() ? 0 : static_cast<std::size_t>(views[i].data() - line.data());
        span.end = span.begin + views[i].size();
        span.width = 0;
      }
    }
  };
  if (line.find(',') != std::string_view::npos) {
    lsdyna::splitAtCommas(line, views.data(), layout.count);
    fromViews(false);
    return spans;
  }
  lsdyna::splitFixed(line, layout, views.data());
  bool parses = true;
  std::int64_t value = 0;
  for (std::size_t i = 0; i < layout.count; ++i)
    if ((nodeMask >> i & 1u) && !io::parseInt(views[i], value)) parses = false;
  if (parses) {
    fromViews(true);
    return spans;
  }
  views = {};
  lsdyna::splitAtBlanks(line, views.data(), layout.count);
  fromViews(false);
  return spans;
}

}  // namespace

lsdyna::CardFormat lsDynaDeckFormat(const FeModel& model) {
  for (const DeckBlock& block : model.blocks) {
    if (block.kind != DeckBlock::Kind::Verbatim) continue;
    io::LineCursor cursor(block.text);
    while (cursor.next()) {
      if (!lsdyna::isKeywordLine(cursor.line())) continue;
      if (lsdyna::parseKeywordLine(cursor.line()).name == "*KEYWORD")
        return lsdyna::keywordLineFormat(cursor.line()).value_or(CardFormat::Standard);
      break;
    }
  }
  return CardFormat::Standard;
}

namespace {

/// Reads the data cards of a keyword read field by field (its spec), after its keyword line at
/// `cursor`, adding a reference for each watched ID in its ID fields.
void scanSpecCards(io::LineCursor& cursor, const lsdyna::KeywordLine& keyword,
                   const KeywordSpec& spec, CardFormat deckFormat, const ReferenceSink& sink) {
  const lsdyna::Layout layout = layoutOf(spec, keyword.suffix.value_or(deckFormat));
  std::size_t card = 0;
  while (cursor.next()) {
    const std::string_view line = cursor.line();
    if (lsdyna::isCommentLine(line) || lsdyna::isKeywordLine(line)) continue;
    if (card++ < spec.leadingCards) continue;
    if (io::trim(line).empty()) continue;
    const auto spans = splitLine(line, layout, spec.nodeMask);
    std::array<std::int64_t, lsdyna::kMaxFields> values{};
    for (std::size_t i = 0; i < layout.count; ++i)
      if (!io::parseInt(spans[i].text, values[i])) values[i] = 0;
    if (spec.ranges) {
      for (std::size_t i = 0; i + 1 < layout.count; i += 2)
        if (values[i] != 0)
          sink.addRange(cursor.lineNumber(), values[i], values[i + 1], 1, keyword.name);
      continue;
    }
    for (std::size_t i = 0; i < layout.count; ++i) {
      if (!(spec.nodeMask >> i & 1u) || values[i] == 0 || !sink.watched.count(values[i])) continue;
      const FieldSpan& span = spans[i];
      sink.add(cursor.begin() + span.begin, span.end - span.begin, span.width, cursor.lineNumber(),
               values[i], ReferenceKind::Field, keyword.name);
      NodeReference& added = sink.references.back();
      added.role = spec.role;
      added.listLast = added.offset;
      added.perLine = layout.count;
    }
  }
}

}  // namespace

void scanLsDynaBlock(std::string_view text, CardFormat deckFormat, const ReferenceSink& sink) {
  io::LineCursor cursor(text);
  if (!cursor.next() || !lsdyna::isKeywordLine(cursor.line())) return;  // a preamble
  const lsdyna::KeywordLine keyword = lsdyna::parseKeywordLine(cursor.line());
  if (const KeywordSpec* spec = findSpec(kKeywords, keyword.name)) {
    scanSpecCards(cursor, keyword, *spec, deckFormat, sink);
    return;
  }
  // Keywords read for their shell IDs name no nodes.
  if (findSpec(kElementKeywords, keyword.name) || !mayNameNodes(keyword.name)) return;
  const bool element = keyword.name.compare(0, 9, "*ELEMENT_") == 0;
  // A segment set's first card (and its title card) holds its ID and attributes, no node.
  const std::string_view name = keyword.name;
  int headerCards = name.compare(0, 12, "*SET_SEGMENT") == 0
                        ? (name.size() > 6 && name.substr(name.size() - 6) == "_TITLE" ? 2 : 1)
                        : 0;
  while (cursor.next()) {
    const std::string_view line = cursor.line();
    if (lsdyna::isCommentLine(line) || lsdyna::isKeywordLine(line)) continue;
    if (headerCards > 0) {
      --headerCards;
      continue;
    }
    // The first field of an element card is the element's own ID.
    sink.scanSuspects(line, cursor.lineNumber(), element ? 1 : 0, keyword.name);
  }
}

void scanLsDynaElementBlock(std::string_view text, CardFormat deckFormat,
                            const ReferenceSink& sink) {
  io::LineCursor cursor(text);
  if (!cursor.next() || !lsdyna::isKeywordLine(cursor.line())) return;
  const lsdyna::KeywordLine keyword = lsdyna::parseKeywordLine(cursor.line());
  if (const KeywordSpec* spec = findSpec(kElementKeywords, keyword.name))
    scanSpecCards(cursor, keyword, *spec, deckFormat, sink);
}

Id lsDynaMaxElementId(std::string_view text) {
  io::LineCursor cursor(text);
  if (!cursor.next() || !lsdyna::isKeywordLine(cursor.line())) return 0;
  const lsdyna::KeywordLine keyword = lsdyna::parseKeywordLine(cursor.line());
  if (keyword.name.compare(0, 9, "*ELEMENT_") != 0) return 0;
  Id largest = 0;
  std::array<std::string_view, 1> first{};
  while (cursor.next()) {
    const std::string_view line = cursor.line();
    if (lsdyna::isCommentLine(line) || lsdyna::isKeywordLine(line)) continue;
    // Over-counting (a second card's first number) only raises the first new ID.
    if (line.find(',') != std::string_view::npos) {
      lsdyna::splitAtCommas(line, first.data(), 1);
    } else if (lsdyna::splitAtBlanks(line, first.data(), 1) == 0) {
      continue;
    }
    std::int64_t value = 0;
    if (io::parseInt(first[0], value)) largest = std::max(largest, value);
  }
  return largest;
}

}  // namespace voxremesh::assembly
