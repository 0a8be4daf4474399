// Abaqus input (.inp) reader: *NODE and the 3-/4-node surface *ELEMENT blocks become geometry,
// everything else is kept verbatim in order; *INCLUDE files are merged in.
#include <algorithm>
#include <array>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "io/abaqus_syntax.h"
#include "io/formats.h"
#include "io/model_checks.h"
#include "io/text_scan.h"
#include "voxremesh/errors.h"

namespace voxremesh::io {

namespace {

namespace fs = std::filesystem;
using abaqus::ElementClass;

constexpr std::size_t kMaxFields = 24;

/// One parameter of a keyword line: KEY or KEY=value (key upper case, blanks removed).
struct Parameter {
  std::string key;
  std::string value;     ///< unquoted, blanks outside quotes removed
  std::string rawValue;  ///< as written (quotes kept), blanks outside quotes removed
};

/// A keyword line (with its continuation lines): name upper case without blanks.
struct Keyword {
  std::string name;
  std::vector<Parameter> parameters;

  const Parameter* find(std::string_view key) const {
    for (const Parameter& p : parameters)
      if (p.key == key) return &p;
    return nullptr;
  }
};

/// Parses `*NAME, KEY=value, ...` (the text after the star). Blanks outside double quotes are
/// ignored, as Abaqus does; quoted values keep their blanks and commas.
Keyword parseKeyword(std::string_view text) {
  std::vector<std::string> items(1);
  std::vector<std::string> raws(1);
  bool inQuotes = false;
  for (char c : text) {
    if (c == '"') {
      inQuotes = !inQuotes;
      raws.back() += c;
      continue;
    }
    if (!inQuotes && c == ',') {
      items.emplace_back();
      raws.emplace_back();
      continue;
    }
    if (!inQuotes && (c == ' ' || c == '\t' || c == '\r' || c == '\n')) continue;
    items.back() += c;
    raws.back() += c;
  }
  Keyword keyword;
  keyword.name = toUpper(items[0]);
  for (std::size_t i = 1; i < items.size(); ++i) {
    if (items[i].empty()) continue;
    Parameter parameter;
    const std::size_t eq = raws[i].find('=');
    if (eq == std::string::npos) {
      parameter.key = toUpper(items[i]);
    } else {
      parameter.key = toUpper(raws[i].substr(0, eq));
      parameter.rawValue = raws[i].substr(eq + 1);
      for (char c : parameter.rawValue)
        if (c != '"') parameter.value += c;
    }
    keyword.parameters.push_back(std::move(parameter));
  }
  return keyword;
}

/// Splits a data line at commas into trimmed fields; returns the number of fields (a trailing
/// empty field after a final comma is not counted). Returns kMaxFields + 1 when there are more.
std::size_t splitCommas(std::string_view line, std::array<std::string_view, kMaxFields>& fields) {
  std::size_t count = 0;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string_view piece = trim(line.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) {
      if (!piece.empty() || count == 0) {
        if (count >= kMaxFields) return kMaxFields + 1;
        fields[count++] = piece;
      }
      return count;
    }
    if (count >= kMaxFields) return kMaxFields + 1;
    fields[count++] = piece;
    start = comma + 1;
  }
}

bool isComment(std::string_view line) {
  return line.size() >= 2 && line[0] == '*' && line[1] == '*';
}

/// The first non-blank character of the line is a single star.
bool isKeywordLine(std::string_view line) {
  const std::string_view t = trim(line);
  return !t.empty() && t[0] == '*' && !(t.size() >= 2 && t[1] == '*');
}

bool endsWithComma(std::string_view line) {
  const std::string_view t = trim(line);
  return !t.empty() && t.back() == ',';
}

/// A part (element set named on *ELEMENT) while reading.
struct PendingPart {
  std::string name;
  Id id = 0;
};

/// Where a keyword line stands: file, line and the line's text (for errors).
struct Location {
  std::string file;
  std::size_t line = 0;
  std::string card;
};

/// True when a keyword line names *INCLUDE (blanks and case ignored).
bool isIncludeLine(std::string_view line) {
  std::string name;
  for (char c : trim(line).substr(1)) {
    if (c == ',') break;
    if (c != ' ' && c != '\t') name += c;
    if (name.size() > 7) return false;
  }
  return iequals(name, "INCLUDE");
}

/// The lines of a deck with its *INCLUDE files merged in, as Abaqus reads them: a keyword's
/// data may go on after the end of an included file. Data files given with INPUT= on *NODE or
/// *ELEMENT are read the same way.
class DeckLines {
 public:
  DeckLines(SourceMap& sources, Warnings& warnings) : sources_(sources), warnings_(warnings) {}

