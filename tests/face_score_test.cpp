// The optimisation's face score (src/optimize/face_score.h): the criteria a face fails, a sliver
// counting as failing every criterion. It skips the degrees of angles that lie inside their soft
// limits (src/quality/windowed_quality.h), and must give exactly the score of the full metrics of
// elementQuality, for any element, including angles a hair either side of a limit, concave and
// degenerate elements.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "optimize/face_score.h"
#include "quality/windowed_quality.h"
#include "voxremesh/quality.h"

namespace {

using voxremesh::ElementQuality;
using voxremesh::QuadMesh;
using voxremesh::QualitySettings;
using Points = std::array<std::array<double, 3>, 4>;

constexpr double kRadians = 3.14159265358979323846 / 180.0;

/// The score computed from the full metrics, as the report computes them.
voxremesh::opt::Score exactScore(const Points& p, int corners, const QualitySettings& s) {
  return voxremesh::opt::scoreOfQuality(voxremesh::elementQuality(p, corners), corners, s);
}

/// faceScore of the element as the only face of a mesh.
voxremesh::opt::Score fastScore(const Points& p, int corners, const QualitySettings& s) {
  QuadMesh mesh;
  for (int k = 0; k < corners; ++k) mesh.points.push_back(p[std::size_t(k)]);
  mesh.faces.push_back({0, 1, 2, corners == 4 ? 3u : voxremesh::kNoCorner});
  return voxremesh::opt::faceScore(mesh, mesh.faces[0], s);
}

void expectSameScore(const Points& p, int corners, const QualitySettings& s) {
  const voxremesh::opt::Score exact = exactScore(p, corners, s), fast = fastScore(p, corners, s);
  EXPECT_EQ(fast.failures, exact.failures);
  EXPECT_EQ(fast.penalty, exact.penalty);  // bit for bit: the same decisions everywhere
}

QualitySettings defaults() {
  QualitySettings s;
  s.targetSize = 1.0;
  return s;
}

TEST(FaceScore, CountsTheCriteriaFailedAndASliverAsFailingEvery) {
  const QualitySettings s = defaults();  // minimum length limit 0.5, a sliver under 0.05
  // A unit square passes all; a 1 x 0.3 rectangle fails the minimum length (0.3) and the aspect
  // ratio (3.33 < 5 passes): one criterion.
  const Points square = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
  const Points thin = {{{0, 0, 0}, {1, 0, 0}, {1, 0.3, 0}, {0, 0.3, 0}}};
  EXPECT_EQ(fastScore(square, 4, s).failures, 0);
  EXPECT_EQ(fastScore(square, 4, s).penalty, 0.0);
  EXPECT_EQ(fastScore(thin, 4, s).failures, 1);
  // 1 x 0.06 fails the minimum length and the aspect ratio; 1 x 0.04 is a sliver.
  const Points narrow = {{{0, 0, 0}, {1, 0, 0}, {1, 0.06, 0}, {0, 0.06, 0}}};
  const Points sliver = {{{0, 0, 0}, {1, 0, 0}, {1, 0.04, 0}, {0, 0.04, 0}}};
  EXPECT_EQ(fastScore(narrow, 4, s).failures, 2);
  EXPECT_EQ(fastScore(sliver, 4, s).failures, voxremesh::kCriterionCount);
  // Four points on a line (a face folded flat along a curve) are a sliver too.
  const Points line = {{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}};
  EXPECT_EQ(fastScore(line, 4, s).failures, voxremesh::kCriterionCount);
  EXPECT_EQ(fastScore(line, 3, s).failures, voxremesh::kCriterionCount);
}

TEST(FaceScore, EqualsTheFullMetricsOnRandomElements) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.45, 0.45), height(-0.3, 0.3);
  const QualitySettings s = defaults();
  for (int i = 0; i < 20000; ++i) {
    Points p = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
    for (auto& corner : p) {
      corner[0] += jitter(random);
      corner[1] += jitter(random);
      corner[2] += i % 2 == 0 ? 0.0 : height(random);
    }
    expectSameScore(p, 4, s);
    expectSameScore(p, 3, s);
  }
}

TEST(FaceScore, EqualsTheFullMetricsAtTheSoftLimitsOfTheAngles) {
  // Rhombi and isosceles triangles whose angles sit within 1e-6 degrees of each soft limit
  // (quads: 55 and 125; triangles: 35 and 110) and of each criterion's limit.
  const QualitySettings s = defaults();
  for (const double limit : {45.0, 55.0, 125.0, 135.0, 30.0, 35.0, 110.0, 120.0})
    for (const double offset : {-1e-6, -1e-9, -1e-12, 0.0, 1e-12, 1e-9, 1e-6}) {
      const double a = (limit + offset) * kRadians;
      const Points rhombus = {
          {{0, 0, 0}, {1, 0, 0}, {1 + std::cos(a), std::sin(a), 0}, {std::cos(a), std::sin(a), 0}}};
      expectSameScore(rhombus, 4, s);
      // Apex angle `a` between two unit legs.
      const Points triangle = {{{0, 0, 0}, {1, 0, 0}, {std::cos(a), std::sin(a), 0}, {}}};
      expectSameScore(triangle, 3, s);
    }
}

