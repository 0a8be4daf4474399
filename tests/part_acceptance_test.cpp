// The acceptance of a remeshed part (defects planted in a grid, each caught with its reason) and
// the fallback of remeshDeck (a part that cannot be meshed is kept, the rest of the deck written).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/half_pass.h"
#include "pipeline/remesh_part.h"
#include "support/test_support.h"
#include "support/unit_grid.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"

using namespace voxremesh;

namespace {

/// acceptPartMesh at size 1 (distance limit 0.25) with the default limits.
PartAcceptance accept(const QuadMesh& mesh, const QuadMesh& original) {
  return pipeline::acceptPartMesh(mesh, original, {}, 1.0, 1.0, QualitySettings{}, {});
}

bool says(const PartAcceptance& a, const std::string& words) {
  return a.reason.find(words) != std::string::npos;
}

/// The mesh without face f.
QuadMesh withoutFace(QuadMesh mesh, std::size_t f) {
  mesh.faces.erase(mesh.faces.begin() + static_cast<std::ptrdiff_t>(f));
  return mesh;
}

TEST(PartAcceptance, TheOriginalItselfPasses) {
  const QuadMesh grid = test::unitGrid(8);
  const PartAcceptance a = accept(grid, grid);
  EXPECT_TRUE(a.accepted) << a.reason;
  EXPECT_EQ(a.componentsBefore, 1u);
  EXPECT_EQ(a.loopsAfter, 1u);
  EXPECT_NEAR(a.distance, 0.0, 1e-12);
}

/// An 8 x 8 unit grid with a fin of 4 x 1 unit quads standing on its line y = 4 from x = 2 to 6
/// (z = 0..1); with `attached` false the fin has nodes of its own on that line between its ends
/// (where the grid has nodes too, unshared): it touches the grid at its two ends only.
QuadMesh gridWithFin(bool attached) {
  QuadMesh mesh = test::unitGrid(8);
  const auto base = CornerIndex(mesh.points.size());
  for (int i = 2; i <= 6; ++i) mesh.points.push_back({double(i), 4.0, 1.0});
  for (int i = 2; i <= 6; ++i) mesh.points.push_back({double(i), 4.0, 0.0});
  auto foot = [&](int i) {
    const bool shared = attached || i == 2 || i == 6;
    return shared ? test::gridPoint(8, i, 4) : CornerIndex(base + 5 + CornerIndex(i - 2));
  };
  for (int i = 2; i < 6; ++i)
    mesh.faces.push_back({foot(i), foot(i + 1), CornerIndex(base + CornerIndex(i - 1)),
                          CornerIndex(base + CornerIndex(i - 2))});
  mesh.constraints.assign(mesh.points.size(), {});
  return mesh;
}

TEST(PartAcceptance, AFinComeApartFromItsSheetFails) {
  // Same shapes, the same components (the fin touches its plate) and loops: only the T-junction
  // line the fin and the plate shared is gone.
  const QuadMesh original = gridWithFin(true);
  const PartAcceptance kept = accept(original, original);
  EXPECT_TRUE(kept.accepted) << kept.reason;
  EXPECT_NEAR(kept.junctionLength, 4.0, 1e-12);
  EXPECT_EQ(kept.junctionLengthLost, 0.0);
  const PartAcceptance apart = accept(gridWithFin(false), original);
  EXPECT_FALSE(apart.accepted);
  EXPECT_NEAR(apart.junctionLengthLost, 4.0, 1e-12);
  EXPECT_TRUE(says(apart, "its sheets come apart along 4 of the 4")) << apart.reason;
}

TEST(PartAcceptance, APlantedFoldFails) {
  // Point (4, 4) pulled across its diagonal neighbour (5, 5): the face between them turns over
  // while it stays in the plane (no distance, no topology change).
  QuadMesh mesh = test::unitGrid(8);
  mesh.points[test::gridPoint(8, 4, 4)] = {5.6, 5.6, 0.0};
  const PartAcceptance a = accept(mesh, test::unitGrid(8));
  EXPECT_FALSE(a.accepted);
  EXPECT_GE(a.folded, 1u);
  EXPECT_TRUE(says(a, "folded")) << a.reason;
  // A fold against the original's normal (from the sheet) counts on its own too.
  const QuadMesh grid = test::unitGrid(8);
  std::vector<std::uint8_t> flags(grid.faces.size(), 0);
  flags[10] = 1;
  const PartAcceptance b =
      pipeline::acceptPartMesh(grid, grid, flags, 1.0, 1.0, QualitySettings{}, {});
  EXPECT_EQ(b.folded, 1u);
  EXPECT_FALSE(b.accepted);
}

TEST(PartAcceptance, AQuadCornerOf180DegreesFails) {
  // Point (4, 4) on the segment from (5, 4) to (4, 3): the face (4,3) (5,3) (5,4) (4,4) gets a
  // straight corner there (CalculiX cannot estimate its normal).
  QuadMesh mesh = test::unitGrid(8);
  mesh.points[test::gridPoint(8, 4, 4)] = {4.5, 3.5, 0.0};
  const PartAcceptance a = accept(mesh, test::unitGrid(8));
  EXPECT_FALSE(a.accepted);
  EXPECT_EQ(a.folded, 0u);
  EXPECT_EQ(a.degenerateCorners, 1u);
  EXPECT_TRUE(says(a, "180 degrees")) << a.reason;
}

TEST(PartAcceptance, ALostIslandFails) {
  QuadMesh original = test::unitGrid(4);
  const QuadMesh island = test::unitGrid(4);
  const CornerIndex offset = static_cast<CornerIndex>(original.points.size());
  for (auto p : island.points) original.points.push_back({p[0] + 10.0, p[1], p[2]});
  for (auto face : island.faces) {
    for (CornerIndex& corner : face) corner += offset;
    original.faces.push_back(face);
  }
  const PartAcceptance a = accept(test::unitGrid(4), original);
  EXPECT_FALSE(a.accepted);
  EXPECT_EQ(a.componentsBefore, 2u);
  EXPECT_EQ(a.componentsAfter, 1u);
  EXPECT_TRUE(says(a, "1 connected pieces instead of 2")) << a.reason;
}

TEST(PartAcceptance, ALostHoleFails) {
  const QuadMesh grid = test::unitGrid(8);
  const QuadMesh holed = withoutFace(grid, 8 * 4 + 4);
  const PartAcceptance a = accept(grid, holed);
  EXPECT_FALSE(a.accepted);
  EXPECT_EQ(a.loopsBefore, 2u);
  EXPECT_TRUE(says(a, "1 boundary loops instead of 2")) << a.reason;
}

TEST(PartAcceptance, AnUncoveredRegionFails) {
  // The mesh covers x = 0..7 of an original reaching x = 8: measured from the original's
  // samples, 1 unit (four times the limit), though every node of the mesh lies on the original.
  QuadMesh mesh = test::unitGrid(8);
  for (auto& p : mesh.points) p[0] *= 7.0 / 8.0;
  const PartAcceptance a = accept(mesh, test::unitGrid(8));
  EXPECT_FALSE(a.accepted);
  EXPECT_NEAR(a.distance, 1.0, 1e-9);
  EXPECT_TRUE(says(a, "distance to the original 1 over its limit 0.25")) << a.reason;
  EXPECT_GT(a.failing, 0u);  // the elements at the uncovered strip fail the distance criterion
}

TEST(PartAcceptance, APartThatCannotBeMeshedIsKeptAndTheRestWritten) {
  // Part 1: a 40 x 40 plate of 4-unit quads; part 2: a Moebius strip of 24 quads beside it, which
  // has no consistent orientation and so no signed distance.
  FeModel model;
  auto node = [](int i, int j) { return Id(1 + j * 11 + i); };
  for (int j = 0; j <= 10; ++j)
    for (int i = 0; i <= 10; ++i) test::addNode(model, node(i, j), 4.0 * i, 4.0 * j, 0.0);
  Id shell = 1;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i)
      test::addShell(model, shell++, 1,
                     {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
  const int n = 24;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * 3.141592653589793 * i / n;
    for (const double s : {-10.0, 10.0})
      test::addNode(model, 500 + 2 * i + (s > 0),
                    200.0 + (50.0 + s * std::cos(t / 2)) * std::cos(t),
                    (50.0 + s * std::cos(t / 2)) * std::sin(t), s * std::sin(t / 2));
  }
  for (int i = 0; i + 1 < n; ++i)
    test::addShell(model, 900 + i, 2, {500 + 2 * i, 501 + 2 * i, 503 + 2 * i, 502 + 2 * i});
  test::addShell(model, 900 + n - 1, 2, {500 + 2 * (n - 1), 501 + 2 * (n - 1), 500, 501});
  FeModel deck = model;
  const RemeshReport report = remeshDeck(deck, RemeshSettings{});
  ASSERT_EQ(report.parts.size(), 2u);
  EXPECT_EQ(report.parts[0].status, PartStatus::Remeshed) << report.parts[0].reason;
  EXPECT_EQ(report.parts[1].status, PartStatus::Kept);
  EXPECT_NE(report.parts[1].reason.find("orient"), std::string::npos) << report.parts[1].reason;
  // The kept part reports what it writes back: its 24 original quads, judged as a new mesh.
  const PartAcceptance& written = report.parts[1].acceptance;
  EXPECT_EQ(written.elements, 24u);
  EXPECT_EQ(written.quads, 24u);
  EXPECT_EQ(written.trias, 0u);
  const QuadMesh strip = quadMeshFromModel(model, 2);
  QualitySettings judged = RemeshSettings{}.optimizeSettings.quality;
  judged.targetSize = report.parts[1].plan.targetSize;
  EXPECT_EQ(written.failing, assessQuality(strip, judged, &strip).failingAny);
  EXPECT_FALSE(report.allAccepted());
  const auto dir = test::scratchDir("acceptance_fallback");
  writeDeck(deck, dir / "out.k");
  const FeModel out = readDeck(dir / "out.k");
  std::size_t plate = 0, kept = 0;
  for (const Shell& s : out.shells) {
    if (s.part == 1) ++plate;
    if (s.part == 2 && s.id >= 900 && s.id < 900 + n) ++kept;
  }
  EXPECT_GT(plate, 0u);
  EXPECT_EQ(kept, std::size_t(n));
  const std::string json = remeshReportJson(report);
  EXPECT_NE(json.find("\"status\": \"kept\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"kept\": 1"), std::string::npos) << json;
}

}  // namespace

