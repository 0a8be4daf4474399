// voxremesh quality: FE quality criteria of a deck's shells as a table, JSON, or .vtu cell data.
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "cli_common.h"
#include "voxremesh/criteria_file.h"
#include "voxremesh/io.h"
#include "voxremesh/quality.h"
#include "voxremesh/remesh_quality.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage =
    "voxremesh quality DECK [--original ORIG] [--json] [--vtu OUT.vtu] [--part PID] [--size H]\n"
    "       [--format F] [--criteria FILE] [limit options]\n"
    "       voxremesh quality --print-criteria [--criteria FILE] [limit options]";

const char* const kHelp =
    "Measures the FE quality of the shells of DECK (all parts, or --part PID): per element the\n"
    "warping angle, aspect ratio, interior angles, skew, Jacobian ratio, scaled Jacobian, taper "
    "and\n"
    "the minimum element length (LS-DYNA characteristic length); per mesh the share of trias and,\n"
    "with --original, the two-sided distance to the original surface. Prints a table (metric,\n"
    "limit, worst value, failing count and share). Definitions: include/voxremesh/quality.h.\n"
    "The mesh passes when at most --max-failing of its elements fail a criterion, none is folded\n"
    "or has a corner of 180 degrees, and the tria share and distance are within their limits.\n"
    "Exit code: 0 when it passes, 3 when it does not (the table's last line, \"pass\" in JSON);\n"
    "1 for unreadable input or bad limits, 2 for a malformed command line.\n"
    "\n"
    "options:\n"
    "  --original ORIG       the deck DECK was remeshed from (the same --part is taken from it)\n"
    "  --json                print the report as JSON\n"
    "  --vtu OUT.vtu         write the elements with every metric, a failure bit mask and a pass\n"
    "                        flag as cell data (and the distance to ORIG as point data)\n"
    "  --part PID            assess only this part's shells\n"
    "  --size H              target element size for the length and distance limits (default:\n"
    "                        the median edge length of the assessed shells)\n"
    "  --format F            read DECK and ORIG as format F instead of by extension\n"
    "  --criteria FILE       the limits, quality index thresholds and weights of a criteria file\n"
    "                        (format: include/voxremesh/criteria_file.h; the defaults:\n"
    "                        share/criteria/default.txt); the limit options below override it\n"
    "  --print-criteria      print the criteria in effect as a criteria file, and stop\n"
    "limits (defaults in brackets):\n"
    "  --warping DEG [15]  --aspect R [5]  --quad-min-angle DEG [45]  --quad-max-angle DEG [135]\n"
    "  --tria-min-angle DEG [30]  --tria-max-angle DEG [120]  --skew DEG [40]\n"
    "  --jacobian R [0.6]  --scaled-jacobian R [0.3]  --taper T [0.6]\n"
    "  --min-length F [0.5 x size]  --tria-share S [0.05]  --distance F [0.25 x size]\n"
    "  --degenerate-corner DEG [179]  --max-failing S [0.05]\n"
    "  --jacobian-at-gauss-points  the Jacobian ratio at the 2 x 2 Gauss points (HyperMesh's\n"
    "                        default) instead of the corners\n";

/// A limit option and the setting it overrides.
struct LimitOption {
  const char* name;
  double QualitySettings::*field;
};

const LimitOption kLimits[] = {
    {"--warping", &QualitySettings::maxWarpingDeg},
    {"--aspect", &QualitySettings::maxAspectRatio},
    {"--quad-min-angle", &QualitySettings::minQuadAngleDeg},
    {"--quad-max-angle", &QualitySettings::maxQuadAngleDeg},
    {"--tria-min-angle", &QualitySettings::minTriaAngleDeg},
    {"--tria-max-angle", &QualitySettings::maxTriaAngleDeg},
    {"--skew", &QualitySettings::maxSkewDeg},
    {"--jacobian", &QualitySettings::minJacobianRatio},
    {"--scaled-jacobian", &QualitySettings::minScaledJacobian},
    {"--taper", &QualitySettings::maxTaper},
    {"--min-length", &QualitySettings::minLengthFactor},
    {"--tria-share", &QualitySettings::maxTriangleShare},
    {"--distance", &QualitySettings::maxDistanceFactor},
    {"--degenerate-corner", &QualitySettings::degenerateCornerDeg},
    {"--max-failing", &QualitySettings::maxFailingShare},
    {"--size", &QualitySettings::targetSize},
};

}  // namespace

