// The optimisation steps on synthetic meshes with planted defects: each removes its defect,
// changes the surface by less than a tolerance and respects the constraints; the driver gives the
// same bytes for one and two threads.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <set>

#include "support/test_support.h"
#include "support/unit_grid.h"
#include "voxremesh/errors.h"
#include "voxremesh/extract.h"
#include "voxremesh/io.h"
#include "voxremesh/optimize.h"
#include "voxremesh/quality.h"
#include "voxremesh/sheets.h"
#include "voxremesh/volume.h"

namespace {

using voxremesh::CornerIndex;
using voxremesh::kNoCorner;
using voxremesh::PointRole;
using voxremesh::QuadMesh;
using voxremesh::ReferenceSurface;

constexpr double kPi = 3.14159265358979323846;

/// An n x n grid of unit quads in the plane z = 0; the boundary is curve 0 (closed, through the
/// boundary points counter-clockwise), its four corners are Corner points, the other boundary
/// points Boundary points.
QuadMesh grid(int n) {
  QuadMesh mesh = voxremesh::test::unitGrid(n);
  auto id = [n](int i, int j) { return voxremesh::test::gridPoint(n, i, j); };
  voxremesh::MeshCurve loop;
  loop.closed = true;
  loop.role = PointRole::Boundary;
  std::vector<CornerIndex> ring;
  for (int i = 0; i < n; ++i) ring.push_back(id(i, 0));
  for (int j = 0; j < n; ++j) ring.push_back(id(n, j));
  for (int i = n; i > 0; --i) ring.push_back(id(i, n));
  for (int j = n; j > 0; --j) ring.push_back(id(0, j));
  for (const CornerIndex v : ring) {
    loop.points.push_back(mesh.points[v]);
    mesh.constraints[v] = {PointRole::Boundary, 0};
  }
  for (const CornerIndex v : {id(0, 0), id(n, 0), id(n, n), id(0, n)})
    mesh.constraints[v] = {PointRole::Corner, voxremesh::kNoCurve};
  mesh.curves.push_back(loop);
  return mesh;
}

/// The search engine (reconnectFailingFaces) with the given edits alone and no point searches,
/// on the flat unit grid of the mesh's extent as the original: the recut of pairs of faces
/// (kRecutPair, edge rotation) or the split of quads (kSplitQuad, within `maxTriangleShare`).
std::size_t engineWithoutSearches(QuadMesh& mesh, const voxremesh::QualitySettings& settings,
                                  unsigned edits, double maxTriangleShare = 0.0, int rounds = 5) {
  voxremesh::ReconnectSettings engine;
  engine.rounds = rounds;
  engine.sweeps = 0;
  engine.edits = edits;
  engine.maxTriangleShare = maxTriangleShare;
  double extent = 0.0;
  for (const auto& p : mesh.points) extent = std::max({extent, p[0], p[1]});
  return voxremesh::reconnectFailingFaces(
      mesh, ReferenceSurface(voxremesh::test::unitGrid(int(std::lround(extent)))), settings,
      engine);
}

CornerIndex addPoint(QuadMesh& mesh, std::array<double, 3> p) {
  mesh.points.push_back(p);
  if (!mesh.constraints.empty()) mesh.constraints.push_back({});
  return static_cast<CornerIndex>(mesh.points.size() - 1);
}

std::size_t countWarped(const QuadMesh& mesh, double limit) {
  std::size_t count = 0;
  for (const auto& q : voxremesh::elementQualities(mesh)) count += q.warpingDeg > limit ? 1 : 0;
  return count;
}

/// Every point's degree (number of edge neighbours), interior points of a valid grid have 4.
std::vector<std::size_t> degrees(const QuadMesh& mesh) {
  std::vector<std::vector<CornerIndex>> nbrs(mesh.points.size());
  for (const auto& f : mesh.faces) {
    const int n = voxremesh::cornerCount(f);
    for (int k = 0; k < n; ++k) {
      nbrs[f[k]].push_back(f[(k + 1) % n]);
      nbrs[f[(k + 1) % n]].push_back(f[k]);
    }
  }
  std::vector<std::size_t> result;
  for (auto& list : nbrs) {
    std::sort(list.begin(), list.end());
    result.push_back(
        static_cast<std::size_t>(std::unique(list.begin(), list.end()) - list.begin()));
  }
  return result;
}

/// Each point bound to the boundary lies on the square's boundary; corners are where they were.
void expectConstraintsHold(const QuadMesh& mesh, int n) {
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    const auto& p = mesh.points[v];
    const PointRole role = mesh.constraints[v].role;
    if (role == PointRole::Corner) {
      EXPECT_TRUE((p[0] == 0.0 || p[0] == n) && (p[1] == 0.0 || p[1] == n) && p[2] == 0.0) << v;
    } else if (role == PointRole::Boundary) {
      const double off =
          std::min({std::abs(p[0]), std::abs(p[0] - n), std::abs(p[1]), std::abs(p[1] - n)});
      EXPECT_LT(off + std::abs(p[2]), 1e-12) << "boundary point " << v << " left its curve";
    }
  }
}

TEST(RemoveWarping, FlattensACheckerboardOfLiftedPoints) {
  const int n = 8;
  QuadMesh mesh = grid(n);
  const QuadMesh flat = mesh;
  // Interior points alternately up and down by 0.15: every interior quad warps by about 17 deg.
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) mesh.points[j * (n + 1) + i][2] = ((i + j) % 2 ? 0.15 : -0.15);
  const QuadMesh planted = mesh;
  ASSERT_GT(countWarped(mesh, 15.0), 30u);
  const voxremesh::WarpingResult r = voxremesh::removeWarping(mesh, 12.0);
  EXPECT_GT(r.warpedBefore, 30u);
  EXPECT_EQ(r.warpedAfter, 0u);
  EXPECT_EQ(countWarped(mesh, 12.0), 0u);
  EXPECT_GT(r.iterations, 0);
  // The surface moved towards the flat one and by less than the planted amplitude.
  EXPECT_LE(voxremesh::surfaceDistance(mesh, planted).max(), 0.15 + 1e-12);
  EXPECT_LT(voxremesh::surfaceDistance(mesh, flat).maxToOriginal, 0.15);
  expectConstraintsHold(mesh, n);
}

TEST(RemoveWarping, MovesNoPointFartherThanAllowed) {
  const int n = 8;
  QuadMesh mesh = grid(n);
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) mesh.points[j * (n + 1) + i][2] = ((i + j) % 2 ? 0.15 : -0.15);
  const QuadMesh planted = mesh;
  const voxremesh::WarpingResult r = voxremesh::removeWarping(mesh, 12.0, 200, 0.05);
  EXPECT_LT(r.warpedAfter, r.warpedBefore);  // 0.05 of the 0.15 lift flattens some quads
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    const auto& a = mesh.points[v];
    const auto& b = planted.points[v];
    EXPECT_LE(std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]), 0.05 + 1e-12) << v;
  }
  EXPECT_THROW(voxremesh::removeWarping(mesh, 12.0, 10, 0.0), std::invalid_argument);
}

