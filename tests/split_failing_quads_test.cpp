// splitFailingQuads on a grid with a quad folded over a corner (warped far beyond the limit, its
// Jacobian ratio failing): the quad becomes the two triangles of the cut that passes, nothing else
// changes (points, the other faces, orientation, Euler characteristic), the triangle share is
// respected, and bad settings are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "voxremesh/errors.h"
#include "voxremesh/optimize.h"
#include "voxremesh/quality.h"

namespace {

using voxremesh::CornerIndex;
using voxremesh::QuadMesh;

/// A 4 x 4 grid of unit quads in the plane z = 0 whose corner point (4, 4), which only the last
/// quad uses, is lifted by 1.2: that quad is folded across its diagonal from (4, 3) to (3, 4).
QuadMesh gridWithAFoldedCorner() {
  const int n = 4;
  QuadMesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) mesh.points.push_back({double(i), double(j), 0.0});
  auto id = [n](int i, int j) { return CornerIndex(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      mesh.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  mesh.points[id(n, n)][2] = 1.2;
  mesh.constraints.resize(mesh.points.size());
  return mesh;
}

voxremesh::QualitySettings unitCriteria() {
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  return settings;
}

/// V - E + F, and whether every edge runs opposite ways in its two faces.
std::pair<long, bool> eulerAndOriented(const QuadMesh& mesh) {
  std::map<std::pair<CornerIndex, CornerIndex>, int> directed;
  for (const auto& face : mesh.faces) {
    const int n = voxremesh::cornerCount(face);
    for (int k = 0; k < n; ++k) ++directed[{face[std::size_t(k)], face[std::size_t((k + 1) % n)]}];
  }
  bool oriented = true;
  long edges = 0;
  for (const auto& [edge, count] : directed) {
    oriented = oriented && count == 1;
    if (edge.first < edge.second || !directed.count({edge.second, edge.first})) ++edges;
  }
  return {long(mesh.points.size()) - edges + long(mesh.faces.size()), oriented};
}

TEST(SplitFailingQuads, SplitsTheFoldedQuadAlongItsFold) {
  QuadMesh mesh = gridWithAFoldedCorner();
  const QuadMesh start = mesh;
  const voxremesh::QualitySettings criteria = unitCriteria();
  const voxremesh::QualityReport before = voxremesh::assessQuality(mesh, criteria);
  ASSERT_EQ(before.failingAny, 1u);  // the folded quad: warping, Jacobian ratio, ...
  const auto [euler, oriented] = eulerAndOriented(mesh);
  ASSERT_TRUE(oriented);

  EXPECT_EQ(voxremesh::splitFailingQuads(mesh, criteria, 0.2), 1u);
  EXPECT_EQ(voxremesh::assessQuality(mesh, criteria).failingAny, 0u);
  ASSERT_EQ(mesh.faces.size(), start.faces.size() + 1);
  EXPECT_EQ(mesh.points, start.points);
  // The other quads are untouched and in place; the two triangles are last, cut along the fold
  // (the diagonal from (4, 3) to (3, 4), points 19 and 23).
  for (std::size_t f = 0; f + 1 < start.faces.size(); ++f) EXPECT_EQ(mesh.faces[f], start.faces[f]);
  const auto& a = mesh.faces[start.faces.size() - 1];
  const auto& b = mesh.faces[start.faces.size()];
  EXPECT_EQ(voxremesh::cornerCount(a), 3);
  EXPECT_EQ(voxremesh::cornerCount(b), 3);
  for (const auto* face : {&a, &b}) {
    EXPECT_NE(std::find(face->begin(), face->begin() + 3, 19u), face->begin() + 3);
    EXPECT_NE(std::find(face->begin(), face->begin() + 3, 23u), face->begin() + 3);
  }
  EXPECT_EQ(eulerAndOriented(mesh), std::make_pair(euler, true));
}

TEST(SplitFailingQuads, KeepsToTheTriangleShareAndLeavesPassingQuads) {
  const voxremesh::QualitySettings criteria = unitCriteria();
  // 16 faces: one split gives 2 triangles of 17 faces (11.8 %).
  QuadMesh mesh = gridWithAFoldedCorner();
  EXPECT_EQ(voxremesh::splitFailingQuads(mesh, criteria, 0.11), 0u);
  EXPECT_EQ(mesh.faces.size(), 16u);
  EXPECT_EQ(voxremesh::splitFailingQuads(mesh, criteria, 0.0), 0u);
  EXPECT_EQ(voxremesh::splitFailingQuads(mesh, criteria, 0.12), 1u);
  // A flat grid has nothing to split.
  QuadMesh flat = gridWithAFoldedCorner();
  flat.points.back()[2] = 0.0;
  EXPECT_EQ(voxremesh::splitFailingQuads(flat, criteria, 1.0), 0u);
}

TEST(SplitFailingQuads, RefusesBadSettings) {
  QuadMesh mesh = gridWithAFoldedCorner();
  voxremesh::QualitySettings criteria = unitCriteria();
  EXPECT_THROW(voxremesh::splitFailingQuads(mesh, criteria, -0.1), voxremesh::SettingError);
  EXPECT_THROW(voxremesh::splitFailingQuads(mesh, criteria, 1.5), voxremesh::SettingError);
  EXPECT_THROW(voxremesh::splitFailingQuads(mesh, criteria, std::nan("")), voxremesh::SettingError);
  criteria.targetSize = 0.0;
  EXPECT_THROW(voxremesh::splitFailingQuads(mesh, criteria, 0.1), std::invalid_argument);
  criteria.targetSize = 1.0;
  mesh.faces.push_back({0, 1, 99, 2});
  EXPECT_THROW(voxremesh::splitFailingQuads(mesh, criteria, 0.1), std::invalid_argument);
}

}  // namespace
