// Quality criteria files (criteria_file.h) and the quality index (quality.h): the shipped default
// file is the defaults, files round-trip, bad lines are refused with their line, the index's
// penalties follow the thresholds, and a user's criteria steer the optimisation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "support/test_support.h"
#include "support/unit_grid.h"
#include "voxremesh/criteria_file.h"
#include "voxremesh/errors.h"
#include "voxremesh/extract.h"
#include "voxremesh/io.h"
#include "voxremesh/optimize.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"
#include "voxremesh/sheets.h"
#include "voxremesh/volume.h"

using namespace voxremesh;

namespace {

/// Every limit, share, flag and index threshold of two settings agree.
void expectSameCriteria(const QualitySettings& a, const QualitySettings& b) {
  for (int c = 0; c < kCriterionCount; ++c) {
    const auto criterion = static_cast<Criterion>(c);
    const std::string name = criterionName(criterion);
    if (const auto field = limitField(criterion)) {
      EXPECT_EQ(a.*field, b.*field) << name;
    }
    const IndexThresholds &x = a.index[std::size_t(c)], &y = b.index[std::size_t(c)];
    EXPECT_EQ(x.ideal, y.ideal) << name;
    EXPECT_EQ(x.good, y.good) << name;
    EXPECT_EQ(x.warn, y.warn) << name;
    EXPECT_EQ(x.worst, y.worst) << name;
    EXPECT_EQ(x.weight, y.weight) << name;
  }
  EXPECT_EQ(a.maxTriangleShare, b.maxTriangleShare);
  EXPECT_EQ(a.maxFailingShare, b.maxFailingShare);
  EXPECT_EQ(a.jacobianAtGaussPoints, b.jacobianAtGaussPoints);
  EXPECT_EQ(a.minLengthAbsolute, b.minLengthAbsolute);
  EXPECT_EQ(a.distanceAbsolute, b.distanceAbsolute);
}

/// The line an InputError names for criteria `text`, or 0 when it parses; `settings` unchanged
/// when it does not.
std::size_t errorLine(const std::string& text) {
  QualitySettings settings;
  try {
    parseCriteria(text, "test.txt", settings);
  } catch (const InputError& error) {
    expectSameCriteria(settings, QualitySettings{});
    EXPECT_EQ(error.file(), "test.txt");
    return error.line() > 0 ? error.line() : 1000;
  }
  return 0;
}

}  // namespace

TEST(CriteriaFile, TheShippedDefaultFileIsTheDefaults) {
  QualitySettings read;
  read.maxWarpingDeg = 3.0;  // every value the file names replaces the settings'
  read.index[0].weight = 7.0;
  readCriteriaFile(
      (std::filesystem::path(VOXREMESH_SOURCE_DIR) / "share" / "criteria" / "default.txt").string(),
      read);
  expectSameCriteria(read, QualitySettings{});
}

TEST(CriteriaFile, WhatAFileWritesReadsBackAndWhatItOmitsStays) {
  QualitySettings changed;
  changed.maxWarpingDeg = 10.0;
  changed.index[std::size_t(Criterion::Warping)] = {0.0, 2.0, 8.0, 25.0, 3.0};
  changed.minLengthFactor = 2.5;  // in model units
  changed.minLengthAbsolute = true;
  changed.index[std::size_t(Criterion::MinLength)] = {6.0, 5.0, 4.0, 1.0, 1.0};
  changed.maxDistanceFactor = 0.3;  // x the size
  changed.maxTriangleShare = 0.1;
  changed.jacobianAtGaussPoints = true;
  QualitySettings read;
  parseCriteria(formatCriteria(changed), "written", read);
  expectSameCriteria(read, changed);

  QualitySettings partial;
  parseCriteria("# only two\nskew 0 5 10 30 50 2\ntria_share 8%\n", "partial", partial);
  EXPECT_EQ(partial.maxSkewDeg, 30.0);
  EXPECT_EQ(partial.index[std::size_t(Criterion::Skew)].weight, 2.0);
  EXPECT_EQ(partial.maxTriangleShare, 0.08);
  EXPECT_EQ(partial.maxWarpingDeg, QualitySettings{}.maxWarpingDeg);
}

