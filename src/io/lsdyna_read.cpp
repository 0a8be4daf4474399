// Reading LS-DYNA keyword decks (.k .key .dyn) into an FeModel: *NODE, *ELEMENT_SHELL (with the
// options _THICKNESS, _BETA, _MCID, _OFFSET), *PART names, *INCLUDE files inlined; every other
// keyword block kept verbatim, byte for byte.
#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "io/formats.h"
#include "io/lsdyna_cards.h"
#include "io/model_checks.h"
#include "io/text_scan.h"
#include "voxremesh/errors.h"

namespace voxremesh::io {

namespace {

using lsdyna::Card;
using lsdyna::CardFormat;
using lsdyna::CardValues;
using lsdyna::KeywordLine;
using lsdyna::Layout;
namespace fs = std::filesystem;

/// One file of the deck being read.
struct SourceFile {
  std::string name;     ///< as messages show it
  fs::path folder;      ///< where its relative includes are resolved
  std::uint32_t index;  ///< SourceMap file index
  CardFormat format;    ///< the card format of its keywords without a suffix
  bool isMain;
  bool suffixWarned = false;
};

/// A data line of a block with its line number.
struct DataLine {
  std::string_view text;
  std::size_t line;
};

const char* formatName(CardFormat format) {
  switch (format) {
    case CardFormat::Long:
      return "long (20-column)";
    case CardFormat::I10:
      return "I10";
    case CardFormat::Standard:
      break;
  }
  return "standard";
}

bool isBlankLine(std::string_view line) {
  return trim(line).empty();
}

/// Moves the cursor to the end of the current block; returns the offset where the block ends (the
/// next keyword line, which the cursor returns again on its next call, or the end of the text).
std::size_t skipBlock(LineCursor& cursor, std::size_t textSize) {
  while (cursor.next()) {
    if (lsdyna::isKeywordLine(cursor.line())) {
      cursor.pushBack();
      return cursor.begin();
    }
  }
  return textSize;
}

/// The next line of the block that is not a comment, or false at the end of the block.
bool nextCardLine(LineCursor& cursor) {
  while (cursor.next()) {
    const std::string_view line = cursor.line();
    if (lsdyna::isKeywordLine(line)) {
      cursor.pushBack();
      return false;
    }
    if (!lsdyna::isCommentLine(line)) return true;
  }
  return false;
}

/// Reads a whole deck, following its includes.
class DeckReader {
 public:
  explicit DeckReader(Warnings& warnings) : warnings_(warnings) {}

  FeModel read(const fs::path& path) {
    model_.sourceFormat = DeckFormat::LsDyna;
    std::error_code ignored;
    includeStack_.push_back(fs::weakly_canonical(path, ignored));
    readFile(path, CardFormat::Standard, true);
    addUndefinedParts();
    checkModel(model_, sources_);
    return std::move(model_);
  }

 private:
  void readFile(const fs::path& path, CardFormat format, bool isMain) {
    const std::string content = loadFile(path);
    requireText(content, path);
    SourceFile file{path.string(), path.parent_path(), sources_.addFile(path.string()), format,
                    isMain};
    LineCursor cursor(content);
    bool preamble = true;
    while (cursor.next()) {
      if (!lsdyna::isKeywordLine(cursor.line())) continue;
      if (preamble && cursor.begin() > 0)
        addVerbatim(file, std::string_view(content).substr(0, cursor.begin()), 1);
      preamble = false;
      if (!readBlock(file, content, cursor)) return;
    }
    if (preamble) {
      addVerbatim(file, content, 1);
      warnings_.push_back(file.name + ": no keyword line (a line starting with '*') in the file");
    }
  }

