// voxremesh slice: one axis-aligned slice of a .vdb volume rendered as a PNG image.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/slice_image.h"
#include "voxremesh/volume.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage =
    "voxremesh slice PART.vdb --axis x|y|z --at WORLD_COORD -o SLICE.png [--scale PIXELS]\n"
    "       [--sheet K]";

const char* const kHelp =
    "Reads a volume written by `voxremesh voxelize` and draws the layer of voxels nearest to the\n"
    "plane AXIS = WORLD_COORD over the bounding box of the active voxels (the same image size for\n"
    "every slice along one axis). Axes in the image: x slices show y to the right and z up,\n"
    "y slices x and z, z slices x and y. The PNG is written completely or not at all; a summary\n"
    "line says what it shows.\n"
    "\n"
    "colours:\n"
    "  blue .. white .. red   signed distance of active (narrow band) voxels: white at the\n"
    "                         surface, blue on the side opposite the element normals, red on\n"
    "                         the side they point to, saturated at the band width\n"
    "  grey                   inactive voxels (farther from the part than the band)\n"
    "  yellow block           invalid voxel (no surface is extracted from a cell touching one)\n"
    "  black square           feature cell (crossed by a feature line) meeting the slice plane,\n"
    "                         centred where its four voxels meet\n"
    "\n"
    "options:\n"
    "  --axis x|y|z       the axis the slice is normal to (required)\n"
    "  --at WORLD_COORD   where along the axis (model units, required); must lie within the\n"
    "                     volume's bounding box (`voxremesh inspect` shows it)\n"
    "  -o SLICE.png       the image to write (required)\n"
    "  --scale PIXELS     pixels per voxel, 1..64 (default: the largest in 2..16 that keeps\n"
    "                     the image within 1200 pixels)\n"
    "  --sheet K          the sheet whose volume to draw, 0..sheets-1 (default 0); a part whose\n"
    "                     sheets meet at a T-junction has one volume per sheet (`voxremesh\n"
    "                     inspect` lists them)\n";

}  // namespace

int runSlice(const std::vector<std::string>& args) {
  if (wantsHelp(args)) {
    std::printf("usage: %s\n\n%s", kUsage, kHelp);
    return 0;
  }
  const ParsedArgs parsed = parseArgs(
      args, {{"--axis", true}, {"--at", true}, {"-o", true}, {"--scale", true}, {"--sheet", true}},
      1, 1, kUsage);
  const auto axisText = parsed.value("--axis"), atText = parsed.value("--at");
  const auto output = parsed.value("-o");
  if (!axisText) throw UsageError("missing --axis x|y|z", kUsage);
  if (!atText) throw UsageError("missing --at WORLD_COORD", kUsage);
  if (!output || output->empty()) throw UsageError("missing -o SLICE.png", kUsage);
  Axis axis = Axis::X;
  double at = 0.0;
  long long sheet = 0;
  SliceStyle style;
  parseOptionValues(kUsage, [&] {
    axis = axisFromName(*axisText);
    at = parseNumber("--at", *atText);
    if (const auto scale = parsed.value("--scale"))
      style.pixelsPerVoxel = static_cast<int>(parseIntegerInRange("--scale", *scale, 1, 64));
    if (const auto text = parsed.value("--sheet")) sheet = parseInteger("--sheet", *text);
  });
  const std::filesystem::path out = *output;
  if (out.extension() != ".png")
    printWarnings({out.string() + " does not end in .png; image viewers may not recognise it"});

  const std::vector<Volume> volumes = readVolumes(parsed.positional[0]);
  const SliceImage image = renderSlice(sheetVolume(volumes, sheet, "--sheet"), axis, at, style);
  writePng(image, out);
  char text[512];
  std::snprintf(text, sizeof text,
                ": %d x %d pixels, %s = %.6g (voxel layer %d), %s %.6g .. %.6g left to right, "
                "%s %.6g .. %.6g bottom to top, %d pixels per voxel\n",
                image.width, image.height, axisName(axis), image.sliceWorld, image.sliceIndex,
                axisName(image.uAxis), image.uMin * image.voxelSize, image.uMax * image.voxelSize,
                axisName(image.vAxis), image.vMin * image.voxelSize, image.vMax * image.voxelSize,
                image.pixelsPerVoxel);
  printOutput("wrote " + out.string() + text);
  return 0;
}

}  // namespace voxremesh::cli
