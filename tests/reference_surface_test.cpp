// ReferenceSurface closest points against brute force, and closest points on polylines.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "voxremesh/reference_surface.h"

namespace {

using voxremesh::QuadMesh;
using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// Distance from p to triangle abc by a different route than the library: the plane projection
/// when it is inside (all edge tests agree in sign), else the closest of the three edges.
double triangleDistance(const Vec& p, const Vec& a, const Vec& b, const Vec& c) {
  const Vec n = cross(sub(b, a), sub(c, a));
  const double nn = dot(n, n);
  const double t = dot(sub(p, a), n) / nn;
  const Vec q = {p[0] - t * n[0], p[1] - t * n[1], p[2] - t * n[2]};
  const bool inside = dot(cross(sub(b, a), sub(q, a)), n) >= 0 &&
                      dot(cross(sub(c, b), sub(q, b)), n) >= 0 &&
                      dot(cross(sub(a, c), sub(q, c)), n) >= 0;
  if (inside) return std::abs(t) * std::sqrt(nn);
  double best = 1e300;
  for (const auto& [u, v] : {std::pair<Vec, Vec>{a, b}, {b, c}, {c, a}}) {
    const Vec s = voxremesh::closestPointOnSegment(p, u, v);
    best = std::min(best, std::sqrt(dot(sub(p, s), sub(p, s))));
  }
  return best;
}

/// A wavy n x n grid of quads of size 1.
QuadMesh wavyGrid(int n) {
  QuadMesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      mesh.points.push_back({double(i), double(j), 0.7 * std::sin(0.9 * i) * std::cos(0.6 * j)});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto a = static_cast<voxremesh::CornerIndex>(j * (n + 1) + i);
      mesh.faces.push_back({a, a + 1, a + n + 2, a + n + 1});
    }
  return mesh;
}

TEST(ReferenceSurface, MatchesBruteForce) {
  const QuadMesh mesh = wavyGrid(12);
  const voxremesh::ReferenceSurface surface(mesh);
  EXPECT_EQ(surface.triangleCount(), 2u * 144u);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> xy(-2.0, 14.0), z(-3.0, 3.0);
  std::vector<Vec> queries;
  for (int i = 0; i < 500; ++i) queries.push_back({xy(random), xy(random), z(random)});
  const std::vector<voxremesh::SurfaceHit> hits = surface.closestPoints(queries);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    double best = 1e300;
    for (const auto& f : mesh.faces) {
      best = std::min(best, triangleDistance(queries[i], mesh.points[f[0]], mesh.points[f[1]],
                                             mesh.points[f[2]]));
      best = std::min(best, triangleDistance(queries[i], mesh.points[f[0]], mesh.points[f[2]],
                                             mesh.points[f[3]]));
    }
    ASSERT_NEAR(hits[i].distance, best, 1e-9) << "query " << i;
    const Vec d = sub(queries[i], hits[i].point);
    EXPECT_NEAR(std::sqrt(dot(d, d)), hits[i].distance, 1e-12);
    const voxremesh::SurfaceHit single = surface.closestPoint(queries[i]);
    EXPECT_EQ(single.face, hits[i].face);
    // A hint only speeds the search up: any face (or none) gives the same answer.
    for (const std::uint32_t hint : {0u, static_cast<std::uint32_t>(i % 144), 143u, 1000u}) {
      const voxremesh::SurfaceHit hinted = surface.closestPoint(queries[i], hint);
      EXPECT_EQ(hinted.face, single.face);
      EXPECT_EQ(hinted.point, single.point);
      EXPECT_EQ(hinted.distance, single.distance);
    }
    EXPECT_LT(hits[i].face, mesh.faces.size());
  }
}

TEST(ReferenceSurface, MovedPointsGiveTheAnswersOfASurfaceBuiltOnThem) {
  QuadMesh mesh = wavyGrid(12);
  voxremesh::ReferenceSurface moved(mesh);
  // Every point moves, some far past where the tree was split.
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    mesh.points[v][2] += 0.4 * std::cos(1.3 * double(v));
    if (v % 7 == 0) mesh.points[v][0] += 3.0;
  }
  moved.movePoints(mesh.points);
  const voxremesh::ReferenceSurface built(mesh);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> xy(-2.0, 16.0), z(-3.0, 3.0);
  for (int i = 0; i < 500; ++i) {
    const Vec q{xy(random), xy(random), z(random)};
    const voxremesh::SurfaceHit a = moved.closestPoint(q), b = built.closestPoint(q);
    ASSERT_EQ(a.face, b.face) << "query " << i;
    EXPECT_EQ(a.point, b.point);
    EXPECT_EQ(a.distance, b.distance);
  }
  EXPECT_THROW(moved.movePoints({{0.0, 0.0, 0.0}}), std::invalid_argument);
  mesh.points[3][1] = std::nan("");
  EXPECT_THROW(moved.movePoints(mesh.points), std::invalid_argument);
}

