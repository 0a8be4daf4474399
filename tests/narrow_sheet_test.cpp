// Narrow sheets meshed from their boundary (src/extract/narrow_sheet.h, polygon_quads.h,
// sheet_patches.h): one row of quads across a strip, nodes only on the boundary, junction nodes
// shared across a cut, refusals where the boundary alone cannot carry the surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "extract/mapped_patch.h"
#include "extract/narrow_sheet.h"
#include "extract/polygon_quads.h"
#include "extract/sheet_patches.h"
#include "geometry/vec3.h"
#include "pipeline/remesh_part.h"
#include "pipeline/seam_spacing.h"
#include "support/test_support.h"
#include "voxremesh/deck_compare.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/quality.h"

using namespace voxremesh;

namespace {

/// A strip of columns x rows quads, each `along` long in x and `across` wide in y, in the plane
/// z = 0 (or folded about the line y = fold by 90 degrees into z when fold > 0); shells of the
/// rows below `splitRow` belong to part 1, the others to part 2 (so that they share a line).
FeModel strip(int columns, int rows, double along, double across, int splitRow = 1000,
              double fold = 0.0) {
  FeModel model;
  auto id = [&](int i, int j) { return Id(j * (columns + 1) + i + 1); };
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= columns; ++i) {
      const double y = j * across;
      const bool folded = fold > 0.0 && y > fold;
      model.nodes.push_back({id(i, j), {i * along, folded ? fold : y, folded ? y - fold : 0.0}});
    }
  }
  Id shell = 1;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
      model.shells.push_back({shell++,
                              j < splitRow ? Id(1) : Id(2),
                              {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}});
  model.partOrAdd(1);
  if (splitRow < rows) model.partOrAdd(2);
  return model;
}

/// A strip of 10 x 1 elements 4 mm long and `across` wide whose far side is shifted by `shift`
/// and scaled by `scale` along x (a trapezoid).
FeModel taperedStrip(double across, double shift, double scale) {
  FeModel model = strip(10, 1, 4.0, across);
  for (Node& node : model.nodes)
    if (node.xyz[1] > 0.0) node.xyz[0] = shift + node.xyz[0] * scale;
  return model;
}

/// Meshes the part's one sheet from its boundary with nodes `spacing` apart.
QuadMesh meshStrip(const FeModel& model, Id part, double spacing, double tolerance = 0.1,
                   double junctionSpacing = 0.0, const SheetSettings& sheetSettings = {},
                   double sagittaShare = 0.0) {
  const std::vector<Sheet> sheets = buildSheets(model, part, sheetSettings);
  EXPECT_EQ(sheets.size(), 1u);
  const QuadMesh surface = pipeline::sheetSurface(sheets.front());
  const ReferenceSurface reference(surface);
  std::vector<VolumeCurve> curves;
  for (const Polyline& curve : sheets.front().junctionCurves) {
    VolumeCurve world;
    world.closed = curve.closed;
    for (const PointIndex p : curve.points) world.points.push_back(sheets.front().points[p]);
    curves.push_back(world);
  }
  const double jSpacing = junctionSpacing > 0.0 ? junctionSpacing : spacing;
  const extract::JunctionNodes junctions(curves, jSpacing, 0.2 * jSpacing);
  extract::NarrowSheetSettings settings;
  settings.spacing = spacing;
  settings.tolerance = tolerance;
  settings.maxChord = 3.0 * spacing;
  settings.sagittaShare = sagittaShare;
  return extract::meshNarrowSheet(sheets.front(), surface, reference, junctions, settings);
}

/// A panel 40 mm long and 10 mm wide (10 x 4 elements of 4 x 2.5) bent across round a cylinder
/// of radius `radius`, with `endPlates` plates 4 mm long at its two ends (parts 2 and 3, bent
/// alike, so that its ends are seams); `panelArea` receives the panel's area.
FeModel curvedPanel(double& panelArea, double radius = 12.5, bool endPlates = false) {
  FeModel model = strip(10, 4, 4.0, 2.5);
  for (int j = 0; j <= 4 && endPlates; ++j) {
    test::addNode(model, 1000 + j, -4.0, 2.5 * j);
    test::addNode(model, 2000 + j, 44.0, 2.5 * j);
    if (j == 4) continue;
    test::addShell(model, 1000 + j, 2, {1000 + j, 1 + 11 * j, 12 + 11 * j, 1001 + j});
    test::addShell(model, 2000 + j, 3, {11 + 11 * j, 2000 + j, 2001 + j, 22 + 11 * j});
  }
  for (Node& node : model.nodes) {
    const double angle = node.xyz[1] / radius;
    node.xyz[1] = radius * std::sin(angle);
    node.xyz[2] = radius * (1.0 - std::cos(angle));
  }
  panelArea = 4.0 * 40.0 * 2.0 * radius * std::sin(2.5 / (2.0 * radius));
  return model;
}

std::size_t triangleCount(const QuadMesh& mesh) {
  std::size_t count = 0;
  for (const auto& face : mesh.faces) count += cornerCount(face) == 3;
  return count;
}

/// Face normals (length: twice the area; a quad's from its diagonals).
std::vector<geom::Vec3> normals(const QuadMesh& mesh) {
  std::vector<geom::Vec3> out;
  for (const auto& f : mesh.faces) {
    const bool triangle = cornerCount(f) == 3;
    out.push_back(geom::elementNormal(mesh.points[f[0]], mesh.points[f[1]], mesh.points[f[2]],
                                      mesh.points[f[triangle ? 2 : 3]], triangle));
  }
  return out;
}

double area(const QuadMesh& mesh) {
  double total = 0.0;
  for (const geom::Vec3& normal : normals(mesh)) total += 0.5 * geom::norm(normal);
  return total;
}

}  // namespace