  /// Reads the block starting at the cursor's keyword line. Returns false after *END.
  bool readBlock(SourceFile& file, std::string_view content, LineCursor& cursor) {
    const std::string_view keywordLine = cursor.line();
    const KeywordLine keyword = lsdyna::parseKeywordLine(keywordLine);
    const std::size_t begin = cursor.begin();
    const std::size_t keywordLineNumber = cursor.lineNumber();
    const std::string& name = keyword.name;
    const CardFormat format = keyword.suffix.value_or(file.format);

    if (name == "*NODE") {
      readNodes(file, cursor, keyword, format);
      return true;
    }
    if (name.compare(0, 14, "*ELEMENT_SHELL") == 0 && (name.size() == 14 || name[14] == '_')) {
      readShells(file, cursor, keyword, format, keywordLine, keywordLineNumber);
      return true;
    }
    if (name == "*END") {
      if (file.isMain) {
        addVerbatim(file, content.substr(begin), keywordLineNumber);
      } else {
        const std::string_view rest = content.substr(cursor.end());
        if (!isBlankLine(rest))
          warnings_.push_back(file.name + ":" + std::to_string(keywordLineNumber) +
                              ": the content after *END of this include file was left out "
                              "(LS-DYNA ignores it too)");
      }
      return false;
    }
    if (name == "*INCLUDE") {
      readInclude(file, cursor, keyword);
      return true;
    }
    if (name == "*INCLUDE_PATH" || name == "*INCLUDE_PATH_RELATIVE") {
      readIncludePath(file, cursor, keyword);
      return true;
    }
    if (name == "*KEYWORD") {
      if (auto selected = lsdyna::keywordLineFormat(keywordLine)) file.format = *selected;
      if (file.isMain) deckFormat_ = file.format;
      const std::size_t end = skipBlock(cursor, content.size());
      if (file.isMain) {
        addVerbatim(file, content.substr(begin, end - begin), keywordLineNumber);
      } else {
        // An include's *KEYWORD line would stand mid-deck once inlined: keep only its comments.
        const std::size_t afterLine = content.find('\n', begin);
        if (afterLine != std::string_view::npos && afterLine + 1 < end)
          addVerbatim(file, content.substr(afterLine + 1, end - afterLine - 1),
                      keywordLineNumber + 1);
      }
      return true;
    }
    if (name.compare(0, 9, "*INCLUDE_") == 0)
      warnings_.push_back(file.name + ":" + std::to_string(keywordLineNumber) + ": " + name +
                          " is kept as it is: the file it names is not read, so its content "
                          "is not part of the model and the written deck still needs it");

    const std::size_t end = skipBlock(cursor, content.size());
    const std::string_view text = content.substr(begin, end - begin);
    if (name == "*PART" || name.compare(0, 6, "*PART_") == 0)
      readParts(file, text, keywordLineNumber, name, format);
    addKeywordBlock(file, text, keyword, keywordLineNumber);
    return true;
  }

  /// Adds verbatim text whose first line is line `line` of `file`.
  void addVerbatim(const SourceFile& file, std::string_view text, std::size_t line) {
    DeckBlock block{DeckBlock::Kind::Verbatim, std::string(text), file.name, line};
    // Inlined include content must end its last line before the next block starts.
    if (!file.isMain && !block.text.empty() && block.text.back() != '\n') block.text += '\n';
    model_.blocks.push_back(std::move(block));
  }

  /// Adds a keyword block verbatim; an include block in a format other than the main deck's gets
  /// the suffix that selects its format, so that the inlined text reads the same.
  void addKeywordBlock(SourceFile& file, std::string_view text, const KeywordLine& keyword,
                       std::size_t line) {
    if (file.isMain || keyword.suffix || file.format == deckFormat_) {
      addVerbatim(file, text, line);
      return;
    }
    std::string marked(text.substr(0, keyword.tokenEnd));
    marked += lsdyna::suffixText(file.format);
    marked += text.substr(keyword.tokenEnd);
    addVerbatim(file, marked, line);
    if (!file.suffixWarned) {
      warnings_.push_back(file.name + " is read in the " + formatName(file.format) +
                          " format, unlike the main deck: its inlined keywords got the '" +
                          std::string(lsdyna::suffixText(file.format) + 1) +
                          "' suffix that selects that format");
      file.suffixWarned = true;
    }
  }