  /// Starts reading `path` (content already loaded) at the current position.
  void open(const fs::path& path, std::string content) {
    auto frame = std::make_unique<Frame>();
    frame->path = path;
    frame->file = path.string();
    frame->identity = identity(path);
    frame->content = std::move(content);
    frame->cursor = LineCursor(frame->content);
    frame->index = sources_.addFile(frame->file);
    frames_.push_back(std::move(frame));
  }

  /// Opens a file named in the deck (relative to the file being read), after checking it
  /// exists, is text and is not already being read. `at` is the line naming it.
  void openNamed(const std::string& name, const Location& at) {
    fs::path target(name);
    if (target.is_relative()) target = path().parent_path() / target;
    std::error_code error;
    if (!fs::is_regular_file(target, error))
      throw InputError(
          at.file, at.line,
          "file '" + name + "' not found as a regular file (looked for " + target.string() + ")",
          at.card);
    const std::string id = identity(target);
    for (const auto& frame : frames_)
      if (frame->identity == id)
        throw InputError(at.file, at.line, "*INCLUDE of '" + name + "' includes itself", at.card);
    if (frames_.size() >= io::kMaxIncludeDepth)
      throw InputError(at.file, at.line, io::includeTooDeepMessage(name), at.card);
    std::string content = loadFile(target);
    if (content.find('\0') != std::string::npos) requireText(content, target);
    open(target, std::move(content));
  }

  /// Moves to the next line, entering *INCLUDE files and going back to the including file at
  /// their end. Returns false at the end of the deck.
  bool next() {
    if (pushedBack_) {
      pushedBack_ = false;
      return true;
    }
    while (!frames_.empty()) {
      Frame& frame = *frames_.back();
      if (!frame.cursor.next()) {
        finished_.push_back(std::move(frames_.back()));  // keeps its text alive for errors
        frames_.pop_back();
        continue;
      }
      const std::string_view line = frame.cursor.line();
      if (!line.empty() && trim(line).size() > 1 && trim(line)[0] == '*' && trim(line)[1] != '*' &&
          isIncludeLine(line)) {
        include(frame);
        continue;
      }
      return true;
    }
    return false;
  }

  /// Goes back so that next() returns the current line again.
  void pushBack() { pushedBack_ = true; }

  std::string_view line() const { return top().cursor.line(); }
  /// The current line with its terminator; a file's last line without one gets "\n" when more
  /// text follows it (an included file), so that lines never run together.
  std::string_view rawLine() const { return top().cursor.rawLine(); }
  bool lastLineOfInclude() const {
    const Frame& frame = top();
    return frames_.size() > 1 && frame.cursor.end() >= frame.content.size();
  }
  std::size_t lineNumber() const { return top().cursor.lineNumber(); }
  const std::string& file() const { return top().file; }
  std::uint32_t fileIndex() const { return top().index; }
  const fs::path& path() const { return top().path; }

 private:
  struct Frame {
    fs::path path;
    std::string file;
    std::string identity;
    std::string content;
    LineCursor cursor{std::string_view()};
    std::uint32_t index = 0;
  };

  /// The file being read; after the end of the deck the last one read (its last line), so that
  /// an error found at the end (a data line continued past the last line) still names a place.
  const Frame& top() const { return frames_.empty() ? *finished_.back() : *frames_.back(); }

