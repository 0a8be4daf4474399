// formatReportTable and formatReportJson: the deck report as text tables and as JSON.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "io/text_scan.h"
#include "json/json.h"
#include "voxremesh/deck_report.h"

namespace voxremesh {

namespace {

// ---------------------------------------------------------------------------------------------
// Text tables

// A number with `digits` significant digits, "-" when not finite.
std::string real(double value, int digits) {
  if (!std::isfinite(value)) return "-";
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

std::string count(std::size_t value) {
  return std::to_string(value);
}

// A part name fit for one table cell: control characters shown as '?', cut to `width` characters
// (UTF-8 sequences are kept whole).
std::string cellName(const std::string& name, std::size_t width) {
  std::vector<std::string> characters;
  for (std::size_t i = 0; i < name.size();) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    std::size_t length = 1;
    if (c >= 0xC0 && c < 0xE0)
      length = 2;
    else if (c >= 0xE0 && c < 0xF0)
      length = 3;
    else if (c >= 0xF0 && c < 0xF8)
      length = 4;
    if (i + length > name.size()) length = 1;
    characters.push_back(c < 0x20 || c == 0x7F ? std::string("?") : name.substr(i, length));
    i += length;
  }
  if (characters.size() > width) {
    characters.resize(width - 1);
    characters.push_back("~");
  }
  std::string out;
  for (const std::string& character : characters) out += character;
  return out;
}

// The display width of a cell (UTF-8 continuation bytes take no column).
std::size_t displayWidth(const std::string& text) {
  std::size_t width = 0;
  for (const char c : text)
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++width;
  return width;
}

// A table with a header row; the first `leftColumns` columns are left-aligned, the rest right.
class Table {
 public:
  Table(std::vector<std::string> header, std::size_t leftColumns) : leftColumns_(leftColumns) {
    rows_.push_back(std::move(header));
  }
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  // Adds a separator line before the next row.
  void rule() { rules_.push_back(rows_.size()); }

  void render(std::string& out) const {
    std::vector<std::size_t> widths(rows_[0].size(), 0);
    for (const auto& row : rows_)
      for (std::size_t c = 0; c < row.size(); ++c)
        widths[c] = std::max(widths[c], displayWidth(row[c]));
    std::size_t total = 0;
    for (const std::size_t w : widths) total += w + 2;
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      if (r == 1 || std::find(rules_.begin(), rules_.end(), r) != rules_.end())
        out += "  " + std::string(total - 2, '-') + "\n";
      std::string line;
      for (std::size_t c = 0; c < rows_[r].size(); ++c) {
        const std::string& cell = rows_[r][c];
        const std::string pad(widths[c] - displayWidth(cell), ' ');
        line += "  ";
        line += c < leftColumns_ ? cell + pad : pad + cell;
      }
      while (!line.empty() && line.back() == ' ') line.pop_back();
      out += line + "\n";
    }
  }

 private:
  std::size_t leftColumns_;
  std::vector<std::vector<std::string>> rows_;
  std::vector<std::size_t> rules_;
};

constexpr std::size_t kNameWidth = 28;

std::vector<std::string> rowLabel(const PartReport& part) {
  std::string name = part.defined ? cellName(part.name, kNameWidth) : "(not defined)";
  if (part.stats.shells() == 0) name += name.empty() ? "(no shells)" : " (no shells)";
  return {std::to_string(part.id), name};
}

template <typename Cells>
void addRows(Table& table, const DeckReport& report, Cells cells) {
  for (const PartReport& part : report.parts) {
    std::vector<std::string> row = rowLabel(part);
    for (std::string& cell : cells(part.stats)) row.push_back(std::move(cell));
    table.add(std::move(row));
  }
  table.rule();
  std::vector<std::string> row{"total", ""};
  for (std::string& cell : cells(report.total)) row.push_back(std::move(cell));
  table.add(std::move(row));
}

std::string edgeList(const std::vector<EdgeExample>& examples) {
  std::string text;
  for (const EdgeExample& example : examples) {
    text += "\n      nodes " + std::to_string(example.nodes[0]) + "-" +
            std::to_string(example.nodes[1]) + ": shells";
    for (const Id shell : example.shells) text += " " + std::to_string(shell);
  }
  return text;
}

std::string idList(const std::vector<Id>& ids, std::size_t total) {
  if (ids.empty()) return {};
  std::string text = "\n      ";
  for (std::size_t i = 0; i < ids.size(); ++i) text += (i ? " " : "") + std::to_string(ids[i]);
  if (total > ids.size()) text += " ...";
  return text;
}

std::string more(std::size_t shown, std::size_t total) {
  return total > shown ? "\n      ..." : "";
}

// ---------------------------------------------------------------------------------------------
// JSON

void appendJsonNumber(std::string& out, double value) {
  if (std::isfinite(value))
    io::appendShortest(out, value);
  else
    out += "null";
}

// Writes objects and arrays with commas and indentation; keys appear in call order.
class JsonWriter {
 public:
  explicit JsonWriter(std::string& out) : out_(out) {}