  [[noreturn]] void malformed(const SourceFile& file, const LineCursor& cursor,
                              const Layout& layout, int field, std::string_view bad,
                              const std::string& keyword) {
    throw InputError(file.name, cursor.lineNumber(),
                     "malformed " + std::string(layout.names[static_cast<std::size_t>(field)]) +
                         " '" + std::string(trim(bad)) + "' in " + keyword,
                     std::string(cursor.line()));
  }

  void readNodes(const SourceFile& file, LineCursor& cursor, const KeywordLine& keyword,
                 CardFormat format) {
    if (!nodesPlaced_) {
      model_.blocks.push_back(DeckBlock{DeckBlock::Kind::Nodes, {}});
      nodesPlaced_ = true;
    }
    const Layout& layout = lsdyna::layout(Card::Node, format);
    CardValues values;
    std::string_view bad;
    while (cursor.next()) {
      const std::string_view line = cursor.line();
      if (line.empty() || lsdyna::isCommentLine(line)) continue;
      if (lsdyna::isKeywordLine(line)) {
        cursor.pushBack();
        break;
      }
      const int failed = lsdyna::parseCard(line, layout, values, bad);
      if (failed >= 0) {
        if (isBlankLine(line)) continue;
        malformed(file, cursor, layout, failed, bad, keyword.name);
      }
      if (values.ints[0] == 0) {
        if (isBlankLine(line)) continue;
        throw InputError(file.name, cursor.lineNumber(), "missing node ID in " + keyword.name,
                         std::string(line));
      }
      model_.nodes.push_back(
          Node{values.ints[0], {values.reals[1], values.reals[2], values.reals[3]}});
      sources_.addNode(file.index, cursor.lineNumber());
      if (values.ints[4] != 0 || values.ints[5] != 0) {
        NodeExtras& extras = model_.nodeExtras[values.ints[0]];
        extras.dynaTc = static_cast<std::int32_t>(values.ints[4]);
        extras.dynaRc = static_cast<std::int32_t>(values.ints[5]);
      }
    }
  }

  void readShells(const SourceFile& file, LineCursor& cursor, const KeywordLine& keyword,
                  CardFormat format, std::string_view keywordLine, std::size_t keywordLineNumber) {
    const std::string suffix = keyword.name.substr(14);
    std::string error;
    const std::optional<lsdyna::ShellOptions> options = lsdyna::parseShellOptions(suffix, error);
    if (!options) throw InputError(file.name, keywordLineNumber, error, std::string(keywordLine));
    if (!shellsPlaced_) {
      model_.blocks.push_back(DeckBlock{DeckBlock::Kind::Shells, {}});
      shellsPlaced_ = true;
    }
    const std::uint8_t type = model_.internShellType(suffix);
    const Layout& card1 = lsdyna::layout(Card::Shell, format);
    const Layout& card2 = lsdyna::layout(Card::ShellThickness, format);
    const Layout& card3 = lsdyna::layout(Card::ShellOffset, format);
    CardValues values;
    std::string_view bad;
    while (cursor.next()) {
      const std::string_view line = cursor.line();
      if (line.empty() || lsdyna::isCommentLine(line)) continue;
      if (lsdyna::isKeywordLine(line)) {
        cursor.pushBack();
        break;
      }
      if (isBlankLine(line)) continue;
      const int failed = lsdyna::parseCard(line, card1, values, bad);
      if (failed >= 0) malformed(file, cursor, card1, failed, bad, keyword.name);
      Shell shell;
      shell.id = values.ints[0];
      shell.part = values.ints[1];
      shell.type = type;
      const std::size_t lineNumber = cursor.lineNumber();
      checkShellCard(file, cursor, keyword.name, values);
      for (int k = 0; k < 4; ++k) shell.nodes[static_cast<std::size_t>(k)] = values.ints[2 + k];
      if (shell.nodes[3] == 0 || shell.nodes[3] == shell.nodes[2]) {
        shell.nodeCount = 3;
        shell.nodes[3] = 0;
      }
      ShellExtras extras;
      if (options->hasThicknessCard()) {
        requireCard(file, cursor, keyword.name, shell.id, "thickness card (card 2)", line,
                    lineNumber);
        const int bad2 = lsdyna::parseCard(cursor.line(), card2, values, bad);
        if (bad2 >= 0) malformed(file, cursor, card2, bad2, bad, keyword.name);
        for (std::size_t k = 0; k < 4; ++k) extras.thickness[k] = values.reals[k];
        extras.angle = values.reals[4];
        extras.angleIsMcid = options->mcid;
      }
      if (options->offset) {
        requireCard(file, cursor, keyword.name, shell.id, "offset card", line, lineNumber);
        const int bad3 = lsdyna::parseCard(cursor.line(), card3, values, bad);
        if (bad3 >= 0) malformed(file, cursor, card3, bad3, bad, keyword.name);
        extras.offset = values.reals[0];
      }
      const bool hasExtras = extras.thickness[0] != 0 || extras.thickness[1] != 0 ||
                             extras.thickness[2] != 0 || extras.thickness[3] != 0 ||
                             extras.angle != 0 || extras.offset != 0;
      if (hasExtras) {
        shell.extras = static_cast<std::int32_t>(model_.shellExtras.size());
        model_.shellExtras.push_back(extras);
      }
      model_.shells.push_back(shell);
      sources_.addShell(file.index, lineNumber);
    }
  }

