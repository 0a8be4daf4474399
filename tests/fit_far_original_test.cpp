// fitFarOriginalPoints on a coarse grid laid over a sheet with a ridge between two of its columns
// of points: the grid cuts across the ridge's crest (0.37 x the element size below it, over the
// 0.25 limit). The step pulls points towards the crest: both directions of the distance drop,
// without failing a criterion, moving the boundary or leaving the original surface, the same for
// any thread count; bad arguments are refused.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "support/unit_grid.h"
#include "voxremesh/errors.h"
#include "voxremesh/optimize.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"

namespace {

using voxremesh::QuadMesh;
using voxremesh::ReferenceSurface;

/// The sheet's height: a ridge 0.6 high and 2 wide along y, its crest at x = 2.5, running out
/// towards y = 0.5 and y = 5.5 (the sheet's edges stay flat).
double ridge(double x, double y) {
  const double along = std::clamp(std::min(y - 0.5, 5.5 - y), 0.0, 1.0);
  return 0.6 * std::max(0.0, 1.0 - std::abs(x - 2.5)) * along;
}

/// The original: a grid of 0.1 over [0, 6] x [0, 6] lifted onto the ridge.
QuadMesh fineSheet() {
  QuadMesh mesh = voxremesh::test::unitGrid(60);
  for (auto& p : mesh.points) {
    p[0] *= 0.1;
    p[1] *= 0.1;
    p[2] = ridge(p[0], p[1]);
  }
  return mesh;
}

/// The mesh to fit: unit quads over the same square, its points on the sheet (x = 2 and x = 3
/// at height 0.1, either side of the crest).
QuadMesh coarseGrid() {
  QuadMesh mesh = voxremesh::test::unitGrid(6);
  for (auto& p : mesh.points) p[2] = ridge(p[0], p[1]);
  return mesh;
}

voxremesh::QualitySettings unitCriteria() {
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;  // distance limit 0.25
  return settings;
}

TEST(FitFarOriginalPoints, PullsPointsTowardsTheCrest) {
  const QuadMesh original = fineSheet();
  const ReferenceSurface surface(original);
  QuadMesh mesh = coarseGrid();
  const QuadMesh start = mesh;
  const voxremesh::QualitySettings criteria = unitCriteria();
  const voxremesh::SurfaceDistance before = voxremesh::surfaceDistance(mesh, original);
  ASSERT_GT(before.maxFromOriginal, 0.28);
  ASSERT_EQ(voxremesh::assessQuality(mesh, criteria).failingAny, 0u);

  EXPECT_GT(voxremesh::fitFarOriginalPoints(mesh, surface, criteria, 10), 0u);
  const voxremesh::SurfaceDistance after = voxremesh::surfaceDistance(mesh, original);
  // The crest comes closer (0.37 -> 0.30; a row of points on it would take a quad 0.5 wide, which
  // fails the minimum length), the faces too (0.29 -> 0.22).
  EXPECT_LT(after.maxFromOriginal, 0.85 * before.maxFromOriginal);
  EXPECT_LE(after.maxToOriginal, before.maxToOriginal);
  EXPECT_EQ(voxremesh::assessQuality(mesh, criteria).failingAny, 0u);
  EXPECT_EQ(mesh.faces, start.faces);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    const auto& p = mesh.points[v];
    EXPECT_LT(surface.closestPoint(p).distance, 1e-9) << v;  // on the original
    const auto& s = start.points[v];
    if (s[0] == 0.0 || s[0] == 6.0 || s[1] == 0.0 || s[1] == 6.0) {
      EXPECT_EQ(p, s) << v;
    }
  }
}

TEST(FitFarOriginalPoints, LeavesAMeshCloseEnoughAsItIs) {
  // A sheet without the ridge: nothing is far, nothing moves.
  QuadMesh original = fineSheet();
  for (auto& p : original.points) p[2] = 0.0;
  QuadMesh mesh = voxremesh::test::unitGrid(6);
  const QuadMesh start = mesh;
  EXPECT_EQ(voxremesh::fitFarOriginalPoints(mesh, ReferenceSurface(original), unitCriteria()), 0u);
  EXPECT_EQ(mesh.points, start.points);
}

TEST(FitFarOriginalPoints, IsThreadIndependentAndRefusesBadArguments) {
  const QuadMesh original = fineSheet();
  const ReferenceSurface surface(original);
  QuadMesh one = coarseGrid(), two = coarseGrid();
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    voxremesh::fitFarOriginalPoints(one, surface, unitCriteria());
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    voxremesh::fitFarOriginalPoints(two, surface, unitCriteria());
  }
  EXPECT_EQ(one.points, two.points);
  QuadMesh mesh = coarseGrid();
  EXPECT_THROW(voxremesh::fitFarOriginalPoints(mesh, surface, unitCriteria(), -1),
               std::invalid_argument);
  EXPECT_THROW(voxremesh::fitFarOriginalPoints(mesh, ReferenceSurface(), unitCriteria()),
               std::invalid_argument);
  voxremesh::QualitySettings noSize = unitCriteria();
  noSize.targetSize = 0.0;
  EXPECT_THROW(voxremesh::fitFarOriginalPoints(mesh, surface, noSize), std::invalid_argument);
  voxremesh::QualitySettings absurd = unitCriteria();
  absurd.maxDistanceFactor = -1.0;
  EXPECT_THROW(voxremesh::fitFarOriginalPoints(mesh, surface, absurd), voxremesh::SettingError);
}

}  // namespace
