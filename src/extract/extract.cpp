// extractQuadMesh: the dual mesh, feature snapping, the boundary strip (see extract.h).
#include "voxremesh/extract.h"

#include <stdexcept>

#include "extract/boundary_strip.h"
#include "extract/dual_mesh.h"
#include "extract/feature_snap.h"
#include "volume/volume_build.h"
#include "volume/volume_grids.h"

namespace voxremesh {

namespace {

/// Merges points with identical coordinates (dual vertices snapped onto one feature point, the
/// ends of a bridge in the boundary strip), keeping the first; a quad that loses a corner becomes
/// a triangle, faces with fewer than three distinct corners are dropped. Returns the number of
/// faces dropped.
std::uint64_t weldCoincidentPoints(QuadMesh& mesh) {
  std::vector<CornerIndex> order(mesh.points.size());
  for (CornerIndex i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](CornerIndex a, CornerIndex b) { return mesh.points[a] < mesh.points[b]; });
  std::vector<CornerIndex> representative(mesh.points.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const bool same = k > 0 && mesh.points[order[k]] == mesh.points[order[k - 1]];
    representative[order[k]] = same ? representative[order[k - 1]] : order[k];
  }
  std::uint64_t dropped = 0;
  std::vector<std::array<CornerIndex, 4>> faces;
  faces.reserve(mesh.faces.size());
  for (const auto& face : mesh.faces) {
    std::array<CornerIndex, 4> out{kNoCorner, kNoCorner, kNoCorner, kNoCorner};
    int count = 0;
    const int n = cornerCount(face);
    for (int c = 0; c < n; ++c) {
      const CornerIndex p = representative[face[std::size_t(c)]];
      if (count > 0 && out[std::size_t(count - 1)] == p) continue;
      out[std::size_t(count++)] = p;
    }
    if (count > 1 && out[std::size_t(count - 1)] == out[0]) out[std::size_t(--count)] = kNoCorner;
    const bool distinct = count < 3 || (out[0] != out[2] && (count < 4 || out[1] != out[3]));
    if (count < 3 || !distinct) {
      ++dropped;
      continue;
    }
    faces.push_back(out);
  }
  mesh.faces = std::move(faces);
  return dropped;
}

/// The dual mesh stops within about two voxels of a boundary loop (cells touching the loop or an
/// invalid voxel emit nothing); a dual boundary vertex farther than this from every loop lies on a
/// gap inside the surface.
constexpr double kStripReachVoxels = 4.0;

MeshCurve toMeshCurve(const VolumeCurve& curve, PointRole role) {
  return {curve.points, curve.closed, role};
}

}  // namespace

QuadMesh extractQuadMesh(const Volume& volume, const ExtractSettings& settings,
                         ExtractStats* stats) {
  if (volume.empty()) throw std::invalid_argument("extractQuadMesh: the volume is empty");
  const Volume::Impl& grids = volume.impl();

  QuadMesh mesh;
  mesh.part = volume.info().part;
  std::vector<std::uint32_t> loopCurves, lineCurves;
  for (const VolumeCurve& loop : volume.boundaryLoops()) {
    loopCurves.push_back(static_cast<std::uint32_t>(mesh.curves.size()));
    mesh.curves.push_back(toMeshCurve(loop, PointRole::Boundary));
  }
  for (const VolumeCurve& line : volume.featureLines()) {
    lineCurves.push_back(static_cast<std::uint32_t>(mesh.curves.size()));
    mesh.curves.push_back(toMeshCurve(line, PointRole::Feature));
  }

  // Cells the boundary loops cross get no vertex when the strip is rebuilt: the dual mesh then
  // stops short of every loop, however small the hole.
  const bool rebuild = settings.rebuildBoundary && !loopCurves.empty();
  const openvdb::MaskGrid::Ptr excludedCells =
      rebuild ? volume::buildFeatureMask(volume.boundaryLoops(), {}, grids.transform)
              : openvdb::MaskGrid::create();
  extract::DualMesh dual =
      extract::buildDualMesh(*grids.sdf, grids.invalid->tree(), excludedCells->tree());
  mesh.points = std::move(dual.points);
  mesh.faces.reserve(dual.quads.size());
  for (const auto& q : dual.quads) mesh.faces.push_back({q[0], q[1], q[2], q[3]});
  mesh.constraints.assign(mesh.points.size(), PointConstraint{});

  ExtractStats counts;
  counts.surfaceCells = dual.surfaceCells;
  counts.tunnelCells = dual.tunnelCells;
  counts.skippedCells = dual.skippedCells;
  counts.cutCells = dual.cutCells;
  counts.dualVertices = mesh.points.size();
  counts.dualQuads = mesh.faces.size();
  if (settings.snapFeatures) {
    counts.snappedVertices =
        extract::snapToFeatures(mesh, dual.pointCells, grids.feature->tree(), *grids.transform,
                                lineCurves, volume.featurePoints());
  }
  if (rebuild) {
    const double voxel = volume.info().voxelSize;
    const double spacing = settings.junctionSpacing > 0.0 ? settings.junctionSpacing : voxel;
    const extract::JunctionNodes junctions(volume.junctionCurves(), spacing, 0.2 * spacing);
    const extract::StripStats strip =
        extract::rebuildBoundaryStrip(mesh, loopCurves, volume.featurePoints(), junctions, voxel,
                                      0.2 * voxel, kStripReachVoxels * voxel);
    counts.stripQuads = strip.quads;
    counts.stripTriangles = strip.triangles;
    counts.junctionNodes = strip.junctionNodes;
  }
  weldCoincidentPoints(mesh);
  eraseUnusedPoints(mesh);
  if (stats) *stats = counts;
  return mesh;
}

}  // namespace voxremesh
