// Writing an FeModel as Nastran bulk data.
//
// A model read from Nastran is written back block by block: verbatim text as it was, all GRIDs
// where the first GRID stood, all shells where the first shell stood, and a PSHELL for every part
// the deck had no property card for just before ENDDATA. A model from another format becomes a
// fresh bulk data deck: BEGIN BULK, one named PSHELL per part, GRIDs, shells, ENDDATA.
//
// GRIDs are written in large field (16 columns) so that coordinates keep their precision; shells
// in small field when their IDs and reals fit 8 columns exactly, else in large field.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "io/formats.h"
#include "io/nastran_cards.h"
#include "io/text_scan.h"

namespace voxremesh::io {

namespace {

/// One data field of a card to write.
struct Value {
  enum class Kind : std::uint8_t { Blank, Int, Real };
  Kind kind = Kind::Blank;
  std::int64_t integer = 0;
  double real = 0.0;

  static Value blank() { return {}; }
  static Value of(std::int64_t v) { return {Kind::Int, v, 0.0}; }
  static Value of(double v) { return {Kind::Real, 0, v}; }
};

constexpr std::int64_t kMaxSmallInt = 99999999;
constexpr std::int64_t kMinSmallInt = -9999999;
constexpr std::int64_t kMaxLargeInt = 9999999999999999;
constexpr std::int64_t kMinLargeInt = -999999999999999;

bool fitsSmall(std::int64_t v) {
  return v >= kMinSmallInt && v <= kMaxSmallInt;
}

void appendName(std::string& out, std::string_view name, bool large) {
  out.append(name);
  std::size_t length = name.size();
  if (large) {
    out.push_back('*');
    ++length;
  }
  if (length < 8) out.append(8 - length, ' ');
}

void appendValue(std::string& out, const Value& value, int width) {
  switch (value.kind) {
    case Value::Kind::Blank:
      out.append(static_cast<std::size_t>(width), ' ');
      break;
    case Value::Kind::Int:
      if (value.integer > kMaxLargeInt || value.integer < kMinLargeInt)
        throw std::range_error("the ID " + std::to_string(value.integer) +
                               " does not fit a Nastran field");
      appendIntRight(out, value.integer, width);
      break;
    case Value::Kind::Real:
      nastran::appendReal(out, value.real, width);
      break;
  }
}

/// Writes a card in small field when every value fits 8 columns exactly, else in large field;
/// continuation lines are implicit ('+' or '*' in field 1, field 10 blank). Trailing blank fields
/// are left out.
void writeCard(std::string& out, std::string_view name, const Value* values, std::size_t count,
               std::string_view eol, bool forceLarge = false) {
  while (count > 0 && values[count - 1].kind == Value::Kind::Blank) --count;
  bool large = forceLarge;
  for (std::size_t k = 0; k < count && !large; ++k) {
    const Value& v = values[k];
    if (v.kind == Value::Kind::Int) large = !fitsSmall(v.integer);
    if (v.kind == Value::Kind::Real) large = !nastran::fitsExactly(v.real, 8);
  }
  const std::size_t perLine = large ? 4 : 8;
  const int width = large ? 16 : 8;
  appendName(out, name, large);
  for (std::size_t k = 0; k < count; ++k) {
    if (k > 0 && k % perLine == 0) {
      out.append(eol);
      out.append(large ? "*       " : "+       ");
    }
    appendValue(out, values[k], width);
  }
  out.append(eol);
}

class Writer {
 public:
  Writer(const FeModel& model, std::string& out, Warnings& warnings)
      : model_(model), out_(out), warnings_(warnings) {
    rFamily_.reserve(model.shellTypes.size());
    for (const std::string& type : model.shellTypes)
      rFamily_.push_back(type == "CQUADR" || type == "CTRIAR");
  }

  void write() {
    std::size_t verbatimSize = 0;
    for (const DeckBlock& block : model_.blocks) verbatimSize += block.text.size();
    out_.reserve(out_.size() + verbatimSize + model_.nodes.size() * 100 +
                 model_.shells.size() * 64 + model_.parts.size() * 120 + 1024);
    if (model_.sourceFormat == DeckFormat::Nastran && !model_.blocks.empty()) {
      writeBackBlocks();
    } else {
      writeFreshDeck();
    }
    warnLargeIds();
  }

 private:
  // ---- the two layouts ------------------------------------------------------------------------

