// voxremesh remesh: the main job; every selected part of a deck remeshed through its volume and
// put back (pipeline.h), with a progress line and a summary.
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/criteria_file.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/progress.h"
#include "voxremesh/remesh_quality.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage =
    "voxremesh remesh IN -o OUT [--size H] [--part-size PID=H,...] [--parts P1,P2,...]\n"
    "       [--feature-angle DEG] [--retries N] [--threads N] [--report REPORT.json]\n"
    "       [--vtu QUALITY.vtu] [--criteria FILE] [--no-optimize] [--quiet]";

const char* const kHelp =
    "Remeshes every shell part of IN (or those of --parts) through a narrow-band volume: sheets,\n"
    "signed distance (one volume per sheet), dual quads with the boundary strip and feature\n"
    "snapping, sheets joined again at their junctions, then quad optimisation (clean-up, rhombic\n"
    "collapse, relaxation on the original surface, triangle merging, searches and reconnections\n"
    "round failing elements, warping removal, folds cut out and refilled, failing quads split\n"
    "into triangle pairs while triangles stay at or under 3 % (on sheets meshed from their\n"
    "boundary: whatever the share), folds they leave cut out again); parts in parallel.\n"
    "Every other part, element and keyword is written back untouched; new node and element IDs\n"
    "lie above all IDs of IN. Hard points, nodes that other keywords use as points (beam, mass,\n"
    "spring and rigid element ends, welds, point loads, SPC and history nodes), stay nodes of the\n"
    "new mesh with their ID and coordinates; a part whose mesh cannot keep them is kept. Node\n"
    "sets and per-node data name regions: they cover the same region of the new mesh (a data\n"
    "line repeated per new node; listed in --report; what cannot be rewritten, such as a range,\n"
    "is printed as a warning and its node kept).\n"
    "Seams stay shared: a seam to a part that is kept keeps every node of that part's side.\n"
    "The output format follows OUT's extension.\n"
    "Each part ends remeshed (its mesh passed the acceptance), retried (passed at a finer voxel,\n"
    "or last from its sheets' boundaries) or kept (its original shells written back unchanged,\n"
    "with the reason). Acceptance: distance to the original within 0.25 x size (sampled inside\n"
    "faces), no folded element, no quad corner of 180 degrees, all hard points kept, as many\n"
    "connected pieces and boundary loops as the original part (its coincident nodes merged), its\n"
    "area (mass) within 1 %, and at most 5 % of the elements failing a quality criterion\n"
    "(voxremesh help quality; distance and folds count). A sheet\n"
    "narrower than 3 sizes is meshed from its boundary, with rows of quads along it, else\n"
    "through a finer voxel (a warning says when sizes were reduced). The\n"
    "summary gives per part the status, elements before and after, size used, failing share,\n"
    "distance and time. Exit code: 0 when every part was remeshed or retried, 3 when some were\n"
    "kept, 1 for errors (nothing is written), 2 for a malformed command line.\n"
    "\n"
    "options:\n"
    "  -o OUT                 the deck to write (required)\n"
    "  --size H               target element size (default: the deck's median edge length)\n"
    "  --part-size PID=H,...  other target sizes for some parts\n"
    "  --retries N            finer retries of a part that misses the acceptance (half the voxel\n"
    "                         and the spacing of boundary-meshed sheets; with 1 or more, a part\n"
    "                         kept with neighbours being remeshed is tried at half its size with\n"
    "                         them, its seams refined too), 0..8 (2: down to 1/4 of the size)\n"
    "  --parts P1,P2,...      the parts to remesh (default: all parts with shells)\n"
    "  --feature-angle DEG    edges turning more than DEG are feature lines (default 45)\n"
    "  --threads N            threads, 0..4096 (default and 0: all cores)\n"
    "  --report REPORT.json   per part counts and times, every node reference remapped\n"
    "  --vtu QUALITY.vtu      the remeshed elements with every quality metric, a failure bit\n"
    "                         mask and a pass flag as cell data, and each node's distance to\n"
    "                         the original as point data (as voxremesh quality --vtu)\n"
    "  --criteria FILE        the quality limits the optimisation and the acceptance use, and\n"
    "                         the quality index's thresholds and weights (format:\n"
    "                         include/voxremesh/criteria_file.h; the defaults:\n"
    "                         share/criteria/default.txt)\n"
    "  --no-optimize          write the extracted quads without the optimisation\n"
    "  --quiet                no progress line (it shows on a terminal only anyway)\n";