TEST(NarrowSheet, AStripGetsOneRowOfQuadsAcrossAtTheSpacing) {
  // 2 x 40 mm in 20 x 1 elements of 2 x 2; meshed at 4 mm: 10 quads of 4 x 2.
  const QuadMesh mesh = meshStrip(strip(20, 1, 2.0, 2.0), 1, 4.0);
  EXPECT_EQ(triangleCount(mesh), 0u);
  EXPECT_EQ(mesh.faces.size(), 10u);
  EXPECT_NEAR(area(mesh), 80.0, 1e-9);
  for (const ElementQuality& quality : elementQualities(mesh))
    EXPECT_NEAR(quality.minAngleDeg, 90.0, 1e-6);
  for (const geom::Vec3& normal : normals(mesh)) EXPECT_GT(normal[2], 0.0);  // as the sheet
  for (const PointConstraint& constraint : mesh.constraints)
    EXPECT_NE(constraint.role, PointRole::Free);  // every node on the boundary
}

TEST(NarrowSheet, ARowAcrossASheetCurvedAcrossIsRefusedWhereItsChordsCutTheArea) {
  // A panel 40 mm long and 10 mm wide bent across round a cylinder of radius 12.5, meshed at
  // 9 mm: a chord straight across lies 0.99 mm from the arc, within the 1.125 mm tolerance, but
  // is 2.7 % shorter; with the sagitta limit no row is made of such chords.
  double panelArea = 0.0;
  const FeModel model = curvedPanel(panelArea);
  const QuadMesh chords = meshStrip(model, 1, 9.0, 1.125);
  EXPECT_LT(area(chords), 0.99 * panelArea);
  try {
    const QuadMesh rows = meshStrip(model, 1, 9.0, 1.125, 0.0, {}, 0.0433);
    EXPECT_GT(area(rows), 0.995 * panelArea);
  } catch (const extract::NarrowSheetRefusal&) {
  }
}

TEST(NarrowSheet, AStripCurvedAcrossIsNoGridWhereItsQuadsCutTheArea) {
  // The panel of the test above round a radius of 10, between plates at its ends, meshed at 5 mm
  // with the seams' nodes 5 mm apart: two pieces across its ends, so a grid would be two quads
  // across, each a chord across 0.5 rad of arc, within the tolerance but 0.8 % short of the
  // panel's area. With the sagitta share, the mesh keeps the area within half the limit, or there
  // is none.
  double panelArea = 0.0;
  const FeModel model = curvedPanel(panelArea, 10.0, true);
  try {
    const QuadMesh mesh = meshStrip(model, 1, 5.0, 1.125, 5.0, {}, kChordSagittaShare);
    EXPECT_GT(area(mesh), (1.0 - 0.5 * kAreaTolerance) * panelArea);
  } catch (const extract::NarrowSheetRefusal&) {
  }
}

TEST(NarrowSheet, AStripBentAlongItsMiddleIsAGridWhoseEdgesCrossTheCrease) {
  // 12 x 3 mm in 0.5 mm elements, bent by 16 degrees along y = 1.5, between plates at its ends
  // (parts 2 and 3, whose seams get nodes 1 mm apart), meshed at 1 mm: a grid of 12 x 3 quads,
  // its middle row across the crease. Each edge across the crease lies 7 % of its length from
  // it, over the sagitta share, but only that row loses area (1 - cos 8 degrees, 1 % of a third
  // of the strip): the grid keeps the strip's area within half the area limit.
  FeModel model = strip(24, 6, 0.5, 0.5);
  for (int j = 0; j <= 6; ++j) {
    test::addNode(model, 1000 + j, -0.5, 0.5 * j);
    test::addNode(model, 2000 + j, 12.5, 0.5 * j);
  }
  for (int j = 0; j < 6; ++j) {
    test::addShell(model, 1000 + j, 2, {1000 + j, 1 + 25 * j, 26 + 25 * j, 1001 + j});
    test::addShell(model, 2000 + j, 3, {25 + 25 * j, 2000 + j, 2001 + j, 50 + 25 * j});
  }
  const double bend = 16.0 * M_PI / 180.0;
  for (Node& node : model.nodes)
    if (node.xyz[1] > 1.5) {
      const double away = node.xyz[1] - 1.5;
      node.xyz[1] = 1.5 + away * std::cos(bend);
      node.xyz[2] = away * std::sin(bend);
    }
  const QuadMesh mesh = meshStrip(model, 1, 1.0, 0.1, 0.0, {}, kChordSagittaShare);
  EXPECT_EQ(mesh.faces.size(), 36u);
  EXPECT_EQ(triangleCount(mesh), 0u);
  EXPECT_GT(area(mesh), (1.0 - 0.5 * kAreaTolerance) * 36.0);
}

