// Seam sampling over the deck (pipeline/seam_counts.h): the growth ratio of the pieces toward a
// sharp corner of a narrow sheet follows the quality criteria, on the curves along its sides.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "pipeline/seam_counts.h"
#include "voxremesh/quality.h"

using namespace voxremesh;

TEST(SeamSampling, AWedgeRatioKeepsTheRowsTrapezoidsHalfwayToTheLimits) {
  const QualitySettings criteria;  // Jacobian ratio 0.6, aspect 5, quad angles from 45
  // A corner a quad can fill is not graded.
  EXPECT_EQ(pipeline::wedgeRatio(45.0, criteria), 0.0);
  EXPECT_EQ(pipeline::wedgeRatio(90.0, criteria), 0.0);
  // At 30 degrees the Jacobian ratio bounds it: parallel sides within sqrt(0.6).
  EXPECT_NEAR(pipeline::wedgeRatio(30.0, criteria), 1.0 / std::sqrt(0.6), 1e-12);
  // At 5 degrees the aspect does: a piece along at most sqrt(5) times the rung across.
  const double tip = pipeline::wedgeRatio(5.0, criteria);
  EXPECT_NEAR(tip, 1.0 + std::sqrt(5.0) * 2.0 * std::tan(2.5 * M_PI / 180.0), 1e-12);
  EXPECT_LT(tip, 1.0 / std::sqrt(0.6));
  // Stricter criteria grade more gently.
  QualitySettings strict = criteria;
  strict.minJacobianRatio = 0.8;
  EXPECT_LT(pipeline::wedgeRatio(30.0, strict), pipeline::wedgeRatio(30.0, criteria));
}

TEST(SeamSampling, OnlyTheCurvesAlongAWedgesSidesShrinkTowardItsTip) {
  // Node 10 is the tip of a wedge whose side runs to node 11. The curve along that side (10, 11,
  // 12), in either direction, is graded at the tip; the curve from 10 to 13 (another sheet's side
  // that only ends there, where the sheet is no wedge) keeps even pieces.
  Sheet sheet;
  sheet.points = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {2.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
  sheet.pointNodeIds = {10, 11, 12, 13};
  Polyline along, back, other;
  along.points = {0, 1, 2};
  back.points = {2, 1, 0};
  other.points = {0, 3};
  sheet.junctionCurves = {along, back, other};
  pipeline::SeamSampling sampling;
  sampling.grading[{10, 11}] = 1.25;
  std::vector<Sheet> sheets{sheet};
  pipeline::setSeamSampling(sheets, sampling);
  const std::vector<Polyline>& curves = sheets.front().junctionCurves;
  using Graded = std::vector<std::pair<std::size_t, double>>;
  EXPECT_EQ(curves[0].grading, (Graded{{0, 1.25}}));
  EXPECT_EQ(curves[1].grading, (Graded{{2, 1.25}}));
  EXPECT_TRUE(curves[2].grading.empty());
}
