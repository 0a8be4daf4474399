// refillFoldedRegions: planted folds in grids are untangled with their faces kept, on a plane and
// on a cylinder, and a fold round a fixed point is not untangled by moving it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "support/unit_grid.h"
#include "voxremesh/optimize.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"

namespace {

using voxremesh::QuadMesh;
using voxremesh::ReferenceSurface;
using voxremesh::test::gridPoint;
using voxremesh::test::unitGrid;

constexpr int kCells = 8;

std::size_t foldCount(const QuadMesh& mesh) {
  const std::vector<std::uint8_t> folded = voxremesh::foldedFaces(mesh);
  return static_cast<std::size_t>(std::count(folded.begin(), folded.end(), std::uint8_t(1)));
}

voxremesh::QualitySettings unitCriteria() {
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  return settings;
}

/// The grid laid on a cylinder of radius `radius` round the y axis (x along its arc).
void rollOntoCylinder(QuadMesh& mesh, double radius) {
  for (auto& p : mesh.points) {
    const double angle = p[0] / radius;
    p = {radius * std::sin(angle), p[1], radius * (1.0 - std::cos(angle))};
  }
}

TEST(RefillFoldedRegions, AFoldInAFlatGridIsUntangledWithItsQuadsKept) {
  const QuadMesh original = unitGrid(kCells);
  const ReferenceSurface surface(original);
  QuadMesh mesh = original;
  // Point (4, 4) pulled down and left across the diagonal of the quad below-left of it, which
  // folds over.
  mesh.points[gridPoint(kCells, 4, 4)] = {2.4, 3.3, 0.0};
  ASSERT_GT(foldCount(mesh), 0u);

  EXPECT_GE(voxremesh::refillFoldedRegions(mesh, surface, unitCriteria()), 1u);
  EXPECT_EQ(foldCount(mesh), 0u);
  EXPECT_EQ(mesh.faces, original.faces);  // untangled, not cut out and refilled
  const auto& p = mesh.points[gridPoint(kCells, 4, 4)];
  // Tutte's embedding of a regular grid puts the point back at the mean of its neighbours.
  EXPECT_NEAR(p[0], 4.0, 1e-6);
  EXPECT_NEAR(p[1], 4.0, 1e-6);
  EXPECT_NEAR(p[2], 0.0, 1e-12);
}

TEST(RefillFoldedRegions, AFoldOnACylinderIsUntangledOntoTheCylinder) {
  constexpr double kRadius = 6.0;
  QuadMesh original = unitGrid(kCells);
  rollOntoCylinder(original, kRadius);
  const ReferenceSurface surface(original);
  QuadMesh mesh = unitGrid(kCells);
  mesh.points[gridPoint(kCells, 3, 5)] = {1.4, 4.3, 0.0};  // folds the quad below-left
  rollOntoCylinder(mesh, kRadius);
  ASSERT_GT(foldCount(mesh), 0u);

  EXPECT_GE(voxremesh::refillFoldedRegions(mesh, surface, unitCriteria()), 1u);
  EXPECT_EQ(foldCount(mesh), 0u);
  EXPECT_EQ(mesh.faces, original.faces);
  for (const auto& p : mesh.points)  // every point on the original surface
    EXPECT_LT(surface.closestPoint(p).distance, 1e-9);
}

TEST(RefillFoldedRegions, AFixedPointInsideAFoldIsNotMoved) {
  const QuadMesh original = unitGrid(kCells);
  const ReferenceSurface surface(original);
  QuadMesh mesh = original;
  const auto v = gridPoint(kCells, 4, 4);
  mesh.points[v] = {2.4, 3.3, 0.0};
  mesh.constraints[v].role = voxremesh::PointRole::Corner;  // a hard point: it must stay
  ASSERT_GT(foldCount(mesh), 0u);

  voxremesh::refillFoldedRegions(mesh, surface, unitCriteria());
  EXPECT_EQ(mesh.points[v][0], 2.4);
  EXPECT_EQ(mesh.points[v][1], 3.3);
}

}  // namespace