/// A tab (part 1, a triangle with corners (0, 0), (0.515, 0.724) and (0, 1.204), its side x = 0 a
/// seam with a plate, part 2) meshed from its boundary at spacing 0.92, its seam cut in two pieces
/// shrinking toward its 35-degree corner at the origin (ratio 1.29: the inner node 0.933 from
/// it), with `followShortPieces` as given; true when a node of the mesh faces that inner node on
/// the tab's free side from the origin, 0.13 from its far corner (closer than 0.4 spacings).
bool tabHasNodeFacingTheSeam(bool followShortPieces) {
  FeModel model;
  test::addNode(model, 1, 0.0, 0.0);
  test::addNode(model, 2, 0.515, 0.724);
  test::addNode(model, 3, 0.0, 1.204);
  test::addNode(model, 4, -1.0, 0.0);
  test::addNode(model, 5, -1.0, 1.204);
  test::addShell(model, 1, 1, {1, 2, 3});
  test::addShell(model, 2, 2, {4, 1, 3, 5});
  const std::vector<Sheet> sheets = buildSheets(model, 1);
  EXPECT_EQ(sheets.size(), 1u);
  const QuadMesh surface = pipeline::sheetSurface(sheets.front());
  const ReferenceSurface reference(surface);
  VolumeCurve seam;
  seam.points = {{0.0, 0.0, 0.0}, {0.0, 1.204, 0.0}};
  seam.nodeCount = 2;
  seam.grading = {{{0.0, 0.0, 0.0}, 1.29}};
  const extract::JunctionNodes junctions({seam}, 0.92, 0.184);
  extract::NarrowSheetSettings settings;
  settings.spacing = 0.92;
  settings.tolerance = 0.1;
  settings.maxChord = 2.76;
  settings.followShortPieces = followShortPieces;
  const QuadMesh mesh =
      extract::meshNarrowSheet(sheets.front(), surface, reference, junctions, settings);
  // The inner node (pieces 1 and 0.29 of 1.204 / 1.29) and its closest point on the free side
  // from the origin to (0.515, 0.724).
  const double t = 1.204 / 1.29 * 0.724 / (0.515 * 0.515 + 0.724 * 0.724);
  const geom::Vec3 facing{0.515 * t, 0.724 * t, 0.0};
  return std::any_of(mesh.points.begin(), mesh.points.end(),
                     [&](const geom::Vec3& p) { return geom::distance(p, facing) < 1e-6; });
}

TEST(NarrowSheet, FreeSidesFollowTheShortPiecesOfAWedgeAcrossWhereAsked) {
  // The seam's inner node leaves a piece of 0.27 to its far corner (the wedge's rows grow toward
  // it); the node facing it across the tab lies 0.13 from the tab's far corner. At 0.4 spacings
  // from the corners it is left out, and the piece between becomes a triangle of 21 degrees;
  // following the short pieces across, it is placed, for a quad and a triangle there.
  EXPECT_FALSE(tabHasNodeFacingTheSeam(false));
  EXPECT_TRUE(tabHasNodeFacingTheSeam(true));
}

TEST(SheetWidth, AStripIsAsWideAsItsRowsAndACompactSheetAsItsShorterSide) {
  // A strip 40 x 2: 2 x area / boundary 1.9, its rectangle's shorter side 2. A square 4 x 4: 2
  // and 4. A triangle tab 0.52 high on a base of 1.2: 0.22 and 0.28, whose rows (aspect limit x
  // width / 1.5) then keep its base one piece, as the tab's one element has it.
  const Sheet strip40 = buildSheets(strip(20, 1, 2.0, 2.0), 1).front();
  EXPECT_NEAR(pipeline::sheetWidth(strip40), 160.0 / 84.0, 1e-9);
  EXPECT_NEAR(pipeline::stripWidth(strip40), 2.0, 1e-9);
  const Sheet square = buildSheets(strip(2, 2, 2.0, 2.0), 1).front();
  EXPECT_NEAR(pipeline::sheetWidth(square), 2.0, 1e-9);
  EXPECT_NEAR(pipeline::stripWidth(square), 4.0, 1e-9);
  FeModel tab;
  test::addNode(tab, 1, 0.0, 0.0);
  test::addNode(tab, 2, 0.515, 0.724);
  test::addNode(tab, 3, 0.0, 1.204);
  test::addShell(tab, 1, 1, {1, 2, 3});
  const Sheet triangle = buildSheets(tab, 1).front();
  EXPECT_LT(pipeline::sheetWidth(triangle), 0.23);
  EXPECT_GT(pipeline::rowLength(triangle, RemeshSettings{}), 1.204 / 1.5);
}

TEST(NarrowSheet, ATaperedEndStillGetsQuadsWhereTheNodesFace) {
  // A trapezoid strip: the ladder's rungs run straight across where the nodes face each other.
  const QuadMesh mesh = meshStrip(taperedStrip(3.0, 2.0, 0.9), 1, 4.0);
  EXPECT_LE(triangleCount(mesh), 1u);
  for (const ElementQuality& quality : elementQualities(mesh)) EXPECT_GT(quality.minAngleDeg, 30.0);
}

TEST(NarrowSheet, AJunctionThroughTheMiddleCutsTheSheetAndBothSidesShareItsNodes) {
  // Two rows, the lower of part 1 and the upper of part 2, over a third part 3 whose edge meets
  // the middle line of a part-1 strip two rows wide: the strip is cut there.
  FeModel model = strip(12, 2, 2.0, 1.5);
  // Part 3: a web standing on the middle line y = 1.5.
  const Id base = 1000;
  for (int i = 0; i <= 12; ++i) model.nodes.push_back({base + Id(i), {2.0 * i, 1.5, 3.0}});
  for (int i = 0; i < 12; ++i)
    model.shells.push_back(
        {Id(500 + i), 3, {Id(i + 14), Id(i + 15), base + Id(i + 1), base + Id(i)}, 4});
  model.partOrAdd(3);
  // buildSheets would cut the strip along the seam itself (sheets.h, "Seams inside a sheet");
  // without cuts the strip is one sheet with the junction curve inside, as a fin of its own
  // part would leave it.
  SheetSettings uncut;
  uncut.sheetCuts = std::make_shared<const std::vector<std::array<Id, 2>>>();
  EXPECT_EQ(buildSheets(model, 1).size(), 2u);
  const std::vector<Sheet> sheets = buildSheets(model, 1, uncut);
  ASSERT_EQ(sheets.size(), 1u);
  const std::vector<extract::SheetPatch> patches = extract::sheetPatches(sheets.front());
  ASSERT_EQ(patches.size(), 2u);
  const QuadMesh mesh = meshStrip(model, 1, 4.0, 0.1, 4.0, uncut);
  EXPECT_EQ(triangleCount(mesh), 0u);
  EXPECT_NEAR(area(mesh), 24.0 * 3.0, 1e-9);
  // The middle line's nodes are shared: one node per junction node, each used by faces above
  // and below.
  std::size_t middle = 0;
  for (std::size_t p = 0; p < mesh.points.size(); ++p) {
    if (std::abs(mesh.points[p][1] - 1.5) > 1e-12) continue;
    ++middle;
    EXPECT_EQ(mesh.constraints[p].role, PointRole::Junction);
  }
  EXPECT_EQ(middle, 7u);  // 24 mm at 4 mm: 6 pieces
}