  /// Refuses element cards without an ID, part or three nodes, and 8-node shells.
  static void checkShellCard(const SourceFile& file, const LineCursor& cursor,
                             const std::string& keyword, const CardValues& values) {
    const auto fail = [&](const std::string& message) {
      throw InputError(file.name, cursor.lineNumber(), message, std::string(cursor.line()));
    };
    if (values.ints[0] == 0) fail("missing element ID in " + keyword);
    const std::string element = "element " + std::to_string(values.ints[0]);
    if (values.ints[1] == 0) fail("missing part ID of " + element + " in " + keyword);
    if (values.ints[2] == 0 || values.ints[3] == 0 || values.ints[4] == 0)
      fail("truncated " + keyword + " card: " + element +
           " has fewer than 3 nodes (N1, N2 and N3 are required)");
    for (std::size_t k = 6; k < 10; ++k)
      if (values.ints[k] != 0)
        fail(element + " is an 8-node shell (N5..N8 given in " + keyword +
             "): voxremesh reads 3- and 4-node shells only");
  }

  /// Moves to the next card line of an element; throws when the block ends before it.
  static void requireCard(const SourceFile& file, LineCursor& cursor, const std::string& keyword,
                          Id element, const char* what, std::string_view card1,
                          std::size_t card1Line) {
    const std::string card1Text(card1);
    if (!nextCardLine(cursor))
      throw InputError(file.name, card1Line,
                       "truncated " + keyword + " card: element " + std::to_string(element) +
                           " has no " + what + " before the next keyword or the end of the file",
                       card1Text);
  }