TEST(CriteriaFile, BadLinesAreRefusedWithTheirLine) {
  EXPECT_EQ(errorLine("warping 0 5 10 15 30\n"), 0u);
  EXPECT_EQ(errorLine("warping 0 5 10 15 30\n\naspect 1 2 4 5\n"), 3u);    // four values
  EXPECT_EQ(errorLine("warping 0 5 20 15 30\n"), 1u);                      // out of order
  EXPECT_EQ(errorLine("# c\nquad_min_angle 90 75 60 70 20\n"), 2u);        // a minimum
  EXPECT_EQ(errorLine("min_length 1 0.8 0.6 0.5 0.2\n"), 0u);              // in model units
  EXPECT_EQ(errorLine("min_length 1h 0.8h 0.6 0.5h 0.2h\n"), 1u);          // both kinds
  EXPECT_EQ(errorLine("skew 0h 10 30 40 60\n"), 1u);                       // an angle with h
  EXPECT_EQ(errorLine("warp 0 5 10 15 30\n"), 1u);                         // unknown
  EXPECT_EQ(errorLine("taper 0 .2 .5 .6 .9\ntaper 0 .2 .5 .6 .9\n"), 2u);  // twice
  EXPECT_EQ(errorLine("tria_share 1.5\n"), 1u);                            // not a share
  EXPECT_EQ(errorLine("jacobian_at nodes\n"), 1u);
  EXPECT_EQ(errorLine("folded 0 0 0 1 1\n"), 1u);  // folded's limit is 0
  EXPECT_EQ(errorLine("skew 0 10 30 40 x\n"), 1u);
  EXPECT_EQ(errorLine("skew 0 10 30 40 60 -1\n"), 1u);  // a negative weight
  // A file whose values checkQualitySettings refuses (an aspect ratio under 1) names no line.
  EXPECT_EQ(errorLine("aspect 0.1 0.2 0.3 0.5 2\n"), 1000u);
  EXPECT_THROW(
      {
        QualitySettings s;
        readCriteriaFile("/nonexistent/criteria.txt", s);
      },
      InputError);
}

TEST(CriteriaFile, LengthsInModelUnitsDoNotScaleWithTheSize) {
  // Unit squares: minimum element length 1. A limit of 0.5h fails them once the size passes 2;
  // a limit of 1.5 in model units fails them whatever the size, and one of 0.8 never does. The
  // quality index follows the thresholds as given.
  const QuadMesh grid = test::unitGrid(3);
  const auto failingMinLength = [&](const std::string& line, double size) {
    QualitySettings settings;
    parseCriteria(line, "test.txt", settings);
    settings.targetSize = size;
    return assessQuality(grid, settings).failing(Criterion::MinLength);
  };
  const std::string relative = "min_length 1h 0.8h 0.6h 0.5h 0.2h\n";
  EXPECT_EQ(failingMinLength(relative, 1.0), 0u);
  EXPECT_EQ(failingMinLength(relative, 4.0), 9u);
  for (const double size : {0.5, 1.0, 4.0}) {
    EXPECT_EQ(failingMinLength("min_length 3 2.5 2 1.5 0.5\n", size), 9u) << size;
    EXPECT_EQ(failingMinLength("min_length 3 2.5 2 0.8 0.5\n", size), 0u) << size;
  }
  QualitySettings settings;
  parseCriteria("min_length 1 1 1 0.5 0.1\n", "test.txt", settings);
  settings.targetSize = 10.0;  // would fail every element were the lengths relative
  const QualityReport report = assessQuality(grid, settings);
  EXPECT_EQ(report.failingAny, 0u);
  EXPECT_EQ(report.meanQualityIndex, 0.0);  // every length at its ideal
  // The distance limit in model units too.
  parseCriteria("distance 0 0.1 0.2 0.4 1\n", "test.txt", settings);
  const QuadMesh original = test::unitGrid(3);
  EXPECT_DOUBLE_EQ(assessQuality(grid, settings, &original).distanceLimit, 0.4);
}

TEST(QualityIndex, PenaltiesFollowTheThresholds) {
  const IndexThresholds warping{0.0, 5.0, 10.0, 30.0, 1.0};
  EXPECT_EQ(indexPenalty(0.0, warping, 15.0, true), 0.0);
  EXPECT_EQ(indexPenalty(5.0, warping, 15.0, true), 0.0);
  EXPECT_DOUBLE_EQ(indexPenalty(7.5, warping, 15.0, true), 0.4);
  EXPECT_DOUBLE_EQ(indexPenalty(10.0, warping, 15.0, true), 0.8);
  EXPECT_DOUBLE_EQ(indexPenalty(15.0, warping, 15.0, true), 1.0);
  EXPECT_DOUBLE_EQ(indexPenalty(30.0, warping, 15.0, true), 10.0);
  EXPECT_DOUBLE_EQ(indexPenalty(45.0, warping, 15.0, true), 19.0);  // on at the last slope
  EXPECT_EQ(indexPenalty(std::nan(""), warping, 15.0, true), 10.0);
  // A minimum: smaller is worse.
  const IndexThresholds angle{90.0, 75.0, 60.0, 20.0, 1.0};
  EXPECT_EQ(indexPenalty(80.0, angle, 45.0, false), 0.0);
  EXPECT_DOUBLE_EQ(indexPenalty(45.0, angle, 45.0, false), 1.0);
  EXPECT_DOUBLE_EQ(indexPenalty(20.0, angle, 45.0, false), 10.0);
  // A limit beyond worst moves worst to it: the limit still scores 1, beyond it 10.
  EXPECT_DOUBLE_EQ(indexPenalty(40.0, warping, 40.0, true), 1.0);
  EXPECT_DOUBLE_EQ(indexPenalty(41.0, warping, 40.0, true), 10.0);
}