  static std::string identity(const fs::path& path) {
    std::error_code error;
    const fs::path canonical = fs::weakly_canonical(path, error);
    return (error ? path.lexically_normal() : canonical).string();
  }

  void include(Frame& frame) {
    const Location at{frame.file, frame.cursor.lineNumber(),
                      std::string(trim(frame.cursor.line()))};
    std::string text(trim(frame.cursor.line()));
    while (endsWithComma(text) && frame.cursor.next()) text += trim(frame.cursor.line());
    const Keyword keyword = parseKeyword(std::string_view(text).substr(1));
    const Parameter* input = keyword.find("INPUT");
    if (!input || input->value.empty())
      throw InputError(at.file, at.line, "*INCLUDE without INPUT=", at.card);
    openNamed(input->value, at);
    warnings_.push_back(at.file + ":" + std::to_string(at.line) + ": *INCLUDE of '" + input->value +
                        "' merged into the deck (the *INCLUDE line is not kept)");
  }

  SourceMap& sources_;
  Warnings& warnings_;
  std::vector<std::unique_ptr<Frame>> frames_;
  std::vector<std::unique_ptr<Frame>> finished_;
  bool pushedBack_ = false;
};

class AbaqusReader {
 public:
  explicit AbaqusReader(Warnings& warnings) : warnings_(warnings), lines_(sources_, warnings) {
    model_.sourceFormat = DeckFormat::Abaqus;
  }

  FeModel read(const fs::path& path) {
    std::string content = loadFile(path);
    requireText(content, path);
    lines_.open(path, std::move(content));
    readDeck();
    finish(path);
    return std::move(model_);
  }

 private:
  /// Appends a line to the pending verbatim text.
  void keepLine() {
    pending_ += lines_.rawLine();
    if (lines_.lastLineOfInclude() && !pending_.empty() && pending_.back() != '\n')
      pending_ += '\n';
  }

  void readDeck() {
    while (lines_.next()) {
      const std::string_view line = lines_.line();
      if (isComment(line)) {
        if (!takePartComment(line)) keepLine();
        continue;
      }
      if (!isKeywordLine(line)) {
        keepLine();  // data of a verbatim keyword, or a blank line
        continue;
      }
      Location at{lines_.file(), lines_.lineNumber(), std::string(trim(line))};
      const std::size_t begin = pending_.size();
      keepLine();
      std::string text(trim(line));
      while (endsWithComma(text) && lines_.next()) {  // keyword line continued
        keepLine();
        text += trim(lines_.line());
      }
      const Keyword keyword = parseKeyword(std::string_view(text).substr(1));
      if (keyword.name == "NODE") {
        pending_.resize(begin);  // regenerated
        readNodes(keyword, at);
      } else if (keyword.name == "ELEMENT") {
        const ElementClass kind = elementClass(keyword, at);
        if (kind == ElementClass::Shell3 || kind == ElementClass::Shell4) {
          pending_.resize(begin);
          readShells(keyword, kind, at);
        } else {
          noteVerbatim(keyword, at);
        }
      } else if (keyword.name == "PART" || keyword.name == "INSTANCE" ||
                 keyword.name == "ASSEMBLY") {
        throw InputError(at.file, at.line,
                         "part-instance input (*" + keyword.name +
                             "): node and element IDs are local to each part there; export a "
                             "flat input file instead (Abaqus/CAE: Model > Edit Attributes > "
                             "'Do not use parts and assemblies in input files')",
                         at.card);
      } else {
        noteVerbatim(keyword, at);
      }
    }
  }

  /// Handles `** voxremesh part <id> "<name>"`; returns false for any other comment.
  bool takePartComment(std::string_view line) {
    if (line.substr(0, abaqus::kPartComment.size()) != abaqus::kPartComment) return false;
    std::string_view rest = trim(line.substr(abaqus::kPartComment.size()));
    const std::size_t blank = rest.find(' ');
    if (blank == std::string_view::npos) return false;
    std::int64_t id = 0;
    if (!parseInt(rest.substr(0, blank), id)) return false;
    std::string_view name = trim(rest.substr(blank + 1));
    if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
      name = name.substr(1, name.size() - 2);
    restoredIds_[toUpper(name)] = id;
    return true;
  }