  void readParts(const SourceFile& file, std::string_view text, std::size_t firstLine,
                 const std::string& keyword, CardFormat format) {
    std::string_view options = std::string_view(keyword).substr(5);
    const bool composite = options.compare(0, 10, "_COMPOSITE") == 0;
    int extraCards = 0;
    bool inertia = false;
    if (!composite) {
      static constexpr std::pair<std::string_view, int> kOptions[] = {
          {"_INERTIA", 3}, {"_REPOSITION", 1},       {"_CONTACT", 1},
          {"_PRINT", 1},   {"_ATTACHMENT_NODES", 1}, {"_AVERAGED", 0}};
      while (!options.empty()) {
        bool known = false;
        for (const auto& [option, cards] : kOptions) {
          if (options.compare(0, option.size(), option) == 0 &&
              (options.size() == option.size() || options[option.size()] == '_')) {
            extraCards += cards;
            inertia = inertia || option == "_INERTIA";
            options.remove_prefix(option.size());
            known = true;
            break;
          }
        }
        if (!known) return;  // *PART_DUPLICATE, *PART_MODES, ...: no part definitions
      }
    }
    std::vector<DataLine> lines;
    LineCursor cursor(text);
    cursor.next();  // the keyword line
    while (cursor.next())
      if (!lsdyna::isCommentLine(cursor.line()))
        lines.push_back({cursor.line(), firstLine + cursor.lineNumber() - 1});
    while (!lines.empty() && isBlankLine(lines.back().text)) lines.pop_back();

    const Layout& partLayout = lsdyna::layout(Card::Part, format);
    const Layout& inertiaLayout = lsdyna::layout(Card::PartInertia, format);
    CardValues values;
    std::string_view bad;
    std::size_t i = 0;
    while (i < lines.size()) {
      const DataLine& title = lines[i];
      if (i + 1 >= lines.size())
        throw InputError(file.name, title.line,
                         "truncated " + keyword + ": the part titled '" +
                             std::string(trim(title.text)) + "' has no card with its PID",
                         std::string(title.text));
      const DataLine& card = lines[i + 1];
      const int failed = lsdyna::parseCard(card.text, partLayout, values, bad);
      if (failed >= 0 || values.ints[0] == 0)
        throw InputError(file.name, card.line,
                         failed >= 0
                             ? "malformed part ID '" + std::string(trim(bad)) + "' in " + keyword
                             : "missing part ID in " + keyword,
                         std::string(card.text));
      const Id pid = values.ints[0];
      std::size_t cards = 2 + static_cast<std::size_t>(extraCards);
      if (inertia && i + 2 < lines.size()) {
        const int badInertia = lsdyna::parseCard(lines[i + 2].text, inertiaLayout, values, bad);
        if (badInertia >= 0)
          throw InputError(file.name, lines[i + 2].line,
                           "malformed IRCS '" + std::string(trim(bad)) + "' in " + keyword,
                           std::string(lines[i + 2].text));
        if (values.ints[4] == 1) ++cards;
      }
      if (!composite && i + cards > lines.size())
        throw InputError(file.name, card.line,
                         "truncated " + keyword + ": part " + std::to_string(pid) + " needs " +
                             std::to_string(cards) + " cards, the block ends after " +
                             std::to_string(lines.size() - i),
                         std::string(card.text));
      definePart(file, pid, trim(title.text), card.line);
      if (composite) break;  // the ply cards run to the end of the block
      i += cards;
    }
  }

  void definePart(const SourceFile& file, Id pid, std::string_view name, std::size_t line) {
    const std::string location = file.name + ":" + std::to_string(line);
    const auto [it, inserted] = partDefinedAt_.emplace(pid, location);
    if (!inserted)
      throw InputError(
          file.name, line,
          "duplicate part ID " + std::to_string(pid) + " (first defined at " + it->second + ")");
    model_.parts.push_back(Part{pid, std::string(name), true});
  }

  void readInclude(SourceFile& file, LineCursor& cursor, const KeywordLine& keyword) {
    const std::size_t keywordLine = cursor.lineNumber();
    const std::string keywordCard(cursor.line());
    bool included = false;
    std::string name;
    std::size_t nameLine = 0;
    std::string card;
    while (nextCardLine(cursor)) {
      const std::string_view line = trim(cursor.line());
      if (line.empty() && name.empty()) continue;
      if (name.empty()) nameLine = cursor.lineNumber();
      card += std::string(cursor.line());
      // A file name longer than a line continues on the next one after " +".
      if (line.size() >= 2 && line.back() == '+' && (line[line.size() - 2] == ' ')) {
        name += trim(line.substr(0, line.size() - 1));
        card += '\n';
        continue;
      }
      name += line;
      includeFile(file, name, nameLine, card, keyword.suffix.value_or(file.format));
      included = true;
      name.clear();
      card.clear();
    }
    if (!name.empty()) {
      includeFile(file, name, nameLine, card, keyword.suffix.value_or(file.format));
      included = true;
    }
    // LS-DYNA requires the FILENAME card; without it the block would vanish silently.
    if (!included)
      throw InputError(file.name, keywordLine, "*INCLUDE without a file name", keywordCard);
  }

