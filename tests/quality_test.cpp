// Quality metrics on elements with hand-computed values, the per-mesh summary, settings checks,
// and the two-sided distance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "quality/fold_check.h"
#include "voxremesh/errors.h"
#include "voxremesh/quality.h"

namespace {

using voxremesh::Criterion;
using voxremesh::ElementQuality;
using voxremesh::QuadMesh;
using Points = std::array<std::array<double, 3>, 4>;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = 180.0 / kPi;

ElementQuality quad(Points p) {
  return voxremesh::elementQuality(p, 4);
}
ElementQuality tria(Points p) {
  return voxremesh::elementQuality(p, 3);
}

TEST(ElementQuality, UnitSquareIsPerfect) {
  const ElementQuality q = quad({{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}});
  EXPECT_DOUBLE_EQ(q.warpingDeg, 0.0);
  EXPECT_DOUBLE_EQ(q.aspectRatio, 1.0);
  EXPECT_NEAR(q.minAngleDeg, 90.0, 1e-12);
  EXPECT_NEAR(q.maxAngleDeg, 90.0, 1e-12);
  EXPECT_NEAR(q.skewDeg, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(q.jacobianRatio, 1.0);
  EXPECT_DOUBLE_EQ(q.jacobianRatioGauss, 1.0);
  EXPECT_DOUBLE_EQ(q.scaledJacobian, 1.0);
  EXPECT_NEAR(q.taper, 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(q.minLength, 1.0);
}

TEST(ElementQuality, WarpedQuadHasTheWiderSplitAngle) {
  // Corner 2 lifted by h: split 0-2 normals (0,-h,1) and (-h,0,1), cos = 1 / (1 + h^2); split 1-3
  // normals (-h,-h,1) and (0,0,1), cos = 1 / sqrt(1 + 2 h^2), the narrower one.
  const double h = 0.3;
  const ElementQuality q = quad({{{0, 0, 0}, {1, 0, 0}, {1, 1, h}, {0, 1, 0}}});
  EXPECT_NEAR(q.warpingDeg, std::acos(1.0 / (1.0 + h * h)) * kDeg, 1e-10);
  EXPECT_GT(q.warpingDeg, std::acos(1.0 / std::sqrt(1.0 + 2.0 * h * h)) * kDeg);
  EXPECT_NEAR(q.warpingDeg, 23.45, 0.01);
}

TEST(ElementQuality, RhombusOf60Degrees) {
  const double s = std::sqrt(3.0) / 2.0;
  const ElementQuality q = quad({{{0, 0, 0}, {1, 0, 0}, {1.5, s, 0}, {0.5, s, 0}}});
  EXPECT_NEAR(q.minAngleDeg, 60.0, 1e-10);
  EXPECT_NEAR(q.maxAngleDeg, 120.0, 1e-10);
  EXPECT_NEAR(q.aspectRatio, 1.0, 1e-12);
  EXPECT_NEAR(q.skewDeg, 30.0, 1e-10);
  EXPECT_NEAR(q.jacobianRatio, 1.0, 1e-12);
  EXPECT_NEAR(q.scaledJacobian, s, 1e-12);
  EXPECT_NEAR(q.taper, 0.0, 1e-12);
  EXPECT_NEAR(q.minLength, s, 1e-12);
  EXPECT_DOUBLE_EQ(q.warpingDeg, 0.0);
}

TEST(ElementQuality, Trapezoid) {
  // Bases 4 and 2, height 1: corner triangle areas 2, 2, 1, 1; quad area 3.
  const ElementQuality q = quad({{{0, 0, 0}, {4, 0, 0}, {3, 1, 0}, {1, 1, 0}}});
  EXPECT_NEAR(q.aspectRatio, 4.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(q.minAngleDeg, 45.0, 1e-10);
  EXPECT_NEAR(q.maxAngleDeg, 135.0, 1e-10);
  EXPECT_NEAR(q.taper, 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(q.jacobianRatio, 0.5, 1e-12);
  // det J = (3 - eta) / 4: 1 and 1/2 at the corners, (3 -+ 1/sqrt 3) / 4 at the Gauss points.
  const double g = 1.0 / std::sqrt(3.0);
  EXPECT_NEAR(q.jacobianRatioGauss, (3.0 - g) / (3.0 + g), 1e-12);
  EXPECT_NEAR(q.scaledJacobian, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(q.skewDeg, 0.0, 1e-10);
  EXPECT_NEAR(q.minLength, 0.75, 1e-12);
}

TEST(ElementQuality, ConcaveQuadIsReflexCorrected) {
  // An arrowhead: corner 3 points inwards.
  const ElementQuality q = quad({{{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.5, 1, 0}}});
  EXPECT_GT(q.maxAngleDeg, 180.0);
  EXPECT_LT(q.jacobianRatio, 0.0);
  EXPECT_LT(q.scaledJacobian, 0.0);
  EXPECT_GT(q.taper, 1.0);
}

TEST(ElementQuality, EquilateralTriangle) {
  const double s = std::sqrt(3.0) / 2.0;
  const ElementQuality q = tria({{{0, 0, 0}, {1, 0, 0}, {0.5, s, 0}, {0, 0, 0}}});
  EXPECT_NEAR(q.minAngleDeg, 60.0, 1e-10);
  EXPECT_NEAR(q.maxAngleDeg, 60.0, 1e-10);
  EXPECT_NEAR(q.skewDeg, 0.0, 1e-10);
  EXPECT_NEAR(q.scaledJacobian, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(q.jacobianRatio, 1.0);
  EXPECT_DOUBLE_EQ(q.warpingDeg, 0.0);
  EXPECT_DOUBLE_EQ(q.taper, 0.0);
  EXPECT_NEAR(q.minLength, s, 1e-12);  // height: 2 A / longest edge
}

TEST(ElementQuality, RightIsoscelesTriangle) {
  const ElementQuality q = tria({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}}});
  EXPECT_NEAR(q.minAngleDeg, 45.0, 1e-10);
  EXPECT_NEAR(q.maxAngleDeg, 90.0, 1e-10);
  EXPECT_NEAR(q.aspectRatio, std::sqrt(2.0), 1e-12);
  // At the 45-degree corners the median (-1, 0.5) meets the midline (0, -0.5) at atan(2).
  EXPECT_NEAR(q.skewDeg, 90.0 - std::atan(2.0) * kDeg, 1e-10);
  EXPECT_NEAR(q.scaledJacobian, 2.0 / std::sqrt(3.0) * std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(q.minLength, 1.0 / std::sqrt(2.0), 1e-12);
}

TEST(ElementQuality, RefusesOtherCornerCounts) {
  EXPECT_THROW(voxremesh::elementQuality({}, 5), std::invalid_argument);
}

/// An nx x ny grid of unit quads at height z.
QuadMesh grid(int nx, int ny, double z = 0.0, double size = 1.0) {
  QuadMesh mesh;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) mesh.points.push_back({i * size, j * size, z});
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const auto a = static_cast<voxremesh::CornerIndex>(j * (nx + 1) + i);
      mesh.faces.push_back({a, a + 1, a + nx + 2, a + nx + 1});
    }
  return mesh;
}

TEST(FoldCheck, PairedOnceItFindsTheFoldsOfThePointsWhereverTheyMove) {
  QuadMesh mesh = grid(3, 3);
  const voxremesh::quality::FoldCheck check(mesh);
  EXPECT_EQ(check.folded(mesh), voxremesh::foldedFaces(mesh));
  // The middle points dragged past their neighbours turn faces over; each position is checked
  // by the pairs made before the moves.
  for (const double x : {0.5, 1.8, 2.6, 3.4}) {
    mesh.points[5][0] = x;
    mesh.points[6][2] = 0.3 * x;
    const std::vector<std::uint8_t> folded = check.folded(mesh);
    EXPECT_EQ(folded, voxremesh::foldedFaces(mesh)) << "at " << x;
    if (x > 3.0) {
      EXPECT_GT(std::count(folded.begin(), folded.end(), 1), 0) << "at " << x;
    }
  }
}

TEST(QualityReport, CountsFailuresPerCriterionAndAny) {
  QuadMesh mesh = grid(4, 1);
  mesh.points[1][2] = 0.5;  // warps faces 0 and 1
  mesh.points.push_back({4.5, 0.5, 0.0});
  mesh.faces.push_back({4, 10, 9, voxremesh::kNoCorner});  // a tria with angles 45, 90, 45
  const voxremesh::QualityReport report = voxremesh::assessQuality(mesh);
  EXPECT_EQ(report.elements, 5u);
  EXPECT_EQ(report.quads, 4u);
  EXPECT_EQ(report.triangles, 1u);
  EXPECT_DOUBLE_EQ(report.triangleShare, 0.2);
  EXPECT_DOUBLE_EQ(report.settings.targetSize, 1.0);  // the median edge
  const auto& warping = report.criteria[static_cast<int>(Criterion::Warping)];
  EXPECT_EQ(warping.applies, 4u);
  EXPECT_EQ(warping.failing, 2u);
  EXPECT_NEAR(warping.share, 0.4, 1e-15);
  EXPECT_GT(warping.worst, 15.0);
  // The tria passes everything (its height 0.5 is exactly the length limit); only the two quads
  // beside the lifted node fail.
  EXPECT_EQ(report.criteria[static_cast<int>(Criterion::TriaMaxAngle)].failing, 0u);
  EXPECT_EQ(report.failingAny, 2u);
  EXPECT_EQ(report.elementFailures[0] & (1u << static_cast<int>(Criterion::Warping)),
            1u << static_cast<int>(Criterion::Warping));
  EXPECT_EQ(report.elementFailures[2], 0u);
  EXPECT_FALSE(report.passes());
}

TEST(QualityReport, FlatGridPasses) {
  const QuadMesh mesh = grid(3, 3);
  const voxremesh::QualityReport report = voxremesh::assessQuality(mesh, {}, &mesh);
  EXPECT_EQ(report.failingAny, 0u);
  ASSERT_TRUE(report.distance.has_value());
  EXPECT_NEAR(report.distance->max(), 0.0, 1e-12);  // samples inside faces round off a little
  EXPECT_TRUE(report.passes());
  const std::string json = voxremesh::qualityReportJson(report);
  EXPECT_NE(json.find("\"pass\":true"), std::string::npos);
  EXPECT_NE(voxremesh::formatQualityTable(report).find("result: pass"), std::string::npos);
}

TEST(QualityReport, MinLengthScalesWithTheTargetSize) {
  voxremesh::QualitySettings settings;
  settings.targetSize = 2.5;  // limit 1.25 > 1
  const voxremesh::QualityReport report = voxremesh::assessQuality(grid(2, 2), settings);
  EXPECT_EQ(report.criteria[static_cast<int>(Criterion::MinLength)].failing, 4u);
  EXPECT_DOUBLE_EQ(report.criteria[static_cast<int>(Criterion::MinLength)].limit, 1.25);
}

TEST(QualityReport, AKnifeEdgeOfTheOriginalIsNoFold) {
  // Two unit quads meeting at x = 0 in a wedge of 30 degrees (a trailing edge): their normals
  // are 150 degrees apart, so each is folded against its only neighbour. With the original given
  // and its feature line along the shared edge, that edge is a ridge of the geometry: no fold.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  QuadMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {c, 1, s}, {c, 0, s}};
  mesh.faces = {{0, 1, 2, 3}, {0, 3, 4, 5}};
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  voxremesh::MeshCurve ridge;
  ridge.points = {{0, 0, 0}, {0, 1, 0}};
  ridge.role = voxremesh::PointRole::Feature;
  const std::vector<voxremesh::MeshCurve> curves{ridge};
  const auto folded = [](const voxremesh::QualityReport& r) {
    return r.criteria[static_cast<int>(Criterion::Folded)].failing;
  };
  EXPECT_EQ(voxremesh::foldedFaces(mesh), (std::vector<std::uint8_t>{1, 1}));
  EXPECT_EQ(folded(voxremesh::assessQuality(mesh, settings, nullptr, &curves)), 2u);
  EXPECT_EQ(folded(voxremesh::assessQuality(mesh, settings, &mesh, &curves)), 0u);
  // A curve across the edge (from its middle out into the first quad) is no ridge along it.
  ridge.points = {{0, 0.5, 0}, {1, 0.5, 0}};
  const std::vector<voxremesh::MeshCurve> across{ridge};
  EXPECT_EQ(folded(voxremesh::assessQuality(mesh, settings, &mesh, &across)), 2u);
}

TEST(ElementFailures, JacobianAtCornersOrGaussPoints) {
  // The trapezoid: Jacobian ratio 0.5 at the corners, 0.677 at the Gauss points.
  const ElementQuality q = quad({{{0, 0, 0}, {4, 0, 0}, {3, 1, 0}, {1, 1, 0}}});
  voxremesh::QualitySettings s;
  s.targetSize = 1.0;
  const std::uint32_t jacobian = 1u << static_cast<int>(Criterion::JacobianRatio);
  EXPECT_FALSE(s.jacobianAtGaussPoints);  // the default: at the corners, as DESIGN.md
  EXPECT_EQ(voxremesh::elementFailures(q, 4, s) & jacobian, jacobian);
  s.jacobianAtGaussPoints = true;  // HyperMesh's default, milder
  EXPECT_EQ(voxremesh::elementFailures(q, 4, s) & jacobian, 0u);
  s.jacobianAtGaussPoints = false;
  // Its 45-degree corners pass a minimum of 44 and fail one of 50.
  const std::uint32_t minAngle = 1u << static_cast<int>(Criterion::QuadMinAngle);
  s.minQuadAngleDeg = 44.0;
  EXPECT_EQ(voxremesh::elementFailures(q, 4, s) & minAngle, 0u);
  s.minQuadAngleDeg = 50.0;
  EXPECT_EQ(voxremesh::elementFailures(q, 4, s) & minAngle, minAngle);
  EXPECT_THROW(voxremesh::elementFailures(q, 5, s), std::invalid_argument);
}

TEST(QualitySettings, AbsurdValuesAreRefused) {
  voxremesh::QualitySettings s;
  EXPECT_NO_THROW(voxremesh::checkQualitySettings(s));
  s.maxWarpingDeg = -1.0;
  EXPECT_THROW(voxremesh::checkQualitySettings(s), voxremesh::SettingError);
  s = {};
  s.maxTaper = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(voxremesh::checkQualitySettings(s), voxremesh::SettingError);
  s = {};
  s.minQuadAngleDeg = 100.0;
  s.maxQuadAngleDeg = 90.0;
  EXPECT_THROW(voxremesh::checkQualitySettings(s), voxremesh::SettingError);
  s = {};
  s.targetSize = -2.0;
  EXPECT_THROW(voxremesh::assessQuality(grid(1, 1), s), voxremesh::SettingError);
}

TEST(MedianEdgeLength, CountsEachEdgeOnce) {
  QuadMesh mesh = grid(2, 1);
  for (auto& p : mesh.points) p[1] *= 3.0;
  // 7 edges: 4 of length 1, 3 of length 3 -> median 1.
  EXPECT_DOUBLE_EQ(voxremesh::medianEdgeLength(mesh), 1.0);
  EXPECT_DOUBLE_EQ(voxremesh::medianEdgeLength(QuadMesh{}), 0.0);
}

TEST(SurfaceDistance, ParallelPlanes) {
  const QuadMesh a = grid(4, 4, 0.0), b = grid(4, 4, 0.1);
  const voxremesh::SurfaceDistance d = voxremesh::surfaceDistance(a, b);
  EXPECT_NEAR(d.maxToOriginal, 0.1, 1e-12);
  EXPECT_NEAR(d.meanToOriginal, 0.1, 1e-12);
  EXPECT_NEAR(d.maxFromOriginal, 0.1, 1e-12);
  EXPECT_NEAR(d.meanFromOriginal, 0.1, 1e-12);
  ASSERT_EQ(d.pointDistance.size(), a.points.size());
  for (double x : d.pointDistance) EXPECT_NEAR(x, 0.1, 1e-12);
}

TEST(SurfaceDistance, IsTwoSided) {
  // A 1 x 1 square inside a 2 x 2 original: nothing of the mesh is off the original, but the
  // original's far corner is sqrt(2) from the mesh.
  const QuadMesh mesh = grid(1, 1), original = grid(2, 2);
  const voxremesh::SurfaceDistance d = voxremesh::surfaceDistance(mesh, original);
  EXPECT_NEAR(d.maxToOriginal, 0.0, 1e-12);
  EXPECT_NEAR(d.maxFromOriginal, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(d.max(), std::sqrt(2.0), 1e-12);
  EXPECT_GT(d.meanFromOriginal, 0.0);
}

}  // namespace