TEST(RemoveWarping, LeavesFlatMeshesAndRefusesBadThresholds) {
  QuadMesh mesh = grid(3);
  const QuadMesh before = mesh;
  EXPECT_EQ(voxremesh::removeWarping(mesh, 15.0).iterations, 0);
  EXPECT_EQ(mesh.points, before.points);
  EXPECT_THROW(voxremesh::removeWarping(mesh, -1.0), std::invalid_argument);
  EXPECT_THROW(voxremesh::removeWarping(mesh, std::nan("")), std::invalid_argument);
}

/// Splits interior grid point (i, j) of grid(n) into two points 0.3 west and east of it joined
/// to its north and south neighbours by a thin rhombic quad (degrees 3, 5, 3, 5).
QuadMesh plantRhombus(int n, int i, int j) {
  QuadMesh mesh = grid(n);
  auto id = [n](int x, int y) { return static_cast<CornerIndex>(y * (n + 1) + x); };
  const CornerIndex v = id(i, j);
  const CornerIndex east = addPoint(mesh, {i + 0.3, double(j), 0.0});
  mesh.points[v][0] -= 0.3;  // v becomes the west point
  for (auto& f : mesh.faces) {
    double x = 0.0;  // the face lies east of v when its centroid does
    for (int k = 0; k < 4; ++k) x += 0.25 * mesh.points[f[k]][0];
    const bool eastern = x > i;
    if (!eastern) continue;
    for (int k = 0; k < 4; ++k)
      if (f[k] == v) f[k] = east;
  }
  mesh.faces.push_back({v, id(i, j - 1), east, id(i, j + 1)});
  return mesh;
}

TEST(CollapseRhombicQuads, RestoresTheRegularGrid) {
  const int n = 6;
  QuadMesh mesh = plantRhombus(n, 2, 3);
  const QuadMesh planted = mesh;
  ASSERT_EQ(mesh.faces.size(), std::size_t(n * n + 1));
  const ReferenceSurface plane(grid(n));
  EXPECT_EQ(voxremesh::collapseRhombicQuads(mesh, &plane), 1u);
  EXPECT_EQ(mesh.faces.size(), std::size_t(n * n));
  EXPECT_EQ(mesh.points.size(), std::size_t((n + 1) * (n + 1)));
  const std::vector<std::size_t> degree = degrees(mesh);
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (mesh.constraints[v].role == PointRole::Free) {
      EXPECT_EQ(degree[v], 4u) << v;
    }
  // The merged point sits at the midpoint (2, 3): the mesh is the grid again.
  EXPECT_LT(voxremesh::surfaceDistance(mesh, grid(n)).max(), 1e-12);
  EXPECT_LT(voxremesh::surfaceDistance(mesh, planted).max(), 0.31);
  expectConstraintsHold(mesh, n);
  // Nothing left to collapse.
  EXPECT_EQ(voxremesh::collapseRhombicQuads(mesh, &plane), 0u);
}

TEST(CleanUpMesh, RemovesDoublets) {
  const int n = 4;
  QuadMesh mesh = grid(n);
  // Quad (a, b, c, d) split by a centre point into (a, b, c, v) and (c, d, a, v).
  const auto face = mesh.faces[5];
  const CornerIndex v = addPoint(mesh, {1.5, 1.5, 0.02});
  mesh.faces[5] = {face[0], face[1], face[2], v};
  mesh.faces.push_back({face[2], face[3], face[0], v});
  const QuadMesh planted = mesh;
  const voxremesh::CleanupResult r = voxremesh::cleanUpMesh(mesh, {1e-6});
  EXPECT_EQ(r.valence2Points, 1u);
  EXPECT_EQ(r.zeroAreaFaces, 0u);
  EXPECT_EQ(mesh.faces.size(), std::size_t(n * n));
  EXPECT_EQ(mesh.points.size(), std::size_t((n + 1) * (n + 1)));
  for (std::size_t s : degrees(mesh)) EXPECT_GE(s, 2u);
  EXPECT_LT(voxremesh::surfaceDistance(mesh, grid(n)).max(), 1e-12);
  EXPECT_LE(voxremesh::surfaceDistance(mesh, planted).max(), 0.02 + 1e-12);
  expectConstraintsHold(mesh, n);
}

TEST(CleanUpMesh, CollapsesAColumnOfZeroAreaQuads) {
  // A 4 x 4 grid cut along x = 2 with a second copy of the points there, joined by quads of zero
  // width: the clean-up merges the copies and the grid is whole again.
  const int n = 4;
  QuadMesh mesh = grid(n);
  std::vector<CornerIndex> copy(n + 1);
  for (int j = 0; j <= n; ++j) {
    const CornerIndex v = static_cast<CornerIndex>(j * (n + 1) + 2);
    copy[j] = addPoint(mesh, mesh.points[v]);
    mesh.constraints[copy[j]] = mesh.constraints[v];
    if (j == 0 || j == n) mesh.constraints[copy[j]] = {PointRole::Boundary, 0};
    for (auto& f : mesh.faces) {
      double x = 0.0;
      for (int k = 0; k < 4; ++k) x += 0.25 * mesh.points[f[k]][0];
      const bool east = x > 2.0;
      for (int k = 0; k < 4 && east; ++k)
        if (f[k] == v) f[k] = copy[j];
    }
  }
  for (int j = 0; j < n; ++j) {
    const CornerIndex v = static_cast<CornerIndex>(j * (n + 1) + 2);
    mesh.faces.push_back({v, copy[j], copy[j + 1], v + n + 1});
  }
  const voxremesh::CleanupResult r = voxremesh::cleanUpMesh(mesh, {1e-9});
  EXPECT_GE(r.zeroAreaFaces, std::size_t(n));
  EXPECT_EQ(mesh.faces.size(), std::size_t(n * n));
  EXPECT_EQ(mesh.points.size(), std::size_t((n + 1) * (n + 1)));
  EXPECT_LT(voxremesh::surfaceDistance(mesh, grid(n)).max(), 1e-12);
  for (const auto& q : voxremesh::elementQualities(mesh)) EXPECT_NEAR(q.minAngleDeg, 90.0, 1e-9);
  expectConstraintsHold(mesh, n);
}

