// The boundary strip's zip (src/extract/strip_zip.h): quads between two rows of different
// lengths, triangles only where the count around the strip is odd, every face convex and
// oriented like the mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "extract/strip_zip.h"

namespace voxremesh::extract {
namespace {

using openvdb::math::Vec3d;

/// n points on a circle of the given radius, clockwise seen from +z (a hole's loop with the
/// mesh, outside it, on its left), starting at angle `phase`.
std::vector<Vec3d> clockwiseCircle(std::size_t n, double radius, double phase) {
  std::vector<Vec3d> points;
  for (std::size_t k = 0; k < n; ++k) {
    const double angle = phase - 2.0 * M_PI * double(k) / double(n);
    points.emplace_back(radius * std::cos(angle), radius * std::sin(angle), 0.0);
  }
  return points;
}

struct ZipCheck {
  std::size_t quads = 0, triangles = 0;
  double smallestCornerSine = 1.0;  ///< over all corners, the signed sine seen from +z
  std::set<std::size_t> innerUsed, outerUsed;
};

ZipCheck zipAround(std::size_t m, std::size_t n) {
  const std::vector<Vec3d> inner = clockwiseCircle(m, 3.0, 0.1),
                           outer = clockwiseCircle(n, 1.5, 0.0);
  const std::vector<Vec3d> normals(m, Vec3d(0.0, 0.0, 1.0));
  std::vector<std::size_t> centre(m);
  for (std::size_t i = 0; i < m; ++i) centre[i] = i * n / m;
  ZipCheck check;
  for (const StripFace& face : zipStrip(inner, normals, outer, centre, n)) {
    ++(face.corners == 4 ? check.quads : check.triangles);
    std::array<Vec3d, 4> q;
    for (int k = 0; k < face.corners; ++k) {
      const std::size_t index = face.index[std::size_t(k)];
      q[std::size_t(k)] = face.outer[std::size_t(k)] ? outer[index] : inner[index];
      (face.outer[std::size_t(k)] ? check.outerUsed : check.innerUsed).insert(index);
    }
    for (int k = 0; k < face.corners; ++k) {
      const Vec3d& p = q[std::size_t(k)];
      const Vec3d next = q[std::size_t((k + 1) % face.corners)] - p;
      const Vec3d previous = q[std::size_t((k + face.corners - 1) % face.corners)] - p;
      check.smallestCornerSine = std::min(
          check.smallestCornerSine, next.cross(previous).z() / (next.length() * previous.length()));
    }
  }
  return check;
}

TEST(StripZip, TwiceAsManyInnerPointsGiveQuadsOnly) {
  const ZipCheck check = zipAround(16, 8);
  EXPECT_EQ(check.triangles, 0u);
  EXPECT_EQ(check.quads, 12u);  // (16 + 8) / 2: every quad uses two edges of the rows
  EXPECT_GT(check.smallestCornerSine, 0.0) << "every corner convex, every face like the mesh";
  EXPECT_EQ(check.innerUsed.size(), 16u);
  EXPECT_EQ(check.outerUsed.size(), 8u);
}

TEST(StripZip, EqualRowsGiveOneQuadPerStep) {
  const ZipCheck check = zipAround(10, 10);
  EXPECT_EQ(check.triangles, 0u);
  EXPECT_EQ(check.quads, 10u);
  EXPECT_GT(check.smallestCornerSine, 0.5);
}

TEST(StripZip, AnOddCountNeedsExactlyOneTriangle) {
  const ZipCheck check = zipAround(15, 8);
  EXPECT_EQ(check.triangles, 1u);
  EXPECT_EQ(check.quads, 11u);
  EXPECT_GT(check.smallestCornerSine, 0.0);
}

TEST(StripZip, RejectsRowsTooShort) {
  const std::vector<Vec3d> one(1, Vec3d(0.0));
  EXPECT_THROW(zipStrip(one, one, one, {0}, 1), std::invalid_argument);
}

}  // namespace
}  // namespace voxremesh::extract
