// reconnectFailingFaces on flat grids with planted connectivity defects that no point move can
// repair: a pair of quads cut along the wrong diagonal, a split point (a thin quad between two
// valence-3 points), a doubled point (two sliver triangles between its copies) and a point of
// three quads with a straight corner. The step
// removes the failures, keeps the surface (every point on the plane, the fixed boundary where it
// was), the Euler characteristic and the orientation, and gives the same mesh for one and two
// threads.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "support/unit_grid.h"
#include "voxremesh/errors.h"
#include "voxremesh/optimize.h"
#include "voxremesh/quality.h"

namespace {

using voxremesh::CornerIndex;
using voxremesh::PointRole;
using voxremesh::QuadMesh;
using voxremesh::ReferenceSurface;

/// An n x n grid of unit quads in the plane z = 0, its boundary points fixed (Corner).
QuadMesh fixedBoundaryGrid(int n) {
  QuadMesh mesh = voxremesh::test::unitGrid(n);
  auto id = [n](int i, int j) { return voxremesh::test::gridPoint(n, i, j); };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      if (i == 0 || j == 0 || i == n || j == n)
        mesh.constraints[id(i, j)] = {PointRole::Corner, voxremesh::kNoCurve};
  return mesh;
}

/// The default criteria for the unit grids.
voxremesh::QualitySettings unitCriteria() {
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  return settings;
}

std::size_t failing(const QuadMesh& mesh) {
  return voxremesh::assessQuality(mesh, unitCriteria()).failingAny;
}

/// V - E + F over the points faces use; and whether every edge has one or two faces, a shared
/// edge running opposite ways in its two faces (manifold and consistently oriented).
std::pair<long, bool> eulerAndOriented(const QuadMesh& mesh) {
  std::map<std::pair<CornerIndex, CornerIndex>, int> directed;
  std::vector<std::uint8_t> used(mesh.points.size(), 0);
  for (const auto& face : mesh.faces) {
    const int n = voxremesh::cornerCount(face);
    for (int k = 0; k < n; ++k) {
      used[face[std::size_t(k)]] = 1;
      ++directed[{face[std::size_t(k)], face[std::size_t((k + 1) % n)]}];
    }
  }
  bool oriented = true;
  long edges = 0;
  for (const auto& [edge, count] : directed) {
    oriented = oriented && count == 1;
    if (edge.first < edge.second || !directed.count({edge.second, edge.first})) ++edges;
  }
  const long points = long(std::count(used.begin(), used.end(), 1));
  return {points - edges + long(mesh.faces.size()), oriented};
}

void expectOnThePlaneWithTheBoundaryKept(const QuadMesh& mesh, const QuadMesh& start) {
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    EXPECT_EQ(mesh.points[v][2], 0.0) << v;
    if (mesh.constraints[v].role == PointRole::Corner) {
      EXPECT_EQ(mesh.points[v], start.points[v]) << v;
    }
  }
}

/// Two unit squares of a 4 x 4 grid cut along the wrong diagonal of the hexagon they make.
QuadMesh badPair() {
  QuadMesh mesh = fixedBoundaryGrid(4);
  auto id = [](int i, int j) { return CornerIndex(j * 5 + i); };
  for (auto& face : mesh.faces) {
    if (face[0] == id(1, 1)) face = {id(1, 1), id(2, 1), id(3, 1), id(3, 2)};
    if (face[0] == id(2, 1)) face = {id(3, 2), id(2, 2), id(1, 2), id(1, 1)};
  }
  return mesh;
}

/// A 6 x 6 grid whose point (3, 3) is split into two points 0.4 apart joined by a thin quad
/// between (3, 2) and (3, 4).
QuadMesh splitPoint() {
  constexpr int n = 6;
  QuadMesh mesh = fixedBoundaryGrid(n);
  auto id = [](int i, int j) { return CornerIndex(j * (n + 1) + i); };
  const CornerIndex left = id(3, 3);
  mesh.points[left] = {2.8, 3.0, 0.0};
  const CornerIndex right = CornerIndex(mesh.points.size());
  mesh.points.push_back({3.2, 3.0, 0.0});
  mesh.constraints.push_back({});
  for (auto& face : mesh.faces)
    if (face[0] == id(3, 2) || face[0] == id(3, 3))  // the two faces right of the point
      std::replace(face.begin(), face.end(), left, right);
  mesh.faces.push_back({left, id(3, 2), right, id(3, 4)});
  return mesh;
}