/// Parses a part ID given in `option`. Throws SettingError naming the option when `text` is not a
/// whole number of at least 1 (part IDs are positive, as the readers require).
Id parsePartId(const std::string& option, const std::string& text) {
  const long long value = parseInteger(option, text);
  if (value < 1) throw SettingError(option + " expects a positive part ID, not '" + text + "'");
  return static_cast<Id>(value);
}

/// Parses --parts P1,P2,... Throws SettingError for an item that is not a positive part ID.
std::vector<Id> parseParts(const std::string& text) {
  std::vector<Id> parts;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string item =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    parts.push_back(parsePartId("--parts", item));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return parts;
}

/// The per-part table: status, elements before and after, quads and trias, the size the mesh
/// was judged at, failing share, distance, folds and the part's time (all stages); a kept part's
/// figures are those of its original shells, which it writes back (keptPartQuality). Then the
/// reason of every kept part and of every reduced voxel.
std::string remeshSummary(const RemeshReport& report) {
  std::string text =
      "  part     status   before    after   trias      size   failing   distance  folded   "
      "time s\n";
  char line[256];
  std::string reasons;
  for (const RemeshedPart& part : report.parts) {
    const PartAcceptance& a = part.acceptance;
    const bool kept = part.status == PartStatus::Kept;
    std::snprintf(
        line, sizeof line, "  %-8lld %-8s %6zu %8zu %7zu %9.4g %7.2f %% %10.4g %7zu %8.2f\n",
        static_cast<long long>(part.plan.part), partStatusName(part.status), part.plan.shells,
        kept ? part.plan.shells : a.elements, a.trias, kept ? part.plan.targetSize : part.voxelSize,
        100.0 * a.failingShare, kept ? 0.0 : a.distance, a.folded, part.totalSeconds);
    text += line;
    if (!part.reason.empty())
      reasons += "  part " + std::to_string(part.plan.part) + " " + partStatusName(part.status) +
                 ": " + part.reason + "\n";
  }
  return text + reasons;
}

/// The last line: totals over the parts.
std::string formatRemeshTotals(const std::string& output, const RemeshReport& report,
                               double seconds) {
  std::size_t before = 0, after = 0, failing = 0, keptFailing = 0;
  double distanceShare = 0.0;
  for (const RemeshedPart& part : report.parts) {
    before += part.plan.shells;
    if (part.status == PartStatus::Kept) {
      after += part.plan.shells;
      keptFailing += part.acceptance.failing;
      continue;
    }
    after += part.acceptance.elements;
    failing += part.acceptance.failing;
    distanceShare = std::max(distanceShare, part.acceptance.distance / part.plan.targetSize);
  }
  char line[512];
  std::snprintf(line, sizeof line,
                "wrote %s: %zu parts remeshed, %zu retried at a finer voxel, %zu kept; %zu -> %zu "
                "elements, %zu remeshed ones failing a criterion, %zu kept ones; largest distance "
                "%.3g x size; %zu hard points kept, %zu node references remapped, %zu not "
                "remappable, %.2f s\n",
                output.c_str(), report.count(PartStatus::Remeshed),
                report.count(PartStatus::Retried), report.count(PartStatus::Kept), before, after,
                failing, keptFailing, distanceShare, report.assembly.hardPointsKept,
                report.assembly.remaps.size(), report.assembly.unmapped.size(), seconds);
  return line;
}

/// Parses --part-size PID=H,PID=H. Throws SettingError for an item that is not a positive part ID,
/// '=' and a positive size.
std::map<Id, double> parsePartSizes(const std::string& text) {
  std::map<Id, double> sizes;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string item =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos)
      throw SettingError("--part-size takes PID=SIZE pairs separated by commas, not '" + item +
                         "'");
    const Id part = parsePartId("--part-size", item.substr(0, equals));
    const std::string sizeText = item.substr(equals + 1);
    const double size = parseNumber("--part-size", sizeText);
    if (!(size > 0))
      throw SettingError("--part-size: the size of part " + std::to_string(part) +
                         " must be positive, not " + sizeText);
    sizes[part] = size;
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return sizes;
}

