// voxremesh remesh: the main job; every selected part of a deck remeshed through its volume and
// put back (pipeline.h), with a progress line and a summary.
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/progress.h"
#include "voxremesh/remesh_quality.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage =
    "voxremesh remesh IN -o OUT [--size H] [--parts P1,P2,...] [--feature-angle DEG]\n"
    "       [--threads N] [--report REPORT.json] [--vtu QUALITY.vtu] [--no-optimize] [--quiet]";

const char* const kHelp =
    "Remeshes every shell part of IN (or those of --parts) through a narrow-band volume: sheets,\n"
    "signed distance (one volume per sheet), dual quads with the boundary strip and feature\n"
    "snapping, sheets joined again at their junctions, then quad optimisation (clean-up, rhombic\n"
    "collapse, relaxation on the original surface, triangle merging, searches and reconnections\n"
    "round failing elements, warping removal, failing quads split into triangle pairs while\n"
    "triangles stay at or under 3 %); parts in parallel.\n"
    "Every other part, element and keyword is written back untouched; new node and element IDs\n"
    "lie above all IDs of IN; keywords naming nodes of a remeshed part are remapped to the\n"
    "nearest new node (listed in --report; what cannot be remapped is printed as a warning and\n"
    "its node kept). The output format follows OUT's extension. The summary gives per part the\n"
    "elements before and after, the elements failing a quality criterion at the default limits\n"
    "(voxremesh help quality; length and distance limits scale with the part's size), the\n"
    "largest two-sided distance to the original shells and the time.\n"
    "\n"
    "options:\n"
    "  -o OUT                 the deck to write (required)\n"
    "  --size H               target element size (default: per part, its median edge length)\n"
    "  --parts P1,P2,...      the parts to remesh (default: all parts with shells)\n"
    "  --feature-angle DEG    edges turning more than DEG are feature lines (default 45)\n"
    "  --threads N            threads (default: all cores)\n"
    "  --report REPORT.json   per part counts and times, every node reference remapped\n"
    "  --vtu QUALITY.vtu      the remeshed elements with every quality metric, a failure bit\n"
    "                         mask and a pass flag as cell data, and each node's distance to\n"
    "                         the original as point data (as voxremesh quality --vtu)\n"
    "  --no-optimize          write the extracted quads without the optimisation\n"
    "  --quiet                no progress line (it shows on a terminal only anyway)\n";

std::vector<Id> parseParts(const std::string& text) {
  std::vector<Id> parts;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string item =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    parts.push_back(parseInteger("--parts", item));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return parts;
}

/// The per-part table: elements before and after, quads and trias, size, quality failures and
/// their share, the largest distance to the original, and the part's time (all stages).
std::string remeshSummary(const RemeshReport& report, const std::vector<PartQuality>& quality) {
  std::string text =
      "  part   before    after    quads   trias     size   failing    share   max dist   time s\n";
  char line[256];
  for (std::size_t i = 0; i < report.parts.size(); ++i) {
    const RemeshedPart& part = report.parts[i];
    const PartQuality& q = quality[i];
    std::snprintf(
        line, sizeof line, "  %-6lld %6zu %8zu %8zu %7zu %8.4g %9zu %6.2f %% %10.4g %8.2f\n",
        static_cast<long long>(part.plan.part), q.elementsBefore, q.elementsAfter, part.quads,
        part.trias, part.plan.targetSize, q.failing(), 100.0 * q.failingShare(), q.maxDistance(),
        part.volumeSeconds + part.extractSeconds + part.optimizeSeconds);
    text += line;
  }
  return text;
}

