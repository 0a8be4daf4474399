// The mesh of a part from its sheet volumes: each sheet extracted, then joined at the junction
// nodes (pipeline.h extractPartMesh).
#include <stdexcept>
#include <string>
#include <vector>

#include "voxremesh/pipeline.h"

namespace voxremesh {

namespace {

void requireVolumes(const std::vector<Volume>& volumes) {
  if (volumes.empty()) throw std::invalid_argument("no sheet volumes to extract");
  for (const Volume& volume : volumes)
    if (volume.empty()) throw std::invalid_argument("cannot extract an empty volume");
}

}  // namespace

void addExtractStats(ExtractStats& sum, const ExtractStats& add) {
  sum.surfaceCells += add.surfaceCells;
  sum.tunnelCells += add.tunnelCells;
  sum.skippedCells += add.skippedCells;
  sum.cutCells += add.cutCells;
  sum.dualVertices += add.dualVertices;
  sum.dualQuads += add.dualQuads;
  sum.stripQuads += add.stripQuads;
  sum.stripTriangles += add.stripTriangles;
  sum.snappedVertices += add.snappedVertices;
  sum.junctionNodes += add.junctionNodes;
}

QuadMesh extractPartMesh(const std::vector<Volume>& volumes, const ExtractSettings& settings,
                         ExtractStats* stats) {
  requireVolumes(volumes);
  std::vector<QuadMesh> meshes;
  meshes.reserve(volumes.size());
  ExtractStats sum;
  for (std::size_t k = 0; k < volumes.size(); ++k) {
    ExtractStats sheet;
    try {
      meshes.push_back(extractQuadMesh(volumes[k], settings, &sheet));
    } catch (const std::runtime_error& error) {
      if (volumes.size() == 1) throw;
      throw std::runtime_error("sheet " + std::to_string(k) + ": " + error.what());
    }
    addExtractStats(sum, sheet);
  }
  if (stats) *stats = sum;
  return joinAtJunctions(meshes);
}

QuadMesh extractPartTriangles(const std::vector<Volume>& volumes) {
  requireVolumes(volumes);
  std::vector<QuadMesh> meshes;
  meshes.reserve(volumes.size());
  for (const Volume& volume : volumes) meshes.push_back(extractTriangles(volume));
  // Triangle points are free, so joining is concatenation.
  return joinAtJunctions(meshes);
}

}  // namespace voxremesh
