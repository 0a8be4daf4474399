// voxremesh remesh: the main job; every selected part of a deck remeshed through its volume and
// put back (pipeline.h), with a progress line and a summary.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/progress.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage =
    "voxremesh remesh IN -o OUT [--size H] [--parts P1,P2,...] [--feature-angle DEG]\n"
    "       [--threads N] [--report REPORT.json] [--quiet]";

const char* const kHelp =
    "Remeshes every shell part of IN (or those of --parts) through a narrow-band volume: sheets,\n"
    "signed distance, dual quads with the boundary strip and feature snapping; parts in parallel.\n"
    "Every other part, element and keyword is written back untouched; new node and element IDs\n"
    "lie above all IDs of IN; keywords naming nodes of a remeshed part are remapped to the\n"
    "nearest new node (listed in --report; what cannot be remapped is printed as a warning and\n"
    "its node kept). The output format follows OUT's extension. (Optimisation and the quality\n"
    "report join when their stages land.)\n"
    "\n"
    "options:\n"
    "  -o OUT                 the deck to write (required)\n"
    "  --size H               target element size (default: per part, its median edge length)\n"
    "  --parts P1,P2,...      the parts to remesh (default: all parts with shells)\n"
    "  --feature-angle DEG    edges turning more than DEG are feature lines (default 30)\n"
    "  --threads N            threads (default: all cores)\n"
    "  --report REPORT.json   per part counts and times, every node reference remapped\n"
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
                                       {"--quiet", false}},
                                      1, 1, kUsage);
  const auto output = parsed.value("-o");
  if (!output || output->empty()) throw UsageError("missing -o OUT", kUsage);
  RemeshSettings settings;
  if (const auto size = parsed.value("--size")) settings.targetSize = parseNumber("--size", *size);
  if (settings.targetSize < 0) throw SettingError("--size must be positive");
  if (const auto parts = parsed.value("--parts")) settings.parts = parseParts(*parts);
  if (const auto angle = parsed.value("--feature-angle"))
    settings.sheets.featureAngleDeg = parseNumber("--feature-angle", *angle);
  if (const auto threads = parsed.value("--threads")) {
    const long long value = parseInteger("--threads", *threads);
    if (value < 0 || value > 4096) throw SettingError("--threads must be within 0..4096");
    settings.threads = static_cast<int>(value);
  }
  formatFromPath(*output);  // an unknown extension fails before any work

  Warnings warnings;
  FeModel deck = readDeck(parsed.positional[0], {}, &warnings);
  printWarnings(warnings);
  ProgressLine progress(stderr, ProgressLine::isTerminal(stderr) && !parsed.has("--quiet"));
  const RemeshReport report =
      remeshDeck(deck, settings, [&](const std::string& stage, Id part, double done) {
        progress.update(stage, part ? "part " + std::to_string(part) : "deck", done);
      });
  warnings.clear();
  writeDeck(deck, *output, {}, &warnings);
  if (const auto path = parsed.value("--report")) writeRemeshReport(report, *path);
  progress.clear();
  for (const UnmappedReference& ref : report.assembly.unmapped)
    warnings.push_back(ref.keyword + " (line " + std::to_string(ref.line) + "): node " +
                       std::to_string(ref.node) + " kept: " + ref.reason);
  printWarnings(warnings);

  std::string text = "  part   elements before   quads   trias   size   volume s   extract s\n";
  char line[256];
  std::size_t before = 0, after = 0;
  for (const RemeshedPart& part : report.parts) {
    std::snprintf(line, sizeof line, "  %-6lld %15zu %7zu %7zu %6.3g %10.2f %11.2f\n",
                  static_cast<long long>(part.plan.part), part.plan.shells, part.quads, part.trias,
                  part.plan.targetSize, part.volumeSeconds, part.extractSeconds);
    text += line;
    before += part.plan.shells;
    after += part.quads + part.trias;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::snprintf(line, sizeof line,
                "wrote %s: %zu parts remeshed, %zu -> %zu elements, %zu node references "
                "remapped, %zu not remappable, %.2f s\n",
                output->c_str(), report.parts.size(), before, after, report.assembly.remaps.size(),
                report.assembly.unmapped.size(), seconds);
  printOutput(text + line);
  return 0;
}

}  // namespace voxremesh::cli