TEST(NarrowSheet, AWebOnARungOfTheStripCutsItThereAndKeepsItsJunctionNodes) {
  // A strip 24 x 1.5 mm in 12 x 1 elements with a web (part 3) standing on its rung x = 12: a
  // junction curve of one edge from side to side, with nodes at 0.5 and 1.0 mm at a junction
  // spacing of 0.5 mm. The web's mesh has those nodes, so the strip's must too, or the web would
  // hang on the strip's edges: the strip is cut at the rung (sheet_patches.h), both rows keep
  // them, fixed for the optimisation.
  FeModel model = strip(12, 1, 2.0, 1.5);
  const Id top = 1000;
  for (int j = 0; j <= 1; ++j) model.nodes.push_back({top + Id(j), {12.0, 1.5 * j, 3.0}});
  model.shells.push_back({500, 3, {7, 20, top + 1, top}, 4});
  model.partOrAdd(3);
  SheetSettings uncut;  // one sheet with the rung inside (not cut along the seam, sheets.h)
  uncut.sheetCuts = std::make_shared<const std::vector<std::array<Id, 2>>>();
  for (const double spacing : {4.0, 0.5}) {
    const QuadMesh mesh = meshStrip(model, 1, spacing, 0.1, 0.5, uncut);
    std::size_t onNodes = 0;
    for (std::size_t p = 0; p < mesh.points.size(); ++p) {
      const auto& q = mesh.points[p];
      if (std::abs(q[0] - 12.0) < 1e-9 && q[1] > 0.25 && q[1] < 1.25) {
        ++onNodes;
        EXPECT_NE(mesh.constraints[p].role, PointRole::Free) << spacing << " " << q[1];
      }
    }
    EXPECT_EQ(onNodes, 2u) << spacing;
    EXPECT_NEAR(area(mesh), 24.0 * 1.5, 1e-9) << spacing;
  }
}

TEST(NarrowSheet, AFoldAlongTheStripThatNoChordFollowsIsACutBetweenTwoRows) {
  // 4 mm wide, folded by 90 degrees along its middle line (an angle section): a chord across
  // would cut the fold's corner by 1.41 mm, more than the tolerance; the fold is a feature line,
  // so the strip is cut there into two flat rows sharing the fold's nodes.
  const FeModel model = strip(10, 2, 4.0, 2.0, 1000, 2.0);
  const QuadMesh mesh = meshStrip(model, 1, 4.0, 0.5);
  EXPECT_EQ(triangleCount(mesh), 0u);
  EXPECT_EQ(mesh.faces.size(), 20u);  // 40 mm at 4 mm, two rows
  std::size_t onFold = 0;
  for (const auto& p : mesh.points)
    onFold += std::abs(p[1] - 2.0) < 1e-12 && std::abs(p[2]) < 1e-12;
  EXPECT_EQ(onFold, 11u);
  EXPECT_NEAR(area(mesh), 40.0 * 4.0, 1e-9);
}

TEST(NarrowSheet, ARoundTubeGetsRowsSweptFromOneEndToTheOther) {
  // A tube of radius 3 (16 facets round) and length 40, open at both ends: a ring whose chords
  // across would pass through its inside; rows of quads run from one end loop to the other.
  FeModel model;
  const int round = 16, along = 10;
  auto id = [&](int i, int j) { return Id(1 + j * round + i % round); };
  for (int j = 0; j <= along; ++j)
    for (int i = 0; i < round; ++i) {
      const double t = 2.0 * M_PI * i / round;
      model.nodes.push_back({id(i, j), {4.0 * j, 3.0 * std::cos(t), 3.0 * std::sin(t)}});
    }
  Id shell = 1;
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < round; ++i)
      model.shells.push_back(
          {shell++, 1, {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}});
  model.partOrAdd(1);
  const QuadMesh mesh = meshStrip(model, 1, 4.0, 0.3);
  EXPECT_EQ(triangleCount(mesh), 0u);
  // Round: 10 nodes (5 pieces of 4 mm would leave the circle by 0.57 mm, over the tolerance);
  // along: 40 mm at 4 mm, 10 rows.
  EXPECT_EQ(mesh.faces.size(), 10u * 10u);
}

TEST(NarrowSheet, ABoxClosedAtOneEndIsCutIntoWallsAndCap) {
  // A 4 x 6 box section 40 long, closed at x = 0 (a cup, one boundary loop): no row of faces
  // across it stays on it, but cut at its four edges and the cap's outline each face is a grid.
  FeModel model;
  std::map<std::array<long, 3>, Id> ids;
  Id next = 1, shell = 1;
  auto node = [&](long x, long y, long z) {
    const auto [it, added] = ids.emplace(std::array<long, 3>{x, y, z}, next);
    if (added) model.nodes.push_back({next++, {double(x), double(y), double(z)}});
    return it->second;
  };
  const std::array<std::array<long, 2>, 5> ring{{{0, 0}, {4, 0}, {4, 6}, {0, 6}, {0, 0}}};
  for (long x = 0; x < 40; x += 2)
    for (std::size_t s = 0; s < 4; ++s) {
      const auto [y0, z0] = ring[s];
      const auto [y1, z1] = ring[s + 1];
      const long steps = std::max(std::abs(y1 - y0), std::abs(z1 - z0)) / 2;
      for (long k = 0; k < steps; ++k) {
        const long ya = y0 + (y1 - y0) * k / steps, za = z0 + (z1 - z0) * k / steps;
        const long yb = y0 + (y1 - y0) * (k + 1) / steps, zb = z0 + (z1 - z0) * (k + 1) / steps;
        model.shells.push_back(
            {shell++,
             1,
             {node(x, ya, za), node(x, yb, zb), node(x + 2, yb, zb), node(x + 2, ya, za)}});
      }
    }
  for (long y = 0; y < 4; y += 2)
    for (long z = 0; z < 6; z += 2)
      model.shells.push_back(
          {shell++,
           1,
           {node(0, y, z), node(0, y, z + 2), node(0, y + 2, z + 2), node(0, y + 2, z)}});
  model.partOrAdd(1);
  const QuadMesh mesh = meshStrip(model, 1, 4.0, 0.2);
  EXPECT_EQ(triangleCount(mesh), 0u);
  EXPECT_NEAR(area(mesh), 40.0 * 20.0 + 4.0 * 6.0, 1e-9);
}