  void beginObject() { open('{'); }
  void endObject() { close('}'); }
  void beginArray() { open('['); }
  void endArray() { close(']'); }
  void key(std::string_view name) {
    separate();
    json::appendJsonString(out_, name);
    out_ += ": ";
    afterKey_ = true;
  }
  void value(std::size_t number) { scalar(std::to_string(number)); }
  void value(Id number) { scalar(std::to_string(number)); }
  void value(double number) {
    std::string text;
    appendJsonNumber(text, number);
    scalar(text);
  }
  void value(bool flag) { scalar(flag ? "true" : "false"); }
  void value(std::string_view text) {
    std::string literal;
    json::appendJsonString(literal, text);
    scalar(literal);
  }
  void null() { scalar("null"); }
  // An array of numbers on one line.
  template <typename T>
  void inlineArray(const T& values) {
    separate();
    out_ += '[';
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i) out_ += ", ";
      if constexpr (std::is_floating_point_v<typename T::value_type>)
        appendJsonNumber(out_, values[i]);
      else
        out_ += std::to_string(values[i]);
    }
    out_ += ']';
  }

 private:
  void separate() {
    if (afterKey_) {
      afterKey_ = false;
      return;
    }
    if (!first_.empty()) {
      if (!first_.back()) out_ += ',';
      first_.back() = false;
      out_ += '\n';
      out_.append(2 * first_.size(), ' ');
    }
  }
  void scalar(const std::string& text) {
    separate();
    out_ += text;
  }
  void open(char bracket) {
    separate();
    out_ += bracket;
    first_.push_back(true);
  }
  void close(char bracket) {
    const bool empty = first_.back();
    first_.pop_back();
    if (!empty) {
      out_ += '\n';
      out_.append(2 * first_.size(), ' ');
    }
    out_ += bracket;
  }

  std::string& out_;
  std::vector<bool> first_;  // per open container: nothing written into it yet
  bool afterKey_ = false;
};

void writeStats(JsonWriter& json, const MeshStats& stats) {
  json.key("nodes");
  json.value(stats.nodes);
  json.key("quads");
  json.value(stats.quads);
  json.key("trias");
  json.value(stats.trias);
  json.key("boundingBox");
  if (stats.box.empty()) {
    json.null();
  } else {
    json.beginObject();
    json.key("min");
    json.inlineArray(stats.box.min);
    json.key("max");
    json.inlineArray(stats.box.max);
    json.endObject();
  }
  json.key("edgeLength");
  if (stats.edgeLength.count == 0) {
    json.null();
  } else {
    json.beginObject();
    json.key("min");
    json.value(stats.edgeLength.min);
    json.key("median");
    json.value(stats.edgeLength.median);
    json.key("max");
    json.value(stats.edgeLength.max);
    json.key("sides");
    json.value(stats.edgeLength.count);
    json.endObject();
  }
  const std::pair<const char*, std::size_t> counts[] = {
      {"edges", stats.edges},
      {"boundaryEdges", stats.boundaryEdges},
      {"boundaryLoops", stats.boundaryLoops},
      {"openBoundaryChains", stats.openBoundaryChains},
      {"nonManifoldEdges", stats.nonManifoldEdges},
      {"inconsistentEdges", stats.inconsistentEdges},
      {"duplicateNodes", stats.duplicateNodes},
      {"freeElements", stats.freeElements},
      {"degenerateElements", stats.degenerateElements},
  };
  for (const auto& [name, value] : counts) {
    json.key(name);
    json.value(value);
  }
}

void writeEdgeExamples(JsonWriter& json, const std::vector<EdgeExample>& examples) {
  json.beginArray();
  for (const EdgeExample& example : examples) {
    json.beginObject();
    json.key("nodes");
    json.inlineArray(example.nodes);
    json.key("shells");
    json.inlineArray(example.shells);
    json.endObject();
  }
  json.endArray();
}

}  // namespace