  void writeBackBlocks() {
    for (const DeckBlock& block : model_.blocks) {
      if (block.kind == DeckBlock::Kind::Verbatim && block.text.find("\r\n") != std::string::npos) {
        eol_ = "\r\n";
        break;
      }
    }
    bool nodesBlock = false;
    bool shellsBlock = false;
    for (const DeckBlock& block : model_.blocks) {
      nodesBlock = nodesBlock || block.kind == DeckBlock::Kind::Nodes;
      shellsBlock = shellsBlock || block.kind == DeckBlock::Kind::Shells;
    }
    bool missingWritten = false;
    const auto writeMissing = [&] {
      missingWritten = true;
      if (!nodesBlock) writeGrids();
      if (!shellsBlock) writeShells();
      writeGeneratedProperties();
    };
    for (const DeckBlock& block : model_.blocks) {
      switch (block.kind) {
        case DeckBlock::Kind::Verbatim:
          if (!missingWritten && isEndData(block.text)) writeMissing();
          endLine();
          out_.append(block.text);
          break;
        case DeckBlock::Kind::Nodes:
          endLine();
          writeGrids();
          break;
        case DeckBlock::Kind::Shells:
          endLine();
          writeShells();
          break;
      }
    }
    if (!missingWritten) writeMissing();
  }

  void writeFreshDeck() {
    line("$ Nastran bulk data written by voxremesh from a " +
         std::string(formatName(model_.sourceFormat)) + " model.");
    if (!model_.parts.empty()) {
      line("$ The PSHELL cards refer to material 1 (MID1, MID2), which this deck does not");
      line("$ define, and give a thickness from the elements (1.0 where they give none):");
      line("$ set material and thickness before running a solver.");
    }
    line("BEGIN BULK");
    std::vector<const Part*> parts;
    for (const Part& part : model_.parts) parts.push_back(&part);
    writeProperties(parts);
    writeGrids();
    writeShells();
    line("ENDDATA");
    if (!parts.empty())
      warnings_.push_back(std::to_string(parts.size()) +
                          " PSHELL card(s) written refer to material 1, which the deck does not "
                          "define: set material and thickness before running Nastran");
  }

  // ---- cards ----------------------------------------------------------------------------------

  void writeGrids() {
    const bool anyExtras = !model_.nodeExtras.empty();
    for (const Node& node : model_.nodes) {
      NodeExtras extras;
      if (anyExtras) {
        const auto it = model_.nodeExtras.find(node.id);
        if (it != model_.nodeExtras.end()) extras = it->second;
      }
      const Value values[8] = {
          Value::of(node.id),
          Value::blank(),
          Value::of(node.xyz[0]),
          Value::of(node.xyz[1]),
          Value::of(node.xyz[2]),
          extras.nastranCd ? Value::of(std::int64_t{extras.nastranCd}) : Value::blank(),
          extras.nastranPs ? Value::of(std::int64_t{extras.nastranPs}) : Value::blank(),
          extras.nastranSeid ? Value::of(std::int64_t{extras.nastranSeid}) : Value::blank()};
      writeCard(out_, "GRID", values, 8, eol_, true);
      noteId(node.id);
    }
  }

  void writeShells() {
    for (const Shell& shell : model_.shells) {
      const bool r = shell.type < rFamily_.size() && rFamily_[shell.type];
      const std::string_view name =
          shell.nodeCount == 3 ? (r ? "CTRIAR" : "CTRIA3") : (r ? "CQUADR" : "CQUAD4");
      const int n = shell.nodeCount == 3 ? 3 : 4;
      noteId(shell.id);
      noteId(shell.part);
      bool small = shell.extras < 0 && fitsSmall(shell.id) && fitsSmall(shell.part);
      for (int i = 0; i < n && small; ++i) small = fitsSmall(shell.nodes[i]);
      if (small) {  // the common case, written directly
        appendName(out_, name, false);
        appendIntRight(out_, shell.id, 8);
        appendIntRight(out_, shell.part, 8);
        for (int i = 0; i < n; ++i) appendIntRight(out_, shell.nodes[i], 8);
        out_.append(eol_);
        continue;
      }
      Value values[14];
      values[0] = Value::of(shell.id);
      values[1] = Value::of(shell.part);
      for (int i = 0; i < n; ++i) values[2 + i] = Value::of(shell.nodes[i]);
      std::size_t count = 2 + static_cast<std::size_t>(n);
      if (shell.extras >= 0) {
        const ShellExtras& extras = model_.shellExtras.at(static_cast<std::size_t>(shell.extras));
        if (extras.angleIsMcid) {
          values[2 + n] = Value::of(static_cast<std::int64_t>(extras.angle));
        } else if (extras.angle != 0.0) {
          values[2 + n] = Value::of(extras.angle);
        }
        if (extras.offset != 0.0) values[3 + n] = Value::of(extras.offset);
        count = 10 + static_cast<std::size_t>(n);  // fields 8, 9 (blank, TFLAG) stay blank
        for (int i = 0; i < n; ++i)
          if (extras.thickness[i] != 0.0) values[10 + i] = Value::of(extras.thickness[i]);
      }
      writeCard(out_, name, values, count, eol_);
    }
  }