namespace {

/// Plans 0..n-1 joined in a chain (plan i shares nodes with i - 1 and i + 1).
std::vector<std::vector<std::size_t>> chain(std::size_t n) {
  std::vector<std::vector<std::size_t>> neighbours(n);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    neighbours[i].push_back(i + 1);
    neighbours[i + 1].push_back(i);
  }
  for (std::vector<std::size_t>& list : neighbours) std::sort(list.begin(), list.end());
  return neighbours;
}

/// A round's result for `statuses`, each part's reason saying `round`.
pipeline::RoundResult roundOf(const std::vector<PartStatus>& statuses, const std::string& round) {
  pipeline::RoundResult result;
  for (std::size_t i = 0; i < statuses.size(); ++i) {
    RemeshedPart part;
    part.plan.part = Id(i + 1);
    part.plan.targetSize = 1.0;
    part.status = statuses[i];
    part.reason = round;
    result.plans.push_back(part.plan);
    result.parts.push_back(part);
    result.meshes.emplace_back();
  }
  return result;
}

}  // namespace

TEST(HalfPass, GroupsAreTheHalvedPartsTheirNeighboursAndTheNeighboursSeamsFollowing) {
  // Eight parts in a chain; parts 1 and 6 are halved, part 7 is not redone (kept from the start).
  // Part 1 refines its seams with 0 and 2, and 2's seam with 3 follows: {0, 1, 2, 3}. Part 6
  // refines its seam with 5, whose seam with 4 follows: {4, 5, 6}. The seam between 3 and 4 is
  // changed by neither, so the two groups stay apart.
  const std::vector<std::uint8_t> halved{0, 1, 0, 0, 0, 0, 1, 0};
  const std::vector<std::uint8_t> redone{1, 1, 1, 1, 1, 1, 1, 0};
  const std::size_t none = pipeline::kNoGroup;
  EXPECT_EQ(pipeline::halvingGroups(chain(8), halved, redone),
            (std::vector<std::size_t>{0, 0, 0, 0, 4, 4, 4, none}));
}

