// Pinched vertices of the dual mesh (src/extract/pinch_fans.h): the smaller fans at a vertex two
// parts of a mesh share go, the larger stays; edges of more than two faces are found, also where
// their ends are distinct points at one position (as before the weld).
#include <gtest/gtest.h>

#include "extract/pinch_fans.h"

namespace voxremesh::extract {
namespace {

/// A 3 x 2 grid of unit quads (points 0..11, row by row, 4 a row) and, touching its corner point
/// 3 only, one more quad beyond it (points 12..14 with 3).
QuadMesh gridWithQuadAtCorner() {
  QuadMesh mesh;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) mesh.points.push_back({double(x), double(y), 0.0});
  for (CornerIndex y = 0; y < 2; ++y)
    for (CornerIndex x = 0; x < 3; ++x)
      mesh.faces.push_back({4 * y + x, 4 * y + x + 1, 4 * y + x + 5, 4 * y + x + 4});
  mesh.points.push_back({4.0, -1.0, 0.0});
  mesh.points.push_back({4.0, 0.0, 0.0});
  mesh.points.push_back({3.0, -1.0, 0.0});
  mesh.faces.push_back({3, 14, 12, 13});
  return mesh;
}

TEST(RemovePinchedFans, TheSmallerFanAtAPinchedVertexGoes) {
  QuadMesh mesh = gridWithQuadAtCorner();
  // Point 3 has two fans: grid face 2 and the extra quad (face 6). Equal sizes: the fan with the
  // lower face stays.
  EXPECT_EQ(removePinchedFans(mesh, {3}), 1u);
  ASSERT_EQ(mesh.faces.size(), 6u);
  for (const auto& face : mesh.faces) EXPECT_NE(face[1], 14u) << "the extra quad is gone";
}

TEST(RemovePinchedFans, RegularVerticesAndUnlistedOnesStay) {
  QuadMesh mesh = gridWithQuadAtCorner();
  EXPECT_EQ(removePinchedFans(mesh, {0, 5, 6, 11, 99}), 0u) << "no pinch among these";
  EXPECT_EQ(mesh.faces.size(), 7u);
}

TEST(RemovePinchedFans, TheLargerFanStays) {
  QuadMesh mesh = gridWithQuadAtCorner();
  // A second quad on the extra part, joined to the first along 3-13: point 3's extra fan now
  // has two faces against the grid's one, and the grid's face goes.
  mesh.points.push_back({4.0, 1.0, 0.0});
  mesh.faces.push_back({3, 13, 15, 7});  // shares 3-7 with the grid too: one fan of three faces
  const QuadMesh before = mesh;
  EXPECT_EQ(removePinchedFans(mesh, {3}), 0u) << "joined across 3-7: no pinch";
  mesh = before;
  mesh.faces.back() = {3, 13, 15, kNoCorner};  // a triangle beyond 3-13 only
  mesh.points.push_back({5.0, 0.0, 0.0});
  EXPECT_EQ(removePinchedFans(mesh, {3}), 1u);
  ASSERT_EQ(mesh.faces.size(), 7u);
  for (const auto& face : mesh.faces)
    EXPECT_FALSE(face[0] == 2 && face[1] == 3) << "the grid's corner face (fan of one) is gone";
}

TEST(EndsOfOverfullEdges, FindsEdgesOfThreeFacesAlsoAcrossCoincidentPoints) {
  QuadMesh mesh = gridWithQuadAtCorner();
  EXPECT_TRUE(endsOfOverfullEdges(mesh).empty());
  // A third face on edge 1-5, its ends given as copies of points 1 and 5.
  mesh.points.push_back(mesh.points[1]);  // 15
  mesh.points.push_back(mesh.points[5]);  // 16
  mesh.points.push_back({1.0, 1.0, 1.0});
  mesh.faces.push_back({15, 16, 17, kNoCorner});
  EXPECT_EQ(endsOfOverfullEdges(mesh), (std::vector<CornerIndex>{1, 5}));
}

}  // namespace
}  // namespace voxremesh::extract
