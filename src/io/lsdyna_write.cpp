// Writing an FeModel as an LS-DYNA keyword deck: the verbatim blocks of an LS-DYNA source in
// their order with *NODE and *ELEMENT_SHELL regenerated at their places, or a fresh deck for a
// model from another format. Fixed columns as LS-PrePost writes them; a keyword whose IDs do not
// fit its standard columns is written in the I10 ('%') or long ('+') format.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "io/formats.h"
#include "io/lsdyna_cards.h"
#include "io/text_scan.h"

namespace voxremesh::io {

namespace {

/// Appends a real in a field of `width` columns, keeping its first column blank so that fields
/// stay apart for readers (and engineers) that split at blanks.
void appendRealField(std::string& out, double value, int width) {
  out += ' ';
  appendRealFixedWidth(out, value, width - 1);
}

using lsdyna::Card;
using lsdyna::CardFormat;
using lsdyna::Layout;
using lsdyna::ShellOptions;

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

/// The narrowest format whose integer fields (standard width `standardWidth`) hold `widest`.
CardFormat neededFormat(int widest, int standardWidth) {
  if (widest <= standardWidth) return CardFormat::Standard;
  if (widest <= 10) return CardFormat::I10;
  return CardFormat::Long;
}

/// The keyword line a verbatim block starts with, after any comment and blank lines ("" for text
/// without a keyword).
std::string_view keywordLineOf(const DeckBlock& block) {
  const std::string_view text = block.text;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(begin, end - begin);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (lsdyna::isKeywordLine(line)) return line;
    if (!lsdyna::isCommentLine(line) && !trim(line).empty()) break;
    begin = end + 1;
  }
  return {};
}

/// The options an element needs for its extras.
ShellOptions optionsFor(const ShellExtras* extras) {
  ShellOptions options;
  if (!extras) return options;
  options.mcid = extras->angleIsMcid;
  options.beta = !extras->angleIsMcid && extras->angle != 0;
  options.thickness = !options.mcid && !options.beta &&
                      (extras->thickness[0] != 0 || extras->thickness[1] != 0 ||
                       extras->thickness[2] != 0 || extras->thickness[3] != 0);
  options.offset = extras->offset != 0;
  return options;
}

/// True when a keyword with `options` can carry `extras`.
bool canCarry(const ShellOptions& options, const ShellExtras* extras) {
  if (!extras) return true;
  const ShellOptions needed = optionsFor(extras);
  if (needed.hasThicknessCard() && !options.hasThicknessCard()) return false;
  if (extras->angle != 0 && extras->angleIsMcid != options.mcid) return false;
  return !needed.offset || options.offset;
}

class DeckWriter {
 public:
  DeckWriter(const FeModel& model, std::string& out, Warnings& warnings)
      : model_(model), out_(out), warnings_(warnings) {}

  void write() {
    std::size_t verbatimBytes = 0;
    for (const DeckBlock& block : model_.blocks) verbatimBytes += block.text.size();
    out_.reserve(out_.size() + verbatimBytes + model_.nodes.size() * 64 +
                 model_.shells.size() * 56 + model_.parts.size() * 256 + 1024);
    const bool fromBlocks = model_.sourceFormat == DeckFormat::LsDyna && !model_.blocks.empty();
    typeOptions_.resize(model_.shellTypes.size());
    for (std::size_t t = 0; t < model_.shellTypes.size(); ++t) {
      std::string ignored;
      if (fromBlocks) typeOptions_[t] = lsdyna::parseShellOptions(model_.shellTypes[t], ignored);
    }
    if (fromBlocks)
      writeFromBlocks();
    else
      writeFresh();
  }

 private:
  void writeFresh() {
    out_ += "$# LS-DYNA keyword deck written by voxremesh";
    out_ += eol_;
    out_ += "*KEYWORD";
    out_ += eol_;
    for (const Part& part : model_.parts) writePart(part.id, part.name);
    writeUndeclaredParts();
    writeNodes();
    writeShells();
    out_ += "*END";
    out_ += eol_;
  }

  void writeFromBlocks() {
    const std::vector<DeckBlock>& blocks = model_.blocks;
    std::size_t keywordAt = kNone;
    std::size_t endAt = kNone;
    bool hasNodes = false;
    bool hasShells = false;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      hasNodes = hasNodes || blocks[i].kind == DeckBlock::Kind::Nodes;
      hasShells = hasShells || blocks[i].kind == DeckBlock::Kind::Shells;
      if (blocks[i].kind != DeckBlock::Kind::Verbatim) continue;
      if (blocks[i].text.find("\r\n") != std::string::npos) eol_ = "\r\n";
      const std::string_view line = keywordLineOf(blocks[i]);
      const std::string keyword =
          line.empty() ? std::string() : lsdyna::parseKeywordLine(line).name;
      if (keyword == "*KEYWORD" && keywordAt == kNone) {
        keywordAt = i;
        if (auto format = lsdyna::keywordLineFormat(line)) deckFormat_ = *format;
      }
      if (keyword == "*END" && endAt == kNone) endAt = i;
    }
    const std::size_t geometryAt = keywordAt == kNone ? 0 : keywordAt + 1;
    for (std::size_t i = 0; i <= blocks.size(); ++i) {
      if (i == geometryAt) {
        if (!hasNodes) writeNodes();
        if (!hasShells) writeShells();
      }
      if (i == endAt || (i == blocks.size() && endAt == kNone)) {
        for (const Part& part : model_.parts)
          if (!part.definedInBlocks) writePart(part.id, part.name);
        writeUndeclaredParts();
      }
      if (i == blocks.size()) break;
      switch (blocks[i].kind) {
        case DeckBlock::Kind::Verbatim:
          if (!blocks[i].text.empty()) {
            endLine();
            out_ += blocks[i].text;
          }
          break;
        case DeckBlock::Kind::Nodes:
          writeNodes();
          break;
        case DeckBlock::Kind::Shells:
          writeShells();
          break;
      }
    }
  }

