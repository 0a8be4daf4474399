// The polygon round two faces and its cuts (optimize/edge_polygon.h): the engine's recuts keep
// the polygon's orientation, and a cut along a diagonal outside a non-convex polygon, which turns
// a face over while each face may still pass its own criteria, is refused.
#include <gtest/gtest.h>

#include <vector>

#include "optimize/edge_polygon.h"
#include "optimize/mesh_topology.h"

namespace {

using voxremesh::CornerIndex;
using voxremesh::kNoCorner;
using voxremesh::QuadMesh;
using voxremesh::opt::Face;

/// A dart in the plane z = 0, counter-clockwise: p0 (0, 0), p1 (1, 0.4) its reflex corner,
/// p2 (2, 0), p3 (1, 2); cut into two triangles along the inner diagonal p1-p3.
QuadMesh dart() {
  QuadMesh mesh;
  mesh.points = {{0.0, 0.0, 0.0}, {1.0, 0.4, 0.0}, {2.0, 0.0, 0.0}, {1.0, 2.0, 0.0}};
  mesh.constraints.resize(4);
  mesh.faces = {Face{1, 2, 3, kNoCorner}, Face{3, 0, 1, kNoCorner}};
  return mesh;
}

TEST(EdgePolygon, TheDartsPolygonIsOrientedLikeItsFaces) {
  const QuadMesh mesh = dart();
  // Face 0 runs the shared edge from p3 to p1: its corners from p1 round to p3, then face 1's
  // after p3 up to before p1.
  EXPECT_EQ(voxremesh::opt::polygonAroundEdge(mesh.faces[0], mesh.faces[1], 3, 1),
            (std::vector<CornerIndex>{1, 2, 3, 0}));
  // Two faces running the edge the same way make no polygon.
  EXPECT_TRUE(
      voxremesh::opt::polygonAroundEdge(mesh.faces[0], Face{3, 1, 0, kNoCorner}, 3, 1).empty());
}

TEST(EdgePolygon, ACutOutsideANonConvexPolygonIsRefused) {
  const QuadMesh mesh = dart();
  const voxremesh::opt::Topology topology = voxremesh::opt::buildTopology(mesh);
  const std::vector<CornerIndex> polygon{0, 1, 2, 3};
  // Along p1-p3, inside the dart: the faces it has.
  EXPECT_TRUE(voxremesh::opt::cutKeepsOrientation(mesh, topology, 0, 1,
                                                  voxremesh::opt::cutPolygon(polygon, 1)));
  // Along p0-p2, below the reflex corner: triangle p0-p1-p2 runs clockwise, turned over against
  // the other.
  const auto outside = voxremesh::opt::cutPolygon(polygon, 0);
  EXPECT_EQ(outside[0], (Face{0, 1, 2, kNoCorner}));
  EXPECT_FALSE(voxremesh::opt::cutKeepsOrientation(mesh, topology, 0, 1, outside));
  // The same cut of a convex quad (p1 moved to (1, -0.4)) keeps its orientation.
  QuadMesh convex = mesh;
  convex.points[1] = {1.0, -0.4, 0.0};
  EXPECT_TRUE(voxremesh::opt::cutKeepsOrientation(convex, topology, 0, 1, outside));
}

}  // namespace