TEST(NarrowSheet, ARingGetsOneRowRoundItsHole) {
  // A square ring 1 mm wide round a 2 x 2 hole (4 x 4 elements of 1 mm without the middle four),
  // meshed at 1 mm: quads only, the hole kept, all nodes on the two loops.
  FeModel model = strip(4, 4, 1.0, 1.0);
  model.shells.erase(model.shells.begin() + 9, model.shells.begin() + 11);  // row 2, i = 1, 2
  model.shells.erase(model.shells.begin() + 5, model.shells.begin() + 7);   // row 1, i = 1, 2
  const std::vector<Sheet> sheets = buildSheets(model, 1);
  ASSERT_EQ(sheets.size(), 1u);
  const std::vector<extract::SheetPatch> patches = extract::sheetPatches(sheets.front());
  ASSERT_EQ(patches.size(), 1u);
  EXPECT_EQ(patches.front().loops.size(), 2u);
  const QuadMesh mesh = meshStrip(model, 1, 1.0, 0.05);
  EXPECT_NEAR(area(mesh), 12.0, 1e-9);
  EXPECT_EQ(triangleCount(mesh), 0u);
  EXPECT_EQ(topologyCounts(mesh).boundaryLoops, 2u);
  for (const PointConstraint& constraint : mesh.constraints)
    EXPECT_NE(constraint.role, PointRole::Free);
}

TEST(NarrowSheet, AWebAcrossARingIsItsRungWithTheWebsNodes) {
  // The square ring of ARingGetsOneRowRoundItsHole with a web (part 3) standing on its edge
  // x = 2 from the outside (node 3 at y = 0) to the hole (node 8 at y = 1): one cut through the
  // ring that parts nothing. The ring is meshed as before, with that edge as the bridge between
  // its loops: at a junction spacing of 0.5 its node at y = 0.5 is a fixed node of the mesh, on
  // an edge to each end of the rung, so that the web does not hang on the ring's faces.
  FeModel model = strip(4, 4, 1.0, 1.0);
  model.shells.erase(model.shells.begin() + 9, model.shells.begin() + 11);
  model.shells.erase(model.shells.begin() + 5, model.shells.begin() + 7);
  const Id top = 1000;
  model.nodes.push_back({top, {2.0, 0.0, 2.0}});
  model.nodes.push_back({top + 1, {2.0, 1.0, 2.0}});
  model.shells.push_back({500, 3, {3, 8, top + 1, top}, 4});
  model.partOrAdd(3);
  SheetSettings uncut;  // the web's line stays inside the ring's one sheet
  uncut.sheetCuts = std::make_shared<const std::vector<std::array<Id, 2>>>();
  const std::vector<Sheet> sheets = buildSheets(model, 1, uncut);
  ASSERT_EQ(sheets.size(), 1u);
  const std::vector<extract::SheetPatch> patches = extract::sheetPatches(sheets.front());
  ASSERT_EQ(patches.size(), 1u);
  ASSERT_EQ(patches.front().loops.size(), 2u);
  EXPECT_EQ(patches.front().rung.size(), 2u);
  const QuadMesh mesh = meshStrip(model, 1, 1.0, 0.05, 0.5, uncut);
  EXPECT_NEAR(area(mesh), 12.0, 1e-9);
  EXPECT_EQ(topologyCounts(mesh).boundaryLoops, 2u);
  std::size_t middle = mesh.points.size();
  for (std::size_t p = 0; p < mesh.points.size(); ++p)
    if (geom::distance(mesh.points[p], {2.0, 0.5, 0.0}) < 1e-9) middle = p;
  ASSERT_LT(middle, mesh.points.size());
  EXPECT_NE(mesh.constraints[middle].role, PointRole::Free);
  std::set<geom::Vec3> joined;  // the points sharing an edge with the rung's middle node
  for (const auto& face : mesh.faces) {
    const int n = cornerCount(face);
    for (int c = 0; c < n; ++c)
      if (face[std::size_t(c)] == middle) {
        joined.insert(mesh.points[face[std::size_t((c + 1) % n)]]);
        joined.insert(mesh.points[face[std::size_t((c + n - 1) % n)]]);
      }
  }
  EXPECT_EQ(joined.count({2.0, 0.0, 0.0}), 1u);
  EXPECT_EQ(joined.count({2.0, 1.0, 0.0}), 1u);
}