TEST(CleanUpMesh, CollapsesQuadsFoldedAlongACurve) {
  // A 4 x 1 strip: bottom points (i, 0) on curve 0, top points (0, 1), (2, 1), (4, 1) on curve 1,
  // the four corners fixed. Quads (b0, b1, b2, t1) and (b2, b3, b4, t2) have a 180-degree corner
  // at b1 and b3 on the bottom curve.
  QuadMesh mesh;
  for (int i = 0; i <= 4; ++i) mesh.points.push_back({double(i), 0.0, 0.0});
  for (int i = 0; i <= 4; i += 2) mesh.points.push_back({double(i), 1.0, 0.0});
  voxremesh::MeshCurve bottom, top;
  bottom.points = {{0, 0, 0}, {4, 0, 0}};
  top.points = {{0, 1, 0}, {4, 1, 0}};
  mesh.curves = {bottom, top};
  mesh.constraints = {{PointRole::Corner, voxremesh::kNoCurve},
                      {PointRole::Boundary, 0},
                      {PointRole::Boundary, 0},
                      {PointRole::Boundary, 0},
                      {PointRole::Corner, voxremesh::kNoCurve},
                      {PointRole::Corner, voxremesh::kNoCurve},
                      {PointRole::Boundary, 1},
                      {PointRole::Corner, voxremesh::kNoCurve}};
  mesh.faces = {{0, 1, 2, 6}, {0, 6, 5, kNoCorner}, {2, 3, 4, 7}, {2, 7, 6, kNoCorner}};
  QuadMesh kept = mesh;
  EXPECT_EQ(voxremesh::cleanUpMesh(kept, {1e-9, 0.0, false}).foldedCurveFaces, 0u);
  EXPECT_EQ(kept.faces, mesh.faces);
  const voxremesh::CleanupResult r = voxremesh::cleanUpMesh(mesh, {1e-9});
  EXPECT_EQ(r.foldedCurveFaces, 2u);
  EXPECT_EQ(mesh.points.size(), 6u);
  double area = 0.0;
  for (const auto& q : voxremesh::elementQualities(mesh)) EXPECT_LT(q.maxAngleDeg, 150.0);
  for (const auto& f : mesh.faces) {
    const auto& a = mesh.points[f[0]];
    const auto& b = mesh.points[f[1]];
    const auto& c = mesh.points[f[2]];
    area += 0.5 * std::abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  }
  EXPECT_DOUBLE_EQ(area, 4.0);  // the outline is kept
  for (const auto& p : mesh.points) EXPECT_TRUE(p[1] == 0.0 || p[1] == 1.0);
}

TEST(CleanUpMesh, CollapsesShortEdgesOnlyWhenAsked) {
  const int n = 4;
  QuadMesh mesh = grid(n);
  mesh.points[2 * (n + 1) + 2][0] = 2.9;  // edge to (3, 2) now 0.1 long
  QuadMesh untouched = mesh;
  EXPECT_EQ(voxremesh::cleanUpMesh(untouched, {1e-9}).shortEdges, 0u);
  EXPECT_EQ(untouched.faces.size(), std::size_t(n * n));
  const voxremesh::CleanupResult r = voxremesh::cleanUpMesh(mesh, {1e-9, 0.2});
  EXPECT_EQ(r.shortEdges, 1u);
  EXPECT_EQ(mesh.points.size(), std::size_t((n + 1) * (n + 1) - 1));
  std::size_t triangles = 0;
  for (const auto& f : mesh.faces) triangles += voxremesh::cornerCount(f) == 3 ? 1 : 0;
  EXPECT_EQ(triangles, 2u);  // the two quads of the collapsed edge
  for (const auto& f : mesh.faces)
    for (int k = 0; k < voxremesh::cornerCount(f); ++k) {
      const auto& a = mesh.points[f[k]];
      const auto& b = mesh.points[f[(k + 1) % voxremesh::cornerCount(f)]];
      EXPECT_GE(std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]), 0.2);
    }
  EXPECT_LT(voxremesh::surfaceDistance(mesh, grid(n)).max(), 1e-12);
  expectConstraintsHold(mesh, n);
  EXPECT_THROW(voxremesh::cleanUpMesh(mesh, {0.0, -1.0}), std::invalid_argument);
}

TEST(CleanUpMesh, RemovesFoldsAndRepeatedFaces) {
  const int n = 3;
  QuadMesh mesh = grid(n);
  const auto f = mesh.faces[4];
  mesh.faces.push_back(f);                         // the same face again, same way round
  mesh.faces.push_back({f[0], f[3], f[2], f[1]});  // and back to back
  const voxremesh::CleanupResult r = voxremesh::cleanUpMesh(mesh, {1e-9});
  EXPECT_EQ(r.duplicateFaces, 3u);  // the fold pair and one of the same-way copies
  EXPECT_EQ(mesh.faces.size(), std::size_t(n * n - 1));
  for (const auto& face : mesh.faces) EXPECT_NE(face, f);
}

TEST(CleanUpMesh, CollapsesSliverTrianglesAlongACurve) {
  // A sliver (b0, b1, b2) under the quad (b0, b2, t2, t0): b1 is on the bottom curve, 0.01 off the
  // line b0-b2, with a 179-degree angle; it merges into b0 and the sliver vanishes.
  QuadMesh mesh;
  mesh.points = {{0, 0, 0}, {1, -0.01, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  voxremesh::MeshCurve bottom;
  bottom.points = {{0, 0, 0}, {1, -0.01, 0}, {2, 0, 0}};
  mesh.curves = {bottom};
  const voxremesh::PointConstraint corner{PointRole::Corner, voxremesh::kNoCurve};
  mesh.constraints = {corner, {PointRole::Boundary, 0}, corner, corner, corner};
  mesh.faces = {{0, 1, 2, kNoCorner}, {0, 2, 3, 4}};
  const voxremesh::CleanupResult r = voxremesh::cleanUpMesh(mesh, {0.0});
  EXPECT_EQ(r.foldedCurveFaces, 1u);
  ASSERT_EQ(mesh.faces.size(), 1u);
  EXPECT_EQ(voxremesh::cornerCount(mesh.faces[0]), 4);
  EXPECT_EQ(mesh.points.size(), 4u);
}

TEST(MergeTrianglePairs, JoinsASplitQuadBack) {
  const int n = 3;
  QuadMesh mesh = grid(n);
  const auto f = mesh.faces[4];
  mesh.faces[4] = {f[0], f[1], f[2], kNoCorner};
  mesh.faces.push_back({f[0], f[2], f[3], kNoCorner});
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  EXPECT_EQ(voxremesh::mergeTrianglePairs(mesh, settings), 1u);
  EXPECT_EQ(mesh.faces.size(), std::size_t(n * n));
  for (const auto& face : mesh.faces) EXPECT_EQ(voxremesh::cornerCount(face), 4);
  EXPECT_LT(voxremesh::surfaceDistance(mesh, grid(n)).max(), 1e-12);
  settings.targetSize = 0.0;
  EXPECT_THROW(voxremesh::mergeTrianglePairs(mesh, settings), std::invalid_argument);
}

TEST(MergeTrianglePairs, KeepsPairsThatWouldMakeABadQuad) {
  // Two triangles folded by 90 degrees over their common edge.
  QuadMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 1}};
  mesh.faces = {{0, 1, 2, kNoCorner}, {1, 0, 3, kNoCorner}};
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  EXPECT_EQ(voxremesh::mergeTrianglePairs(mesh, settings), 0u);
  EXPECT_EQ(mesh.faces.size(), 2u);
}

/// A quarter cylinder of radius 10 around the y axis, n x n quads, with the same constraints as
/// grid(): the boundary is curve 0 and its four corners are fixed.
QuadMesh cylinder(int n, double jitter, unsigned seed) {
  QuadMesh mesh = grid(n);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> d(-jitter, jitter);
  auto place = [n](double u, double v) -> std::array<double, 3> {
    const double a = 0.5 * kPi * u / n;
    return {10.0 * std::sin(a), v * 10.0 / n, 10.0 * std::cos(a)};
  };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool inside = i > 0 && i < n && j > 0 && j < n;
      mesh.points[j * (n + 1) + i] =
          inside ? place(i + d(random), j + d(random)) : place(double(i), double(j));
    }
  for (std::size_t k = 0; k < mesh.curves[0].points.size(); ++k) {
    const auto& p = mesh.curves[0].points[k];
    mesh.curves[0].points[k] = place(p[0], p[1]);
  }
  return mesh;
}