  /// The PSHELLs of the parts that have no property card among the blocks.
  void writeGeneratedProperties() {
    std::vector<const Part*> parts;
    for (const Part& part : model_.parts)
      if (!part.definedInBlocks) parts.push_back(&part);
    if (parts.empty()) return;
    endLine();
    line("$ voxremesh: PSHELL cards for properties the elements use without a property card;");
    line("$ they refer to material 1: set material and thickness before running a solver.");
    writeProperties(parts);
    warnings_.push_back(std::to_string(parts.size()) +
                        " PSHELL card(s) generated for properties the deck did not define; they "
                        "refer to material 1: set material and thickness before running Nastran");
  }

  void writeProperties(const std::vector<const Part*>& parts) {
    const std::unordered_map<Id, double> thickness = meanThickness();
    for (const Part* part : parts) {
      if (!part->name
               .empty()) {  // HyperMesh's name comment; quotes and line breaks cannot be in it
        out_.append("$HMNAME PROP");
        appendIntRight(out_, part->id, 20);
        out_.push_back('"');
        for (const char c : part->name)
          out_.push_back(c == '\n' || c == '\r' || c == '"' ? ' ' : c);
        out_.push_back('"');
        out_.append(eol_);
      }
      const auto it = thickness.find(part->id);
      const Value values[4] = {Value::of(part->id), Value::of(std::int64_t{1}),
                               Value::of(it == thickness.end() ? 1.0 : it->second),
                               Value::of(std::int64_t{1})};
      writeCard(out_, "PSHELL", values, 4, eol_);
      noteId(part->id);
    }
  }

  /// The mean of the nonzero element thicknesses of each part that has any.
  std::unordered_map<Id, double> meanThickness() const {
    std::unordered_map<Id, std::pair<double, std::size_t>> sums;
    for (const Shell& shell : model_.shells) {
      if (shell.extras < 0) continue;
      const ShellExtras& extras = model_.shellExtras.at(static_cast<std::size_t>(shell.extras));
      for (int i = 0; i < shell.nodeCount; ++i) {
        if (extras.thickness[i] == 0.0) continue;
        auto& sum = sums[shell.part];
        sum.first += extras.thickness[i];
        ++sum.second;
      }
    }
    std::unordered_map<Id, double> means;
    for (const auto& [part, sum] : sums)
      means.emplace(part, sum.first / static_cast<double>(sum.second));
    return means;
  }

  // ---- helpers --------------------------------------------------------------------------------

  static bool isEndData(std::string_view text) {
    const std::size_t start = text.find_first_not_of(" \t");
    return start != std::string_view::npos && istartsWith(text.substr(start), "ENDDATA");
  }

  void line(std::string_view text) {
    out_.append(text);
    out_.append(eol_);
  }

  /// Ends an unterminated last line (a verbatim block may end without a line break).
  void endLine() {
    if (!out_.empty() && out_.back() != '\n') out_.append(eol_);
  }

  void noteId(Id id) { largeIds_ = largeIds_ || id > kMaxSmallInt; }

  void warnLargeIds() {
    if (largeIds_)
      warnings_.push_back(
          "IDs above 99,999,999 were written in large field; many Nastran solvers do not accept "
          "them");
  }

  const FeModel& model_;
  std::string& out_;
  Warnings& warnings_;
  std::vector<bool> rFamily_;
  std::string_view eol_ = "\n";
  bool largeIds_ = false;
};

}  // namespace

void writeNastran(const FeModel& model, std::string& out, Warnings& warnings) {
  Writer writer(model, out, warnings);
  writer.write();
}

}  // namespace voxremesh::io
