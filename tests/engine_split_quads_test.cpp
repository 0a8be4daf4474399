// The search engine's quad split (reconnectFailingFaces with kSplitQuad, no searches) on a grid
// with a quad folded over a corner (warped far beyond the limit, its Jacobian ratio failing): the
// quad becomes the two triangles of the cut that passes, nothing else changes (points, the other
// faces, orientation, Euler characteristic), the triangle share is respected, and bad settings are
// refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "support/mesh_topology.h"
#include "support/unit_grid.h"
#include "voxremesh/errors.h"
#include "voxremesh/optimize.h"
#include "voxremesh/quality.h"

namespace {

using voxremesh::CornerIndex;
using voxremesh::QuadMesh;

/// A 4 x 4 grid of unit quads in the plane z = 0 whose corner point (4, 4), which only the last
/// quad uses, is lifted by 1.2: that quad is folded across its diagonal from (4, 3) to (3, 4).
QuadMesh gridWithAFoldedCorner() {
  QuadMesh mesh = voxremesh::test::unitGrid(4);
  mesh.points[voxremesh::test::gridPoint(4, 4, 4)][2] = 1.2;
  return mesh;
}

voxremesh::QualitySettings unitCriteria() {
  voxremesh::QualitySettings settings;
  settings.targetSize = 1.0;
  return settings;
}

/// The surface the folded quad stands for: the grid with that quad as the two triangles of its
/// fold.
voxremesh::ReferenceSurface foldedSurface() {
  QuadMesh mesh = gridWithAFoldedCorner();
  const auto quad = mesh.faces.back();  // (3, 3), (4, 3), (4, 4), (3, 4): points 18, 19, 24, 23
  mesh.faces.back() = {quad[0], quad[1], quad[3], voxremesh::kNoCorner};
  mesh.faces.push_back({quad[1], quad[2], quad[3], voxremesh::kNoCorner});
  return voxremesh::ReferenceSurface(mesh);
}

/// The engine with quad splits alone, no point searches, on foldedSurface() as the original;
/// returns the number of quads split.
std::size_t splitFailingQuads(QuadMesh& mesh, const voxremesh::QualitySettings& criteria,
                              double maxTriangleShare) {
  voxremesh::ReconnectSettings engine;
  engine.sweeps = 0;
  engine.edits = voxremesh::kSplitQuad;
  engine.maxTriangleShare = maxTriangleShare;
  return voxremesh::reconnectFailingFaces(mesh, foldedSurface(), criteria, engine);
}

/// The faces, each turned to start at its smallest corner, sorted.
std::vector<std::array<CornerIndex, 4>> sortedFaces(std::vector<std::array<CornerIndex, 4>> faces) {
  for (auto& face : faces)
    std::rotate(face.begin(),
                std::min_element(face.begin(), face.begin() + voxremesh::cornerCount(face)),
                face.begin() + voxremesh::cornerCount(face));
  std::sort(faces.begin(), faces.end());
  return faces;
}

TEST(EngineSplitQuads, SplitsTheFoldedQuadAlongItsFold) {
  QuadMesh mesh = gridWithAFoldedCorner();
  const QuadMesh start = mesh;
  const voxremesh::QualitySettings criteria = unitCriteria();
  const voxremesh::QualityReport before = voxremesh::assessQuality(mesh, criteria);
  ASSERT_EQ(before.failingAny, 1u);  // the folded quad: warping, Jacobian ratio, ...
  const voxremesh::test::MeshTopology topology = voxremesh::test::meshTopology(mesh);
  ASSERT_EQ(topology.inconsistentEdges, 0u);

  EXPECT_EQ(splitFailingQuads(mesh, criteria, 0.2), 1u);
  EXPECT_EQ(voxremesh::assessQuality(mesh, criteria).failingAny, 0u);
  ASSERT_EQ(mesh.faces.size(), start.faces.size() + 1);
  EXPECT_EQ(mesh.points, start.points);
  // The other quads are untouched; the folded one (the last) became two triangles cut along the
  // fold (the diagonal from (4, 3) to (3, 4), points 19 and 23).
  std::vector<std::array<CornerIndex, 4>> quads, triangles;
  for (const auto& face : mesh.faces)
    (voxremesh::cornerCount(face) == 4 ? quads : triangles).push_back(face);
  std::vector<std::array<CornerIndex, 4>> others(start.faces.begin(), start.faces.end() - 1);
  EXPECT_EQ(sortedFaces(quads), sortedFaces(others));
  ASSERT_EQ(triangles.size(), 2u);
  for (const auto& face : triangles) {
    EXPECT_NE(std::find(face.begin(), face.begin() + 3, 19u), face.begin() + 3);
    EXPECT_NE(std::find(face.begin(), face.begin() + 3, 23u), face.begin() + 3);
  }
  const voxremesh::test::MeshTopology after = voxremesh::test::meshTopology(mesh);
  EXPECT_EQ(after.eulerCharacteristic, topology.eulerCharacteristic);
  EXPECT_EQ(after.inconsistentEdges, 0u);
  EXPECT_EQ(after.nonManifoldEdges, 0u);
}

TEST(EngineSplitQuads, DoesNotCutAlongAnExistingEdge) {
  // A triangle standing on the fold's diagonal (19, 23): cutting along it would give that edge
  // three faces, so the quad is cut along its other diagonal (18, 24), or not at all.
  QuadMesh mesh = gridWithAFoldedCorner();
  mesh.points.push_back({3.5, 3.5, 5.0});
  mesh.constraints.emplace_back();
  mesh.faces.push_back({23, 19, CornerIndex(mesh.points.size() - 1), voxremesh::kNoCorner});
  splitFailingQuads(mesh, unitCriteria(), 1.0);
  std::size_t onTheDiagonal = 0;
  for (const auto& face : mesh.faces) {
    const auto end = face.begin() + voxremesh::cornerCount(face);
    const bool has19 = std::find(face.begin(), end, 19u) != end;
    const bool has23 = std::find(face.begin(), end, 23u) != end;
    onTheDiagonal += has19 && has23 ? 1 : 0;
  }
  EXPECT_EQ(onTheDiagonal, 1u);  // the standing triangle alone
  EXPECT_EQ(voxremesh::test::meshTopology(mesh).nonManifoldEdges, 0u);
}

TEST(EngineSplitQuads, KeepsToTheTriangleShareAndLeavesPassingQuads) {
  const voxremesh::QualitySettings criteria = unitCriteria();
  // 16 faces: one split gives 2 triangles of 17 faces (11.8 %).
  QuadMesh mesh = gridWithAFoldedCorner();
  EXPECT_EQ(splitFailingQuads(mesh, criteria, 0.11), 0u);
  EXPECT_EQ(mesh.faces.size(), 16u);
  EXPECT_EQ(splitFailingQuads(mesh, criteria, 0.0), 0u);
  EXPECT_EQ(splitFailingQuads(mesh, criteria, 0.12), 1u);
  // A flat grid has nothing to split.
  QuadMesh flat = gridWithAFoldedCorner();
  flat.points.back()[2] = 0.0;
  EXPECT_EQ(splitFailingQuads(flat, criteria, 1.0), 0u);
}

TEST(EngineSplitQuads, RefusesBadSettings) {
  QuadMesh mesh = gridWithAFoldedCorner();
  voxremesh::QualitySettings criteria = unitCriteria();
  EXPECT_THROW(splitFailingQuads(mesh, criteria, -0.1), voxremesh::SettingError);
  EXPECT_THROW(splitFailingQuads(mesh, criteria, 1.5), voxremesh::SettingError);
  EXPECT_THROW(splitFailingQuads(mesh, criteria, std::nan("")), voxremesh::SettingError);
  criteria.targetSize = 0.0;
  EXPECT_THROW(splitFailingQuads(mesh, criteria, 0.1), std::invalid_argument);
  criteria.targetSize = 1.0;
  mesh.faces.push_back({0, 1, 99, 2});
  EXPECT_THROW(splitFailingQuads(mesh, criteria, 0.1), std::invalid_argument);
}

}  // namespace