TEST(Triangle, ClosestPointAgreesWithPlaneProjectionAndEdges) {
  // Random points round random triangles: the closest point's distance is the independent
  // route's, and the point lies on the triangle (in its plane, within its edges' distance).
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec a{u(random), u(random), u(random)}, b{u(random), u(random), u(random)},
        c{u(random), u(random), u(random)}, p{u(random), u(random), u(random)};
    const Vec q = voxremesh::closestPointOnTriangle(p, a, b, c);
    const double d = std::sqrt(dot(sub(p, q), sub(p, q)));
    EXPECT_NEAR(d, triangleDistance(p, a, b, c), 1e-9);
    EXPECT_NEAR(triangleDistance(q, a, b, c), 0.0, 1e-9);
  }
  // A degenerate triangle (three points on a line) gives the closest point of the segment.
  const Vec q = voxremesh::closestPointOnTriangle({1.0, 1.0, 0.0}, {0.0, 0.0, 0.0}, {2.0, 0.0, 0.0},
                                                  {4.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(q[0], 1.0);
  EXPECT_DOUBLE_EQ(q[1], 0.0);
}

TEST(ReferenceSurface, ExactTiesGoToTheFirstFaceWhateverTheHint) {
  // Every face twice (the second copy after all the first ones): each triangle has a twin at
  // exactly the same distance, so the first copy must win every query, with any hint, including
  // queries on vertices and edges where neighbouring triangles tie as well.
  QuadMesh mesh = wavyGrid(10);
  const std::size_t faces = mesh.faces.size();
  for (std::size_t f = 0; f < faces; ++f) mesh.faces.push_back(mesh.faces[f]);
  const voxremesh::ReferenceSurface surface(mesh);
  const voxremesh::ReferenceSurface once(wavyGrid(10));
  std::mt19937 random(11);
  std::uniform_real_distribution<double> xy(-1.0, 11.0), z(-2.0, 2.0);
  std::vector<Vec> queries = mesh.points;
  for (int i = 0; i < 300; ++i) queries.push_back({xy(random), xy(random), z(random)});
  for (int i = 0; i < 100; ++i) queries.push_back({0.5 * (i % 21), 0.5 * (i / 21), 0.0});
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const voxremesh::SurfaceHit expected = once.closestPoint(queries[i]);
    for (const std::uint32_t hint : {std::uint32_t(i % faces), std::uint32_t(faces + i % faces),
                                     std::uint32_t(2 * faces - 1), std::uint32_t(-1)}) {
      const voxremesh::SurfaceHit hit = surface.closestPoint(queries[i], hint);
      EXPECT_EQ(hit.face, expected.face) << "query " << i << " hint " << hint;
      EXPECT_EQ(hit.point, expected.point) << "query " << i << " hint " << hint;
      EXPECT_EQ(hit.distance, expected.distance) << "query " << i << " hint " << hint;
    }
  }
}

TEST(ReferenceSurface, PointOnTheSurfaceIsItsOwnClosestPoint) {
  const QuadMesh mesh = wavyGrid(4);
  const voxremesh::ReferenceSurface surface(mesh);
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    EXPECT_NEAR(surface.closestPoint(mesh.points[v]).distance, 0.0, 1e-12);
}

TEST(ReferenceSurface, RefusesMissingPoints) {
  QuadMesh mesh = wavyGrid(1);
  mesh.faces[0][2] = 99;
  EXPECT_THROW(voxremesh::ReferenceSurface{mesh}, std::invalid_argument);
}

TEST(Polyline, ClosestPointOpenAndClosed) {
  const std::vector<Vec> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  // Near the closing segment (0,1)-(0,0): open polylines do not have it.
  const Vec p = {-0.5, 0.5, 0.0};
  const Vec closed = voxremesh::closestPointOnPolyline(square, true, p);
  EXPECT_NEAR(closed[0], 0.0, 1e-15);
  EXPECT_NEAR(closed[1], 0.5, 1e-15);
  const Vec open = voxremesh::closestPointOnPolyline(square, false, p);
  // (0,0) and (0,1) are equally close: the first segment wins.
  EXPECT_EQ(open, (Vec{0, 0, 0}));
  EXPECT_THROW(voxremesh::closestPointOnPolyline({}, false, p), std::invalid_argument);
  const Vec single = voxremesh::closestPointOnPolyline({{2, 2, 2}}, false, p);
  EXPECT_EQ(single, (Vec{2, 2, 2}));
}

}  // namespace
