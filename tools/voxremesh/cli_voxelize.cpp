// voxremesh voxelize: reads a deck, splits one part into sheets and writes their narrow-band
// signed-distance volumes, one per sheet (grids sdf, invalid, feature each), to one .vdb file.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/sheets.h"
#include "voxremesh/volume.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage =
    "voxremesh voxelize DECK -o PART.vdb [--size H | --voxel V] [--part PID] [--band N]\n"
    "       [--feature-angle DEG] [--invalid-angle DEG] [--format F]";

const char* const kHelp =
    "Reads DECK, splits one part into manifold, consistently oriented sheets and writes each\n"
    "sheet into a narrow-band signed-distance volume of its own, all at one voxel size (sheets\n"
    "meeting at a T-junction have no common inside and outside). The .vdb file holds per sheet\n"
    "the grids sdf (float, level set), invalid (mask: voxels whose closest point is on a free\n"
    "boundary, seen at a steep angle) and feature (mask: cells crossed by feature lines); sheet\n"
    "0's grids have these names, sheet K's the suffix .sheetK (sdf.sheet1, ...). For vdb_print,\n"
    "vdb_view, Houdini, Blender and `voxremesh inspect` / `slice` / `extract`. Prints a one-line\n"
    "summary (voxel counts summed over the sheets); warnings about the input go to stderr. The\n"
    "file is written completely or not at all.\n"
    "\n"
    "options:\n"
    "  -o PART.vdb           the volume to write (required)\n"
    "  --part PID            the part to voxelize; may be left out when the deck has only one\n"
    "                        part with shells\n"
    "  --size H              target element size of the new mesh; the voxel size is H\n"
    "  --voxel V             voxel size V (model units), instead of --size\n"
    "                        (neither: the mean element edge length of the part)\n"
    "  --band N              narrow band half width in voxels, 1..64 (default 3)\n"
    "  --feature-angle DEG   edges where the face normals turn by more than DEG degrees are\n"
    "                        feature lines (0 = flat; default 45)\n"
    "  --invalid-angle DEG   a voxel whose closest point is on a free boundary is invalid when\n"
    "                        its distance vector leans more than DEG degrees away from the face\n"
    "                        normal, 0..90 (default 60)\n"
    "  --format F            read DECK as format F instead of guessing it from the extension\n"
    "                        (k, lsdyna, bdf, nastran, inp, abaqus, obj, off, stl, ply)\n"
    "\n"
    "Settings the machine cannot hold (a voxel size needing more memory than half of it) are\n"
    "refused before anything is allocated, with the smallest voxel size that fits.\n";

/// The part to voxelize: `given` (--part, 0 when not given; it must have shells), else the deck's
/// only shell part.
Id choosePartOption(const FeModel& model, Id given, const std::string& deck) {
  try {
    return choosePart(model, given, deck, "--part");
  } catch (const SettingError& error) {
    if (given) throw;
    throw UsageError(error.what(), kUsage);
  }
}

VolumeSettings volumeSettings(const ParsedArgs& parsed) {
  VolumeSettings settings;
  const auto size = parsed.value("--size"), voxel = parsed.value("--voxel");
  if (size && voxel) throw UsageError("give either --size or --voxel, not both", kUsage);
  if (voxel) {
    settings.rule = VoxelSizeRule::Explicit;
    settings.voxelSize = parseNumber("--voxel", *voxel);
  } else {
    settings.rule = VoxelSizeRule::TargetElementSize;
    if (size) settings.targetElementSize = parseNumber("--size", *size);
  }
  if (const auto band = parsed.value("--band"))
    settings.bandWidthVoxels = parseNumber("--band", *band);
  if (const auto angle = parsed.value("--invalid-angle"))
    settings.invalidAngleDeg = parseNumber("--invalid-angle", *angle);
  checkVolumeSettings(settings);
  return settings;
}

std::string plural(std::size_t count, const char* noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

}  // namespace

int runVoxelize(const std::vector<std::string>& args) {
  if (wantsHelp(args)) {
    std::printf("usage: %s\n\n%s", kUsage, kHelp);
    return 0;
  }
  const auto start = std::chrono::steady_clock::now();
  const ParsedArgs parsed = parseArgs(args,
                                      {{"-o", true},
                                       {"--part", true},
                                       {"--size", true},
                                       {"--voxel", true},
                                       {"--band", true},
                                       {"--feature-angle", true},
                                       {"--invalid-angle", true},
                                       {"--format", true}},
                                      1, 1, kUsage);
  const auto output = parsed.value("-o");
  if (!output || output->empty()) throw UsageError("missing -o PART.vdb", kUsage);
  // Settings first, so that a bad value fails before the deck is read.
  VolumeSettings settings;
  SheetSettings sheetSettings;
  ReadOptions readOptions;
  Id givenPart = 0;
  parseOptionValues(kUsage, [&] {
    settings = volumeSettings(parsed);
    if (const auto text = parsed.value("--part")) givenPart = parseInteger("--part", *text);
    if (const auto angle = parsed.value("--feature-angle"))
      sheetSettings.featureAngleDeg = parseAngle("--feature-angle", *angle);
    if (const auto format = parsed.value("--format")) readOptions.format = formatFromName(*format);
  });
  const std::filesystem::path out = *output;
  if (out.has_parent_path() && !std::filesystem::is_directory(out.parent_path()))
    throw std::runtime_error("cannot write " + out.string() + ": no folder " +
                             out.parent_path().string());

  const std::string& deck = parsed.positional[0];
  Warnings warnings;
  const FeModel model = readDeck(deck, readOptions, &warnings);
  const Id part = choosePartOption(model, givenPart, deck);
  const std::vector<Sheet> sheets = buildSheets(model, part, sheetSettings);
  std::size_t shells = 0, faces = 0;
  for (const Shell& shell : model.shells) shells += shell.part == part ? 1 : 0;
  for (const Sheet& sheet : sheets) faces += sheet.faces.size();
  if (faces < shells)
    warnings.push_back(plural(shells - faces, "shell") + " of part " + std::to_string(part) +
                       " without area (collapsed to a line or a point) left out");
  if (out.extension() != ".vdb")
    warnings.push_back(out.string() + " does not end in .vdb; VDB tools may not recognise it");
  printWarnings(warnings);
  if (sheets.empty())
    throw std::runtime_error("part " + std::to_string(part) + " of " + deck +
                             " has no shell with an area to voxelize");

  const std::vector<Volume> volumes = buildSheetVolumes(sheets, settings, VolumeSource{deck});
  writeVolumes(volumes, out);
  unsigned long long active = 0, invalid = 0, feature = 0;
  for (const VolumeReport& report : inspectVolumes(volumes)) {
    active += report.grids.at(0).activeVoxels;
    invalid += report.invalidVoxels;
    feature += report.featureVoxels;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const Part* named = model.findPart(part);
  const std::string name = named && !named->name.empty() ? " (" + named->name + ")" : "";
  char numbers[256];
  std::snprintf(numbers, sizeof numbers,
                "voxel size %.6g, %llu active voxels, %llu invalid voxels, %llu feature cells, "
                "%.2f s\n",
                volumes.front().info().voxelSize, active, invalid, feature, seconds);
  printOutput("wrote " + out.string() + ": part " + std::to_string(part) + name + ", " +
              plural(sheets.size(), "sheet") + ", " + numbers);
  return 0;
}

}  // namespace voxremesh::cli