/// The last line: totals over the parts.
std::string formatRemeshTotals(const std::string& output, const RemeshReport& report,
                               const std::vector<PartQuality>& quality, double seconds) {
  std::size_t before = 0, after = 0, failing = 0;
  double distance = 0.0;
  for (const PartQuality& q : quality) {
    before += q.elementsBefore;
    after += q.elementsAfter;
    failing += q.failing();
    distance = std::max(distance, q.maxDistance());
  }
  char line[512];
  std::snprintf(line, sizeof line,
                "wrote %s: %zu parts remeshed, %zu -> %zu elements, %zu failing a quality "
                "criterion (%.2f %%), max distance to the original %.4g, %zu node references "
                "remapped, %zu not remappable, %.2f s\n",
                output.c_str(), report.parts.size(), before, after, failing,
                after ? 100.0 * double(failing) / double(after) : 0.0, distance,
                report.assembly.remaps.size(), report.assembly.unmapped.size(), seconds);
  return line;
}

}  // namespace

int runRemesh(const std::vector<std::string>& args) {
  if (wantsHelp(args)) {
    std::printf("usage: %s\n\n%s", kUsage, kHelp);
    return 0;
  }
  const auto start = std::chrono::steady_clock::now();
  const ParsedArgs parsed = parseArgs(args,
                                      {{"-o", true},
                                       {"--size", true},
                                       {"--parts", true},
                                       {"--feature-angle", true},
                                       {"--threads", true},
                                       {"--report", true},
                                       {"--vtu", true},
                                       {"--no-optimize", false},
                                       {"--quiet", false}},
                                      1, 1, kUsage);
  const auto output = parsed.value("-o");
  if (!output || output->empty()) throw UsageError("missing -o OUT", kUsage);
  RemeshSettings settings;
  if (const auto size = parsed.value("--size")) settings.targetSize = parseNumber("--size", *size);
  if (settings.targetSize < 0) throw SettingError("--size must be positive");
  if (const auto parts = parsed.value("--parts")) settings.parts = parseParts(*parts);
  settings.optimize = !parsed.has("--no-optimize");
  if (const auto angle = parsed.value("--feature-angle"))
    settings.sheets.featureAngleDeg = parseNumber("--feature-angle", *angle);
  if (const auto threads = parsed.value("--threads")) {
    const long long value = parseInteger("--threads", *threads);
    if (value < 0 || value > 4096) throw SettingError("--threads must be within 0..4096");
    settings.threads = static_cast<int>(value);
  }
  formatFromPath(*output);  // an unknown extension fails before any work
  const auto vtu = parsed.value("--vtu");
  if (vtu && formatFromPath(*vtu) != DeckFormat::Vtu)
    throw SettingError("--vtu needs a .vtu file, not " + *vtu);

  Warnings warnings;
  FeModel deck = readDeck(parsed.positional[0], {}, &warnings);
  printWarnings(warnings);
  const FeModel original = deck;
  ProgressLine progress(stderr, ProgressLine::isTerminal(stderr) && !parsed.has("--quiet"));
  const RemeshReport report =
      remeshDeck(deck, settings, [&](const std::string& stage, Id part, double done) {
        progress.update(stage, part ? "part " + std::to_string(part) : "deck", done);
      });
  progress.update("quality", "deck", 1.0);
  std::vector<PartQuality> quality;
  tbb::task_arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic)
      .execute([&] { quality = assessRemeshedParts(original, deck, report); });
  warnings.clear();
  writeDeck(deck, *output, {}, &warnings);
  if (vtu) writeRemeshQualityVtu(deck, quality, *vtu);
  if (const auto path = parsed.value("--report")) writeRemeshReport(report, *path);
  progress.clear();
  for (const UnmappedReference& ref : report.assembly.unmapped)
    warnings.push_back(ref.keyword + " (" +
                       (ref.blockLine ? "line " + std::to_string(ref.line) + " of its block"
                                      : (ref.file.empty() ? "" : ref.file + " ") + "line " +
                                            std::to_string(ref.line)) +
                       "): node " + std::to_string(ref.node) + " kept: " + ref.reason);
  printWarnings(warnings);

  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  printOutput(remeshSummary(report, quality) +
              formatRemeshTotals(*output, report, quality, seconds));
  return 0;
}

}  // namespace voxremesh::cli