TEST(FaceScore, EqualsTheFullMetricsAtTheSoftLimitOfWarping) {
  // A unit square folded along its diagonal 0-2 by an angle within a hair of 10.5 degrees (0.7 x
  // the 15-degree limit) and of 15 degrees.
  const QualitySettings s = defaults();
  for (const double limit : {10.5, 15.0})
    for (const double offset : {-1e-6, -1e-9, 0.0, 1e-9, 1e-6}) {
      const double fold = (limit + offset) * kRadians;
      // Corner 3 turned about the diagonal 0-2 by `fold`: the two halves' normals differ by it.
      const double h = std::sqrt(0.5);
      const Points p = {
          {{0, 0, 0},
           {1, 0, 0},
           {1, 1, 0},
           {0.5 - h * std::cos(fold) * h, 0.5 + h * std::cos(fold) * h, h * std::sin(fold)}}};
      expectSameScore(p, 4, s);
    }
}

TEST(FaceScore, EqualsTheFullMetricsOnConcaveAndDegenerateElements) {
  const QualitySettings s = defaults();
  const Points concave = {{{0, 0, 0}, {2, 0, 0}, {0.5, 0.5, 0}, {0, 2, 0}}};
  const Points zeroEdge = {{{0, 0, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
  const Points line = {{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}};
  const Points bowtie = {{{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}}};
  for (const Points& p : {concave, zeroEdge, line, bowtie}) {
    expectSameScore(p, 4, s);
    expectSameScore(p, 3, s);
  }
}

TEST(FaceScore, EqualsTheFullMetricsUnderOtherLimits) {
  // Other limits (the windows are kept per settings), the Jacobian at the Gauss points, and soft
  // limits outside 0..180 degrees, where nothing may be skipped.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> jitter(-0.4, 0.4);
  QualitySettings strict = defaults(), gauss = defaults(), odd = defaults();
  strict.minQuadAngleDeg = 80.0;
  strict.maxQuadAngleDeg = 100.0;
  strict.maxWarpingDeg = 2.0;
  strict.maxSkewDeg = 5.0;
  gauss.jacobianAtGaussPoints = true;
  odd.minQuadAngleDeg = 175.0;  // soft limit 185 degrees
  odd.maxTriaAngleDeg = 5.0;    // soft limit -5 degrees
  for (int i = 0; i < 5000; ++i) {
    Points p = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
    for (auto& corner : p)
      for (double& x : corner) x += jitter(random);
    for (const QualitySettings& s : {strict, gauss, odd, defaults()}) {
      expectSameScore(p, 4, s);
      expectSameScore(p, 3, s);
    }
  }
}

TEST(FaceFailures, EqualsTheMasksOfTheFullMetricsOfEveryFace) {
  // A mesh of jittered and warped quads and triangles, the masks per criterion (not only their
  // count) under the defaults, strict limits and the Jacobian at the Gauss points.
  std::mt19937 random(13);
  std::uniform_real_distribution<double> jitter(-0.45, 0.45);
  QuadMesh mesh;
  for (int i = 0; i < 4000; ++i) {
    const auto first = static_cast<voxremesh::CornerIndex>(mesh.points.size());
    for (const auto& corner : Points{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}})
      mesh.points.push_back(
          {corner[0] + jitter(random), corner[1] + jitter(random), 0.5 * jitter(random)});
    mesh.faces.push_back(
        {first, first + 1, first + 2, i % 3 == 0 ? voxremesh::kNoCorner : first + 3});
  }
  QualitySettings strict = defaults(), gauss = defaults();
  strict.minQuadAngleDeg = 80.0;
  strict.maxWarpingDeg = 2.0;
  strict.maxSkewDeg = 5.0;
  gauss.jacobianAtGaussPoints = true;
  const std::vector<ElementQuality> qualities = voxremesh::elementQualities(mesh);
  for (const QualitySettings& s : {defaults(), strict, gauss}) {
    std::size_t failing = 0;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const int corners = voxremesh::cornerCount(mesh.faces[f]);
      const std::uint32_t failures = voxremesh::opt::faceFailures(mesh, mesh.faces[f], s);
      EXPECT_EQ(failures, voxremesh::elementFailures(qualities[f], corners, s)) << f;
      failing += failures != 0;
    }
    EXPECT_GT(failing, mesh.faces.size() / 10);  // the masks are not all empty
  }
}

}  // namespace