std::string formatReportTable(const DeckReport& report) {
  const MeshStats& total = report.total;
  std::string out;
  out += "Deck report: " + count(report.parts.size()) + " part(s), " + count(total.shells()) +
         " shells (" + count(total.quads) + " quads, " + count(total.trias) + " trias), " +
         count(report.modelNodes) + " nodes (" + count(report.unusedNodes) +
         " not used by shells)\n\n";

  out += "Sizes (edge lengths over the element sides)\n";
  Table sizes({"PID", "name", "nodes", "quads", "trias", "edge min", "median", "max"}, 2);
  addRows(sizes, report, [](const MeshStats& s) {
    const bool any = s.edgeLength.count > 0;
    return std::vector<std::string>{count(s.nodes),
                                    count(s.quads),
                                    count(s.trias),
                                    any ? real(s.edgeLength.min, 4) : "-",
                                    any ? real(s.edgeLength.median, 4) : "-",
                                    any ? real(s.edgeLength.max, 4) : "-"};
  });
  sizes.render(out);

  out += "\nBounding boxes\n";
  Table boxes({"PID", "name", "min x", "min y", "min z", "max x", "max y", "max z"}, 2);
  addRows(boxes, report, [](const MeshStats& s) {
    std::vector<std::string> cells;
    for (const auto* corner : {&s.box.min, &s.box.max})
      for (int k = 0; k < 3; ++k) cells.push_back(s.box.empty() ? "-" : real((*corner)[k], 7));
    return cells;
  });
  boxes.render(out);

  out += "\nTopology\n";
  Table topology({"PID", "name", "edges", "boundary", "loops", "open", "non-manif.", "inconsist.",
                  "dup. nodes", "free", "degenerate"},
                 2);
  addRows(topology, report, [](const MeshStats& s) {
    return std::vector<std::string>{count(s.edges),
                                    count(s.boundaryEdges),
                                    count(s.boundaryLoops),
                                    count(s.openBoundaryChains),
                                    count(s.nonManifoldEdges),
                                    count(s.inconsistentEdges),
                                    count(s.duplicateNodes),
                                    count(s.freeElements),
                                    count(s.degenerateElements)};
  });
  topology.render(out);

  const ReportExamples& ex = report.examples;
  out += "\nFindings (whole model)\n";
  out += "  - boundary: " + count(total.boundaryEdges) + " edge(s) in " +
         count(total.boundaryLoops) + " closed loop(s)";
  if (total.openBoundaryChains > 0)
    out +=
        " and " + count(total.openBoundaryChains) + " open chain(s) ending at non-manifold edges";
  out += "\n";
  out += "  - non-manifold edges (3 or more shells on one edge): " + count(total.nonManifoldEdges) +
         edgeList(ex.nonManifoldEdges) + more(ex.nonManifoldEdges.size(), total.nonManifoldEdges) +
         "\n";
  const std::size_t flipped = total.inconsistentEdges - total.nonManifoldEdges;
  out += "  - edges with inconsistent orientation: " + count(total.inconsistentEdges);
  if (total.inconsistentEdges > 0)
    out += " (" + count(flipped) + " between two shells with opposite normals, plus the " +
           count(total.nonManifoldEdges) + " non-manifold edges)";
  out += edgeList(ex.inconsistentEdges) + more(ex.inconsistentEdges.size(), flipped) + "\n";
  out += "  - duplicate nodes (distinct IDs within " + real(report.tolerance, 6) +
         "; nodes a merge would remove): " + count(total.duplicateNodes);
  for (const NodePairExample& pair : ex.duplicateNodes)
    out += "\n      nodes " + std::to_string(pair.nodes[0]) + " and " +
           std::to_string(pair.nodes[1]) + " (distance " + real(pair.distance, 3) + ")";
  out += more(ex.duplicateNodes.size(), total.duplicateNodes) + "\n";
  out += "  - unused nodes (no shell uses them): " + count(report.unusedNodes);
  if (report.unusedNodes > 0)
    out +=
        " (they may belong to other elements such as SPH particles, beams or solids, or to "
        "other keywords, and are kept)";
  out += idList(ex.unusedNodes, report.unusedNodes) + "\n";
  out += "  - free elements (sharing no node with another shell): " + count(total.freeElements) +
         idList(ex.freeElements, total.freeElements) + "\n";
  out += "  - degenerate elements (zero area): " + count(total.degenerateElements) +
         idList(ex.degenerateElements, total.degenerateElements) + "\n";
  return out;
}

std::string formatReportJson(const DeckReport& report) {
  std::string out;
  JsonWriter json(out);
  json.beginObject();
  json.key("model");
  json.beginObject();
  json.key("nodes");
  json.value(report.modelNodes);
  json.key("unusedNodes");
  json.value(report.unusedNodes);
  json.key("shells");
  json.value(report.total.shells());
  json.key("parts");
  json.value(report.parts.size());
  json.key("tolerance");
  json.value(report.tolerance);
  json.endObject();

  json.key("parts");
  json.beginArray();
  for (const PartReport& part : report.parts) {
    json.beginObject();
    json.key("id");
    json.value(part.id);
    json.key("name");
    json.value(std::string_view(part.name));
    json.key("defined");
    json.value(part.defined);
    writeStats(json, part.stats);
    json.endObject();
  }
  json.endArray();

  json.key("total");
  json.beginObject();
  writeStats(json, report.total);
  json.endObject();

  const ReportExamples& ex = report.examples;
  json.key("examples");
  json.beginObject();
  json.key("nonManifoldEdges");
  writeEdgeExamples(json, ex.nonManifoldEdges);
  json.key("inconsistentEdges");
  writeEdgeExamples(json, ex.inconsistentEdges);
  json.key("duplicateNodes");
  json.beginArray();
  for (const NodePairExample& pair : ex.duplicateNodes) {
    json.beginObject();
    json.key("nodes");
    json.inlineArray(pair.nodes);
    json.key("distance");
    json.value(pair.distance);
    json.endObject();
  }
  json.endArray();
  json.key("unusedNodes");
  json.inlineArray(ex.unusedNodes);
  json.key("freeElements");
  json.inlineArray(ex.freeElements);
  json.key("degenerateElements");
  json.inlineArray(ex.degenerateElements);
  json.endObject();
  json.endObject();
  out += '\n';
  return out;
}

}  // namespace voxremesh
