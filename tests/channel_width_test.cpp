// The width of the channel an element lies in (quality/channel_width.h) and the minimum length
// judged against it (quality.h): a strip's elements are judged at its width, a plate's at the
// target size, a corner's small elements are not excused.
#include <gtest/gtest.h>

#include <vector>

#include "quality/channel_width.h"
#include "voxremesh/quality.h"
#include "voxremesh/sheets.h"

namespace {

using voxremesh::Criterion;
using voxremesh::MeshCurve;
using voxremesh::QuadMesh;
using voxremesh::quality::ChannelWidth;

MeshCurve line(std::array<double, 3> a, std::array<double, 3> b) {
  MeshCurve curve;
  curve.points = {a, b};
  return curve;
}

constexpr std::array<double, 3> kUp{0.0, 0.0, 1.0};

TEST(ChannelWidth, BetweenTwoParallelLinesIsTheirDistance) {
  const ChannelWidth width({line({0, 0, 0}, {20, 0, 0}), line({0, 1, 0}, {20, 1, 0})}, 5.0);
  EXPECT_NEAR(width.at({10.0, 0.5, 0.0}, kUp), 1.0, 0.01);
  EXPECT_NEAR(width.at({10.0, 0.1, 0.0}, kUp), 1.0, 0.01);  // off centre: the same strip
}

TEST(ChannelWidth, NextToOneLineIsTheCap) {
  const ChannelWidth width({line({0, 0, 0}, {20, 0, 0})}, 5.0);
  EXPECT_DOUBLE_EQ(width.at({10.0, 0.3, 0.0}, kUp), 5.0);
  EXPECT_DOUBLE_EQ(width.at({10.0, 30.0, 0.0}, kUp), 5.0);  // no curve near
}

TEST(ChannelWidth, ARightAngledCornerDoesNotExcuseSmallElements) {
  // The largest empty ball through (a, a) in the corner of the axes has a diameter of about
  // 6.8 a: a small element in the corner is not in a narrow channel.
  const ChannelWidth width({line({0, 0, 0}, {20, 0, 0}), line({0, 0, 0}, {0, 20, 0})}, 10.0);
  EXPECT_GT(width.at({0.3, 0.3, 0.0}, kUp), 1.8);
}

TEST(ChannelWidth, AnAcuteTipIsNarrow) {
  // A 20-degree wedge: near its tip the channel is as narrow as the wedge there.
  const double t = std::tan(10.0 * M_PI / 180.0);
  const ChannelWidth width({line({0, 0, 0}, {20, 20 * t, 0}), line({0, 0, 0}, {20, -20 * t, 0})},
                           10.0);
  EXPECT_LT(width.at({2.0, 0.0, 0.0}, kUp), 2.0 * 2.0 * t * 1.2);
}

/// A grid of nx x ny square quads of side `cell` in the plane z = 0, from the origin.
QuadMesh grid(int nx, int ny, double cell) {
  QuadMesh mesh;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) mesh.points.push_back({i * cell, j * cell, 0.0});
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const auto a = static_cast<voxremesh::CornerIndex>(j * (nx + 1) + i);
      mesh.faces.push_back({a, a + 1, a + static_cast<voxremesh::CornerIndex>(nx) + 2,
                            a + static_cast<voxremesh::CornerIndex>(nx) + 1});
    }
  return mesh;
}

std::vector<MeshCurve> outline(double length, double width) {
  MeshCurve curve;
  curve.points = {{0, 0, 0}, {length, 0, 0}, {length, width, 0}, {0, width, 0}};
  curve.closed = true;
  return {curve};
}

TEST(MinLengthInChannels, AStripIsJudgedAtItsWidth) {
  const QuadMesh mesh = grid(10, 1, 1.0);
  voxremesh::QualitySettings settings;
  settings.targetSize = 4.0;
  const auto without = voxremesh::assessQuality(mesh, settings);
  EXPECT_EQ(without.failing(Criterion::MinLength), 10u);
  const std::vector<MeshCurve> channels = outline(10.0, 1.0);
  const auto with = voxremesh::assessQuality(mesh, settings, nullptr, &channels);
  EXPECT_EQ(with.failing(Criterion::MinLength), 0u);
  EXPECT_EQ(with.narrowChannelElements, 10u);
  for (double size : with.judgedSize) EXPECT_NEAR(size, 1.0, 0.01);
}

TEST(MinLengthInChannels, APlateIsJudgedAtTheTargetSize) {
  // 1 x 1 quads on a 12 x 12 plate at a target size of 4: only the boundary is a curve, the
  // channel is the whole plate, and every element is too short. Even the four corner elements
  // lie in balls about 3.4 wide, too wide to excuse them (an element is excused by a channel
  // narrower than twice its length), so every element is judged at the target size.
  const QuadMesh mesh = grid(12, 12, 1.0);
  voxremesh::QualitySettings settings;
  settings.targetSize = 4.0;
  const std::vector<MeshCurve> channels = outline(12.0, 12.0);
  const auto report = voxremesh::assessQuality(mesh, settings, nullptr, &channels);
  EXPECT_EQ(report.failing(Criterion::MinLength), 144u);
  EXPECT_EQ(report.narrowChannelElements, 0u);
  for (double size : report.judgedSize) EXPECT_DOUBLE_EQ(size, 4.0);
}

TEST(ChannelWidth, ACapOfTheQueryBoundsTheSearch) {
  // A strip 3 wide: measured up to a cap of 2, it is "at least 2"; up to 5, its width.
  const ChannelWidth width({line({0, 0, 0}, {20, 0, 0}), line({0, 3, 0}, {20, 3, 0})}, 5.0);
  EXPECT_DOUBLE_EQ(width.at({10.0, 1.5, 0.0}, kUp, 2.0), 2.0);
  EXPECT_NEAR(width.at({10.0, 1.5, 0.0}, kUp, 5.0), 3.0, 0.01);
  EXPECT_NEAR(width.at({10.0, 1.5, 0.0}, kUp), 3.0, 0.01);
}

TEST(MinLengthInChannels, TwoRowsAcrossAStripAreTooShort) {
  // A strip 1 wide meshed with two rows of 0.5 x 0.5 quads: the strip, not the rows, sets the
  // size they are judged at (1), so under a limit of 0.6 x that size they fail; one row across
  // would pass.
  const QuadMesh mesh = grid(20, 2, 0.5);
  voxremesh::QualitySettings settings;
  settings.targetSize = 4.0;
  settings.minLengthFactor = 0.6;
  const std::vector<MeshCurve> channels = outline(10.0, 1.0);
  const auto report = voxremesh::assessQuality(mesh, settings, nullptr, &channels);
  EXPECT_EQ(report.failing(Criterion::MinLength), 40u);
}

TEST(ChannelCurves, AreTheSheetsBoundaryFeatureAndJunctionCurves) {
  voxremesh::Sheet sheet;
  sheet.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  sheet.faces = {{0, 1, 2, 3}};
  sheet.boundaryLoops = {{{0, 1, 2, 3}, true, false}};
  sheet.featureLines = {{{0, 2}, false, false}};
  sheet.junctionCurves = {{{1, 3}, false, false}};
  const std::vector<MeshCurve> curves = voxremesh::channelCurves({sheet});
  ASSERT_EQ(curves.size(), 3u);
  EXPECT_TRUE(curves[0].closed);
  EXPECT_EQ(curves[0].points.size(), 4u);
  EXPECT_EQ(curves[1].points[1], (std::array<double, 3>{1, 1, 0}));
  EXPECT_EQ(curves[2].role, voxremesh::PointRole::Junction);
}

}  // namespace