  /// Ends an unterminated last line before generated content follows it.
  void endLine() {
    if (!out_.empty() && out_.back() != '\n') out_ += eol_;
  }

  /// Writes a keyword line for content that needs `needed`; returns the format to write in.
  CardFormat keyword(std::string_view name, CardFormat needed) {
    endLine();
    out_ += name;
    if (needed > deckFormat_) {
      out_ += lsdyna::suffixText(needed);
      out_ += eol_;
      return needed;
    }
    out_ += eol_;
    return deckFormat_;
  }

  /// Writes a "$#" line naming the fields of a card over their columns, as LS-PrePost does.
  void columnTitles(const Layout& layout, std::size_t count, const char* const* names) {
    out_ += "$#";
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t width = layout.widths[i] - (i == 0 ? 2u : 0u);
      const std::size_t length = std::char_traits<char>::length(names[i]);
      if (length < width) out_.append(width - length, ' ');
      out_ += names[i];
    }
    out_ += eol_;
  }

  void writeNodes() {
    const bool anyExtras = !model_.nodeExtras.empty();
    int widest = 1;
    for (const Node& node : model_.nodes) widest = std::max(widest, lsdyna::decimalWidth(node.id));
    for (const auto& [id, extras] : model_.nodeExtras)
      widest = std::max(
          {widest, lsdyna::decimalWidth(extras.dynaTc), lsdyna::decimalWidth(extras.dynaRc)});
    const CardFormat format = keyword("*NODE", neededFormat(widest, 8));
    const Layout& layout = lsdyna::layout(Card::Node, format);
    static const char* const kNames[] = {"nid", "x", "y", "z", "tc", "rc"};
    columnTitles(layout, 6, kNames);
    const int w[6] = {layout.widths[0], layout.widths[1], layout.widths[2],
                      layout.widths[3], layout.widths[4], layout.widths[5]};
    for (const Node& node : model_.nodes) {
      appendIntRight(out_, node.id, w[0]);
      appendRealField(out_, node.xyz[0], w[1]);
      appendRealField(out_, node.xyz[1], w[2]);
      appendRealField(out_, node.xyz[2], w[3]);
      if (anyExtras) {
        const auto it = model_.nodeExtras.find(node.id);
        if (it != model_.nodeExtras.end() && (it->second.dynaTc != 0 || it->second.dynaRc != 0)) {
          appendIntRight(out_, it->second.dynaTc, w[4]);
          appendIntRight(out_, it->second.dynaRc, w[5]);
        }
      }
      out_ += eol_;
    }
  }

  const ShellExtras* extrasOf(const Shell& shell) const {
    if (shell.extras < 0 || static_cast<std::size_t>(shell.extras) >= model_.shellExtras.size())
      return nullptr;
    return &model_.shellExtras[static_cast<std::size_t>(shell.extras)];
  }

  /// How an element is written: with its type's options when they can carry its extras (key =
  /// the type, name as the source wrote it), else with the options its extras need (key 256 +
  /// the option bits, canonical name).
  struct ShellChoice {
    int key = 0;
    ShellOptions options;
  };

  ShellChoice choiceOf(const Shell& shell) const {
    const ShellExtras* extras = extrasOf(shell);
    if (shell.type < typeOptions_.size() && typeOptions_[shell.type] &&
        canCarry(*typeOptions_[shell.type], extras))
      return {shell.type, *typeOptions_[shell.type]};
    const ShellOptions options = optionsFor(extras);
    return {256 + (options.thickness ? 1 : 0) + (options.beta ? 2 : 0) + (options.mcid ? 4 : 0) +
                (options.offset ? 8 : 0),
            options};
  }

  void writeShells() {
    const std::vector<Shell>& shells = model_.shells;
    std::size_t begin = 0;
    while (begin < shells.size()) {
      const ShellChoice choice = choiceOf(shells[begin]);
      std::size_t end = begin + 1;
      while (end < shells.size() && choiceOf(shells[end]).key == choice.key) ++end;
      const std::string suffix = choice.key < 256
                                     ? model_.shellTypes[static_cast<std::size_t>(choice.key)]
                                     : lsdyna::shellSuffix(choice.options);
      writeShellRun(begin, end, suffix, choice.options);
      begin = end;
    }
  }

  void writeShellRun(std::size_t begin, std::size_t end, const std::string& suffix,
                     const ShellOptions& options) {
    int widest = 1;
    for (std::size_t i = begin; i < end; ++i) {
      const Shell& shell = model_.shells[i];
      widest = std::max({widest, lsdyna::decimalWidth(shell.id), lsdyna::decimalWidth(shell.part)});
      for (int k = 0; k < shell.nodeCount; ++k)
        widest = std::max(widest, lsdyna::decimalWidth(shell.nodes[static_cast<std::size_t>(k)]));
    }
    const CardFormat format = keyword("*ELEMENT_SHELL" + suffix, neededFormat(widest, 8));
    const Layout& card1 = lsdyna::layout(Card::Shell, format);
    const Layout& card2 = lsdyna::layout(Card::ShellThickness, format);
    const Layout& card3 = lsdyna::layout(Card::ShellOffset, format);
    static const char* const kNames[] = {"eid", "pid", "n1", "n2", "n3", "n4"};
    columnTitles(card1, 6, kNames);
    if (options.hasThicknessCard()) {
      const char* const names[] = {"thic1", "thic2", "thic3", "thic4",
                                   options.mcid ? "mcid" : "beta"};
      columnTitles(card2, 5, names);
    }
    if (options.offset) {
      static const char* const kOffset[] = {"offset"};
      columnTitles(card3, 1, kOffset);
    }
    const int w = card1.widths[0];
    const ShellExtras none;
    for (std::size_t i = begin; i < end; ++i) {
      const Shell& shell = model_.shells[i];
      appendIntRight(out_, shell.id, w);
      appendIntRight(out_, shell.part, w);
      appendIntRight(out_, shell.nodes[0], w);
      appendIntRight(out_, shell.nodes[1], w);
      appendIntRight(out_, shell.nodes[2], w);
      appendIntRight(out_, shell.nodes[shell.nodeCount == 3 ? 2 : 3], w);
      out_ += eol_;
      if (!options.hasThicknessCard() && !options.offset) continue;
      const ShellExtras* found = extrasOf(shell);
      const ShellExtras& extras = found ? *found : none;
      if (options.hasThicknessCard()) {
        for (std::size_t k = 0; k < 4; ++k)
          appendRealField(out_, extras.thickness[k], card2.widths[k]);
        if (options.mcid)
          appendIntRight(out_, static_cast<std::int64_t>(std::llround(extras.angle)),
                         card2.widths[4]);
        else
          appendRealField(out_, extras.angle, card2.widths[4]);
        out_ += eol_;
      }
      if (options.offset) {
        appendRealField(out_, extras.offset, card3.widths[0]);
        out_ += eol_;
      }
    }
  }

  /// Writes *PART blocks for part IDs that shells use but model.parts does not list.
  void writeUndeclaredParts() {
    std::unordered_set<Id> known;
    for (const Part& part : model_.parts) known.insert(part.id);
    Id last = 0;
    bool haveLast = false;
    std::size_t count = 0;
    for (const Shell& shell : model_.shells) {
      if (haveLast && shell.part == last) continue;
      last = shell.part;
      haveLast = true;
      if (!known.insert(shell.part).second) continue;
      writePart(shell.part, {});
      ++count;
    }
    if (count > 0)
      warnings_.push_back(std::to_string(count) +
                          " part ID(s) used by shells have no part in the model: *PART cards "
                          "without a title were written for them");
  }

  /// Writes a *PART block; SECID and MID are not known to the model and are flagged.
  void writePart(Id id, const std::string& name) {
    std::string title = name;
    for (char& c : title)
      if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    if (title.size() > 80) {
      warnings_.push_back("the name of part " + std::to_string(id) +
                          " is longer than the 80 columns of an LS-DYNA *PART title: cut to '" +
                          title.substr(0, 80) + "'");
      title.resize(80);
    }
    const CardFormat format = keyword("*PART", neededFormat(lsdyna::decimalWidth(id), 10));
    const Layout& layout = lsdyna::layout(Card::Part, format);
    out_ += "$#                                                                         title";
    out_ += eol_;
    out_ += title;
    out_ += eol_;
    static const char* const kNames[] = {"pid", "secid", "mid"};
    columnTitles(layout, 3, kNames);
    out_ += "$ voxremesh: SECID and MID of part ";
    out_ += std::to_string(id);
    out_ += " are not known to the model; set them before running LS-DYNA";
    out_ += eol_;
    appendIntRight(out_, id, layout.widths[0]);
    appendIntRight(out_, 0, layout.widths[1]);
    appendIntRight(out_, 0, layout.widths[2]);
    out_ += eol_;
  }

  const FeModel& model_;
  std::string& out_;
  Warnings& warnings_;
  std::vector<std::optional<ShellOptions>> typeOptions_;
  std::string_view eol_ = "\n";
  CardFormat deckFormat_ = CardFormat::Standard;
};

}  // namespace

void writeLsDyna(const FeModel& model, std::string& out, Warnings& warnings) {
  DeckWriter writer(model, out, warnings);
  writer.write();
}

}  // namespace voxremesh::io