  /// Warns about verbatim keywords that generate geometry or name other files.
  void noteVerbatim(const Keyword& keyword, const Location& at) {
    static constexpr std::string_view kGenerators[] = {"NGEN", "NFILL", "NCOPY",
                                                       "NMAP", "ELGEN", "ELCOPY"};
    for (std::string_view generator : kGenerators)
      if (keyword.name == generator)
        warnings_.push_back(at.file + ":" + std::to_string(at.line) + ": *" + keyword.name +
                            " generates nodes or elements that voxremesh does not evaluate; it "
                            "is kept verbatim");
    if (const Parameter* input = keyword.find("INPUT"))
      warnings_.push_back(at.file + ":" + std::to_string(at.line) + ": *" + keyword.name +
                          " reads INPUT=" + input->value +
                          "; the reference is kept as written (relative to the deck's folder)");
  }

  void flushPending() {
    if (!pending_.empty()) {
      model_.blocks.push_back(DeckBlock{DeckBlock::Kind::Verbatim, std::move(pending_)});
      pending_.clear();
    }
  }

  ElementClass elementClass(const Keyword& keyword, const Location& at) {
    const Parameter* type = keyword.find("TYPE");
    if (!type || type->value.empty())
      throw InputError(at.file, at.line, "*ELEMENT without TYPE=", at.card);
    const std::string name = toUpper(type->value);
    const ElementClass kind = abaqus::classifyElementType(name);
    if (kind == ElementClass::Unknown)
      throw InputError(at.file, at.line,
                       "unknown element type '" + type->value + "' (not an Abaqus element type)",
                       at.card);
    if (kind == ElementClass::HigherShell)
      throw InputError(at.file, at.line,
                       "element type " + name +
                           " has midside nodes; voxremesh reads 3- and 4-node shells only "
                           "(S3R, S4R, M3D3, M3D4, R3D3, R3D4, ...)",
                       at.card);
    return kind;
  }

  /// Reads the data lines of *NODE / *ELEMENT (from the deck, or first from an INPUT= file)
  /// up to the next keyword line, calling `body` for each. Comments and blank lines after the
  /// data belong to what follows and are returned; those between data lines are counted and
  /// dropped.
  template <typename Body>
  std::string readData(const Keyword& keyword, const Location& at, Body body) {
    if (const Parameter* input = keyword.find("INPUT")) lines_.openNamed(input->value, at);
    std::string held;
    std::size_t heldLines = 0;
    while (lines_.next()) {
      const std::string_view t = trim(lines_.line());
      if (t.empty() || isComment(t)) {
        if (!isComment(t) || !takePartComment(t)) {
          held += lines_.rawLine();
          if (lines_.lastLineOfInclude() && held.back() != '\n') held += '\n';
          ++heldLines;
        }
        continue;
      }
      if (t[0] == '*') {
        lines_.pushBack();
        break;
      }
      if (heldLines > 0) {
        droppedComments_ += heldLines;
        held.clear();
        heldLines = 0;
      }
      body();
    }
    return held;
  }