TEST(ImproveFailingElements, MovesPlantedPointsBackUntilNothingFails) {
  // A flat 6 x 6 grid with one interior point and one boundary point dragged off: their quads
  // fail the angle and Jacobian criteria; the step moves them until none fails, the interior
  // point stays on the plane, the boundary point on its edge, the corners where they were.
  const int n = 6;
  QuadMesh mesh = grid(n);
  const ReferenceSurface plane(grid(n));
  mesh.points[2 * (n + 1) + 2] = {2.8, 2.7, 0.0};  // interior
  mesh.points[3] = {3.6, 0.0, 0.0};                // on the edge y = 0
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  auto failing = [&] {
    std::size_t count = 0;
    const auto qualities = voxremesh::elementQualities(mesh);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      count += voxremesh::elementFailures(qualities[f], 4, settings) != 0 ? 1 : 0;
    return count;
  };
  ASSERT_GT(failing(), 0u);
  EXPECT_GT(voxremesh::improveFailingElements(mesh, plane, settings, 10), 0u);
  EXPECT_EQ(failing(), 0u);
  for (const auto& p : mesh.points) EXPECT_EQ(p[2], 0.0);
  EXPECT_EQ(mesh.points[3][1], 0.0);
  EXPECT_EQ(mesh.points[0], (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(mesh.points[n], (std::array<double, 3>{double(n), 0.0, 0.0}));
  settings.targetSize = 0.0;
  EXPECT_THROW(voxremesh::improveFailingElements(mesh, plane, settings), std::invalid_argument);
}

TEST(ImproveFailingElements, MovesAPointOffAStraightCorner) {
  // Interior point (2, 2) of a flat 4 x 4 grid put at (1.5, 1.5), on the line between (2, 1) and
  // (1, 2): the quad (1, 1)-(2, 1)-p-(1, 2) has a 180 degree corner there, which no acceptance
  // allows. Moving the point alone mends it, on the plane.
  const int n = 4;
  QuadMesh mesh = grid(n);
  const ReferenceSurface plane(grid(n));
  const CornerIndex p = 2 * (n + 1) + 2;
  mesh.points[p] = {1.5, 1.5, 0.0};
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  const auto degenerate = [&] {
    return voxremesh::assessQuality(mesh, settings)
        .criteria[static_cast<int>(voxremesh::Criterion::DegenerateCorner)]
        .failing;
  };
  ASSERT_EQ(degenerate(), 1u);
  EXPECT_GT(voxremesh::improveFailingElements(mesh, plane, settings, 10), 0u);
  EXPECT_EQ(degenerate(), 0u);
  EXPECT_EQ(voxremesh::assessQuality(mesh, settings).failingAny, 0u);
  EXPECT_EQ(voxremesh::test::foldedCount(mesh), 0u);
  EXPECT_EQ(mesh.points[p][2], 0.0);
}
TEST(ImproveFailingElements, JitteredCylinderFailsFarLessStaysOnItAndIgnoresThreads) {
  // Interior points of a quarter cylinder jittered by up to 0.45 of an edge: many quads fail the
  // angle, skew and Jacobian criteria. The pattern search must fix most of them, in parallel
  // colour classes, with the same bytes for one and two threads, every point on its surface.
  const int n = 16;
  const ReferenceSurface fine(cylinder(4 * n, 0.0, 0));
  voxremesh::QualitySettings settings;
  settings.targetSize = 0.5 * kPi * 10.0 / n;
  auto failing = [&](const QuadMesh& mesh) {
    std::size_t count = 0;
    const auto qualities = voxremesh::elementQualities(mesh);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      count += voxremesh::elementFailures(qualities[f], 4, settings) != 0 ? 1 : 0;
    return count;
  };
  const std::size_t before = failing(cylinder(n, 0.45, 7));
  ASSERT_GT(before, 40u);
  auto run = [&](int threads) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism,
                                static_cast<std::size_t>(threads));
    QuadMesh mesh = cylinder(n, 0.45, 7);
    EXPECT_GT(voxremesh::improveFailingElements(mesh, fine, settings, 3), 0u);
    return mesh;
  };
  const QuadMesh one = run(1), two = run(2);
  EXPECT_EQ(
      std::memcmp(one.points.data(), two.points.data(), one.points.size() * sizeof(one.points[0])),
      0);
  EXPECT_LT(failing(one), before / 10) << before;
  // Free points on the cylinder (the fine reference's chord error is below 0.001), boundary points
  // on their curve (a polyline through the coarse boundary points).
  const auto& boundary = one.curves[0];
  for (std::size_t v = 0; v < one.points.size(); ++v) {
    const auto& p = one.points[v];
    if (one.constraints[v].role == PointRole::Free) {
      EXPECT_NEAR(std::hypot(p[0], p[2]), 10.0, 0.001) << v;
    } else {
      const auto q = voxremesh::closestPointOnPolyline(boundary.points, boundary.closed, p);
      EXPECT_LT(std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]), 1e-9) << v;
    }
  }
}

/// The directed edges of a mesh's faces, and how many faces each undirected edge lies in.
struct EdgeCensus {
  std::map<std::pair<CornerIndex, CornerIndex>, int> directed, undirected;
};

EdgeCensus edgeCensus(const QuadMesh& mesh) {
  EdgeCensus census;
  for (const auto& face : mesh.faces) {
    const int n = voxremesh::cornerCount(face);
    for (int k = 0; k < n; ++k) {
      const CornerIndex a = face[std::size_t(k)], b = face[std::size_t((k + 1) % n)];
      ++census.directed[{a, b}];
      ++census.undirected[{std::min(a, b), std::max(a, b)}];
    }
  }
  return census;
}

/// The largest distance from an edge's midpoint to the cylinder of radius 10 around the y axis.
double largestChordError(const QuadMesh& mesh) {
  double largest = 0.0;
  for (const auto& [edge, faces] : edgeCensus(mesh).undirected) {
    const auto& a = mesh.points[edge.first];
    const auto& b = mesh.points[edge.second];
    largest = std::max(largest, 10.0 - std::hypot(0.5 * (a[0] + b[0]), 0.5 * (a[2] + b[2])));
  }
  return largest;
}

