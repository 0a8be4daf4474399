// Node (grid) references in Nastran bulk data cards (the cards listed in deck_assembly.h).
#include <array>
#include <cstdint>
#include <string>

#include "assembly/reference_scanners.h"
#include "io/nastran_cards.h"
#include "io/text_scan.h"
#include "voxremesh/errors.h"

namespace voxremesh::assembly {

namespace {

namespace nastran = io::nastran;

/// A card read field by field: data fields (0 = the first after the name) holding grid IDs, and
/// optionally every integer field from `allFrom` on, or every `stride`-th (pairs of a grid and
/// its components).
struct CardSpec {
  std::string_view name;
  std::array<std::int8_t, 6> fields;  ///< -1 ends the list
  std::int8_t allFrom = -1;
  NodeRole role = NodeRole::Point;  ///< what its grid references mean
  std::int8_t stride = 1;
};

constexpr CardSpec kCards[] = {
    {"SPC", {1, 4, -1}},
    {"SPCD", {1, 4, -1}},
    {"SPC1", {-1}, 2, NodeRole::Member},
    {"SUPORT", {-1}, 0, NodeRole::Point, 2},   // grid, components, grid, components, ...
    {"SUPORT1", {-1}, 1, NodeRole::Point, 2},  // the same after its set ID
    {"SET1", {-1}, 1, NodeRole::Member},
    {"RBE2", {1, -1}, 3},
    {"CONM2", {1, -1}},
    {"CBUSH", {2, 3, 4, -1}},
    {"CBAR", {2, 3, 4, -1}},
    {"CBEAM", {2, 3, 4, -1}},
    {"CROD", {2, 3, -1}},
    {"CONROD", {1, 2, -1}},
    {"CELAS1", {2, 4, -1}},
    {"CELAS2", {2, 4, -1}},
    {"CDAMP1", {2, 4, -1}},
    {"CDAMP2", {2, 4, -1}},
    {"CWELD", {2, 4, 5, -1}},
    {"PLOTEL", {1, 2, -1}},
    {"FORCE", {1, -1}},
    {"MOMENT", {1, -1}},
    {"CORD1R", {1, 2, 3, 5, 6, 7}},
    {"CORD1C", {1, 2, 3, 5, 6, 7}},
    {"CORD1S", {1, 2, 3, 5, 6, 7}},
    {"CHEXA", {-1}, 2},
    {"CPENTA", {-1}, 2},
    {"CTETRA", {-1}, 2},
    {"RBE3", {2, -1}},
    {"PLOAD4", {6, 7, -1}},  // G1 and G3 of a solid face (its element: scanLoads)
};

/// Cards not read field by field whose data may still name grids (their first field, the card's
/// own ID, is not scanned).
bool mayNameGrids(const std::string& name) {
  static constexpr std::string_view kNames[] = {"MPC",    "ASET",   "ASET1",   "OMIT",    "OMIT1",
                                                "FORCE1", "FORCE2", "MOMENT1", "MOMENT2", "TEMP"};
  for (std::string_view known : kNames)
    if (name == known) return true;
  if (name.compare(0, 4, "CORD") == 0) return false;  // CORD2x: coordinates and system IDs
  return !name.empty() && (name[0] == 'C' || name[0] == 'R');
}

/// One card of the block: its line span and collected fields.
struct Card {
  std::string name;  ///< upper case
  std::size_t firstLine = 0;
  std::vector<std::pair<std::size_t, std::string_view>> lines;  ///< (line in block, text)
  std::vector<std::size_t> lineBegins;                          ///< offsets in the block
};

/// True when a field is an integer (a grid ID); reals and names are not.
bool integerField(std::string_view text, std::int64_t& value) {
  return !text.empty() && io::parseInt(text, value);
}

/// The fields of a card, its continuation lines included; false when they cannot be read.
bool readFields(const Card& card, nastran::CardFields& fields) {
  static const std::string kName = "deck";
  try {
    fields.start(&kName, card.lines[0].first, card.lines[0].second);
    for (std::size_t i = 1; i < card.lines.size(); ++i)
      fields.addContinuation(card.lines[i].first, card.lines[i].second);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

class CardScanner {
 public:
  explicit CardScanner(const ReferenceSink& sink) : sink_(sink) {}

  void scan(const Card& card) {
    const CardSpec* spec = nullptr;
    for (const CardSpec& candidate : kCards)
      if (card.name == candidate.name) spec = &candidate;
    if (!spec) {
      if (mayNameGrids(card.name))
        for (std::size_t i = 0; i < card.lines.size(); ++i)
          sink_.scanSuspects(withoutComment(card.lines[i].second), card.lines[i].first,
                             i == 0 ? 2 : 1, card.name);
      return;
    }
    nastran::CardFields fields;
    if (!readFields(card, fields)) {
      for (std::size_t i = 0; i < card.lines.size(); ++i)
        sink_.scanSuspects(withoutComment(card.lines[i].second), card.lines[i].first,
                           i == 0 ? 2 : 1, card.name);
      return;
    }
    if (spec->allFrom >= 0) {  // a list: "G1 THRU G2" instead of its grids
      const std::size_t from = static_cast<std::size_t>(spec->allFrom);
      if (from + 2 < fields.size() && io::iequals(fields[from + 1], "THRU")) {
        std::int64_t first = 0, last = 0;
        if (integerField(fields[from], first) && integerField(fields[from + 2], last))
          sink_.addRange(fields.lineOf(from), first, last, 1, card.name);
        return;
      }
    }
    std::vector<std::size_t> gridFields;
    if (card.name == "PLOAD4" && io::iequals(fields[6], "THRU")) return;  // elements, no grids
    for (const std::int8_t k : spec->fields) {
      if (k < 0) break;
      gridFields.push_back(static_cast<std::size_t>(k));
    }
    if (spec->allFrom >= 0)
      for (std::size_t k = static_cast<std::size_t>(spec->allFrom); k < fields.size();
           k += static_cast<std::size_t>(spec->stride))
        gridFields.push_back(k);
    if (card.name == "RBE3") addRbe3Grids(fields, gridFields);
    for (const std::size_t k : gridFields) {
      std::int64_t value = 0;
      if (!integerField(fields[k], value) || !sink_.watched.count(value)) continue;
      const std::size_t before = sink_.references.size();
      addField(card, fields, k, value);
      if (spec->role != NodeRole::Point && sink_.references.size() > before)
        describeList(card, sink_.references.back(), spec->role);
    }
  }

 private:
  static std::string_view withoutComment(std::string_view line) {
    const std::size_t dollar = line.find('$');
    return dollar == std::string_view::npos ? line : line.substr(0, dollar);
  }

  /// RBE3: after REFGRID (field 2) and REFC come groups "weight, components, grids..." and after
  /// "UM" pairs "grid, components".
  static void addRbe3Grids(const nastran::CardFields& fields, std::vector<std::size_t>& out) {
    std::size_t k = 4;
    bool um = false;
    bool afterWeight = false;
    while (k < fields.size()) {
      const std::string_view text = fields[k];
      std::int64_t value = 0;
      if (io::iequals(text, "UM")) {
        um = true;
        k += 1;
        continue;
      }
      if (um) {
        out.push_back(k);
        k += 2;
        continue;
      }
      if (text.find_first_of(".eEdD") != std::string_view::npos) {  // a weight, then components
        afterWeight = true;
        k += 2;
        continue;
      }
      if (afterWeight && integerField(text, value)) out.push_back(k);
      ++k;
    }
  }

 public:
  /// A PLOAD4 on a watched element: a Record of the whole card (a THRU range is left as it is).
  void scanLoads(const Card& card) {
    if (card.name != "PLOAD4") return;
    nastran::CardFields fields;
    if (!readFields(card, fields)) return;
    std::int64_t element = 0;
    if (io::iequals(fields[6], "THRU") || !integerField(fields[1], element) ||
        !sink_.watched.count(element))
      return;
    const std::size_t before = sink_.references.size();
    addField(card, fields, 1, element);
    if (sink_.references.size() == before) return;
    NodeReference& load = sink_.references.back();
    load.role = NodeRole::Record;
    load.group = card.lineBegins.front();
    load.recordFirst = card.lineBegins.front();
    load.recordLast = card.lineBegins.back();
    // The pressures scale with the share of a new shell the load covers; where one cannot be
    // rewritten in place, none is (the load then goes whole to the new shells mostly on it).
    for (std::size_t k = 2; k <= 5; ++k) {
      if (fields[k].empty()) continue;
      BlockField span;
      if (!blockField(card, fields, k, span)) {
        load.scaledFields.clear();
        break;
      }
      load.scaledFields.push_back(span);
    }
  }

 private:
  /// Marks a reference as a member of the card's list: new grids go on continuation lines after
  /// the card's last line, in its field width (8 to a small-field line, 4 to a large-field one,
  /// after a comma in free format).
  static void describeList(const Card& card, NodeReference& reference, NodeRole role) {
    reference.role = role;
    reference.group = card.lineBegins.front();
    reference.listLast = card.lineBegins.back();
    reference.perLine = reference.width == 16 ? 4 : 8;
    reference.linePrefix = reference.width == 0    ? ","
                           : reference.width == 16 ? "*       "
                                                   : "        ";
  }

  void addField(const Card& card, const nastran::CardFields& fields, std::size_t k, Id value) {
    BlockField span;
    if (!blockField(card, fields, k, span)) {
      sink_.add(0, 0, 0, fields.lineOf(k), value, ReferenceKind::Range, card.name,
                "the field is in a tab-separated line and cannot be rewritten in place");
      return;
    }
    sink_.add(span.offset, span.length, span.width, fields.lineOf(k), value, ReferenceKind::Field,
              card.name);
  }

  /// Where data field k of a card stands in the block: the whole fixed-width field (its width)
  /// or the free-format token (width 0); false when it cannot be rewritten in place (a
  /// tab-separated line).
  static bool blockField(const Card& card, const nastran::CardFields& fields, std::size_t k,
                         BlockField& span) {
    const std::size_t lineNumber = fields.lineOf(k);
    const std::string_view line = fields.lineTextOf(k);
    const std::string_view text = fields[k];
    std::size_t index = 0;
    while (index < card.lines.size() && card.lines[index].first != lineNumber) ++index;
    const bool inLine =
        text.data() >= line.data() && text.data() + text.size() <= line.data() + line.size();
    if (!inLine || index == card.lines.size()) return false;
    const std::size_t at = static_cast<std::size_t>(text.data() - line.data());
    const std::size_t base = card.lineBegins[index];
    if (line.find(',') != std::string_view::npos) {
      span = {base + at, text.size(), 0};
      return true;
    }
    const bool large = index == 0 ? nastran::cardName(line).large : line[0] == '*';
    const std::size_t width = large ? 16 : 8;
    const std::size_t begin = 8 + (at - 8) / width * width;
    span = {base + begin, std::min(begin + width, line.size()) - begin, width};
    return true;
  }

  const ReferenceSink& sink_;
};

/// Calls `visit(card)` for each card of a run of bulk data lines.
template <typename Visit>
void forEachCard(std::string_view text, Visit visit) {
  io::LineCursor cursor(text);
  Card card;
  const auto flush = [&]() {
    if (!card.lines.empty()) visit(card);
    card = Card{};
  };
  while (cursor.next()) {
    const std::string_view line = cursor.line();
    if (nastran::isCommentOrBlank(line)) continue;
    if (nastran::isContinuationLine(line)) {
      if (!card.lines.empty()) {
        card.lines.emplace_back(cursor.lineNumber(), line);
        card.lineBegins.push_back(cursor.begin());
      }
      continue;
    }
    flush();
    card.name = io::toUpper(nastran::cardName(line).name);
    card.lines.emplace_back(cursor.lineNumber(), line);
    card.lineBegins.push_back(cursor.begin());
  }
  flush();
}

}  // namespace

void scanNastranBlock(std::string_view text, const ReferenceSink& sink) {
  CardScanner scanner(sink);
  forEachCard(text, [&](const Card& card) { scanner.scan(card); });
}

void scanNastranLoads(std::string_view text, const ReferenceSink& sink) {
  CardScanner scanner(sink);
  forEachCard(text, [&](const Card& card) { scanner.scanLoads(card); });
}

void scanNastranPressures(std::string_view text, std::size_t block,
                          std::vector<ElementPressure>& out) {
  forEachCard(text, [&](const Card& card) {
    if (card.name != "PLOAD4") return;
    nastran::CardFields fields;
    ElementPressure load;
    load.block = block;
    load.line = card.lines[0].first;
    std::int64_t last = 0;
    if (!readFields(card, fields) || !integerField(fields[1], load.first) ||
        !io::parseReal(fields[2], load.pressure[0]))
      return;
    for (std::size_t k = 1; k < 4; ++k)
      if (!io::parseReal(fields[2 + k], load.pressure[k], load.pressure[0])) return;
    load.last = load.first;
    if (io::iequals(fields[6], "THRU") && integerField(fields[7], last)) load.last = last;
    out.push_back(load);
  });
}

Id nastranMaxElementId(std::string_view text) {
  Id largest = 0;
  forEachCard(text, [&](const Card& card) {
    const bool element =
        (!card.name.empty() && card.name[0] == 'C' && card.name.compare(0, 4, "CORD") != 0) ||
        card.name.compare(0, 2, "RB") == 0 || card.name == "PLOTEL";
    if (!element) return;
    io::nastran::LineFields split;
    std::string scratch;
    io::nastran::splitLine(card.lines[0].second, false, split, scratch);
    std::int64_t value = 0;
    if (integerField(split.data[0], value)) largest = std::max(largest, value);
  });
  return largest;
}

}  // namespace voxremesh::assembly
