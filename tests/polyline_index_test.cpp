// PolylineIndex and the indexed opt::constrainedPosition against the linear scan of
// closestPointOnPolyline: bit-identical answers on random queries, exact ties included.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "geometry/polyline_index.h"
#include "optimize/mesh_topology.h"
#include "voxremesh/reference_surface.h"

namespace {

using Vec = std::array<double, 3>;

/// A random wiggly polyline of n points around a helix, with some repeated points (zero-length
/// segments).
std::vector<Vec> randomPolyline(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<Vec> points;
  for (int i = 0; i < n; ++i) {
    if (i > 0 && i % 17 == 0) {
      points.push_back(points.back());
      continue;
    }
    const double t = 0.15 * i;
    points.push_back({10.0 * std::cos(t) + jitter(rng), 10.0 * std::sin(t) + jitter(rng),
                      0.8 * t + jitter(rng)});
  }
  return points;
}

void expectSameBits(const Vec& a, const Vec& b) {
  for (int k = 0; k < 3; ++k) EXPECT_EQ(a[std::size_t(k)], b[std::size_t(k)]) << k;
}

TEST(PolylineIndex, MatchesTheScanOnRandomQueries) {
  std::mt19937 rng(7);
  for (const bool closed : {false, true})
    for (const int n : {1, 2, 3, 5, 40, 300}) {
      const std::vector<Vec> points = randomPolyline(rng, n);
      const voxremesh::PolylineIndex index(points, closed);
      std::uniform_real_distribution<double> coordinate(-15.0, 40.0);
      std::uniform_real_distribution<double> near(-0.5, 0.5);
      std::uniform_int_distribution<int> pick(0, n - 1);
      for (int i = 0; i < 2000; ++i) {
        Vec p;
        if (i % 2 == 0) {
          p = {coordinate(rng), coordinate(rng), coordinate(rng)};
        } else {  // close to the curve: the case the optimisation has
          const Vec& q = points[std::size_t(pick(rng))];
          p = {q[0] + near(rng), q[1] + near(rng), q[2] + near(rng)};
        }
        SCOPED_TRACE(testing::Message() << "n " << n << " closed " << closed << " query " << i);
        expectSameBits(index.closestPoint(p), voxremesh::closestPointOnPolyline(points, closed, p));
      }
    }
}

TEST(PolylineIndex, ExactTiesGoToTheFirstSegment) {
  // A square loop traced twice (every segment has an identical twin later on), and queries at its
  // vertices, on its edges and at its centre, where several segments are at exactly the same
  // distance: the first of them must win, as in the scan.
  std::vector<Vec> loop;
  for (int round = 0; round < 2; ++round)
    for (int i = 0; i < 12; ++i) {
      const int side = i / 3, step = i % 3;
      const double s = step / 3.0;
      const Vec corners[4] = {{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {0, 3, 0}};
      const Vec& a = corners[side];
      const Vec& b = corners[(side + 1) % 4];
      loop.push_back({a[0] + (b[0] - a[0]) * s, a[1] + (b[1] - a[1]) * s, 0.0});
    }
  for (const bool closed : {false, true}) {
    const voxremesh::PolylineIndex index(loop, closed);
    for (int x = -2; x <= 8; ++x)
      for (int y = -2; y <= 8; ++y)
        for (const double z : {0.0, 1.0}) {
          const Vec p = {0.5 * x, 0.5 * y, z};
          expectSameBits(index.closestPoint(p), voxremesh::closestPointOnPolyline(loop, closed, p));
        }
  }
}

TEST(PolylineIndex, NonFiniteInputsAsTheScan) {
  const std::vector<Vec> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},
                                   {0, 1, 0}, {0, 2, 0}, {5, 5, 5}};
  const voxremesh::PolylineIndex index(points, false);
  const double inf = std::numeric_limits<double>::infinity();
  for (const Vec& p : {Vec{inf, 0, 0}, Vec{std::nan(""), 0, 0}, Vec{1e300, -1e300, 1e300}}) {
    const Vec a = index.closestPoint(p);
    const Vec b = voxremesh::closestPointOnPolyline(points, false, p);
    for (int k = 0; k < 3; ++k)
      EXPECT_TRUE(a[std::size_t(k)] == b[std::size_t(k)] ||
                  (std::isnan(a[std::size_t(k)]) && std::isnan(b[std::size_t(k)])));
  }
  std::vector<Vec> bad = points;
  bad[2][1] = inf;  // unindexed: scanned
  const voxremesh::PolylineIndex scanned(bad, true);
  expectSameBits(scanned.closestPoint({0.2, 0.9, 0.0}),
                 voxremesh::closestPointOnPolyline(bad, true, {0.2, 0.9, 0.0}));
  EXPECT_THROW(voxremesh::PolylineIndex().closestPoint({0, 0, 0}), std::invalid_argument);
}

TEST(PolylineIndex, ConstrainedPositionWithIndexesAsWithout) {
  voxremesh::QuadMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.faces = {{0, 1, 2, 3}};
  std::mt19937 rng(3);
  using voxremesh::PointRole;
  mesh.curves.push_back({randomPolyline(rng, 50), false, PointRole::Feature});
  mesh.curves.push_back({randomPolyline(rng, 30), true, PointRole::Boundary});
  mesh.constraints = {{PointRole::Free, voxremesh::kNoCurve},
                      {PointRole::Feature, 0},
                      {PointRole::Boundary, 1},
                      {PointRole::Corner, voxremesh::kNoCurve}};
  const std::vector<voxremesh::PolylineIndex> curves = voxremesh::opt::indexCurves(mesh);
  ASSERT_EQ(curves.size(), 2u);
  std::uniform_real_distribution<double> coordinate(-12.0, 12.0);
  for (int i = 0; i < 500; ++i) {
    const Vec wanted = {coordinate(rng), coordinate(rng), coordinate(rng)};
    for (voxremesh::CornerIndex v = 0; v < 4; ++v)
      expectSameBits(voxremesh::opt::constrainedPosition(mesh, curves, v, wanted),
                     voxremesh::opt::constrainedPosition(mesh, v, wanted));
  }
  EXPECT_THROW(voxremesh::opt::constrainedPosition(mesh, {}, 1, {0, 0, 0}), std::invalid_argument);
}

}  // namespace