TEST(SplitLongEdges, CutsChordsAcrossACylinderAndKeepsTheMeshSound) {
  // A 3 x 3 quarter cylinder (radius 10): its edges around the cylinder span 30 degrees (chord
  // 5.2, sagitta 0.34), along it 3.3. Splitting edges over 4 with a chord error over 0.1 halves
  // the interior ones around the cylinder; the boundary edges between constrained points stay.
  const QuadMesh original = cylinder(60, 0.0, 1);
  const ReferenceSurface surface(original);
  QuadMesh mesh = cylinder(3, 0.0, 1);
  const EdgeCensus before = edgeCensus(mesh);
  const double errorBefore = largestChordError(mesh);
  const std::size_t split = voxremesh::splitLongEdges(mesh, 4.0, &surface, 0.1);
  EXPECT_EQ(split, 6u);  // two interior rows of three edges
  const EdgeCensus after = edgeCensus(mesh);
  // Manifold and consistently oriented: every directed edge once, every edge in one or two faces;
  // the boundary keeps its 12 edges; the Euler characteristic of a disc (1) is kept.
  for (const auto& [edge, count] : after.directed) EXPECT_EQ(count, 1);
  std::size_t boundaryBefore = 0, boundaryAfter = 0;
  for (const auto& [edge, count] : before.undirected) boundaryBefore += count == 1;
  for (const auto& [edge, count] : after.undirected) {
    EXPECT_LE(count, 2);
    boundaryAfter += count == 1;
  }
  EXPECT_EQ(boundaryBefore, 12u);
  EXPECT_EQ(boundaryAfter, boundaryBefore);
  EXPECT_EQ(long(mesh.points.size()) - long(after.undirected.size()) + long(mesh.faces.size()), 1);
  EXPECT_EQ(mesh.constraints.size(), mesh.points.size());
  // The new points lie on the cylinder, and the interior chords follow it four times closer.
  for (const auto& p : mesh.points) EXPECT_NEAR(std::hypot(p[0], p[2]), 10.0, 0.01);
  EXPECT_GT(errorBefore, 0.3);
  double interiorError = 0.0;
  for (const auto& [edge, count] : after.undirected) {
    if (count == 1) continue;
    const auto& a = mesh.points[edge.first];
    const auto& b = mesh.points[edge.second];
    interiorError =
        std::max(interiorError, 10.0 - std::hypot(0.5 * (a[0] + b[0]), 0.5 * (a[2] + b[2])));
  }
  EXPECT_LT(interiorError, 0.1);
  // Chords within the tolerance, or no edge that long: nothing to split.
  QuadMesh fine = cylinder(12, 0.0, 1);
  EXPECT_EQ(voxremesh::splitLongEdges(fine, 0.5, &surface, 0.1), 0u);
  EXPECT_EQ(voxremesh::splitLongEdges(fine, 4.0, nullptr), 0u);
  EXPECT_THROW(voxremesh::splitLongEdges(fine, 0.0, &surface), std::invalid_argument);
  EXPECT_THROW(voxremesh::splitLongEdges(fine, 1.0, &surface, -1.0), std::invalid_argument);
}

/// Two unit squares of a 4 x 4 grid cut along the wrong diagonal of the hexagon they make: two
/// quads with a straight corner each. `recut` (returning the number of changes) must restore the
/// squares with one change; points stay where they are; nothing changes once nothing fails.
void expectPlantedBadPairRecut(
    const std::function<std::size_t(QuadMesh&, voxremesh::QualitySettings&)>& recut) {
  QuadMesh mesh = grid(4);
  auto id = [](int i, int j) { return static_cast<CornerIndex>(j * 5 + i); };
  const std::vector<std::array<CornerIndex, 4>> squares = mesh.faces;
  std::size_t left = 0, right = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (mesh.faces[f][0] == id(1, 1)) left = f;
    if (mesh.faces[f][0] == id(2, 1)) right = f;
  }
  mesh.faces[left] = {id(1, 1), id(2, 1), id(3, 1), id(3, 2)};
  mesh.faces[right] = {id(3, 2), id(2, 2), id(1, 2), id(1, 1)};
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  EXPECT_EQ(voxremesh::assessQuality(mesh, settings).failingAny, 2u);
  const auto points = mesh.points;
  EXPECT_EQ(recut(mesh, settings), 1u);
  EXPECT_EQ(mesh.points, points);
  EXPECT_EQ(voxremesh::assessQuality(mesh, settings).failingAny, 0u);
  std::vector<std::array<CornerIndex, 4>> sortedFaces, sortedSquares;
  for (auto face : mesh.faces) {  // the same squares, each starting at its smallest corner
    std::rotate(face.begin(), std::min_element(face.begin(), face.end()), face.end());
    sortedFaces.push_back(face);
  }
  for (auto face : squares) {
    std::rotate(face.begin(), std::min_element(face.begin(), face.end()), face.end());
    sortedSquares.push_back(face);
  }
  std::sort(sortedFaces.begin(), sortedFaces.end());
  std::sort(sortedSquares.begin(), sortedSquares.end());
  EXPECT_EQ(sortedFaces, sortedSquares);
  EXPECT_EQ(recut(mesh, settings), 0u);
  settings.targetSize = 0.0;
  EXPECT_THROW(recut(mesh, settings), std::invalid_argument);
}

TEST(EngineRecut, RecutsAPlantedBadPairBackIntoSquares) {
  // The search engine's recut of a pair of faces, without searches.
  expectPlantedBadPairRecut([](QuadMesh& mesh, voxremesh::QualitySettings& settings) {
    return engineWithoutSearches(mesh, settings, voxremesh::kRecutPair);
  });
}

TEST(SplitInvertedQuads, CutsAnArrowheadAtItsReflexCorner) {
  // An arrowhead (reflex at its fourth corner: a negative corner Jacobian) next to a square; the
  // arrowhead becomes two triangles turning the same way, the square stays.
  QuadMesh mesh;
  mesh.points = {{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.5, 1, 0}, {2, 3, 0}};
  mesh.faces = {{0, 1, 2, 3}, {2, 1, 4, kNoCorner}};
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  EXPECT_LT(voxremesh::assessQuality(mesh, settings)
                .criteria[static_cast<int>(voxremesh::Criterion::JacobianRatio)]
                .worst,
            0.0);
  EXPECT_EQ(voxremesh::splitInvertedQuads(mesh), 1u);
  ASSERT_EQ(mesh.faces.size(), 3u);
  for (const auto& face : mesh.faces) {
    ASSERT_EQ(voxremesh::cornerCount(face), 3);
    const auto& a = mesh.points[face[0]];
    const auto& b = mesh.points[face[1]];
    const auto& c = mesh.points[face[2]];
    EXPECT_GT((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]), 0.0) << "turns left";
  }
  EXPECT_EQ(mesh.faces[2], (std::array<CornerIndex, 4>{2, 1, 4, kNoCorner}));
  // Convex quads stay.
  QuadMesh square = grid(2);
  const auto faces = square.faces;
  EXPECT_EQ(voxremesh::splitInvertedQuads(square), 0u);
  EXPECT_EQ(square.faces, faces);
}

TEST(SplitInvertedQuads, CutsAQuadWithAFlatCorner) {
  // A quad whose second corner lies 0.004 off the line between its neighbours (a corner of
  // 179.5 degrees: solvers cannot estimate a shell normal there) becomes two triangles cut at
  // that corner; with the corner 0.05 off (177 degrees) it stays.
  for (const double offset : {0.004, 0.05}) {
    QuadMesh mesh;
    mesh.points = {{0, 0, 0}, {1, -offset, 0}, {2, 0, 0}, {1, 1, 0}};
    mesh.faces = {{0, 1, 2, 3}};
    const std::size_t split = voxremesh::splitInvertedQuads(mesh, 179.0);
    voxremesh::QualitySettings settings;
    settings.targetSize = 1.0;
    const auto report = voxremesh::assessQuality(mesh, settings);
    if (offset < 0.01) {
      EXPECT_EQ(split, 1u);
      ASSERT_EQ(mesh.faces.size(), 2u);
      EXPECT_EQ(mesh.faces[0], (std::array<CornerIndex, 4>{1, 2, 3, kNoCorner}));
      EXPECT_EQ(mesh.faces[1], (std::array<CornerIndex, 4>{3, 0, 1, kNoCorner}));
      EXPECT_EQ(report.criteria[static_cast<int>(voxremesh::Criterion::DegenerateCorner)].failing,
                0u);
    } else {
      EXPECT_EQ(split, 0u);
      EXPECT_EQ(mesh.faces.size(), 1u);
    }
  }
}