  void readNodes(const Keyword& keyword, const Location& at) {
    for (const Parameter& p : keyword.parameters) {
      if (p.key == "NSET" || p.key == "INPUT") continue;
      if (p.key == "SYSTEM" && (p.value == "R" || p.value == "r")) continue;
      if (p.key == "SYSTEM")
        throw InputError(at.file, at.line,
                         "*NODE in a cylindrical or spherical system (SYSTEM=" + p.value +
                             ") is not supported; give rectangular coordinates",
                         at.card);
      throw InputError(at.file, at.line, "*NODE parameter " + p.key + " is not supported", at.card);
    }
    if (!nodesPlaced_) {
      flushPending();
      model_.blocks.push_back(DeckBlock{DeckBlock::Kind::Nodes, {}});
      nodesPlaced_ = true;
    }
    const Parameter* nset = keyword.find("NSET");
    const std::size_t first = model_.nodes.size();
    std::array<std::string_view, kMaxFields> fields;
    const std::string after = readData(keyword, at, [&]() {
      const std::string_view line = lines_.line();
      const std::size_t n = splitCommas(line, fields);
      auto fail = [&](const std::string& message) {
        throw InputError(lines_.file(), lines_.lineNumber(), message, std::string(trim(line)));
      };
      if (n > 7) fail("too many fields on a *NODE data line (expected id, x, y, z)");
      Node node;
      if (!parseInt(fields[0], node.id) || fields[0].empty())
        fail("malformed node ID '" + std::string(fields[0]) + "' in *NODE");
      if (node.id <= 0) fail("node ID " + std::to_string(node.id) + " is not positive");
      static constexpr const char* kAxis[] = {"x", "y", "z"};
      for (std::size_t k = 0; k < 3; ++k) {
        const std::string_view value = k + 1 < n ? fields[k + 1] : std::string_view{};
        if (!parseReal(value, node.xyz[k]))
          fail("malformed " + std::string(kAxis[k]) + " coordinate '" + std::string(value) +
               "' in *NODE");
      }
      for (std::size_t k = 4; k < n; ++k)
        if (!fields[k].empty())
          fail("node " + std::to_string(node.id) +
               " gives normal direction cosines (fields 5-7), which voxremesh cannot "
               "carry through regeneration; define normals with *NORMAL instead");
      model_.nodes.push_back(node);
      sources_.addNode(lines_.fileIndex(), lines_.lineNumber());
    });
    if (nset) {
      // The set named on *NODE survives as an equivalent *NSET block right after the nodes.
      std::string text = "*NSET, NSET=" + nset->rawValue + "\n";
      for (std::size_t i = first; i < model_.nodes.size(); ++i) {
        text += std::to_string(model_.nodes[i].id);
        text += ((i - first) % 16 == 15 || i + 1 == model_.nodes.size()) ? "\n" : ", ";
      }
      pending_ += text;
    }
    pending_ += after;
  }

  void readShells(const Keyword& keyword, ElementClass kind, const Location& at) {
    for (const Parameter& p : keyword.parameters)
      if (p.key != "TYPE" && p.key != "ELSET" && p.key != "INPUT")
        throw InputError(at.file, at.line,
                         "*ELEMENT parameter " + p.key + " is not supported for shell elements",
                         at.card);
    if (!shellsPlaced_) {
      flushPending();
      model_.blocks.push_back(DeckBlock{DeckBlock::Kind::Shells, {}});
      shellsPlaced_ = true;
    }
    const std::string typeName = toUpper(keyword.find("TYPE")->value);
    const std::uint8_t type = model_.internShellType(typeName);
    const Parameter* elset = keyword.find("ELSET");
    const std::size_t part = partIndex(elset && !elset->value.empty() ? elset->value : typeName);
    const int nodeCount = kind == ElementClass::Shell3 ? 3 : 4;
    std::array<std::string_view, kMaxFields> fields;
    std::array<std::int64_t, 5> values{};
    pending_ += readData(keyword, at, [&]() {
      const std::string& file = lines_.file();
      const std::uint32_t fileIndex = lines_.fileIndex();
      const std::size_t startLine = lines_.lineNumber();
      const std::string_view firstLine = lines_.line();
      std::size_t current = startLine;
      int have = 0;
      values[0] = 0;
      auto fail = [&](const std::string& message) {
        std::string card(trim(firstLine));
        if (current != startLine) card += " / " + std::string(trim(lines_.line()));
        throw InputError(file, current, message, card);
      };
      while (true) {
        const std::string_view line = lines_.line();
        const std::size_t n = splitCommas(line, fields);
        for (std::size_t k = 0; k < n; ++k) {
          if (fields[k].empty()) {
            if (k + 1 == n) break;
            fail("empty field in *ELEMENT data");
          }
          if (have > nodeCount)
            fail("too many nodes for element type " + typeName + " (" + std::to_string(nodeCount) +
                 " expected)");
          if (!parseInt(fields[k], values[static_cast<std::size_t>(have)]))
            fail(std::string(have == 0 ? "malformed element ID '" : "malformed node ID '") +
                 std::string(fields[k]) + "' in *ELEMENT");
          ++have;
        }
        if (have > nodeCount || !endsWithComma(line)) break;
        // The element continues on the next line (unless a keyword or comment follows).
        if (!lines_.next()) break;
        if (trim(lines_.line()).empty() || trim(lines_.line())[0] == '*' || lines_.file() != file) {
          lines_.pushBack();
          break;
        }
        current = lines_.lineNumber();
      }
      if (have < nodeCount + 1)
        fail("element " + std::to_string(values[0]) + " has " +
             std::to_string(std::max(have - 1, 0)) + " node(s); type " + typeName + " needs " +
             std::to_string(nodeCount));
      if (values[0] <= 0) fail("element ID " + std::to_string(values[0]) + " is not positive");
      Shell shell;
      shell.id = values[0];
      shell.part = static_cast<Id>(part);
      shell.nodeCount = static_cast<std::uint8_t>(nodeCount);
      shell.type = type;
      for (int k = 0; k < nodeCount; ++k)
        shell.nodes[static_cast<std::size_t>(k)] = values[static_cast<std::size_t>(k) + 1];
      model_.shells.push_back(shell);
      sources_.addShell(fileIndex, startLine);
    });
  }