TEST(NarrowSheet, ARoundRingsLoopsGetNodesCloseEnoughToKeepItsArea) {
  // A flat ring between radii 6 and 8.6 in 24 quads round, meshed at 9 (the edge of a frame at a
  // deck's size): nodes about 9 apart on its loops, plus the loop points farther than the
  // tolerance from their chords, cut 11 % of its area off. With the sagitta limit every loop
  // point lies within 4.33 % of its chord's length, and less than 1 % of the area is lost.
  FeModel model;
  const double pi = std::acos(-1.0);
  for (int i = 0; i < 24; ++i)
    for (int r = 0; r < 2; ++r) {
      const double radius = r == 0 ? 6.0 : 8.6, angle = 2.0 * pi * i / 24.0;
      model.nodes.push_back(
          {Id(1 + 2 * i + r), {radius * std::cos(angle), radius * std::sin(angle), 0.0}});
    }
  for (int i = 0; i < 24; ++i) {
    const int j = (i + 1) % 24;
    model.shells.push_back(
        {Id(i + 1), 1, {Id(1 + 2 * i), Id(1 + 2 * j), Id(2 + 2 * j), Id(2 + 2 * i)}});
  }
  model.partOrAdd(1);
  double ringArea = 0.0;
  for (const double radius : {8.6, -6.0})
    ringArea += (radius > 0 ? 1.0 : -1.0) * 12.0 * radius * radius * std::sin(2.0 * pi / 24.0);
  EXPECT_LT(area(meshStrip(model, 1, 9.0, 1.125)), 0.99 * ringArea);
  EXPECT_GT(area(meshStrip(model, 1, 9.0, 1.125, 0.0, {}, 0.0433)), 0.99 * ringArea);
}

/// One triangular shell with the given corners in the plane z = 0.
FeModel triangle(const std::array<double, 2>& a, const std::array<double, 2>& b,
                 const std::array<double, 2>& c) {
  FeModel model;
  model.nodes = {{1, {a[0], a[1], 0.0}}, {2, {b[0], b[1], 0.0}}, {3, {c[0], c[1], 0.0}}};
  model.shells.push_back({1, 1, {1, 2, 3, 0}, 3});
  model.partOrAdd(1);
  return model;
}

TEST(NarrowSheet, AThreeSidedPatchGetsThreeGridsRoundItsCentre) {
  // An equilateral triangle of side 12 at spacing 3: four pieces a side, split in the middle and
  // joined to the centre, three grids of 2 x 2 quads with angles of 60 to 120 degrees (a row
  // across it fans out from its corners).
  const QuadMesh mesh =
      meshStrip(triangle({0.0, 0.0}, {12.0, 0.0}, {6.0, 6.0 * std::sqrt(3.0)}), 1, 3.0);
  EXPECT_EQ(mesh.faces.size(), 12u);
  EXPECT_EQ(triangleCount(mesh), 0u);
  EXPECT_NEAR(area(mesh), 36.0 * std::sqrt(3.0), 1e-9);
  for (const ElementQuality& quality : elementQualities(mesh)) {
    EXPECT_GT(quality.minAngleDeg, 59.9);
    EXPECT_LT(quality.maxAngleDeg, 120.1);
  }
}

TEST(MidpointPatch, ASixSidedPatchGetsAGridRoundEachCorner) {
  // A regular hexagon of side 6 with two pieces a side: each side split in its middle and joined
  // to the centre, one quad round each corner (a kite of 60 to 120 degrees).
  const double pi = std::acos(-1.0);
  QuadMesh surface;
  surface.points.push_back({0.0, 0.0, 0.0});
  std::vector<extract::LoopNode> nodes;
  for (int k = 0; k < 12; ++k) {
    const std::array<double, 3> corner{6.0 * std::cos((k / 2) * pi / 3.0),
                                       6.0 * std::sin((k / 2) * pi / 3.0), 0.0};
    const std::array<double, 3> next{6.0 * std::cos((k / 2 + 1) * pi / 3.0),
                                     6.0 * std::sin((k / 2 + 1) * pi / 3.0), 0.0};
    const double t = k % 2 == 0 ? 0.0 : 0.5;
    nodes.push_back(
        {3.0 * k,
         {corner[0] + t * (next[0] - corner[0]), corner[1] + t * (next[1] - corner[1]), 0.0},
         PointRole::Boundary,
         false});
    if (k % 2 == 0) {
      surface.points.push_back(corner);
      surface.faces.push_back(
          {0, std::uint32_t(k / 2 + 1), std::uint32_t((k / 2 + 1) % 6 + 1), kNoCorner});
    }
  }
  const ReferenceSurface reference(surface);
  const auto up = [](const std::array<double, 3>&) { return std::array<double, 3>{0, 0, 1}; };
  const auto grids = extract::midpointPatch(nodes, reference, up, 0.1, 0.0);
  ASSERT_TRUE(grids.has_value());
  EXPECT_EQ(grids->quads.size(), 6u);
  EXPECT_EQ(grids->inner.size(), 1u);  // the centre
  QuadMesh mesh;
  for (const extract::LoopNode& node : grids->loop) mesh.points.push_back(node.point);
  for (const auto& p : grids->inner) mesh.points.push_back(p);
  for (const auto& q : grids->quads) mesh.faces.push_back({q[0], q[1], q[2], q[3]});
  EXPECT_NEAR(area(mesh), 54.0 * std::sqrt(3.0), 1e-9);
  for (const ElementQuality& quality : elementQualities(mesh)) {
    EXPECT_NEAR(quality.minAngleDeg, 60.0, 1e-6);
    EXPECT_NEAR(quality.maxAngleDeg, 120.0, 1e-6);
  }
}