TEST(RelaxMesh, EqualisesAJitteredCylinderAndStaysOnIt) {
  const int n = 10;
  QuadMesh mesh = cylinder(n, 0.35, 3);
  const ReferenceSurface fine(cylinder(4 * n, 0.0, 0));
  const auto before = voxremesh::elementQualities(mesh);
  voxremesh::relaxMesh(mesh, fine, 20, 0.5);
  const auto after = voxremesh::elementQualities(mesh);
  double worstBefore = 180.0, worstAfter = 180.0;
  for (const auto& q : before) worstBefore = std::min(worstBefore, q.minAngleDeg);
  for (const auto& q : after) worstAfter = std::min(worstAfter, q.minAngleDeg);
  EXPECT_GT(worstAfter, worstBefore + 10.0);
  EXPECT_GT(worstAfter, 80.0);
  double worstJacobian = 1.0;
  for (const auto& q : after) worstJacobian = std::min(worstJacobian, q.jacobianRatio);
  EXPECT_GT(worstJacobian, 0.9);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    const auto& p = mesh.points[v];
    // Every point on the cylinder (the fine reference's chord error is below 0.01).
    EXPECT_NEAR(std::hypot(p[0], p[2]), 10.0, 0.01) << v;
  }
  // Corners did not move; the whole boundary stayed on its curve (the cylinder's edges).
  const QuadMesh exact = cylinder(n, 0.0, 0);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    if (mesh.constraints[v].role == PointRole::Corner) {
      EXPECT_EQ(mesh.points[v], exact.points[v]);
    }
    if (mesh.constraints[v].role == PointRole::Boundary) {
      const auto& p = mesh.points[v];
      const bool onEdge = std::abs(p[1]) < 1e-9 || std::abs(p[1] - 10.0) < 1e-9 ||
                          std::abs(p[0]) < 1e-9 || std::abs(p[2]) < 1e-9;
      EXPECT_TRUE(onEdge) << v;
    }
  }
  EXPECT_THROW(voxremesh::relaxMesh(mesh, ReferenceSurface{}, 1, 0.5), std::invalid_argument);
  EXPECT_THROW(voxremesh::relaxMesh(mesh, fine, 1, 0.0), std::invalid_argument);
  EXPECT_THROW(voxremesh::relaxMesh(mesh, fine, 1, 0.9), std::invalid_argument);
  EXPECT_THROW(voxremesh::relaxMesh(mesh, fine, 1, 0.5, -1.0), std::invalid_argument);
}

TEST(RelaxMesh, UnconstrainedBoundaryPointsSlideAlongTheBoundary) {
  // Without constraints the boundary points are Free: they may only slide along the boundary,
  // so the mesh keeps its outline instead of shrinking.
  const int n = 8;
  QuadMesh mesh = grid(n);
  mesh.constraints.clear();
  mesh.curves.clear();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> d(-0.3, 0.3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      auto& p = mesh.points[j * (n + 1) + i];
      if (i > 0 && i < n) p[0] += d(random);
      if (j > 0 && j < n) p[1] += d(random);
    }
  const ReferenceSurface plane(grid(n));
  voxremesh::relaxMesh(mesh, plane, 30, 0.5);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const auto& p = mesh.points[j * (n + 1) + i];
      if (i == 0 || i == n) {
        EXPECT_NEAR(p[0], i, 1e-12);
      }
      if (j == 0 || j == n) {
        EXPECT_NEAR(p[1], j, 1e-12);
      }
    }
  EXPECT_LT(voxremesh::surfaceDistance(mesh, grid(n)).max(), 1e-12);
  for (const auto& q : voxremesh::elementQualities(mesh)) EXPECT_GT(q.minAngleDeg, 80.0);
}

/// Defects at once on the jittered cylinder: points pushed out (warped quads), a doublet, a quad
/// split into two triangles.
QuadMesh plantedCylinder() {
  const int n = 12;
  QuadMesh mesh = cylinder(n, 0.2, 11);
  for (std::size_t v = 0; v < mesh.points.size(); v += 7)
    if (mesh.constraints[v].role == PointRole::Free)
      for (double& x : mesh.points[v]) x *= 1.02;
  const auto f = mesh.faces[30];
  mesh.faces[30] = {f[0], f[1], f[2], kNoCorner};
  mesh.faces.push_back({f[0], f[2], f[3], kNoCorner});
  const auto g = mesh.faces[80];
  const CornerIndex c = addPoint(mesh, mesh.points[g[0]]);
  for (int k = 0; k < 3; ++k)
    for (int x = 0; x < 3; ++x) mesh.points[c][x] += mesh.points[g[k + 1]][x];
  for (double& x : mesh.points[c]) x *= 0.25;
  mesh.faces[80] = {g[0], g[1], g[2], c};
  mesh.faces.push_back({g[2], g[3], g[0], c});
  return mesh;
}

TEST(OptimizeQuadMesh, RemovesPlantedDefectsAndPassesTheCriteria) {
  QuadMesh mesh = plantedCylinder();
  const QuadMesh original = cylinder(48, 0.0, 0);
  const ReferenceSurface surface(original);
  voxremesh::OptimizeStats stats;
  voxremesh::optimizeQuadMesh(mesh, surface, {}, &stats);
  EXPECT_EQ(stats.cleanup.valence2Points, 1u);
  EXPECT_EQ(stats.trianglesMerged, 1u);
  EXPECT_GE(stats.totalSeconds, stats.relaxSeconds);
  voxremesh::QualitySettings settings;
  const voxremesh::QualityReport report = voxremesh::assessQuality(mesh, settings, &original);
  EXPECT_EQ(report.failingAny, 0u) << voxremesh::formatQualityTable(report);
  EXPECT_EQ(report.triangles, 0u);
  EXPECT_LT(report.distance->max(), 0.1 * report.settings.targetSize);
}

TEST(OptimizeQuadMesh, SameBytesForOneAndTwoThreads) {
  const QuadMesh original = cylinder(48, 0.0, 0);
  const ReferenceSurface surface(original);
  auto run = [&](int threads) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism,
                                static_cast<std::size_t>(threads));
    QuadMesh mesh = plantedCylinder();
    voxremesh::optimizeQuadMesh(mesh, surface);
    return mesh;
  };
  const QuadMesh one = run(1), two = run(2);
  ASSERT_EQ(one.points.size(), two.points.size());
  ASSERT_EQ(one.faces, two.faces);
  EXPECT_EQ(
      std::memcmp(one.points.data(), two.points.data(), one.points.size() * sizeof(one.points[0])),
      0);
}

