// Triangles filling corners of the original sharper than the triangle angle limit (quality.h,
// "Sharp corners"): judged by their other angles; two triangles sharing such a corner, and sharp
// triangles elsewhere, still fail.
#include <gtest/gtest.h>

#include <vector>

#include "voxremesh/quality.h"

namespace {

using voxremesh::CornerIndex;
using voxremesh::Criterion;
using voxremesh::kNoCorner;
using voxremesh::MeshCurve;
using voxremesh::PointRole;
using voxremesh::QuadMesh;

/// The tail of a wing rib: a wedge of about 14 degrees from its tip at the origin, a triangle
/// (tip to x = 4) and a quad (x = 4 to 6).
QuadMesh wedge() {
  QuadMesh mesh;
  mesh.points = {{0, 0, 0}, {4, -0.5, 0}, {4, 0.5, 0}, {6, -0.75, 0}, {6, 0.75, 0}};
  mesh.faces = {{0, 1, 2, kNoCorner}, {1, 3, 4, 2}};
  return mesh;
}

MeshCurve curve(std::vector<std::array<double, 3>> points, bool closed, PointRole role) {
  MeshCurve c;
  c.points = std::move(points);
  c.closed = closed;
  c.role = role;
  return c;
}

/// The wedge's outline as its only channel curve.
std::vector<MeshCurve> wedgeOutline() {
  return {curve({{0, 0, 0}, {4, -0.5, 0}, {6, -0.75, 0}, {6, 0.75, 0}, {4, 0.5, 0}}, true,
                PointRole::Boundary)};
}

voxremesh::QualitySettings unitSize() {
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  return settings;
}

TEST(SharpCorners, ATriangleFillingASharpCornerIsJudgedByItsOtherAngles) {
  const QuadMesh mesh = wedge();
  const auto alone = voxremesh::assessQuality(mesh, unitSize());
  EXPECT_EQ(alone.failing(Criterion::TriaMinAngle), 1u);  // 14 degrees at the tip
  const std::vector<MeshCurve> channels = wedgeOutline();
  const auto judged = voxremesh::assessQuality(mesh, unitSize(), &mesh, &channels);
  EXPECT_EQ(judged.sharpCornerElements, 1u);
  EXPECT_EQ(judged.failing(Criterion::TriaMinAngle), 0u);
  EXPECT_EQ(judged.failing(Criterion::Skew), 0u);
  EXPECT_EQ(judged.failingAny, 0u);
}

TEST(SharpCorners, TwoTrianglesSharingASharpCornerBothFail) {
  const QuadMesh original = wedge();
  QuadMesh split = original;
  split.points.push_back({4, 0, 0});  // point 5, on the rung
  split.faces = {{0, 1, 5, kNoCorner}, {0, 5, 2, kNoCorner}, {1, 3, 4, 2}};
  const std::vector<MeshCurve> channels = wedgeOutline();
  const auto report = voxremesh::assessQuality(split, unitSize(), &original, &channels);
  EXPECT_EQ(report.sharpCornerElements, 0u);
  EXPECT_EQ(report.failing(Criterion::TriaMinAngle), 2u);
}

TEST(SharpCorners, ASharpTriangleInARightAngledCornerFails) {
  QuadMesh plate;
  plate.points = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  plate.faces = {{0, 1, 2, 3}};
  const std::vector<MeshCurve> channels = {
      curve({{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}}, true, PointRole::Boundary)};
  QuadMesh sliver = plate;
  sliver.points.push_back({4, 1, 0});  // point 4: a 14-degree triangle in the corner at 0
  sliver.faces = {{0, 1, 4, kNoCorner}, {0, 4, 2, 3}};
  const auto report = voxremesh::assessQuality(sliver, unitSize(), &plate, &channels);
  EXPECT_EQ(report.sharpCornerElements, 0u);
  EXPECT_EQ(report.failing(Criterion::TriaMinAngle), 1u);
}

TEST(SharpCorners, TwoSeamsMeetingAtASharpAngleMakeACorner) {
  // A plate with a seam from its corner at the origin to (4, 1): the seam and the boundary along
  // x enclose 14 degrees, which the triangle between them fills.
  QuadMesh plate;
  plate.points = {{0, 0, 0}, {4, 0, 0}, {4, 1, 0}, {4, 4, 0}, {0, 4, 0}};
  plate.faces = {{0, 1, 2, kNoCorner}, {0, 2, 3, 4}};
  std::vector<MeshCurve> channels = {
      curve({{0, 0, 0}, {4, 0, 0}, {4, 1, 0}, {4, 4, 0}, {0, 4, 0}}, true, PointRole::Boundary)};
  const auto withoutSeam = voxremesh::assessQuality(plate, unitSize(), &plate, &channels);
  EXPECT_EQ(withoutSeam.failing(Criterion::TriaMinAngle), 1u);
  channels.push_back(curve({{0, 0, 0}, {4, 1, 0}}, false, PointRole::Junction));
  const auto withSeam = voxremesh::assessQuality(plate, unitSize(), &plate, &channels);
  EXPECT_EQ(withSeam.sharpCornerElements, 1u);
  EXPECT_EQ(withSeam.failing(Criterion::TriaMinAngle), 0u);
}

}  // namespace
