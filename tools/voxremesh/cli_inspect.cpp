// voxremesh inspect: the report of a .vdb volume written by `voxremesh voxelize`, as a table or
// JSON.
#include <cstdio>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/volume.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage = "voxremesh inspect PART.vdb [--json]";

const char* const kHelp =
    "Reads a volume written by `voxremesh voxelize` and reports the settings it was built with\n"
    "(voxel size, band, invalid angle, source deck and part) and per grid (sdf, invalid,\n"
    "feature): class, value type, active voxels, leaf nodes, memory, index and world bounding\n"
    "box and, for sdf, the range of the active values; then the invalid voxel and feature cell\n"
    "counts and the numbers of feature lines, feature points and boundary loops kept for\n"
    "extraction. A volume of several sheets (one per sheet of the part) is reported sheet by\n"
    "sheet; its JSON is {\"sheet_count\": N, \"sheets\": [one report per sheet]} (one sheet:\n"
    "the report itself).\n"
    "\n"
    "options:\n"
    "  --json   print the report as JSON instead of a table\n";

}  // namespace

int runInspect(const std::vector<std::string>& args) {
  if (wantsHelp(args)) {
    std::printf("usage: %s\n\n%s", kUsage, kHelp);
    return 0;
  }
  const ParsedArgs parsed = parseArgs(args, {{"--json", false}}, 1, 1, kUsage);
  const std::string& path = parsed.positional[0];
  const std::vector<VolumeReport> reports = inspectVolumes(readVolumes(path));
  if (parsed.has("--json")) {
    printOutput(volumeReportsJson(reports) + "\n");
  } else {
    printOutput(path + "\n\n" + formatVolumeReports(reports));
  }
  return 0;
}

}  // namespace voxremesh::cli