TEST(OptimizeQuadMesh, RefusesBadMeshes) {
  const ReferenceSurface surface(grid(2));
  QuadMesh mesh = grid(2);
  mesh.points[4][1] = std::nan("");
  EXPECT_THROW(voxremesh::optimizeQuadMesh(mesh, surface), std::invalid_argument);
  EXPECT_THROW(surface.closestPoint(mesh.points[4]), std::invalid_argument);
  mesh = grid(2);
  mesh.faces[0][1] = 99;
  EXPECT_THROW(voxremesh::optimizeQuadMesh(mesh, surface), std::invalid_argument);
  mesh = grid(2);
  mesh.constraints[1].curve = 7;  // a boundary point bound to a missing curve
  EXPECT_THROW(voxremesh::optimizeQuadMesh(mesh, surface), std::invalid_argument);
  mesh = grid(2);
  mesh.constraints.pop_back();
  EXPECT_THROW(voxremesh::optimizeQuadMesh(mesh, surface), std::invalid_argument);
}

TEST(OptimizeQuadMesh, RefusesBadSettings) {
  QuadMesh mesh = grid(2);
  const ReferenceSurface surface(mesh);
  voxremesh::OptimizeSettings settings;
  settings.relaxDamping = 2.0;
  EXPECT_THROW(voxremesh::optimizeQuadMesh(mesh, surface, settings), voxremesh::SettingError);
  settings = {};
  settings.quality.maxWarpingDeg = std::nan("");
  EXPECT_THROW(voxremesh::optimizeQuadMesh(mesh, surface, settings), voxremesh::SettingError);
}

TEST(OptimizeQuadMesh, TheWarpingRemovalFollowsTheCriteriaUnlessSet) {
  // A grid whose inner points are lifted alternately up and down: its quads warp by about 10
  // degrees, the original surface the same. Unset, the removal's threshold is kWarpingRemovalShare
  // of the criteria's warping limit: with a limit of 10 it works as with 8 set, and leaves fewer
  // quads warped past 8 degrees than under the default limit of 15.
  const int n = 8;
  QuadMesh lifted = grid(n);
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) lifted.points[j * (n + 1) + i][2] = ((i + j) % 2 ? 0.09 : -0.09);
  const ReferenceSurface surface(lifted);
  const auto run = [&](double limit, std::optional<double> warpingDeg,
                       voxremesh::OptimizeStats& stats) {
    voxremesh::OptimizeSettings settings;
    settings.quality.maxWarpingDeg = limit;
    settings.warpingDeg = warpingDeg;
    QuadMesh mesh = lifted;
    voxremesh::optimizeQuadMesh(mesh, surface, settings, &stats);
    return mesh;
  };
  voxremesh::OptimizeStats fromCriteria, set, defaults;
  const QuadMesh a = run(10.0, std::nullopt, fromCriteria);
  const QuadMesh b = run(10.0, 10.0 * voxremesh::kWarpingRemovalShare, set);
  const QuadMesh c = run(15.0, std::nullopt, defaults);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(fromCriteria.warping.warpedBefore, set.warping.warpedBefore);
  EXPECT_LT(countWarped(a, 8.0), countWarped(c, 8.0));
  // A threshold set outside 0 .. 180 is refused.
  voxremesh::OptimizeStats unused;
  EXPECT_THROW(run(15.0, std::nan(""), unused), voxremesh::SettingError);
  EXPECT_THROW(run(15.0, 200.0, unused), voxremesh::SettingError);
}

/// Boundary loops of a mesh: connected sets of edges that lie in one face.
std::size_t boundaryLoops(const QuadMesh& mesh) {
  std::map<std::pair<CornerIndex, CornerIndex>, int> edges;
  for (const auto& f : mesh.faces)
    for (int k = 0; k < voxremesh::cornerCount(f); ++k) {
      const CornerIndex a = f[k], b = f[(k + 1) % voxremesh::cornerCount(f)];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  std::vector<CornerIndex> parent(mesh.points.size());
  for (CornerIndex v = 0; v < parent.size(); ++v) parent[v] = v;
  auto find = [&](CornerIndex v) {
    while (parent[v] != v) v = parent[v];
    return v;
  };
  std::set<CornerIndex> onBoundary;
  for (const auto& [edge, count] : edges)
    if (count == 1) {
      onBoundary.insert(edge.first);
      onBoundary.insert(edge.second);
      parent[find(edge.first)] = find(edge.second);
    }
  std::set<CornerIndex> roots;
  for (const CornerIndex v : onBoundary) roots.insert(find(v));
  return roots.size();
}

TEST(OptimizeQuadMesh, BracketImprovesKeepsItsHolesAndIsThreadIndependent) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "bracket.k");
  const voxremesh::FeModel model = voxremesh::readDeck(deck);
  const std::vector<voxremesh::Sheet> sheets = voxremesh::buildAllSheets(model);
  const QuadMesh input = voxremesh::quadMeshFromModel(model, sheets[0].part);
  voxremesh::VolumeSettings volumeSettings;
  volumeSettings.targetElementSize = 4.5;
  const QuadMesh extracted =
      voxremesh::extractQuadMesh(voxremesh::buildVolume(sheets, volumeSettings));
  const ReferenceSurface surface(input);
  voxremesh::OptimizeSettings settings;
  settings.quality.targetSize = 4.5;
  auto run = [&](int threads) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism,
                                static_cast<std::size_t>(threads));
    QuadMesh mesh = extracted;
    voxremesh::optimizeQuadMesh(mesh, surface, settings);
    return mesh;
  };
  const QuadMesh one = run(1), two = run(2);
  ASSERT_EQ(one.faces, two.faces);
  ASSERT_EQ(one.points.size(), two.points.size());
  EXPECT_EQ(
      std::memcmp(one.points.data(), two.points.data(), one.points.size() * sizeof(one.points[0])),
      0);
  // Issue 5's goals on the bracket at its median edge length (bench_optimize prints the
  // details): under 1 % of the elements fail a default criterion with the Jacobian ratio at the
  // corners (0.44 %; 1.51 % before the reconnection of failing faces; the input deck itself fails
  // 25 %, the extraction 25 %), triangles under 3 % (2.97 %), the two-sided distance to the input
  // under the 0.25 x size limit (1.09 against 1.125), every hole and the outer contour kept.
  voxremesh::QualitySettings quality;
  quality.targetSize = 4.5;
  const auto before = voxremesh::assessQuality(extracted, quality, &input);
  const auto after = voxremesh::assessQuality(one, quality, &input);
  EXPECT_LT(after.failingAnyShare, 0.1 * before.failingAnyShare);
  EXPECT_LT(after.failingAnyShare, 0.01);
  EXPECT_LT(after.triangleShare, 0.03);
  EXPECT_LT(after.distance->max(), 0.25 * 4.5);
  EXPECT_LT(after.criteria[static_cast<int>(voxremesh::Criterion::Warping)].share, 0.025);
  EXPECT_LT(after.distance->meanToOriginal, 0.1 * 4.5);
  EXPECT_EQ(boundaryLoops(input), 12u);
  EXPECT_EQ(boundaryLoops(one), boundaryLoops(input));
}

}  // namespace