TEST(MappedPatch, AnLShapedPatchIsTwoGridsEitherSideOfACutFromItsReflexCorner) {
  // An L of arms 2 wide (6 x 6 outside) with nodes 1 apart: no grid (six corners) and no midpoint
  // split (its sides' counts do not pair up round it); cut from its inner corner (2, 2) to (0, 2)
  // with a node at (1, 2), it is a 2 x 4 grid above and a 6 x 2 grid below.
  QuadMesh surface;
  surface.points = {{0, 0, 0}, {6, 0, 0}, {6, 2, 0}, {2, 2, 0}, {2, 6, 0}, {0, 6, 0}, {0, 2, 0}};
  surface.faces = {{0, 1, 2, 6}, {6, 3, 4, 5}};
  const std::vector<std::array<double, 3>> corners{{0, 0, 0}, {6, 0, 0}, {6, 2, 0},
                                                   {2, 2, 0}, {2, 6, 0}, {0, 6, 0}};
  std::vector<extract::LoopNode> nodes;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const auto& a = corners[k];
    const auto& b = corners[(k + 1) % corners.size()];
    const int pieces = int(std::lround(geom::distance(a, b)));
    for (int j = 0; j < pieces; ++j) {
      const double t = double(j) / pieces;
      nodes.push_back({double(nodes.size()),
                       {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0},
                       PointRole::Junction,
                       true});
    }
  }
  std::vector<std::array<double, 3>> points;
  for (const extract::LoopNode& node : nodes) points.push_back(node.point);
  EXPECT_EQ(extract::reflexCorners(points), std::vector<std::size_t>{12});  // (2, 2)
  const ReferenceSurface reference(surface);
  const auto up = [](const std::array<double, 3>&) { return std::array<double, 3>{0, 0, 1}; };
  const auto grids = extract::lShapedPatch(nodes, reference, up, 0.1, kChordSagittaShare);
  ASSERT_TRUE(grids.has_value());
  EXPECT_EQ(grids->quads.size(), 20u);
  // The cut's node, then the grids' inner nodes: 3 above, 5 below.
  ASSERT_EQ(grids->inner.size(), 9u);
  EXPECT_NEAR(geom::distance(grids->inner[0], {1.0, 2.0, 0.0}), 0.0, 1e-12);
  QuadMesh mesh;
  for (const extract::LoopNode& node : grids->loop) mesh.points.push_back(node.point);
  for (const auto& p : grids->inner) mesh.points.push_back(p);
  for (const auto& q : grids->quads) mesh.faces.push_back({q[0], q[1], q[2], q[3]});
  EXPECT_NEAR(area(mesh), 20.0, 1e-9);
  for (const geom::Vec3& normal : normals(mesh)) EXPECT_GT(normal[2], 0.0);
  for (const ElementQuality& quality : elementQualities(mesh))
    EXPECT_NEAR(quality.minAngleDeg, 90.0, 1e-6);
  EXPECT_FALSE(extract::midpointPatch(nodes, reference, up, 0.1, 0.0).has_value());
}

TEST(MidpointPatch, FourSidesWithDifferentCountsOppositeHaveNoSplit) {
  // A square with 2, 2, 2 and 4 pieces: every second side's splits must add up to the side
  // between them, which 2 and 4 opposite cannot.
  QuadMesh surface;
  surface.points = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  surface.faces = {{0, 1, 2, 3}};
  std::vector<extract::LoopNode> nodes;
  const std::vector<std::array<double, 3>> loop{{0, 0, 0}, {2, 0, 0}, {4, 0, 0}, {4, 2, 0},
                                                {4, 4, 0}, {2, 4, 0}, {0, 4, 0}, {0, 3, 0},
                                                {0, 2, 0}, {0, 1, 0}};
  for (std::size_t k = 0; k < loop.size(); ++k)
    nodes.push_back({double(k), loop[k], PointRole::Boundary, false});
  const ReferenceSurface reference(surface);
  const auto up = [](const std::array<double, 3>&) { return std::array<double, 3>{0, 0, 1}; };
  EXPECT_FALSE(extract::midpointPatch(nodes, reference, up, 0.1, 0.0).has_value());
}

TEST(NarrowSheet, ASheetWithTwoHolesIsRefused) {
  FeModel model = strip(5, 3, 1.0, 1.0);
  model.shells.erase(model.shells.begin() + 8);  // row 1, i = 3
  model.shells.erase(model.shells.begin() + 6);  // row 1, i = 1
  const std::vector<Sheet> sheets = buildSheets(model, 1);
  ASSERT_EQ(sheets.size(), 1u);
  EXPECT_THROW(extract::sheetPatches(sheets.front()), extract::NarrowSheetRefusal);
}

TEST(PolygonQuads, AnLShapedPolygonIsCoveredByQuads) {
  // An L of width 1: (0,0) (3,0) (3,1) (1,1) (1,3) (0,3), with points every 1 along its sides.
  const std::vector<std::array<double, 3>> corners{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0},
                                                   {3, 1, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0},
                                                   {1, 3, 0}, {0, 3, 0}, {0, 2, 0}, {0, 1, 0}};
  const std::vector<std::array<double, 3>> up(corners.size(), {0.0, 0.0, 1.0});
  const auto faces =
      extract::polygonQuads(corners, up, 3.0, [](std::size_t, std::size_t) { return true; }, {});
  ASSERT_EQ(faces.size(), 5u);
  QuadMesh mesh;
  mesh.points = corners;
  for (const auto& face : faces) {
    EXPECT_NE(face[3], UINT32_MAX);
    mesh.faces.push_back({face[0], face[1], face[2], face[3]});
  }
  EXPECT_NEAR(area(mesh), 5.0, 1e-12);
  // Facing down, no triangle agrees with the normals: no mesh.
  const std::vector<std::array<double, 3>> down(corners.size(), {0.0, 0.0, -1.0});
  EXPECT_TRUE(
      extract::polygonQuads(corners, down, 3.0, [](std::size_t, std::size_t) { return true; }, {})
          .empty());
}