TEST(QualityIndex, ASquareScoresNothingAndAWarpedQuadItsPenalties) {
  QuadMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0.3}};
  mesh.faces = {{0, 1, 2, 3}, {1, 4, 5, 2}};
  QualitySettings settings;
  settings.targetSize = 1.0;
  const QualityReport report = assessQuality(mesh, settings);
  ASSERT_EQ(report.qualityIndex.size(), 2u);
  EXPECT_EQ(report.qualityIndex[0], 0.0);
  // The second quad is warped: its index is at least its warping penalty.
  const double warping = report.elementValues[1].warpingDeg;
  ASSERT_GT(warping, 5.0);
  EXPECT_GE(report.qualityIndex[1],
            indexPenalty(warping, settings.index[0], settings.maxWarpingDeg, true));
  EXPECT_DOUBLE_EQ(report.meanQualityIndex, 0.5 * report.qualityIndex[1]);
  // Weighting warping twice doubles that part of the index.
  QualitySettings heavy = settings;
  heavy.index[std::size_t(Criterion::Warping)].weight = 2.0;
  const QualityReport weighted = assessQuality(mesh, heavy);
  EXPECT_DOUBLE_EQ(weighted.qualityIndex[1] - report.qualityIndex[1],
                   indexPenalty(warping, settings.index[0], settings.maxWarpingDeg, true));
}

TEST(CriteriaFile, AStricterWarpingGivesFewerWarpedElementsALooserFileFewerEdits) {
  // The bracket's extracted quads at 4.5 mm, optimised with the default criteria, with a file
  // allowing 6 degrees of warping instead of 15, and with one whose angle, skew, aspect, taper and
  // Jacobian limits are loose: the strict file leaves fewer quads warped past 6 degrees, the loose
  // one makes fewer edits on failing elements.
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "bracket.k");
  const FeModel model = readDeck(deck);
  const std::vector<Sheet> sheets = buildAllSheets(model);
  const QuadMesh input = quadMeshFromModel(model, sheets[0].part);
  VolumeSettings volumeSettings;
  volumeSettings.targetElementSize = 4.5;
  const QuadMesh extracted = extractQuadMesh(buildVolume(sheets, volumeSettings));
  const ReferenceSurface surface(input);
  struct Result {
    std::size_t warped = 0;  ///< quads warped past 6 degrees
    std::size_t edits = 0;   ///< point moves, rotations, reconnections, splits on failing faces
  };
  const auto optimise = [&](const std::string& criteria) {
    OptimizeSettings settings;
    parseCriteria(criteria, "test", settings.quality);
    settings.quality.targetSize = 4.5;
    QuadMesh mesh = extracted;
    OptimizeStats stats;
    optimizeQuadMesh(mesh, surface, settings, &stats);
    Result result;
    for (const ElementQuality& quality : elementQualities(mesh))
      result.warped += quality.warpingDeg > 6.0;
    result.edits =
        stats.improvedMoves + stats.edgesRotated + stats.reconnected + stats.failingSplit;
    return result;
  };
  const Result defaults = optimise("");
  const Result strict = optimise("warping 0 2 4 6 30\n");
  const Result loose = optimise(
      "aspect 1 2 4 10 20\nquad_min_angle 90 75 60 20 10\nquad_max_angle 90 105 120 160 170\n"
      "skew 0 10 30 70 80\njacobian_ratio 1 0.9 0.7 0.2 0.1\ntaper 0 0.2 0.5 0.9 0.95\n"
      "tria_min_angle 60 50 40 10 5\ntria_max_angle 60 75 100 160 170\n");
  EXPECT_LT(strict.warped, defaults.warped);
  EXPECT_LT(loose.edits, defaults.edits);
}