namespace {

/// The positions of the Junction points of a mesh, sorted (indices change with topology steps).
std::vector<std::array<double, 3>> junctionPositions(const QuadMesh& mesh) {
  std::vector<std::array<double, 3>> result;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (mesh.constraints[v].role == PointRole::Junction) result.push_back(mesh.points[v]);
  std::sort(result.begin(), result.end());
  return result;
}

/// A 6 x 6 grid whose middle row j = 3 is a junction curve (curve 1, shared with another sheet),
/// with defects that every step would fix by moving or merging a point: the junction row lifted
/// and jittered (warped quads), a Free point on a junction point (a zero-area quad), a doublet and
/// a split quad beside the junction, Free points jittered.
QuadMesh junctionGrid() {
  constexpr int n = 6;
  QuadMesh mesh = grid(n);
  auto id = [](int i, int j) { return static_cast<CornerIndex>(j * (n + 1) + i); };
  voxremesh::MeshCurve seam;
  seam.role = PointRole::Junction;
  for (int i = 1; i < n; ++i) {
    auto& p = mesh.points[id(i, 3)];
    p[2] = (i % 2 ? 0.3 : -0.3);
    p[0] += 0.1 * (i % 3);
    seam.points.push_back(p);
    mesh.constraints[id(i, 3)] = {PointRole::Junction, 1};
  }
  mesh.curves.push_back(seam);
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i)
      if (j != 3) mesh.points[id(i, j)][0] += 0.15 * ((i * 7 + j * 3) % 5 - 2) / 2.0;
  mesh.points[id(2, 2)] = mesh.points[id(2, 3)];  // a Free point on a junction point
  // A doublet at the centroid of the quad right of (3, 3), and that quad's neighbour split.
  const std::size_t f = 3 * n + 3;
  const auto g = mesh.faces[f];
  const CornerIndex c = addPoint(mesh, {3.5, 3.5, 0.0});
  mesh.faces[f] = {g[0], g[1], g[2], c};
  mesh.faces.push_back({g[2], g[3], g[0], c});
  const auto h = mesh.faces[f + 1];
  mesh.faces[f + 1] = {h[0], h[1], h[2], kNoCorner};
  mesh.faces.push_back({h[0], h[2], h[3], kNoCorner});
  return mesh;
}

TEST(Junction, PointsSurviveEveryStepUnchanged) {
  const QuadMesh start = junctionGrid();
  const auto expected = junctionPositions(start);
  ASSERT_EQ(expected.size(), 5u);
  const ReferenceSurface surface(start);
  voxremesh::QualitySettings quality;
  quality.targetSize = 1.0;
  voxremesh::CleanupSettings cleanup;
  cleanup.zeroArea = 1e-6;
  cleanup.shortEdge = 0.3;
  const std::vector<std::pair<const char*, std::function<void(QuadMesh&)>>> steps = {
      {"removeWarping", [](QuadMesh& m) { voxremesh::removeWarping(m, 1.0); }},
      {"collapseRhombicQuads", [&](QuadMesh& m) { voxremesh::collapseRhombicQuads(m, &surface); }},
      {"relaxMesh", [&](QuadMesh& m) { voxremesh::relaxMesh(m, surface, 20); }},
      {"cleanUpMesh", [&](QuadMesh& m) { voxremesh::cleanUpMesh(m, cleanup); }},
      {"mergeTrianglePairs", [&](QuadMesh& m) { voxremesh::mergeTrianglePairs(m, quality); }},
      {"optimizeQuadMesh", [&](QuadMesh& m) { voxremesh::optimizeQuadMesh(m, surface); }},
  };
  for (const auto& [name, step] : steps) {
    QuadMesh mesh = start;
    step(mesh);
    EXPECT_EQ(junctionPositions(mesh), expected) << name;
    // Every junction point is still used by a face.
    std::vector<std::uint8_t> used(mesh.points.size(), 0);
    for (const auto& face : mesh.faces)
      for (int k = 0; k < voxremesh::cornerCount(face); ++k) used[face[k]] = 1;
    for (std::size_t v = 0; v < mesh.points.size(); ++v) {
      if (mesh.constraints[v].role == PointRole::Junction) {
        EXPECT_TRUE(used[v]) << name << " " << v;
      }
    }
  }
  // The clean-up did fix the defect beside the junction: the zero-length edge is gone.
  QuadMesh cleaned = start;
  const voxremesh::CleanupResult result = voxremesh::cleanUpMesh(cleaned, cleanup);
  EXPECT_GE(result.zeroAreaFaces + result.shortEdges, 1u);
  EXPECT_EQ(cleaned.points.size(), start.points.size() - 2);  // the merged point, the doublet
}

}  // namespace

namespace {

TEST(RelaxMesh, CurveEndsDoNotSlideTowardsCornersOffTheirCurve) {
  // A feature line along row 2 from (1, 2) to (3, 2); the Corner at (1, 3) ends another line and
  // is joined to the first point by an edge across the surface, not along the feature line.
  QuadMesh mesh = grid(4);
  voxremesh::MeshCurve line;
  line.points = {{1.0, 2.0, 0.0}, {3.0, 2.0, 0.0}};
  mesh.curves.push_back(line);
  for (CornerIndex v : {11u, 12u, 13u}) mesh.constraints[v] = {PointRole::Feature, 1};
  mesh.constraints[16] = {PointRole::Corner, voxremesh::kNoCurve};
  const auto end = mesh.points[11];
  voxremesh::relaxMesh(mesh, ReferenceSurface(grid(4)), 10, 0.5, 1.0);
  EXPECT_EQ(mesh.points[11], end);
  EXPECT_EQ(mesh.points[16], (std::array<double, 3>{1.0, 3.0, 0.0}));
}

}  // namespace

// A flipped face can pass every criterion of its own: the point search and the edge rotation must
// not fold faces while they repair failing ones (jittered grids, some faces folded to begin with).
// Runs `step` (returning how much it changed) on twelve such grids; returns the total changed.
namespace {
std::size_t expectNoNewFolds(const std::function<std::size_t(QuadMesh&)>& step) {
  std::size_t changed = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    QuadMesh mesh = voxremesh::test::unitGrid(10);
    voxremesh::test::jitterInnerPoints(mesh, 10, seed, 0.6);
    const std::size_t before = voxremesh::test::foldedCount(mesh);
    changed += step(mesh);
    EXPECT_LE(voxremesh::test::foldedCount(mesh), before) << "seed " << seed;
  }
  return changed;
}
}  // namespace

TEST(ImproveFailingElements, NeverFoldsMoreFacesThanItFound) {
  const ReferenceSurface plane(voxremesh::test::unitGrid(10));
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  EXPECT_GT(expectNoNewFolds([&](QuadMesh& mesh) {
              return voxremesh::improveFailingElements(mesh, plane, settings, 5);
            }),
            0u);
}

TEST(EngineSplitQuads, NeverFoldsMoreFacesThanItFound) {
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  EXPECT_GT(expectNoNewFolds([&](QuadMesh& mesh) {
              return engineWithoutSearches(mesh, settings, voxremesh::kSplitQuad, 1.0);
            }),
            0u);
}

TEST(EngineRecut, NeverFoldsMoreFacesThanItFound) {
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  EXPECT_GT(expectNoNewFolds([&](QuadMesh& mesh) {
              return engineWithoutSearches(mesh, settings, voxremesh::kRecutPair);
            }),
            0u);
}
