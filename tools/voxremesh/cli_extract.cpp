// voxremesh extract: reads the sheet volumes of a .vdb file written by `voxremesh voxelize` and
// writes the quad mesh extracted from them (dual quads, boundary strip, feature snapping; the
// sheets joined at their junction nodes), or the MC33 triangles.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/extract.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/quad_mesh.h"
#include "voxremesh/volume.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage =
    "voxremesh extract PART.vdb -o OUT [--triangles] [--no-boundary] [--no-features]";

const char* const kHelp =
    "Reads a volume written by `voxremesh voxelize` and extracts its surface: one vertex per MC33\n"
    "surface component of every valid cell, one quad per sign-changing grid edge, the strip up\n"
    "to the original boundary loops (holes included) and vertices snapped onto feature lines\n"
    "and points. A volume of several sheets (a part whose sheets meet at a T-junction) gives one\n"
    "mesh per sheet, joined at the nodes the sheets share on their junction curves. Writes OUT\n"
    "in the format its extension names (.k .bdf .inp .obj .off .stl .ply .vtu); the file is\n"
    "written completely or not at all. Prints a one-line summary.\n"
    "\n"
    "options:\n"
    "  -o OUT           the mesh to write (required)\n"
    "  --triangles      write the MC33 triangulation of the valid cells instead (inspection;\n"
    "                   the sheets' triangles one after the other, not joined)\n"
    "  --no-boundary    leave out the boundary strip: the bare dual mesh, stopping short of the\n"
    "                   boundary as the invalid mask makes it\n"
    "  --no-features    do not snap vertices to feature lines and points\n";

}  // namespace

int runExtract(const std::vector<std::string>& args) {
  if (wantsHelp(args)) {
    std::printf("usage: %s\n\n%s", kUsage, kHelp);
    return 0;
  }
  const auto start = std::chrono::steady_clock::now();
  const ParsedArgs parsed = parseArgs(
      args,
      {{"-o", true}, {"--triangles", false}, {"--no-boundary", false}, {"--no-features", false}}, 1,
      1, kUsage);
  const auto output = parsed.value("-o");
  if (!output || output->empty()) throw UsageError("missing -o OUT", kUsage);
  const std::filesystem::path out = *output;
  formatFromPath(out);  // an unknown extension fails before the volume is read
  if (out.has_parent_path() && !std::filesystem::is_directory(out.parent_path()))
    throw std::runtime_error("cannot write " + out.string() + ": no folder " +
                             out.parent_path().string());

  const std::vector<Volume> volumes = readVolumes(parsed.positional[0]);
  ExtractSettings settings;
  settings.rebuildBoundary = !parsed.has("--no-boundary");
  settings.snapFeatures = !parsed.has("--no-features");
  ExtractStats stats;
  const QuadMesh mesh = parsed.has("--triangles") ? extractPartTriangles(volumes)
                                                  : extractPartMesh(volumes, settings, &stats);
  const Id part = volumes.front().info().part != 0 ? volumes.front().info().part : 1;
  writeDeck(modelFromQuadMesh(mesh, part), out);
  std::size_t quads = 0;
  for (const auto& face : mesh.faces) quads += cornerCount(face) == 4 ? 1 : 0;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  char text[512];
  std::snprintf(text, sizeof text,
                "wrote %s: %zu nodes, %zu quads, %zu triangles (%llu surface cells, %llu tunnel "
                "cells, %llu snapped vertices, %zu sheet%s), %.2f s\n",
                out.string().c_str(), mesh.points.size(), quads, mesh.faces.size() - quads,
                static_cast<unsigned long long>(stats.surfaceCells),
                static_cast<unsigned long long>(stats.tunnelCells),
                static_cast<unsigned long long>(stats.snappedVertices), volumes.size(),
                volumes.size() == 1 ? "" : "s", seconds);
  printOutput(text);
  return 0;
}

}  // namespace voxremesh::cli