/// A 6 x 6 grid whose point (3, 3) is doubled: the two faces above it use a copy `gap` higher, and
/// two sliver triangles (left and right of the pair) fill the gap. Every other point is fixed.
QuadMesh doubledPoint(double gap = 0.05) {
  constexpr int n = 6;
  QuadMesh mesh = voxremesh::test::unitGrid(n);
  auto id = [](int i, int j) { return CornerIndex(j * (n + 1) + i); };
  const CornerIndex low = id(3, 3);
  for (CornerIndex v = 0; v < mesh.points.size(); ++v)
    if (v != low) mesh.constraints[v] = {PointRole::Corner, voxremesh::kNoCurve};
  const CornerIndex high = CornerIndex(mesh.points.size());
  mesh.points.push_back({3.0, 3.0 + gap, 0.0});
  mesh.constraints.push_back({});
  for (auto& face : mesh.faces)
    if (face[0] == id(2, 3) || face[0] == id(3, 3))  // the two faces above the point
      std::replace(face.begin(), face.end(), low, high);
  mesh.faces.push_back({id(2, 3), low, high, voxremesh::kNoCorner});
  mesh.faces.push_back({low, id(4, 3), high, voxremesh::kNoCorner});
  return mesh;
}

/// Two unit squares of a 4 x 4 grid, (1..3) x (1..2), replaced by three quads round a point
/// added at (2, 1.5): the quad over it has a straight (180 degree) corner at (2, 2). Every other
/// point is fixed.
QuadMesh threeQuadsRoundAPoint() {
  QuadMesh mesh = voxremesh::test::unitGrid(4);
  auto id = [](int i, int j) { return CornerIndex(j * 5 + i); };
  for (auto& constraint : mesh.constraints) constraint = {PointRole::Corner, voxremesh::kNoCurve};
  const CornerIndex v = CornerIndex(mesh.points.size());
  mesh.points.push_back({2.0, 1.5, 0.0});
  mesh.constraints.push_back({});
  mesh.faces.erase(
      std::remove_if(mesh.faces.begin(), mesh.faces.end(),
                     [&](const auto& face) { return face[0] == id(1, 1) || face[0] == id(2, 1); }),
      mesh.faces.end());
  mesh.faces.push_back({v, id(1, 2), id(1, 1), id(2, 1)});
  mesh.faces.push_back({v, id(2, 1), id(3, 1), id(3, 2)});
  mesh.faces.push_back({v, id(3, 2), id(2, 2), id(1, 2)});
  return mesh;
}

TEST(ReconnectFailingFaces, TakesOutAPointOfThreeQuadsWhoseCornersCannotPass) {
  const QuadMesh start = threeQuadsRoundAPoint();
  ASSERT_TRUE(eulerAndOriented(start).second);
  ASSERT_GT(failing(start), 0u);
  const ReferenceSurface plane(voxremesh::test::unitGrid(4));
  // No position of the one free point mends the straight corner, nor does an edge rotation (the
  // point would keep two faces): the hexagon of the three quads cut into two does.
  QuadMesh moved = start;
  voxremesh::improveFailingElements(moved, plane, unitCriteria(), 5);
  ASSERT_GT(failing(moved), 0u);
  QuadMesh mesh = start;
  EXPECT_EQ(voxremesh::reconnectFailingFaces(mesh, plane, unitCriteria()), 1u);
  EXPECT_EQ(failing(mesh), 0u);
  // The grid again: the point gone, two unit squares in place of the three quads.
  EXPECT_EQ(mesh.faces.size(), 16u);
  EXPECT_EQ(mesh.points.size(), 25u);
  EXPECT_EQ(eulerAndOriented(mesh), eulerAndOriented(start));
  EXPECT_EQ(voxremesh::test::foldedCount(mesh), 0u);
  expectOnThePlaneWithTheBoundaryKept(mesh, start);
}

