// Junctions: sheets that met along a curve (the wheel's disc and rim at their T-junction) are
// voxelised and extracted separately and share nodes along the curve again (extract.h,
// "Junctions"; pipeline.h partVolumes; quad_mesh.h joinAtJunctions).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "extract/junction_nodes.h"
#include "support/mesh_topology.h"
#include "support/surface_distance.h"
#include "support/test_support.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"

namespace voxremesh {
namespace {

using Point3 = std::array<double, 3>;

TEST(JoinAtJunctions, JunctionNodesAFewUnitsInTheLastPlaceApartAreOne) {
  // Two triangles sharing the edge 0-1 as junction nodes; the second sheet's copy of the edge's
  // end lies one unit in the last place away (the node computed along another chain of its
  // curve). A Free point at the same place is never merged.
  auto sheet = [](const Point3& a, const Point3& b, const Point3& c) {
    QuadMesh mesh;
    mesh.points = {a, b, c};
    mesh.faces = {{0, 1, 2, kNoCorner}};
    mesh.constraints = {{PointRole::Junction, kNoCurve}, {PointRole::Junction, kNoCurve}, {}};
    return mesh;
  };
  const double y = -9.6750325067012302;
  const double yNext = std::nextafter(y, 0.0);
  const QuadMesh first = sheet({4.5, y, 32.0}, {4.5, 0.0, 30.0}, {0.0, 0.0, 31.0});
  const QuadMesh second = sheet({4.5, 0.0, 30.0}, {4.5, yNext, 32.0}, {9.0, 0.0, 31.0});
  const QuadMesh joined = joinAtJunctions({first, second});
  EXPECT_EQ(joined.points.size(), 4u);
  EXPECT_EQ(joined.faces[1][1], joined.faces[0][0]);
  // Points 1e-6 of the extent apart stay two.
  const QuadMesh apart = sheet({4.5, 0.0, 30.0}, {4.5, y + 1e-6 * 40.0, 32.0}, {9.0, 0.0, 31.0});
  EXPECT_EQ(joinAtJunctions({first, apart}).points.size(), 5u);
}

TEST(JoinAtJunctions, AJunctionCurvesEndThatIsACornerOnOneSideIsOneNode) {
  // A plate meets a wall along a junction curve; the curve's end, where the plate's free edge
  // meets the wall, is a Corner of the plate's mesh and a Junction point of the wall's. Without
  // the weld the plate hangs loose at that node (ISat part 7: 20 pieces instead of 4).
  QuadMesh wall;
  wall.points = {{0, 0, 0}, {0, 4, 0}, {0, 4, 4}, {0, 0, 4}};
  wall.faces = {{0, 1, 2, 3}};
  wall.constraints = {{PointRole::Junction, kNoCurve},
                      {PointRole::Junction, kNoCurve},
                      {PointRole::Boundary, kNoCurve},
                      {PointRole::Boundary, kNoCurve}};
  QuadMesh plate;
  plate.points = {{0, 0, 0}, {0, 4, 0}, {3, 4, 0}, {3, 0, 0}};
  plate.faces = {{0, 1, 2, 3}};
  plate.constraints = {{PointRole::Corner, kNoCurve},
                       {PointRole::Junction, kNoCurve},
                       {PointRole::Boundary, kNoCurve},
                       {PointRole::Boundary, kNoCurve}};
  const QuadMesh joined = joinAtJunctions({wall, plate});
  EXPECT_EQ(joined.points.size(), 6u);
  EXPECT_EQ(joined.faces[1][0], joined.faces[0][0]);
  EXPECT_EQ(joined.faces[1][1], joined.faces[0][1]);
  // A Boundary point at the same place as another's Boundary point stays its own.
  QuadMesh touching = plate;
  touching.constraints[0] = {PointRole::Boundary, kNoCurve};
  touching.points[1] = {0, 4, 4};  // meets the wall's Boundary corner only
  touching.constraints[1] = {PointRole::Boundary, kNoCurve};
  EXPECT_EQ(joinAtJunctions({wall, touching}).points.size(), 8u);
}

TEST(JunctionNodes, ACurveWithASpacingOfItsOwnIsSampledAtIt) {
  // Two straight curves 12 long; the second asks for nodes 2 apart (a narrow strip along it),
  // the first takes the spacing given (4): 2 and 5 inner nodes.
  VolumeCurve wide, narrow;
  wide.points = {{0, 0, 0}, {12, 0, 0}};
  narrow.points = {{0, 5, 0}, {12, 5, 0}};
  narrow.nodeSpacing = 2.0;
  const extract::JunctionNodes nodes({wide, narrow}, 4.0, 0.8);
  ASSERT_NE(nodes.edge(wide.points[0], wide.points[1]), nullptr);
  ASSERT_NE(nodes.edge(narrow.points[0], narrow.points[1]), nullptr);
  EXPECT_EQ(nodes.edge(wide.points[0], wide.points[1])->points.size(), 2u);
  EXPECT_EQ(nodes.edge(narrow.points[0], narrow.points[1])->points.size(), 5u);
}

TEST(JunctionNodes, ACurveWithACountOfItsOwnHasThatManyPiecesSpreadOverItsSpans) {
  // An L of legs 6 and 12 (its corner an anchor) at spacing 4 would get 2 + 3 pieces; with a
  // count of 7 (the side across a narrow sheet has 7) each leg gets one and the other 5 are
  // spread by length (1.67 and 3.33, the larger remainder first): 3 and 4 pieces, 2 and 3 inner
  // nodes, the corner a node.
  VolumeCurve curve;
  curve.points = {{0, 0, 0}, {6, 0, 0}, {6, 12, 0}};
  curve.nodeCount = 7;
  const extract::JunctionNodes nodes({curve}, 4.0, 0.8);
  EXPECT_TRUE(nodes.isNodePoint(curve.points[1]));
  ASSERT_NE(nodes.edge(curve.points[0], curve.points[1]), nullptr);
  ASSERT_NE(nodes.edge(curve.points[1], curve.points[2]), nullptr);
  EXPECT_EQ(nodes.edge(curve.points[0], curve.points[1])->points.size(), 2u);
  EXPECT_EQ(nodes.edge(curve.points[1], curve.points[2])->points.size(), 3u);
  // A count equal to its segments keeps its points, whatever the spacing.
  VolumeCurve kept = curve;
  kept.nodeCount = 2;
  const extract::JunctionNodes same({kept}, 1.0, 0.2);
  EXPECT_TRUE(same.edge(kept.points[0], kept.points[1])->points.empty());
  EXPECT_TRUE(same.edge(kept.points[1], kept.points[2])->points.empty());
}

TEST(JunctionNodes, PiecesShrinkTowardAGradedEndWithinItsRatio) {
  // A straight seam 30 long (its points 3 apart, which the spacing 3 would keep) graded toward
  // its end at x = 30 with ratio 1.25: still ten pieces, the one at the graded end as long as
  // the far ones, and each node at most 1.25 times as far from that end as the node before.
  VolumeCurve curve;
  for (int i = 0; i <= 10; ++i) curve.points.push_back({3.0 * i, 0.0, 0.0});
  curve.grading = {{curve.points.back(), 1.25}};
  const extract::JunctionNodes nodes({curve}, 3.0, 0.6);
  std::vector<double> fromEnd;  // distances of the nodes from x = 30, the end itself excluded
  for (const auto& p : nodes.nodes())
    if (p[0] < 30.0) fromEnd.push_back(30.0 - p[0]);
  std::sort(fromEnd.begin(), fromEnd.end());
  ASSERT_EQ(fromEnd.size(), 10u);
  EXPECT_DOUBLE_EQ(fromEnd.back(), 30.0);
  const double far = fromEnd[9] - fromEnd[8];
  EXPECT_NEAR(fromEnd[0], far, 1e-9);
  for (std::size_t k = 1; k < fromEnd.size(); ++k)
    EXPECT_LE(fromEnd[k], 1.25 * fromEnd[k - 1] + 1e-9) << k;
  EXPECT_LT(fromEnd[1] - fromEnd[0], 0.5 * far);  // the first rung inside the wedge is close
  // Reversed, the curve is graded toward the same point (grading goes by position).
  VolumeCurve reversed = curve;
  std::reverse(reversed.points.begin(), reversed.points.end());
  const extract::JunctionNodes same({reversed}, 3.0, 0.6);
  EXPECT_EQ(same.nodes(), nodes.nodes());
}

TEST(JunctionNodes, NodesStandAtStationsWithEachStretchsOwnCount) {
  // A straight seam 12 long (points 1 apart) facing, across a narrow patch, two curves that meet
  // across from x = 5: a station there, 2 pieces before it and 4 after (the counts of the curves
  // across), so that its nodes line up with theirs instead of lying 2 apart at the spacing 2.
  // Reversed, the same nodes (stations and their pieces go with the curve's direction).
  VolumeCurve curve;
  for (int i = 0; i <= 12; ++i) curve.points.push_back({double(i), 0.0, 0.0});
  curve.stations = {{5.0, 0.3, 0.0}};
  curve.stationPieces = {2, 4};
  const extract::JunctionNodes nodes({curve}, 2.0, 0.4);
  std::vector<double> xs;
  for (const auto& p : nodes.nodes()) xs.push_back(p[0]);
  std::sort(xs.begin(), xs.end());
  const std::vector<double> expected{0.0, 2.5, 5.0, 6.75, 8.5, 10.25, 12.0};
  ASSERT_EQ(xs.size(), expected.size());
  for (std::size_t k = 0; k < xs.size(); ++k) EXPECT_NEAR(xs[k], expected[k], 1e-9) << k;
  VolumeCurve reversed = curve;
  std::reverse(reversed.points.begin(), reversed.points.end());
  reversed.stationPieces = {4, 2};
  const extract::JunctionNodes same({reversed}, 2.0, 0.4);
  EXPECT_EQ(same.nodes(), nodes.nodes());
  // Stations that do not fit (a stretch with no pieces) leave the even spacing.
  curve.stationPieces = {0, 6};
  const extract::JunctionNodes even({curve}, 2.0, 0.4);
  EXPECT_EQ(even.nodes().size(), 7u);
  EXPECT_NEAR(even.nodes()[1][0] - even.nodes()[0][0], 2.0, 1e-9);
}

TEST(JunctionNodes, AnEvenPieceEndingOnACurvePointButForRoundingEndsOnIt) {
  // 10 long in three pieces at 10/3: the first piece ends 1e-14 short of the curve point there.
  // That point is the node (every sheet along the curve then has it), not a node 1e-14 from it
  // that a sheet's own corner at the point would leave as a gap of its own (ISat part 2).
  VolumeCurve curve;
  curve.points = {{0, 0, 0}, {10.0 / 3.0 + 1e-14, 0, 0}, {10, 0, 0}};
  const extract::JunctionNodes nodes({curve}, 10.0 / 3.0, 0.5);
  EXPECT_TRUE(nodes.isNodePoint(curve.points[1]));
  ASSERT_NE(nodes.edge(curve.points[0], curve.points[1]), nullptr);
  EXPECT_TRUE(nodes.edge(curve.points[0], curve.points[1])->points.empty());
  ASSERT_NE(nodes.edge(curve.points[1], curve.points[2]), nullptr);
  EXPECT_EQ(nodes.edge(curve.points[1], curve.points[2])->points.size(), 1u);
}

TEST(JunctionNodes, ACircleGetsNodesCloseEnoughToKeepItsLengthWithTheSagittaLimit) {
  // A circle of radius 8.6 in 24 points (the edge of a ring) at spacing 9: six even pieces whose
  // chords lie 1.15 from it, within the tolerance of 1.8, but 4.5 % shorter than the circle.
  // With the sagitta limit (kChordSagittaShare, 4.33 % of a chord's length) every curve point
  // lies within that share of its chord, and the nodes' polygon is less than 0.5 % shorter.
  VolumeCurve curve;
  curve.closed = true;
  const double radius = 8.6, pi = std::acos(-1.0);
  for (int i = 0; i < 24; ++i)
    curve.points.push_back(
        {0.0, radius * std::cos(2.0 * pi * i / 24.0), radius * std::sin(2.0 * pi * i / 24.0)});
  const auto polygonLength = [&](const extract::JunctionNodes& nodes) {
    double length = 0.0;
    const std::vector<Point3> all = nodes.nodes();
    // The nodes of a circle in angular order.
    std::vector<std::pair<double, Point3>> byAngle;
    for (const Point3& p : all) byAngle.push_back({std::atan2(p[2], p[1]), p});
    std::sort(byAngle.begin(), byAngle.end());
    for (std::size_t i = 0; i < byAngle.size(); ++i) {
      const Point3& a = byAngle[i].second;
      const Point3& b = byAngle[(i + 1) % byAngle.size()].second;
      length += std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    }
    return length;
  };
  const double circle = 24.0 * 2.0 * radius * std::sin(pi / 24.0);
  const extract::JunctionNodes even({curve}, 9.0, 1.8);
  EXPECT_EQ(even.nodes().size(), 6u);
  EXPECT_LT(polygonLength(even), 0.96 * circle);
  const extract::JunctionNodes kept({curve}, 9.0, 1.8, 0.0433);
  EXPECT_GT(polygonLength(kept), 0.995 * circle);
}

TEST(JunctionNodes, SameNodesWhicheverWayAndWhereverTheCurveStarts) {
  // A closed square-ish curve with a bend, given from different start points and directions.
  VolumeCurve curve;
  curve.closed = true;
  curve.points = {{0, 0, 0}, {10, 0, 0}, {20, 1, 0}, {20, 10, 0}, {10, 12, 0}, {0, 10, 0}};
  const extract::JunctionNodes reference({curve}, 3.0, 0.2);
  VolumeCurve other = curve;
  std::reverse(other.points.begin(), other.points.end());
  std::rotate(other.points.begin(), other.points.begin() + 2, other.points.end());
  const extract::JunctionNodes same({other}, 3.0, 0.2);
  std::size_t nodes = 0;
  for (std::size_t i = 0; i < curve.points.size(); ++i) {
    const Point3& a = curve.points[i];
    const Point3& b = curve.points[(i + 1) % curve.points.size()];
    const extract::JunctionEdgeNodes* x = reference.edge(a, b);
    const extract::JunctionEdgeNodes* y = same.edge(b, a);
    ASSERT_NE(x, nullptr);
    ASSERT_NE(y, nullptr);
    EXPECT_EQ(x->points, y->points);  // bit-identical
    EXPECT_EQ(reference.isNodePoint(a), same.isNodePoint(a));
    nodes += x->points.size() + (reference.isNodePoint(a) ? 1 : 0);
  }
  // About one node per spacing (perimeter 63.6 / 3), corners included.
  EXPECT_GE(nodes, 18u);
  EXPECT_LE(nodes, 26u);
  EXPECT_EQ(reference.edge({0, 0, 0}, {20, 10, 0}), nullptr);
}

TEST(JunctionNodes, ACurveAlreadySpacedAsTheSamplingWouldBeKeepsItsPoints) {
  // Points 2.5, 3.5, 4 and 3 apart: within a factor 1.5 of the spacing 3, so each is a node and
  // no node is added.
  VolumeCurve fits;
  fits.points = {{0, 0, 0}, {2.5, 0, 0}, {6, 0, 0}, {10, 0, 0}, {13, 0, 0}};
  const extract::JunctionNodes kept({fits}, 3.0, 0.2);
  for (std::size_t i = 0; i + 1 < fits.points.size(); ++i) {
    EXPECT_TRUE(kept.isNodePoint(fits.points[i])) << i;
    ASSERT_NE(kept.edge(fits.points[i], fits.points[i + 1]), nullptr);
    EXPECT_TRUE(kept.edge(fits.points[i], fits.points[i + 1])->points.empty()) << i;
  }
  // One segment 5 long (over 1.5 x 3): the curve is sampled evenly instead, 13 / 3 -> 4 pieces
  // of 3.25, so the points at 2.5, 6 and 10 are not nodes.
  VolumeCurve resampled = fits;
  resampled.points[3] = {11, 0, 0};  // 6 -> 11 is 5 long
  const extract::JunctionNodes sampled({resampled}, 3.0, 0.2);
  EXPECT_FALSE(sampled.isNodePoint(resampled.points[1]));
  EXPECT_FALSE(sampled.isNodePoint(resampled.points[2]));
  EXPECT_TRUE(sampled.isNodePoint(resampled.points.front()));
  EXPECT_TRUE(sampled.isNodePoint(resampled.points.back()));
}

TEST(Junctions, WheelSheetsShareTheirNodesAlongTheTJunction) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "wheel.k");
  const FeModel deck = readDeck(path);
  const RemeshSettings settings;
  const std::vector<PartPlan> plans = planRemesh(deck, settings);
  ASSERT_EQ(plans.size(), 1u);
  const std::vector<SheetVolume> volumes = partVolumes(deck, plans[0], settings);
  ASSERT_EQ(volumes.size(), 3u);  // rim front, rim back, disc
  std::vector<QuadMesh> meshes;
  std::vector<std::set<Point3>> junctionPoints;
  for (const SheetVolume& sheet : volumes) {
    ASSERT_EQ(sheet.sheet.junctionCurves.size(), 1u);
    meshes.push_back(extractQuadMesh(sheet.volume));
    // Each sheet alone keeps its boundary loops (the junction ring is one of them). The rim's
    // sheets are manifold and consistently oriented; the disc still has a few edges where the
    // strip around its holes next to the junction overlaps (see the extraction notes).
    const test::MeshTopology topology = test::meshTopology(meshes.back());
    EXPECT_EQ(topology.boundaryLoops, sheet.sheet.boundaryLoops.size());
    if (meshes.size() <= 2) {
      EXPECT_EQ(topology.nonManifoldEdges, 0u);
      EXPECT_EQ(topology.inconsistentEdges, 0u);
    }
    EXPECT_LE(topology.nonManifoldEdges, 13u);  // measured 13 (disc)
    std::set<Point3> points;
    for (std::size_t p = 0; p < meshes.back().points.size(); ++p)
      if (meshes.back().constraints[p].role == PointRole::Junction)
        points.insert(meshes.back().points[p]);
    junctionPoints.push_back(points);
  }
  // The same junction nodes on all three sides, about one per voxel along the 168-edge ring.
  EXPECT_GT(junctionPoints[0].size(), 150u);
  EXPECT_EQ(junctionPoints[0], junctionPoints[1]);
  EXPECT_EQ(junctionPoints[0], junctionPoints[2]);