  std::size_t partIndex(const std::string& name) {
    const std::string key = toUpper(name);
    const auto it = partsByKey_.find(key);
    if (it != partsByKey_.end()) return it->second;
    parts_.push_back(PendingPart{name, 0});
    partsByKey_.emplace(key, parts_.size() - 1);
    return parts_.size() - 1;
  }

  void finish(const fs::path& path) {
    flushPending();
    // Part IDs: restored from our writer's comments first, then 1.. in order of appearance.
    std::set<Id> taken;
    std::vector<bool> fixed(parts_.size(), false);
    for (std::size_t i = 0; i < parts_.size(); ++i) {
      const auto restored = restoredIds_.find(toUpper(parts_[i].name));
      if (restored != restoredIds_.end() && taken.insert(restored->second).second) {
        parts_[i].id = restored->second;
        fixed[i] = true;
      }
    }
    Id next = 1;
    for (std::size_t i = 0; i < parts_.size(); ++i) {
      if (fixed[i]) continue;
      while (taken.count(next)) ++next;
      parts_[i].id = next;
      taken.insert(next);
    }
    for (Shell& shell : model_.shells) shell.part = parts_[static_cast<std::size_t>(shell.part)].id;
    for (const PendingPart& part : parts_) model_.parts.push_back(Part{part.id, part.name, false});
    if (droppedComments_ > 0)
      warnings_.push_back(path.string() + ": " + std::to_string(droppedComments_) +
                          " comment or blank line(s) between node or element data lines are not "
                          "kept (the data is regenerated)");
    if (model_.shells.empty())
      warnings_.push_back(path.string() +
                          ": no 3- or 4-node shell elements (S3R, S4R, M3D4, R3D4, ...)");
    checkModel(model_, sources_);
  }

  Warnings& warnings_;
  FeModel model_;
  SourceMap sources_;
  DeckLines lines_;
  std::string pending_;
  bool nodesPlaced_ = false;
  bool shellsPlaced_ = false;
  std::vector<PendingPart> parts_;
  std::unordered_map<std::string, std::size_t> partsByKey_;
  std::unordered_map<std::string, Id> restoredIds_;
  std::size_t droppedComments_ = 0;
};

}  // namespace

FeModel readAbaqus(const std::filesystem::path& path, Warnings& warnings) {
  AbaqusReader reader(warnings);
  return reader.read(path);
}

}  // namespace voxremesh::io
