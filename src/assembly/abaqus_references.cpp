// Node and element references in Abaqus input lines (the keywords listed in deck_assembly.h).
#include <string>

#include "assembly/reference_scanners.h"
#include "io/text_scan.h"

namespace voxremesh::assembly {

namespace {

bool isComment(std::string_view line) {
  return line.size() >= 2 && line[0] == '*' && line[1] == '*';
}

bool isKeyword(std::string_view line) {
  return !line.empty() && line[0] == '*' && !isComment(line);
}

/// A keyword line: its name (upper case, blanks removed, as Abaqus compares them) and whether it
/// has the GENERATE parameter.
struct Keyword {
  std::string name;
  bool generate = false;
  std::size_t begin = 0;  ///< the offset of its line in the block
};

Keyword parseKeyword(std::string_view line) {
  Keyword keyword;
  std::string upper = io::toUpper(line.substr(1));
  std::string compact;
  for (const char c : upper)
    if (c != ' ' && c != '\t' && c != '\r') compact += c;
  const std::size_t comma = compact.find(',');
  keyword.name = "*" + compact.substr(0, comma);
  if (comma != std::string::npos) {
    std::size_t at = comma;
    while (at != std::string::npos) {
      const std::size_t next = compact.find(',', at + 1);
      if (compact.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1) ==
          "GENERATE")
        keyword.generate = true;
      at = next;
    }
  }
  return keyword;
}

/// The comma-separated tokens of a data line with their offsets in the line.
std::vector<std::pair<std::size_t, std::string_view>> tokens(std::string_view line) {
  std::vector<std::pair<std::size_t, std::string_view>> result;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = line.find(',', begin);
    const std::string_view raw = line.substr(
        begin, comma == std::string_view::npos ? std::string_view::npos : comma - begin);
    const std::string_view text = io::trim(raw);
    const std::size_t at =
        text.empty() ? begin : static_cast<std::size_t>(text.data() - line.data());
    result.emplace_back(at, text);
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
  return result;
}

/// Calls visit(keyword, line, lineNumber, lineBegin, firstOfRecord) for every data line of the
/// block; a data line ending in ',' continues its record on the next line (element records).
template <typename Visit>
void forEachDataLine(std::string_view text, Visit visit) {
  io::LineCursor cursor(text);
  Keyword keyword;
  bool continued = false;
  bool keywordContinues = false;
  while (cursor.next()) {
    const std::string_view line = cursor.line();
    if (isComment(line)) continue;
    if (keywordContinues) {
      keywordContinues = !io::trim(line).empty() && io::trim(line).back() == ',';
      continue;
    }
    if (isKeyword(line)) {
      keyword = parseKeyword(line);
      keyword.begin = cursor.begin();
      keywordContinues = !io::trim(line).empty() && io::trim(line).back() == ',';
      continued = false;
      continue;
    }
    if (keyword.name.empty() || io::trim(line).empty()) continue;
    visit(keyword, line, cursor.lineNumber(), cursor.begin(), !continued);
    continued = io::trim(line).back() == ',';
  }
}

}  // namespace

namespace {

/// Adds the references of a *NSET or *ELSET data line: a GENERATE line as a range, else each
/// watched ID as a member of the list (new members go on lines of at most 16 after its last
/// reference; Abaqus reads no empty entry, so a field left over repeats a member, which a set
/// holds once).
void addSetLine(const Keyword& keyword, std::string_view line, std::size_t number,
                std::size_t begin, const ReferenceSink& sink) {
  const auto fields = tokens(line);
  if (keyword.generate) {
    std::int64_t first = 0, last = 0, step = 1;
    if (fields.size() >= 2 && io::parseInt(fields[0].second, first) &&
        io::parseInt(fields[1].second, last) &&
        (fields.size() < 3 || io::parseInt(fields[2].second, step, 1)))
      sink.addRange(number, first, last, step, keyword.name);
    return;
  }
  std::int64_t value = 0;
  for (const auto& [at, text] : fields) {
    if (text.empty() || !io::parseInt(text, value) || !sink.watched.count(value)) continue;
    sink.add(begin + at, text.size(), 0, number, value, ReferenceKind::Field, keyword.name);
    NodeReference& member = sink.references.back();
    member.role = NodeRole::Member;
    member.group = keyword.begin;
    member.listLast = member.offset;
    member.perLine = 16;
    member.blankAllowed = false;
  }
}

}  // namespace

void scanAbaqusBlock(std::string_view text, const ReferenceSink& sink) {
  forEachDataLine(text, [&](const Keyword& keyword, std::string_view line, std::size_t number,
                            std::size_t begin, bool firstOfRecord) {
    const std::string& name = keyword.name;
    const auto fields = tokens(line);
    std::int64_t value = 0;
    const auto addToken = [&](std::size_t i) {
      if (i < fields.size() && io::parseInt(fields[i].second, value) && !fields[i].second.empty() &&
          sink.watched.count(value))
        sink.add(begin + fields[i].first, fields[i].second.size(), 0, number, value,
                 ReferenceKind::Field, name);
    };
    if (name == "*NSET") {
      addSetLine(keyword, line, number, begin, sink);
    } else if (name == "*BOUNDARY" || name == "*CLOAD") {
      addToken(0);
    } else if (name == "*ELEMENT") {
      for (std::size_t i = firstOfRecord ? 1 : 0; i < fields.size(); ++i) addToken(i);
    } else if (name == "*EQUATION" || name == "*MPC" || name == "*INITIALCONDITIONS" ||
               name == "*KINEMATICCOUPLING") {
      sink.scanSuspects(line, number, 0, name);
    }
  });
}

void scanAbaqusElementBlock(std::string_view text, const ReferenceSink& sink) {
  forEachDataLine(text, [&](const Keyword& keyword, std::string_view line, std::size_t number,
                            std::size_t begin, bool) {
    if (keyword.name == "*ELSET") {
      addSetLine(keyword, line, number, begin, sink);
      return;
    }
    if (keyword.name != "*DLOAD") return;
    // A line naming an element (not an element set): the record repeated for the new shells.
    const auto fields = tokens(line);
    std::int64_t value = 0;
    if (fields.empty() || !io::parseInt(fields[0].second, value) || !sink.watched.count(value))
      return;
    sink.add(begin + fields[0].first, fields[0].second.size(), 0, number, value,
             ReferenceKind::Field, keyword.name);
    NodeReference& record = sink.references.back();
    record.role = NodeRole::Record;
    record.group = keyword.begin;
  });
}

Id abaqusMaxElementId(std::string_view text) {
  Id largest = 0;
  forEachDataLine(text, [&](const Keyword& keyword, std::string_view line, std::size_t, std::size_t,
                            bool firstOfRecord) {
    if (keyword.name != "*ELEMENT" || !firstOfRecord) return;
    std::int64_t value = 0;
    const auto fields = tokens(line);
    if (io::parseInt(fields[0].second, value)) largest = std::max(largest, value);
  });
  return largest;
}

}  // namespace voxremesh::assembly
