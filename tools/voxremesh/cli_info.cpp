// voxremesh info: the mesh report of a deck, as tables or JSON.
#include <cstdio>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/deck_report.h"
#include "voxremesh/io.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage = "voxremesh info DECK [--json] [--format F] [--tolerance T]";

const char* const kHelp =
    "Reads a deck or mesh file and reports, per part and in total: nodes, quads, trias, bounding\n"
    "box, edge lengths, boundary edges and loops, non-manifold edges, edges with inconsistent\n"
    "orientation, duplicate (coincident) nodes, unused nodes, free and degenerate elements.\n"
    "Warnings about the input go to stderr, the report to stdout.\n"
    "\n"
    "options:\n"
    "  --json          print the report as JSON instead of tables\n"
    "  --format F      read DECK as format F instead of guessing it from the extension\n"
    "                  (k, lsdyna, bdf, nastran, inp, abaqus, obj, off, stl, ply)\n"
    "  --tolerance T   distance under which two nodes coincide, and height under which an\n"
    "                  element is degenerate (model units; default 1e-6 x the diagonal of the\n"
    "                  bounding box of the shells)\n";

}  // namespace

int runInfo(const std::vector<std::string>& args) {
  if (wantsHelp(args)) {
    std::printf("usage: %s\n\n%s", kUsage, kHelp);
    return 0;
  }
  const ParsedArgs parsed =
      parseArgs(args, {{"--json", false}, {"--format", true}, {"--tolerance", true}}, 1, 1, kUsage);
  ReadOptions readOptions;
  ReportSettings settings;
  parseOptionValues(kUsage, [&] {
    if (const auto format = parsed.value("--format")) readOptions.format = formatFromName(*format);
    if (const auto tolerance = parsed.value("--tolerance")) {
      settings.tolerance = parseNumber("--tolerance", *tolerance);
      if (*settings.tolerance < 0.0)
        throw SettingError("--tolerance must be zero or positive, not " + *tolerance);
    }
  });

  const std::string& path = parsed.positional[0];
  Warnings warnings;
  const FeModel model = readDeck(path, readOptions, &warnings);
  printWarnings(warnings);
  const DeckReport report = reportDeck(model, settings);
  if (parsed.has("--json")) {
    printOutput(formatReportJson(report));
  } else {
    printOutput(path + " (" + formatName(model.sourceFormat) + ")\n\n" + formatReportTable(report));
  }
  return 0;
}

}  // namespace voxremesh::cli