  void includeFile(const SourceFile& file, std::string name, std::size_t line,
                   const std::string& card, CardFormat format) {
    std::replace(name.begin(), name.end(), '\\', '/');
    const fs::path given(name);
    std::vector<fs::path> candidates;
    if (given.is_absolute()) {
      candidates.push_back(given);
    } else {
      candidates.push_back(file.folder / given);
      for (const fs::path& folder : includePaths_) candidates.push_back(folder / given);
    }
    std::error_code ignored;
    const auto found = std::find_if(candidates.begin(), candidates.end(), [&](const fs::path& p) {
      return fs::is_regular_file(p, ignored);
    });
    if (found == candidates.end()) {
      std::string looked;
      for (const fs::path& p : candidates) looked += (looked.empty() ? "" : ", ") + p.string();
      throw InputError(
          file.name, line,
          "include file '" + name + "' not found as a regular file (looked for " + looked + ")",
          card);
    }
    const fs::path canonical = fs::weakly_canonical(*found, ignored);
    if (std::find(includeStack_.begin(), includeStack_.end(), canonical) != includeStack_.end())
      throw InputError(file.name, line,
                       "include cycle: '" + found->string() +
                           "' is already being read (it includes " + file.name +
                           " directly or through other files)",
                       card);
    if (includeStack_.size() >= io::kMaxIncludeDepth)
      throw InputError(file.name, line, io::includeTooDeepMessage(name), card);
    warnings_.push_back("inlined *INCLUDE '" + name + "' (" + file.name + ":" +
                        std::to_string(line) +
                        "): the written deck holds its content instead of including the file");
    includeStack_.push_back(canonical);
    readFile(*found, format, false);
    includeStack_.pop_back();
  }

  void readIncludePath(const SourceFile& file, LineCursor& cursor, const KeywordLine& keyword) {
    while (nextCardLine(cursor)) {
      const std::string_view line = trim(cursor.line());
      if (line.empty()) continue;
      std::string folder(line);
      std::replace(folder.begin(), folder.end(), '\\', '/');
      const fs::path path(folder);
      includePaths_.push_back(path.is_absolute() ? path : file.folder / path);
    }
    warnings_.push_back(file.name + ": " + keyword.name +
                        " was used to find include files and is left out of the written deck, "
                        "which holds their content");
  }

  /// Adds the parts that shells use but no *PART defines.
  void addUndefinedParts() {
    const std::vector<Id> missing = io::addUndefinedParts(model_);
    if (missing.empty()) return;
    warnings_.push_back(std::to_string(missing.size()) +
                        " part(s) used by shells are not defined by any *PART (" +
                        listIds(missing) +
                        "): they are added without a name, and a written LS-DYNA deck gets *PART "
                        "cards for them whose SECID and MID must be set");
  }

  FeModel model_;
  SourceMap sources_;
  Warnings& warnings_;
  std::vector<fs::path> includeStack_;
  std::vector<fs::path> includePaths_;
  std::unordered_map<Id, std::string> partDefinedAt_;
  CardFormat deckFormat_ = CardFormat::Standard;
  bool nodesPlaced_ = false;
  bool shellsPlaced_ = false;
};

}  // namespace

FeModel readLsDyna(const std::filesystem::path& path, Warnings& warnings) {
  DeckReader reader(warnings);
  return reader.read(path);
}

}  // namespace voxremesh::io
