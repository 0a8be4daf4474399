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
#include "voxremesh/io.h"
#include "voxremesh/quality.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage =
    "voxremesh quality DECK [--original ORIG] [--json] [--vtu OUT.vtu] [--part PID] [--size H]\n"
    "       [--format F] [limit options]";

const char* const kHelp =
    "Measures the FE quality of the shells of DECK (all parts, or --part PID): per element the\n"
    "warping angle, aspect ratio, interior angles, skew, Jacobian ratio, scaled Jacobian, taper "
    "and\n"
    "the minimum element length (LS-DYNA characteristic length); per mesh the share of trias and,\n"
    "with --original, the two-sided distance to the original surface. Prints a table (metric,\n"
    "limit, worst value, failing count and share). Definitions: include/voxremesh/quality.h.\n"
    "The exit code is 0 whether or not the mesh passes (the table's last line, \"pass\" in JSON);\n"
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
    "limits (defaults in brackets):\n"
    "  --warping DEG [15]  --aspect R [5]  --quad-min-angle DEG [45]  --quad-max-angle DEG [135]\n"
    "  --tria-min-angle DEG [30]  --tria-max-angle DEG [120]  --skew DEG [40]\n"
    "  --jacobian R [0.6]  --scaled-jacobian R [0.3]  --taper T [0.6]\n"
    "  --min-length F [0.5 x size]  --tria-share S [0.05]  --distance F [0.25 x size]\n"
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
    {"--size", &QualitySettings::targetSize},
};

/// The shells of one part (all shells for part 0) with the nodes they use, numbered by first use
/// so that node i is point i of quadMeshFromModel. Throws std::runtime_error when there are none.
FeModel shellsOf(const FeModel& model, Id part, const std::string& path) {
  const std::unordered_map<Id, std::size_t> index = model.nodeIndex();
  FeModel out;
  out.sourceFormat = model.sourceFormat;
  std::unordered_map<Id, bool> used;
  for (const Shell& shell : model.shells) {
    if (part != 0 && shell.part != part) continue;
    out.shells.push_back(shell);
    out.shells.back().extras = -1;
    out.shells.back().type = 0;
    for (int k = 0; k < shell.nodeCount; ++k) {
      const Id node = shell.nodes[static_cast<std::size_t>(k)];
      if (!used.emplace(node, true).second) continue;
      const auto found = index.find(node);
      if (found == index.end())
        throw std::runtime_error(path + ": shell " + std::to_string(shell.id) + " names node " +
                                 std::to_string(node) + ", which is not defined");
      out.nodes.push_back(model.nodes[found->second]);
    }
  }
  if (out.shells.empty())
    throw std::runtime_error(path + (part ? " has no shells of part " + std::to_string(part)
                                          : std::string(" has no shell elements")));
  return out;
}

/// A value ParaView can read: non-finite values become +-1e30.
double finiteForVtu(double value) {
  if (std::isnan(value)) return 1e30;
  if (std::isinf(value)) return value > 0 ? 1e30 : -1e30;
  return value;
}

/// The cell data of the .vtu: every metric, the failure bit mask and the pass flag.
std::vector<FieldData> cellFields(const QualityReport& report) {
  std::vector<FieldData> fields = {
      {"warping_deg", {}},          {"aspect_ratio", {}},    {"min_angle_deg", {}},
      {"max_angle_deg", {}},        {"skew_deg", {}},        {"jacobian_ratio", {}},
      {"jacobian_ratio_gauss", {}}, {"scaled_jacobian", {}}, {"taper", {}},
      {"min_length", {}},           {"fail_mask", {}},       {"pass", {}}};
  for (std::size_t f = 0; f < report.elements; ++f) {
    const ElementQuality& q = report.elementValues[f];
    const double values[] = {q.warpingDeg,
                             q.aspectRatio,
                             q.minAngleDeg,
                             q.maxAngleDeg,
                             q.skewDeg,
                             q.jacobianRatio,
                             q.jacobianRatioGauss,
                             q.scaledJacobian,
                             q.taper,
                             q.minLength,
                             double(report.elementFailures[f]),
                             report.elementFailures[f] == 0 ? 1.0 : 0.0};
    for (std::size_t k = 0; k < fields.size(); ++k)
      fields[k].values.push_back(finiteForVtu(values[k]));
  }
  return fields;
}

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
                                       {"--distance", true}},
                                      1, 1, kUsage);

  QualitySettings settings;
  for (const LimitOption& option : kLimits)
    if (const auto text = parsed.value(option.name))
      settings.*(option.field) = parseNumber(option.name, *text);
  settings.jacobianAtGaussPoints = parsed.has("--jacobian-at-gauss-points");
  checkQualitySettings(settings);
  ReadOptions readOptions;
  if (const auto format = parsed.value("--format")) readOptions.format = formatFromName(*format);
  const Id part = parsed.has("--part") ? parseInteger("--part", *parsed.value("--part")) : 0;

  const std::string& path = parsed.positional[0];
  Warnings warnings;
  const FeModel shells = shellsOf(readDeck(path, readOptions, &warnings), part, path);
  const QuadMesh mesh = quadMeshFromModel(shells);
  std::optional<QuadMesh> original;
  if (const auto originalPath = parsed.value("--original")) {
    const FeModel originalModel = readDeck(*originalPath, readOptions, &warnings);
    original = quadMeshFromModel(shellsOf(originalModel, part, *originalPath));
  }
  printWarnings(warnings);
  const QualityReport report = assessQuality(mesh, settings, original ? &*original : nullptr);

  if (const auto vtu = parsed.value("--vtu")) {
    std::vector<FieldData> pointFields;
    if (report.distance) pointFields.push_back({"distance", report.distance->pointDistance});
    writeVtu(shells, *vtu, cellFields(report), pointFields);
  }
  if (parsed.has("--json"))
    printOutput(qualityReportJson(report));
  else
    printOutput(path + (part ? " part " + std::to_string(part) : std::string()) + "\n" +
                formatQualityTable(report));
  return 0;
}

}  // namespace voxremesh::cli