/// The settings the options of `parsed` give (--size, --part-size, --parts, --retries,
/// --feature-angle, --threads, --no-optimize). Throws UsageError (exit 2) for a value that is not
/// a number of the right kind or lies outside its range: nothing has been read at that point.
RemeshSettings remeshSettings(const ParsedArgs& parsed) {
  RemeshSettings settings;
  settings.optimize = !parsed.has("--no-optimize");
  parseOptionValues(kUsage, [&] {
    if (const auto size = parsed.value("--size")) {
      settings.targetSize = parseNumber("--size", *size);
      if (settings.targetSize < 0)
        throw SettingError(
            "--size must be positive (or 0 for the deck's median edge length), not " + *size);
    }
    if (const auto parts = parsed.value("--parts")) settings.parts = parseParts(*parts);
    if (const auto sizes = parsed.value("--part-size")) settings.partSizes = parsePartSizes(*sizes);
    if (const auto retries = parsed.value("--retries"))
      settings.retries = static_cast<int>(parseIntegerInRange("--retries", *retries, 0, 8));
    if (const auto angle = parsed.value("--feature-angle"))
      settings.sheets.featureAngleDeg = parseAngle("--feature-angle", *angle);
    if (const auto threads = parsed.value("--threads"))
      settings.threads = static_cast<int>(parseIntegerInRange("--threads", *threads, 0, 4096));
  });
  return settings;
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
                                       {"--part-size", true},
                                       {"--retries", true},
                                       {"--parts", true},
                                       {"--feature-angle", true},
                                       {"--threads", true},
                                       {"--report", true},
                                       {"--vtu", true},
                                       {"--criteria", true},
                                       {"--no-optimize", false},
                                       {"--quiet", false}},
                                      1, 1, kUsage);
  const auto output = parsed.value("-o");
  if (!output || output->empty()) throw UsageError("missing -o OUT", kUsage);
  RemeshSettings settings = remeshSettings(parsed);
  if (const auto criteria = parsed.value("--criteria"))
    readCriteriaFile(*criteria, settings.optimizeSettings.quality);
  formatFromPath(*output);  // an unknown extension fails before any work
  const auto vtu = parsed.value("--vtu");
  refuseOverwritingInput(parsed.positional[0], *output, "-o");
  if (vtu) refuseOverwritingInput(parsed.positional[0], *vtu, "--vtu");
  if (const auto report = parsed.value("--report"))
    refuseOverwritingInput(parsed.positional[0], *report, "--report");
  if (vtu && formatFromPath(*vtu) != DeckFormat::Vtu)
    throw SettingError("--vtu needs a .vtu file, not " + *vtu);

  Warnings warnings;
  FeModel deck = readDeck(parsed.positional[0], {}, &warnings);
  printWarnings(warnings);
  std::optional<FeModel> original;  // the deck before remeshing, for --vtu's distances only
  if (vtu) original = deck;
  ProgressLine progress(stderr, ProgressLine::isTerminal(stderr) && !parsed.has("--quiet"));
  const RemeshReport report =
      remeshDeck(deck, settings, [&](const std::string& stage, Id part, double done) {
        progress.update(stage, part ? "part " + std::to_string(part) : "deck", done);
      });
  warnings.clear();
  writeDeck(deck, *output, {}, &warnings);
  try {  // the outputs are one result: none stays when one cannot be written
    if (vtu) {
      progress.update("quality", "deck", 1.0);
      std::vector<PartQuality> quality;
      tbb::task_arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic)
          .execute([&] {
            quality = assessRemeshedParts(*original, deck, report,
                                          settings.optimizeSettings.quality, settings.sheets);
          });
      writeRemeshQualityVtu(deck, quality, *vtu);
    }
    if (const auto path = parsed.value("--report")) writeRemeshReport(report, *path);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(*output, ignored);
    if (vtu) std::filesystem::remove(*vtu, ignored);
    throw;
  }
  progress.clear();
  for (const UnmappedReference& ref : report.assembly.unmapped)
    warnings.push_back(ref.keyword + " (" +
                       (ref.blockLine ? "line " + std::to_string(ref.line) + " of its block"
                                      : (ref.file.empty() ? "" : ref.file + " ") + "line " +
                                            std::to_string(ref.line)) +
                       "): node " + std::to_string(ref.node) + " kept: " + ref.reason);
  for (const RemeshedPart& part : report.parts)
    if (part.status != PartStatus::Kept && !part.reason.empty())
      warnings.push_back("part " + std::to_string(part.plan.part) + ": " + part.reason);
  for (const auto& [parts, count] : report.seamsBefore.sharedNodes)
    if (report.seamsAfter.sharedNodes.count(parts) == 0)
      warnings.push_back("parts " + std::to_string(parts.first) + " and " +
                         std::to_string(parts.second) + " shared " + std::to_string(count) +
                         " nodes and share none now");
  if (report.moreHangingNodes())
    warnings.push_back("nodes inside an edge of a part they share a seam with: " +
                       std::to_string(report.seamsAfter.hangingNodes) + " (" +
                       std::to_string(report.seamsBefore.hangingNodes) + " in the input)");
  printWarnings(warnings);

  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  printOutput(remeshSummary(report) + formatRemeshTotals(*output, report, seconds));
  return report.allAccepted() ? 0 : kExitShortfall;
}

}  // namespace voxremesh::cli