/// Of the faces of polygonQuads over `corners` (all chords allowed, normals +z): those failing
/// one of the default element criteria other than the minimum length, triangles and quads.
std::array<std::size_t, 3> polygonFaceCounts(const std::vector<std::array<double, 3>>& corners) {
  const std::vector<std::array<double, 3>> up(corners.size(), {0.0, 0.0, 1.0});
  const auto faces = extract::polygonQuads(
      corners, up, 10.0, [](std::size_t, std::size_t) { return true; }, QualitySettings{});
  EXPECT_FALSE(faces.empty());
  QualitySettings settings;
  settings.targetSize = 1.0;
  const std::uint32_t lengthBit = 1u << static_cast<int>(Criterion::MinLength);
  std::size_t failing = 0, triangles = 0, quads = 0;
  for (const auto& face : faces) {
    const int count = face[3] == UINT32_MAX ? 3 : 4;
    std::array<std::array<double, 3>, 4> p{corners[face[0]], corners[face[1]], corners[face[2]],
                                           corners[face[count == 3 ? 2 : 3]]};
    const std::uint32_t fails = elementFailures(elementQuality(p, count), count, settings);
    failing += (fails & ~lengthBit) != 0;
    triangles += count == 3;
    quads += count == 4;
  }
  return {failing, triangles, quads};
}

TEST(PolygonQuads, ARowAcrossAStripThatTurnsTwoToOneHasNoFailingFace) {
  // A strip 1.5 wide: its lower side has nodes 2 apart; its upper side 1 apart over the left half
  // (a seam with a finer neighbour there), 2 apart over the right half. A quad over one lower and
  // one upper piece of the left half is a 2:1 trapezoid (Jacobian ratio 0.5 at the corners, under
  // 0.6): the left half takes triangles that pass, the right half rectangles.
  std::vector<std::array<double, 3>> corners;
  for (int i = 0; i <= 8; i += 2) corners.push_back({double(i), 0.0, 0.0});
  for (int i = 8; i >= 4; i -= 2) corners.push_back({double(i), 1.5, 0.0});
  for (int i = 3; i >= 0; --i) corners.push_back({double(i), 1.5, 0.0});
  const auto [failing, triangles, quads] = polygonFaceCounts(corners);
  EXPECT_EQ(failing, 0u);
  EXPECT_EQ(quads, 2u);
  EXPECT_EQ(triangles, 6u);
}

TEST(NarrowSheet, AFourSidedPatchTwoElementsWideGetsAGridWithNodesInside) {
  // 12 x 8 mm in 3 x 2 elements, meshed at 4 mm: a 3 x 2 grid, its two inner nodes on the plate.
  const QuadMesh mesh = meshStrip(strip(3, 2, 4.0, 4.0), 1, 4.0);
  EXPECT_EQ(mesh.faces.size(), 6u);
  EXPECT_EQ(triangleCount(mesh), 0u);
  std::size_t inner = 0;
  for (std::size_t p = 0; p < mesh.points.size(); ++p) {
    if (mesh.constraints[p].role != PointRole::Free) continue;
    ++inner;
    EXPECT_NEAR(mesh.points[p][1], 4.0, 1e-9);
    EXPECT_NEAR(mesh.points[p][2], 0.0, 1e-12);
  }
  EXPECT_EQ(inner, 2u);
  for (const ElementQuality& quality : elementQualities(mesh))
    EXPECT_NEAR(quality.minAngleDeg, 90.0, 1e-6);
}

TEST(NarrowSheet, AFreeSideIsSpacedAgainToMatchTheSideAcross) {
  // A strip 5 mm wide whose long sides differ (40 and 34 mm): at 4 mm one would get 10 pieces, the
  // other 8 or 9; the grid spaces the second again with 10 so that every element is a quad.
  const QuadMesh mesh = meshStrip(taperedStrip(5.0, 3.0, 0.85), 1, 4.0);
  EXPECT_EQ(triangleCount(mesh), 0u);
  EXPECT_EQ(mesh.faces.size(), 10u);
}

TEST(NarrowSheet, AJunctionSideIsNeverSpacedAgainEvenWithoutNodesInside) {
  // Part 1 (40 x 2.5) meets part 2 along y = 2.5, whose junction nodes are 40 apart: only its
  // ends. The free side across gets 10 pieces at 4 mm; matching the counts must not put nodes on
  // the junction side (part 2 has none there), so the free side is the one spaced again.
  const FeModel model = strip(10, 2, 4.0, 2.5, 1);
  const QuadMesh mesh = meshStrip(model, 1, 4.0, 0.1, 40.0);
  std::size_t onJunction = 0;
  for (const auto& p : mesh.points) onJunction += std::abs(p[1] - 2.5) < 1e-12;
  EXPECT_EQ(onJunction, 2u);
}

TEST(NarrowSheet, ANarrowSheetAtATJunctionSharesItsNodesWithTheSheetsMeshedThroughVolumes) {
  // One part: a strip 2 mm wide (meshed from its boundary) along a plate 18 mm wide and a wall
  // 10 mm high (both through volumes), all three meeting at the line y = 2, z = 0.
  FeModel model;
  Id next = 1;
  std::map<std::array<long, 3>, Id> ids;
  auto node = [&](long x, long y, long z) {
    const auto [it, added] = ids.emplace(std::array<long, 3>{x, y, z}, next);
    if (added) model.nodes.push_back({next++, {double(x), double(y), double(z)}});
    return it->second;
  };
  Id shell = 1;
  for (long x = 0; x < 40; x += 2) {
    for (long y = 0; y < 20; y += 2)
      model.shells.push_back(
          {shell++,
           1,
           {node(x, y, 0), node(x + 2, y, 0), node(x + 2, y + 2, 0), node(x, y + 2, 0)}});
    for (long z = 0; z < 10; z += 2)
      model.shells.push_back(
          {shell++,
           1,
           {node(x, 2, z), node(x + 2, 2, z), node(x + 2, 2, z + 2), node(x, 2, z + 2)}});
  }
  model.partOrAdd(1);
  RemeshSettings settings;
  settings.targetSize = 2.0;
  const RemeshReport report = remeshDeck(model, settings);
  ASSERT_EQ(report.parts.size(), 1u);
  const RemeshedPart& part = report.parts.front();
  EXPECT_EQ(part.acceptance.loopsAfter, part.acceptance.loopsBefore) << part.reason;
  EXPECT_EQ(part.acceptance.componentsAfter, 1u) << part.reason;
}
