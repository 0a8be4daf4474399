// formatComparisonTable, formatComparisonJson: a DeckComparison in words and as JSON
// (deck_compare.h).
#include <cmath>
#include <cstdio>
#include <string>

#include "geometry/vec3.h"
#include "io/text_scan.h"
#include "json/json.h"
#include "voxremesh/deck_compare.h"

namespace voxremesh {

namespace {

double length(const std::array<double, 3>& v) {
  return geom::norm(v);
}

/// A share in percent, or "-" without a whole.
std::string percent(double part, double whole) {
  if (whole <= 0.0) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f %%", 100.0 * part / whole);
  return buffer;
}

}  // namespace

std::string formatComparisonTable(const DeckComparison& c) {
  std::string out;
  char line[256];
  out += "  part   shells before  after    area before        after   change\n";
  for (const PartComparison& p : c.parts) {
    std::snprintf(line, sizeof line, "  %-6lld %13zu %6zu %14.6g %12.6g %8s\n",
                  static_cast<long long>(p.part), p.shellsBefore, p.shellsAfter, p.areaBefore,
                  p.areaAfter, percent(p.areaAfter - p.areaBefore, p.areaBefore).c_str());
    out += line;
  }
  out += "\n  seam (parts)      shared nodes before  after\n";
  for (const SeamComparison& s : c.seams) {
    std::snprintf(line, sizeof line, "  %6lld - %-6lld %23zu %6zu\n",
                  static_cast<long long>(s.first), static_cast<long long>(s.second), s.before,
                  s.after);
    out += line;
  }
  std::snprintf(line, sizeof line, "  T-junction edges: %zu before, %zu after\n",
                c.tJunctionEdgesBefore, c.tJunctionEdgesAfter);
  out += line;
  std::snprintf(line, sizeof line,
                "  nodes inside an edge of a part they share a seam with: %zu before, %zu after\n",
                c.hangingNodesBefore, c.hangingNodesAfter);
  out += line;
  std::snprintf(line, sizeof line,
                "\nhard points: %zu, %zu missing, %zu moved (largest move %.6g)\n", c.hardPoints,
                c.hardPointsMissing, c.hardPointsMoved, c.largestHardPointMove);
  out += line;
  if (!c.sets.empty()) {
    out +=
        "\n  node set (keyword, line)            members before  after  repeated  area before"
        "      after\n";
    for (const SetComparison& s : c.sets) {
      std::snprintf(line, sizeof line, "  %-28s %6zu %15zu %6zu %9zu %12.6g %10.6g\n",
                    s.keyword.c_str(), s.line, s.membersBefore, s.membersAfter, s.repeatedAfter,
                    s.areaBefore, s.areaAfter);
      out += line;
    }
  }
  if (!c.coverage.empty()) {
    out += "\n  per-node data                  part   covered before         after\n";
    for (const CoverageComparison& r : c.coverage) {
      std::snprintf(line, sizeof line, "  %-28s %6lld %7zu of %-6zu %6zu of %-6zu\n",
                    r.keyword.c_str(), static_cast<long long>(r.part), r.coveredBefore,
                    r.nodesBefore, r.coveredAfter, r.nodesAfter);
      out += line;
    }
  }
  if (c.loadCardsBefore + c.loadCardsAfter > 0) {
    std::snprintf(line, sizeof line,
                  "\npressure load (PLOAD4): %zu cards before, %zu after; total force %.6g "
                  "before, %.6g after\n",
                  c.loadCardsBefore, c.loadCardsAfter, length(c.forceBefore), length(c.forceAfter));
    out += line;
  }
  std::snprintf(line, sizeof line, "dangling references: %zu\n", c.dangling.size());
  out += line;
  for (std::size_t i = 0; i < c.dangling.size() && i < 10; ++i) {
    const DanglingReference& d = c.dangling[i];
    std::snprintf(line, sizeof line, "  %s, line %zu of its block: %s %lld\n", d.keyword.c_str(),
                  d.line, d.element ? "shell" : "node", static_cast<long long>(d.id));
    out += line;
  }
  if (c.losses.empty()) return out + "\nnothing lost\n";
  out += "\nlost:\n";
  for (const std::string& loss : c.losses) out += "  " + loss + "\n";
  return out;
}

std::string formatComparisonJson(const DeckComparison& c) {
  std::string out = "{\n  \"parts\": [";
  const auto number = [&](const char* key, double value, bool comma = true) {
    out += std::string("\"") + key + "\": ";
    if (std::isfinite(value))
      io::appendShortest(out, value);
    else
      out += "null";
    if (comma) out += ", ";
  };
  for (std::size_t i = 0; i < c.parts.size(); ++i) {
    const PartComparison& p = c.parts[i];
    out += i ? ",\n    {" : "\n    {";
    number("part", double(p.part));
    number("shells_before", double(p.shellsBefore));
    number("shells_after", double(p.shellsAfter));
    number("area_before", p.areaBefore);
    number("area_after", p.areaAfter, false);
    out += "}";
  }
  out += "\n  ],\n  \"seams\": [";
  for (std::size_t i = 0; i < c.seams.size(); ++i) {
    const SeamComparison& s = c.seams[i];
    out += i ? ",\n    {" : "\n    {";
    out += "\"parts\": [" + std::to_string(s.first) + ", " + std::to_string(s.second) + "], ";
    number("shared_nodes_before", double(s.before));
    number("shared_nodes_after", double(s.after), false);
    out += "}";
  }
  out += "\n  ],\n  ";
  number("t_junction_edges_before", double(c.tJunctionEdgesBefore));
  number("t_junction_edges_after", double(c.tJunctionEdgesAfter));
  number("hanging_nodes_before", double(c.hangingNodesBefore));
  number("hanging_nodes_after", double(c.hangingNodesAfter));
  out += "\n  ";
  number("hard_points", double(c.hardPoints));
  number("hard_points_missing", double(c.hardPointsMissing));
  number("hard_points_moved", double(c.hardPointsMoved));
  number("largest_hard_point_move", c.largestHardPointMove);
  out += "\n  \"sets\": [";
  for (std::size_t i = 0; i < c.sets.size(); ++i) {
    const SetComparison& s = c.sets[i];
    out += i ? ",\n    {" : "\n    {";
    out += "\"keyword\": " + json::quote(s.keyword) + ", ";
    number("line", double(s.line));
    number("members_before", double(s.membersBefore));
    number("members_after", double(s.membersAfter));
    number("repeated_before", double(s.repeatedBefore));
    number("repeated_after", double(s.repeatedAfter));
    number("area_before", s.areaBefore);
    number("area_after", s.areaAfter, false);
    out += "}";
  }
  out += "\n  ],\n  \"coverage\": [";
  for (std::size_t i = 0; i < c.coverage.size(); ++i) {
    const CoverageComparison& r = c.coverage[i];
    out += i ? ",\n    {" : "\n    {";
    out += "\"keyword\": " + json::quote(r.keyword) + ", ";
    number("part", double(r.part));
    number("nodes_before", double(r.nodesBefore));
    number("covered_before", double(r.coveredBefore));
    number("nodes_after", double(r.nodesAfter));
    number("covered_after", double(r.coveredAfter), false);
    out += "}";
  }
  out += "\n  ],\n  ";
  number("load_cards_before", double(c.loadCardsBefore));
  number("load_cards_after", double(c.loadCardsAfter));
  number("total_force_before", length(c.forceBefore));
  number("total_force_after", length(c.forceAfter));
  number("total_force_change",
         length({c.forceAfter[0] - c.forceBefore[0], c.forceAfter[1] - c.forceBefore[1],
                 c.forceAfter[2] - c.forceBefore[2]}));
  number("dangling_references", double(c.dangling.size()), false);
  out += ",\n  \"losses\": [";
  for (std::size_t i = 0; i < c.losses.size(); ++i)
    out += std::string(i ? ", " : "") + json::quote(c.losses[i]);
  return out + "]\n}\n";
}

}  // namespace voxremesh