/// Expects reconnectFailingFaces to mend the two slivers of `start` (doubledPoint) under
/// `settings` by making both copies one again: the grid's faces and points, nothing failing.
void expectCopiesMadeOne(const QuadMesh& start, const voxremesh::QualitySettings& settings) {
  ASSERT_TRUE(eulerAndOriented(start).second);
  ASSERT_EQ(voxremesh::assessQuality(start, settings).failingAny, 2u);
  QuadMesh mesh = start;
  EXPECT_GE(voxremesh::reconnectFailingFaces(mesh, ReferenceSurface(voxremesh::test::unitGrid(6)),
                                             settings),
            1u);
  EXPECT_EQ(voxremesh::assessQuality(mesh, settings).failingAny, 0u);
  EXPECT_EQ(mesh.faces.size(), 36u);
  EXPECT_EQ(mesh.points.size(), 49u);
  EXPECT_EQ(eulerAndOriented(mesh), eulerAndOriented(start));
  EXPECT_EQ(voxremesh::test::foldedCount(mesh), 0u);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) EXPECT_EQ(mesh.points[v][2], 0.0) << v;
}

TEST(ReconnectFailingFaces, CollapsesTheShortSideOfSliverTriangles) {
  // Triangles pass only when nearly equilateral: no position of the two copies between their
  // fixed neighbours mends both slivers, nor does another cut; collapsing their short side does.
  voxremesh::QualitySettings settings = unitCriteria();
  settings.minTriaAngleDeg = 55.0;
  expectCopiesMadeOne(doubledPoint(), settings);
}

TEST(ReconnectFailingFaces, CollapsesSliverTrianglesWhoseSidesAreLongEnough) {
  // The copies 0.3 apart, the size 0.2: the slivers' sides pass the minimum length and their
  // corners fail the minimum angle only. Collapsing a side is tried for them too.
  voxremesh::QualitySettings settings = unitCriteria();
  settings.targetSize = 0.2;
  settings.minTriaAngleDeg = 55.0;
  const QuadMesh start = doubledPoint(0.3);
  ASSERT_EQ(voxremesh::assessQuality(start, settings).failing(voxremesh::Criterion::MinLength), 0u);
  expectCopiesMadeOne(start, settings);
}

TEST(ReconnectFailingFaces, RecutsAPairCutAlongTheWrongDiagonal) {
  QuadMesh mesh = badPair();
  const QuadMesh start = mesh;
  const ReferenceSurface plane(fixedBoundaryGrid(4));
  voxremesh::QualitySettings settings = unitCriteria();
  ASSERT_EQ(failing(mesh), 2u);
  // Moving points alone leaves the pair failing: only another cut repairs it.
  QuadMesh moved = mesh;
  voxremesh::improveFailingElements(moved, plane, settings, 5);
  ASSERT_GT(failing(moved), 0u);
  EXPECT_EQ(voxremesh::reconnectFailingFaces(mesh, plane, settings), 1u);
  EXPECT_EQ(failing(mesh), 0u);
  EXPECT_EQ(mesh.faces.size(), start.faces.size());
  EXPECT_EQ(mesh.points.size(), start.points.size());
  EXPECT_EQ(eulerAndOriented(mesh), eulerAndOriented(start));
  EXPECT_TRUE(eulerAndOriented(mesh).second);
  expectOnThePlaneWithTheBoundaryKept(mesh, start);
  // Nothing failing: nothing changes.
  const QuadMesh passed = mesh;
  EXPECT_EQ(voxremesh::reconnectFailingFaces(mesh, plane, settings), 0u);
  EXPECT_EQ(mesh.faces, passed.faces);
  EXPECT_EQ(mesh.points, passed.points);
}