int runQuality(const std::vector<std::string>& args) {
  if (wantsHelp(args)) {
    std::printf("usage: %s\n\n%s", kUsage, kHelp);
    return 0;
  }
  const ParsedArgs parsed = parseArgs(args,
                                      {{"--original", true},
                                       {"--json", false},
                                       {"--vtu", true},
                                       {"--part", true},
                                       {"--format", true},
                                       {"--criteria", true},
                                       {"--print-criteria", false},
                                       {"--size", true},
                                       {"--warping", true},
                                       {"--aspect", true},
                                       {"--quad-min-angle", true},
                                       {"--quad-max-angle", true},
                                       {"--tria-min-angle", true},
                                       {"--tria-max-angle", true},
                                       {"--skew", true},
                                       {"--jacobian", true},
                                       {"--jacobian-at-gauss-points", false},
                                       {"--scaled-jacobian", true},
                                       {"--taper", true},
                                       {"--min-length", true},
                                       {"--tria-share", true},
                                       {"--distance", true},
                                       {"--degenerate-corner", true},
                                       {"--max-failing", true}},
                                      0, 1, kUsage);
  const bool printCriteria = parsed.has("--print-criteria");
  if (parsed.positional.size() != (printCriteria ? 0u : 1u))
    throw UsageError(printCriteria ? "--print-criteria takes no DECK" : "missing DECK", kUsage);

  QualitySettings settings;
  if (const auto criteria = parsed.value("--criteria")) readCriteriaFile(*criteria, settings);
  ReadOptions readOptions;
  Id part = 0;
  parseOptionValues(kUsage, [&] {
    for (const LimitOption& option : kLimits)
      if (const auto text = parsed.value(option.name))
        settings.*(option.field) = parseNumber(option.name, *text);
    // The length options are multiples of the size, whatever a criteria file said.
    if (parsed.value("--min-length")) settings.minLengthAbsolute = false;
    if (parsed.value("--distance")) settings.distanceAbsolute = false;
    if (parsed.has("--jacobian-at-gauss-points")) settings.jacobianAtGaussPoints = true;
    checkQualitySettings(settings);
    if (const auto format = parsed.value("--format")) readOptions.format = formatFromName(*format);
    if (const auto text = parsed.value("--part")) part = parseInteger("--part", *text);
  });
  if (printCriteria) {
    printOutput(formatCriteria(settings));
    return 0;
  }

  const std::string& path = parsed.positional[0];
  Warnings warnings;
  const FeModel deck = readDeck(path, readOptions, &warnings);
  const FeModel shells = partShells(deck, part, path);
  const QuadMesh mesh = quadMeshFromModel(shells);
  std::optional<QuadMesh> original;
  std::vector<MeshCurve> channels;
  if (const auto originalPath = parsed.value("--original")) {
    const FeModel originalModel = readDeck(*originalPath, readOptions, &warnings);
    original = quadMeshFromModel(partShells(originalModel, part, *originalPath));
    channels = deckChannelCurves(originalModel, part);
  } else {
    channels = deckChannelCurves(deck, part);
  }
  printWarnings(warnings);
  const QualityReport report =
      assessQuality(mesh, settings, original ? &*original : nullptr, &channels);

  if (const auto vtu = parsed.value("--vtu")) {
    std::vector<FieldData> pointFields;
    if (report.distance) pointFields.push_back({"distance", report.distance->pointDistance});
    writeVtu(shells, *vtu, qualityCellFields(report), pointFields);
  }
  if (parsed.has("--json"))
    printOutput(qualityReportJson(report));
  else
    printOutput(path + (part ? " part " + std::to_string(part) : std::string()) + "\n" +
                formatQualityTable(report));
  return report.passes() ? 0 : kExitShortfall;
}

}  // namespace voxremesh::cli
