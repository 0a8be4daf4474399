// extractQuadMesh: the dual mesh, feature snapping, the boundary strip (see extract.h).
#include "voxremesh/extract.h"

#include <openvdb/tools/Interpolation.h>

#include <cmath>
#include <stdexcept>

#include "extract/boundary_strip.h"
#include "extract/dual_mesh.h"
#include "extract/feature_snap.h"
#include "volume/volume_build.h"
#include "volume/volume_grids.h"
#include "voxremesh/deck_compare.h"

namespace voxremesh {

namespace {

/// How strongly a role binds a point, for merging coincident points: Junction, Corner, a curve,
/// Free.
int constraintStrength(PointRole role) {
  switch (role) {
    case PointRole::Junction:
      return 3;
    case PointRole::Corner:
      return 2;
    case PointRole::Feature:
    case PointRole::Boundary:
      return 1;
    case PointRole::Free:
      return 0;
  }
  return 0;
}

/// Merges points with identical coordinates (dual vertices snapped onto one feature point, the
/// ends of a bridge in the boundary strip) into the first of them, which takes the strongest
/// constraint among them; a quad that loses a corner becomes a triangle, faces with fewer than
/// three distinct corners are dropped. Returns the number of faces dropped.
std::uint64_t weldCoincidentPoints(QuadMesh& mesh) {
  std::vector<CornerIndex> order(mesh.points.size());
  for (CornerIndex i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](CornerIndex a, CornerIndex b) { return mesh.points[a] < mesh.points[b]; });
  std::vector<CornerIndex> representative(mesh.points.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const bool same = k > 0 && mesh.points[order[k]] == mesh.points[order[k - 1]];
    representative[order[k]] = same ? representative[order[k - 1]] : order[k];
    // The point that stays keeps the strongest constraint of the merged ones: a Junction point
    // must stay one (the seam with the other sheet or part is made of them), a Corner stays fixed.
    const CornerIndex kept = representative[order[k]];
    if (same && !mesh.constraints.empty() &&
        constraintStrength(mesh.constraints[order[k]].role) >
            constraintStrength(mesh.constraints[kept].role))
      mesh.constraints[kept] = mesh.constraints[order[k]];
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

/// Moves p onto the zero level of the signed distance by Newton steps along its gradient (central
/// differences of the trilinear interpolant), where that converges within a voxel of p; else p
/// stays. For the bridge nodes of the boundary strip, which lie on a straight chord across a neck.
void projectOnLevelSet(const openvdb::FloatGrid& sdf, std::array<double, 3>& p) {
  const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(sdf);
  const double voxel = sdf.voxelSize()[0], h = 0.5 * voxel;
  const openvdb::Vec3d start(p[0], p[1], p[2]);
  openvdb::Vec3d x = start;
  double value = sampler.wsSample(x);
  for (int step = 0; step < 6 && std::abs(value) > 1e-6 * voxel; ++step) {
    openvdb::Vec3d gradient;
    for (int axis = 0; axis < 3; ++axis) {
      openvdb::Vec3d d(0.0);
      d[axis] = h;
      gradient[axis] = (sampler.wsSample(x + d) - sampler.wsSample(x - d)) / (2.0 * h);
    }
    const double length2 = gradient.lengthSqr();
    if (!(length2 > 1e-12)) return;
    x -= gradient * (value / length2);
    value = sampler.wsSample(x);
  }
  if (std::abs(value) <= 0.05 * voxel && (x - start).length() <= voxel) p = {x[0], x[1], x[2]};
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
    const extract::JunctionNodes junctions(volume.junctionCurves(), spacing, 0.2 * spacing,
                                           kChordSagittaShare);
    const extract::StripStats strip =
        extract::rebuildBoundaryStrip(mesh, loopCurves, volume.featurePoints(), junctions, voxel,
                                      0.2 * voxel, kStripReachVoxels * voxel);
    counts.stripQuads = strip.quads;
    counts.stripTriangles = strip.triangles;
    counts.junctionNodes = strip.junctionNodes;
    counts.bridgeNodes = strip.bridgeNodes.size() / 2;  // each visited twice, welded into one
    counts.ladderQuads = strip.ladderQuads;
    counts.pinchedFaces = strip.pinchedFaces;
    for (const std::uint32_t node : strip.bridgeNodes)
      projectOnLevelSet(*grids.sdf, mesh.points[node]);
    for (const std::uint32_t node : strip.ladderNodes)
      projectOnLevelSet(*grids.sdf, mesh.points[node]);
  }
  weldCoincidentPoints(mesh);
  eraseUnusedPoints(mesh);
  if (stats) *stats = counts;
  return mesh;
}

}  // namespace voxremesh