TEST(HalfPass, AGroupsResultsStayWhenMoreOfItsPartsPassAndNoneIsLost) {
  // Two groups, {0, 1} and {2, 3}. At half the size part 0 passes and 1 still does: that group
  // takes the half pass's results. Part 2 passes too but 3, which passed at the full size, is
  // lost: that group keeps the full size's.
  using S = PartStatus;
  std::vector<std::vector<std::size_t>> neighbours = chain(4);
  neighbours[1] = {0};
  neighbours[2] = {3};
  pipeline::RoundResult full = roundOf({S::Kept, S::Remeshed, S::Kept, S::Remeshed}, "full");
  pipeline::RoundResult half = roundOf({S::Retried, S::Remeshed, S::Retried, S::Kept}, "half");
  pipeline::takeHalvedGroups(full, half, {0, 0, 2, 2}, neighbours);
  std::vector<std::string> taken, left;
  for (std::size_t i = 0; i < 4; ++i) {
    taken.push_back(full.parts[i].reason);
    left.push_back(half.parts[i].reason);
  }
  EXPECT_EQ(taken, (std::vector<std::string>{"half", "half", "full", "full"}));
  EXPECT_EQ(left, (std::vector<std::string>{"full", "full", "half", "half"}));
  EXPECT_EQ(full.parts[0].status, S::Retried);
  EXPECT_EQ(full.parts[3].status, S::Remeshed);
}