  const QuadMesh joined = joinAtJunctions(meshes);
  const test::MeshTopology topology = test::meshTopology(joined);
  // The junction ring: one edge per pair of neighbouring junction nodes, three faces each, and
  // the three sheets one connected mesh again.
  const test::MeshTopology discTopology = test::meshTopology(meshes[2]);
  EXPECT_EQ(topology.nonManifoldEdges, junctionPoints[0].size() + discTopology.nonManifoldEdges);
  EXPECT_EQ(topology.components, 1u);
  // Every point of the original junction curve lies on the new ring (within the strip's
  // tolerance of 0.2 voxel), so the T-junction stays where it was and connected.
  // the edges of three or more faces
  const auto ring = test::edgeSegments(joined, 3, std::numeric_limits<int>::max());
  const double voxel = volumes[0].volume.info().voxelSize;
  const Sheet& disc = volumes[2].sheet;
  double worst = 0.0;
  for (const PointIndex p : disc.junctionCurves[0].points)
    worst = std::max(worst, test::distanceToSegments(disc.points[p], ring));
  EXPECT_LT(worst, 0.2 * voxel + 1e-9);
  // The input's 25 boundary loops of the sheets (rim ends and the disc's holes, the junction ring
  // not counted) are all kept.
  std::size_t inputLoops = 0;
  for (const SheetVolume& sheet : volumes) inputLoops += sheet.sheet.boundaryLoops.size();
  EXPECT_EQ(topology.boundaryLoops, inputLoops - 3 * 1);
}

}  // namespace
}  // namespace voxremesh