TEST(ReconnectFailingFaces, CollapsesASplitPointBackIntoTheGrid) {
  const QuadMesh start = splitPoint();
  ASSERT_GT(failing(start), 0u);
  QuadMesh mesh = start;
  EXPECT_GE(voxremesh::reconnectFailingFaces(mesh, ReferenceSurface(fixedBoundaryGrid(6)),
                                             unitCriteria()),
            1u);
  EXPECT_EQ(failing(mesh), 0u);
  // The thin quad's diagonal collapsed: the grid's point and face counts again.
  EXPECT_EQ(mesh.faces.size(), 36u);
  EXPECT_EQ(mesh.points.size(), 49u);
  EXPECT_EQ(eulerAndOriented(mesh), eulerAndOriented(start));
  EXPECT_TRUE(eulerAndOriented(mesh).second);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) EXPECT_EQ(mesh.points[v][2], 0.0) << v;
}

TEST(ReconnectFailingFaces, SameMeshForOneAndTwoThreads) {
  QuadMesh start = splitPoint();
  // Both defects at once, and the interior jittered.
  for (std::size_t v = 0; v < start.points.size(); ++v)
    if (start.constraints[v].role == PointRole::Free) start.points[v][0] += 0.07 * double(v % 3);
  auto id = [](int i, int j) { return CornerIndex(j * 7 + i); };
  for (auto& face : start.faces) {
    if (face[0] == id(1, 4)) face = {id(1, 4), id(2, 4), id(3, 4), id(3, 5)};
    if (face[0] == id(2, 4)) face = {id(3, 5), id(2, 5), id(1, 5), id(1, 4)};
  }
  const ReferenceSurface plane(fixedBoundaryGrid(6));
  voxremesh::QualitySettings settings = unitCriteria();
  auto run = [&](int threads) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    QuadMesh mesh = start;
    voxremesh::reconnectFailingFaces(mesh, plane, settings);
    return mesh;
  };
  const QuadMesh one = run(1), two = run(2);
  EXPECT_LT(failing(one), failing(start));
  ASSERT_EQ(one.faces, two.faces);
  ASSERT_EQ(one.points.size(), two.points.size());
  EXPECT_EQ(
      std::memcmp(one.points.data(), two.points.data(), one.points.size() * sizeof(one.points[0])),
      0);
}

TEST(ReconnectFailingFaces, RefusesBadArguments) {
  QuadMesh mesh = badPair();
  const ReferenceSurface plane(fixedBoundaryGrid(4));
  voxremesh::QualitySettings settings = unitCriteria();
  voxremesh::ReconnectSettings engine;
  engine.rounds = -1;
  EXPECT_THROW(voxremesh::reconnectFailingFaces(mesh, plane, settings, engine),
               std::invalid_argument);
  engine.rounds = 3;
  engine.sweeps = -1;
  EXPECT_THROW(voxremesh::reconnectFailingFaces(mesh, plane, settings, engine),
               std::invalid_argument);
  engine.sweeps = 3;
  engine.maxTriangleShare = 1.5;
  EXPECT_THROW(voxremesh::reconnectFailingFaces(mesh, plane, settings, engine),
               voxremesh::SettingError);
  EXPECT_THROW(voxremesh::reconnectFailingFaces(mesh, ReferenceSurface(QuadMesh{}), settings),
               std::invalid_argument);
  settings.targetSize = 0.0;
  EXPECT_THROW(voxremesh::reconnectFailingFaces(mesh, plane, settings), std::invalid_argument);
  settings.targetSize = 1.0;
  mesh.faces[0][1] = 999;  // a missing point
  EXPECT_THROW(voxremesh::reconnectFailingFaces(mesh, plane, settings), std::invalid_argument);
}

TEST(ReconnectFailingFaces, NeverFoldsMoreFacesThanItFound) {
  const ReferenceSurface plane(fixedBoundaryGrid(10));
  std::size_t changed = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    QuadMesh mesh = fixedBoundaryGrid(10);
    voxremesh::test::jitterInnerPoints(mesh, 10, seed, 0.6);
    const std::size_t before = voxremesh::test::foldedCount(mesh);
    changed += voxremesh::reconnectFailingFaces(mesh, plane, unitCriteria());
    EXPECT_LE(voxremesh::test::foldedCount(mesh), before) << "seed " << seed;
    EXPECT_TRUE(eulerAndOriented(mesh).second) << "seed " << seed;
  }
  EXPECT_GT(changed, 0u);  // the step did work on these meshes
}

}  // namespace