TEST(HalfPass, PointsInsideTheOtherMeshsEdgesHangWhereverTheEdgesAre) {
  // Two parts sharing the area of a 2 x 2 square (layers on the same nodes), one meshed with unit
  // quads, the other with quads of 0.5. The finer mesh's points in the middle of the coarser's
  // edges hang: 8 on its boundary, 4 on its inner edges (a T-junction or a shared area does not
  // conform either). Its points inside the coarser's faces and on its corners do not; no point of
  // the coarser mesh hangs on the finer one.
  const QuadMesh coarse = test::unitGrid(2);
  QuadMesh fine = test::unitGrid(4);
  for (auto& point : fine.points)
    for (double& coordinate : point) coordinate *= 0.5;
  EXPECT_EQ(pipeline::hangingPoints(fine, coarse, 1e-6), 12u);
  EXPECT_EQ(pipeline::hangingPoints(coarse, fine, 1e-6), 0u);
}

TEST(HardPoints, APointOnAnEdgeSplitsItAndBothFacesAlongIt) {
  // A 2 x 2 grid of unit quads; a hard point on the inner edge x = 1, y = 0..1 lies inside no
  // face: it splits the edge, each of its two quads becoming three triangles round it, oriented
  // as the quads, nothing folded. A point inside a quad still becomes a fan of four.
  QuadMesh mesh = test::unitGrid(2);
  const std::size_t points = mesh.points.size();
  EXPECT_EQ(pipeline::insertHardPoints(mesh, {{1.0, 0.5, 0.0}, {0.5, 1.5, 0.0}}, 1e-6), 2u);
  ASSERT_EQ(mesh.points.size(), points + 2);
  EXPECT_EQ(mesh.points[points], (std::array<double, 3>{1.0, 0.5, 0.0}));
  EXPECT_EQ(mesh.constraints[points].role, PointRole::Corner);
  std::size_t aroundEdgePoint = 0, aroundInnerPoint = 0;
  for (const auto& face : mesh.faces) {
    aroundEdgePoint += std::count(face.begin(), face.end(), CornerIndex(points));
    aroundInnerPoint += std::count(face.begin(), face.end(), CornerIndex(points + 1));
  }
  EXPECT_EQ(aroundEdgePoint, 6u);
  EXPECT_EQ(aroundInnerPoint, 4u);
  EXPECT_EQ(mesh.faces.size(), 1u + 6u + 4u);
  EXPECT_EQ(test::foldedCount(mesh), 0u);
  double area = 0.0;
  for (const auto& face : mesh.faces) {
    const int n = cornerCount(face);
    const auto& p = mesh.points;
    for (int k = 1; k + 1 < n; ++k) {  // counter-clockwise seen from +z: positive
      const auto& a = p[face[0]];
      const auto& b = p[face[std::size_t(k)]];
      const auto& c = p[face[std::size_t(k + 1)]];
      area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
  }
  EXPECT_NEAR(area, 4.0, 1e-12);
}
