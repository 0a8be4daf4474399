// Seam sampling over the deck (pipeline/seam_counts.h): the growth ratio of the pieces toward a
// sharp corner of a narrow sheet follows the quality criteria, on the curves along its sides; the
// curves facing each other across a narrow strip get the same counts, curve by curve; a curve
// facing several gets stations at their joints.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/seam_counts.h"
#include "support/test_support.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/quality.h"

using namespace voxremesh;

TEST(SeamSampling, AWedgeRatioKeepsTheRowsTrapezoidsHalfwayToTheLimits) {
  const QualitySettings criteria;  // Jacobian ratio 0.6, aspect 5, quad angles from 45
  // A corner a quad can fill is not graded.
  EXPECT_EQ(pipeline::wedgeRatio(45.0, criteria), 0.0);
  EXPECT_EQ(pipeline::wedgeRatio(90.0, criteria), 0.0);
  // At 30 degrees the Jacobian ratio bounds it: parallel sides within sqrt(0.6).
  EXPECT_NEAR(pipeline::wedgeRatio(30.0, criteria), 1.0 / std::sqrt(0.6), 1e-12);
  // At 5 degrees the aspect does: a piece along at most sqrt(5) times the rung across.
  const double tip = pipeline::wedgeRatio(5.0, criteria);
  EXPECT_NEAR(tip, 1.0 + std::sqrt(5.0) * 2.0 * std::tan(2.5 * M_PI / 180.0), 1e-12);
  EXPECT_LT(tip, 1.0 / std::sqrt(0.6));
  // Stricter criteria grade more gently.
  QualitySettings strict = criteria;
  strict.minJacobianRatio = 0.8;
  EXPECT_LT(pipeline::wedgeRatio(30.0, strict), pipeline::wedgeRatio(30.0, criteria));
}

TEST(SeamSampling, OnlyTheCurvesAlongAWedgesSidesShrinkTowardItsTip) {
  // Node 10 is the tip of a wedge whose side runs to node 11. The curve along that side (10, 11,
  // 12), in either direction, is graded at the tip; the curve from 10 to 13 (another sheet's side
  // that only ends there, where the sheet is no wedge) keeps even pieces.
  Sheet sheet;
  sheet.points = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {2.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
  sheet.pointNodeIds = {10, 11, 12, 13};
  Polyline along, back, other;
  along.points = {0, 1, 2};
  back.points = {2, 1, 0};
  other.points = {0, 3};
  sheet.junctionCurves = {along, back, other};
  pipeline::SeamSampling sampling;
  sampling.grading[{10, 11}] = 1.25;
  std::vector<Sheet> sheets{sheet};
  pipeline::setSeamSampling(sheets, sampling);
  const std::vector<Polyline>& curves = sheets.front().junctionCurves;
  using Graded = std::vector<std::pair<std::size_t, double>>;
  EXPECT_EQ(curves[0].grading, (Graded{{0, 1.25}}));
  EXPECT_EQ(curves[1].grading, (Graded{{2, 1.25}}));
  EXPECT_TRUE(curves[2].grading.empty());
}

/// Where the plates beside the strip of stripBetweenSplitPlates change parts, below and above.
std::pair<double, double> stripJoints(bool tip) {
  return tip ? std::make_pair(10.8, 10.6) : std::make_pair(10.6, 10.4);
}

/// A strip (part 1, one row of quads in z = 0 along y = 0..1, x = 0..39) between plates 10 wide,
/// each side's plate made of two parts (stripJoints): below, parts 2 and 3 meet at x = 10.6; above,
/// parts 4 and 5 at x = 10.4. So each side of the strip is two seams, their joints facing each
/// other. The strip is 1 wide; with `tip`, it tapers from 1 wide at x = 0 to a tip at (39, 0)
/// instead (the plate above following its top side), and its joints are at 10.8 and 10.6.
FeModel stripBetweenSplitPlates(bool tip) {
  const auto [below, above] = stripJoints(tip);
  FeModel model;
  std::vector<double> bottomX, topX;  // the strip's node abscissae along its two sides
  for (int i = 0; i <= 39; ++i) {
    bottomX.push_back(i);
    topX.push_back(i);
    if (i == 10) bottomX.push_back(below), topX.push_back(above);
  }
  const std::size_t n = bottomX.size();  // nodes per side
  const auto topY = [&](double x) { return tip ? 1.0 - x / 39.0 : 1.0; };
  const auto id = [&](int row, std::size_t i) {
    return tip && row == 1 && i + 1 == n ? Id(1 + Id(i)) : Id(1000 * row + 1 + Id(i));
  };
  for (std::size_t i = 0; i < n; ++i) {
    test::addNode(model, id(0, i), bottomX[i], 0.0);
    if (id(1, i) != id(0, i)) test::addNode(model, id(1, i), topX[i], topY(topX[i]));
    test::addNode(model, id(2, i), bottomX[i], -10.0);
    test::addNode(model, id(3, i), topX[i], 11.0);
  }
  Id shell = 1;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (id(1, i + 1) == id(0, i + 1))
      test::addShell(model, shell++, 1, {id(0, i), id(0, i + 1), id(1, i)});
    else
      test::addShell(model, shell++, 1, {id(0, i), id(0, i + 1), id(1, i + 1), id(1, i)});
    test::addShell(model, shell++, bottomX[i] < below - 0.05 ? 2 : 3,
                   {id(2, i), id(2, i + 1), id(0, i + 1), id(0, i)});
    test::addShell(model, shell++, topX[i] < above - 0.05 ? 4 : 5,
                   {id(1, i), id(1, i + 1), id(3, i + 1), id(3, i)});
  }
  return model;
}

/// After a remesh of the strip of stripBetweenSplitPlates at size 3: how many of part 1's nodes lie
/// on its bottom and top sides before the joints and after them (the tip excepted), and how many
/// of its elements are triangles.
struct StripCounts {
  std::map<std::pair<int, bool>, int> nodes;  // (side: 0 below, 1 above; after the joints)
  int triangles = 0;
  PartStatus status = PartStatus::Kept;  ///< the strip's
  std::string reason;                    ///< the strip's
};

/// Remeshes stripBetweenSplitPlates(tip) at size 3, expecting no part kept.
StripCounts remeshedStrip(bool tip) {
  FeModel model = stripBetweenSplitPlates(tip);
  RemeshSettings settings;
  settings.targetSize = 3.0;
  const RemeshReport report = remeshDeck(model, settings);
  StripCounts counts;
  for (const RemeshedPart& part : report.parts) {
    EXPECT_NE(part.status, PartStatus::Kept) << part.plan.part << ": " << part.reason;
    if (part.plan.part == 1) counts.status = part.status, counts.reason = part.reason;
  }
  std::set<Id> ids;
  for (const Shell& shell : model.shells)
    if (shell.part == 1) {
      counts.triangles += shell.nodeCount == 3;
      for (int c = 0; c < shell.nodeCount; ++c) ids.insert(shell.nodes[std::size_t(c)]);
    }
  const auto [below, above] = stripJoints(tip);
  const double middle = 0.5 * (below + above);
  for (const Node& node : model.nodes)
    if (ids.count(node.id) && node.xyz[0] < 38.9 && std::abs(node.xyz[0] - middle) > 0.2)
      ++counts.nodes[{node.xyz[1] > 1e-9, node.xyz[0] > middle}];
  return counts;
}

TEST(SeamSampling, TheSeamsFacingEachOtherAcrossAStripGetTheSameCountsOneByOne) {
  // Sampled on its own at size 3, each seam would get round(length / 3) pieces: 4 and 9 below
  // (10.6 and 28.4 long), 3 and 10 above (10.4 and 28.6). The totals match; the stretches do not,
  // so the strip's row would slant and need triangles. Since the joints face each other, each
  // seam gets the count of the one across: the row is quads only, its rungs straight across.
  const StripCounts counts = remeshedStrip(false);
  EXPECT_EQ(counts.status, PartStatus::Remeshed) << counts.reason;
  EXPECT_EQ(counts.triangles, 0);
  EXPECT_EQ((counts.nodes.at({0, false})), (counts.nodes.at({1, false})));
  EXPECT_EQ((counts.nodes.at({0, true})), (counts.nodes.at({1, true})));
}

TEST(SeamSampling, TheTwoLongSidesOfAStripRunningIntoATipAreTiedToo) {
  // The strip tapering into a tip: its patch has three corners, and its long sides face each other
  // (the base, 1 long, is the shortest side). Its row length is about 1.65 (its mean width, 0.49,
  // times the aspect limit over 1.5): alone, the seams before the joints (10.8 and 10.6 long) would
  // get 7 and 6 pieces. The long sides are tied as a four-sided strip's are: the rungs run
  // straight across, and the one triangle is at the tip.
  const StripCounts counts = remeshedStrip(true);
  EXPECT_EQ(counts.status, PartStatus::Remeshed) << counts.reason;
  EXPECT_EQ(counts.triangles, 1);
  EXPECT_EQ((counts.nodes.at({0, false})), (counts.nodes.at({1, false})));
  EXPECT_EQ((counts.nodes.at({0, true})), (counts.nodes.at({1, true})));
}

TEST(SeamSampling, AStripTaperingAlongGetsRungsWithinTheJacobianRatio) {
  // A strip (part 1, z = 0) widening from 1 at x = 0 to 2.5 at x = 6, between a plate below
  // (part 2, its seam along y = 0) and one above (part 3, its seam the strip's slanting top). At
  // size 6 its row length (4.5) would give it one quad, its parallel sides 1 and 2.5 (Jacobian
  // ratio 0.4). Its seams get the pieces that keep each quad's sides within sqrt(0.6) instead:
  // the strip passes at its first attempt.
  FeModel model;
  for (int i = 0; i <= 6; ++i) {
    test::addNode(model, Id(1 + i), i, 0.0);
    test::addNode(model, Id(11 + i), i, 1.0 + 0.25 * i);
    test::addNode(model, Id(21 + i), i, -6.0);
    test::addNode(model, Id(31 + i), i, 8.0);
  }
  Id shell = 1;
  for (int i = 0; i < 6; ++i) {
    test::addShell(model, shell++, 1, {Id(1 + i), Id(2 + i), Id(12 + i), Id(11 + i)});
    test::addShell(model, shell++, 2, {Id(21 + i), Id(22 + i), Id(2 + i), Id(1 + i)});
    test::addShell(model, shell++, 3, {Id(11 + i), Id(12 + i), Id(32 + i), Id(31 + i)});
  }
  RemeshSettings settings;
  settings.targetSize = 6.0;
  const RemeshReport report = remeshDeck(model, settings);
  ASSERT_EQ(report.parts.size(), 3u);
  const RemeshedPart& strip = report.parts[0];
  ASSERT_EQ(strip.plan.part, 1);
  EXPECT_EQ(strip.status, PartStatus::Remeshed) << strip.reason;
  EXPECT_EQ(strip.acceptance.failing, 0u) << strip.reason;
}

TEST(SeamSampling, AStripTallerInItsMiddleThanAtItsEndsGetsRowsWithinTheAspectLimit) {
  // A rib web (part 1, z = 0) 40 long, 2 tall at its ends and 12 in its middle (its top a sine),
  // between plates below and above (parts 2 and 3) that place their seams with it 1 apart, and
  // with plates at its ends too (parts 4 and 5). Its ends sampled as those seams (2 pieces) would
  // make two rows across, quads up to 6 x 1 in the middle (aspect 6); its tallest rung asks for
  // three rows.
  FeModel model;
  const auto top = [](int i) { return 2.0 + 10.0 * std::sin(M_PI * i / 40.0); };
  for (int i = 0; i <= 40; ++i) {
    test::addNode(model, Id(1 + i), i, 0.0);
    test::addNode(model, Id(101 + i), i, top(i));
    test::addNode(model, Id(201 + i), i, -3.0);
    test::addNode(model, Id(301 + i), i, top(i) + 3.0);
  }
  Id shell = 1;
  for (int i = 0; i < 40; ++i) {
    test::addShell(model, shell++, 1, {Id(1 + i), Id(2 + i), Id(102 + i), Id(101 + i)});
    test::addShell(model, shell++, 2, {Id(201 + i), Id(202 + i), Id(2 + i), Id(1 + i)});
    test::addShell(model, shell++, 3, {Id(101 + i), Id(102 + i), Id(302 + i), Id(301 + i)});
  }
  test::addNode(model, 401, -3.0, 0.0);
  test::addNode(model, 402, -3.0, 2.0);
  test::addNode(model, 501, 43.0, 0.0);
  test::addNode(model, 502, 43.0, 2.0);
  test::addShell(model, shell++, 4, {401, 1, 101, 402});
  test::addShell(model, shell++, 5, {41, 501, 502, 141});
  RemeshSettings settings;
  settings.partSizes = {{1, 3.0}, {2, 1.0}, {3, 1.0}, {4, 3.0}, {5, 3.0}};
  const RemeshReport report = remeshDeck(model, settings);
  ASSERT_EQ(report.parts.size(), 5u);
  const RemeshedPart& web = report.parts[0];
  ASSERT_EQ(web.plan.part, 1);
  EXPECT_EQ(web.status, PartStatus::Remeshed) << web.reason;
  EXPECT_EQ(web.acceptance.failing, 0u) << web.reason;
}

/// The remesh of a deck at one target size, default settings otherwise.
RemeshReport remeshAtSize(FeModel& model, double size) {
  RemeshSettings settings;
  settings.targetSize = size;
  return remeshDeck(model, settings);
}

/// Part 1's entry in a remesh report, or null.
const RemeshedPart* partOne(const RemeshReport& report) {
  for (const RemeshedPart& part : report.parts)
    if (part.plan.part == 1) return &part;
  return nullptr;
}

TEST(SeamSampling, TheSidesOfAnLShapedStripAddUpAcrossItSoThatItIsTwoGrids) {
  // An L-shaped strip (part 1, z = 0) with arms 2 wide, 20 long outside and 18 inside, in 1 mm
  // quads, every side a seam of its own: panels in its inner corner (parts 2 and 7, meeting on
  // the diagonal from its inner corner), plates below and left of it (parts 3 and 4, meeting
  // beyond its outer corner) and at its arms' ends (parts 5 and 6). At size 4 the inner sides
  // would get 5 pieces (4.5 rounded up), the outer ones 5 and the ends 1: 5 + 1 against 5, no
  // two grids. The two sides along each direction are tied to the side across from them; cut
  // from its inner corner the strip is two grids of quads.
  FeModel model;
  const auto id = [](int i, int j) { return Id(1 + (i + 6) + 100 * (j + 6)); };
  const auto partAt = [](int i, int j) -> Id {  // the part of the unit square at (i, j)
    if ((j >= 0 && j < 2 && i >= 0 && i < 20) || (i >= 0 && i < 2 && j >= 0 && j < 20)) return 1;
    if (i >= 2 && i < 20 && j >= 2 && j < 20) return i > j ? 2 : i < j ? 7 : 0;  // 0: split
    if (j < 0 && i < 20) return 3;  // the corner too, so that parts 3 and 4 share a seam
    if (i < 0 && j >= 0 && j < 20) return 4;
    if (i >= 20 && j >= 0 && j < 2) return 5;
    if (j >= 20 && i >= 0 && i < 2) return 6;
    return -1;
  };
  std::set<Id> used;
  const auto node = [&](int i, int j) {
    if (used.insert(id(i, j)).second) test::addNode(model, id(i, j), i, j);
    return id(i, j);
  };
  Id shell = 1;
  for (int j = -6; j < 26; ++j)
    for (int i = -6; i < 26; ++i) {
      const Id part = partAt(i, j);
      if (part > 0)
        test::addShell(model, shell++, part,
                       {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
      if (part != 0) continue;
      test::addShell(model, shell++, 2, {node(i, j), node(i + 1, j), node(i + 1, j + 1)});
      test::addShell(model, shell++, 7, {node(i, j), node(i + 1, j + 1), node(i, j + 1)});
    }
  const RemeshReport report = remeshAtSize(model, 4.0);
  const RemeshedPart* strip = partOne(report);
  ASSERT_NE(strip, nullptr);
  EXPECT_EQ(strip->status, PartStatus::Remeshed) << strip->reason;
  EXPECT_EQ(strip->acceptance.failing, 0u) << strip->reason;
  EXPECT_EQ(strip->trias, 0u) << strip->reason;
}

TEST(SeamSampling, ATipWhoseBaseHasTwoPiecesGetsRowsInsteadOfAFan) {
  // A triangular tab (part 1, z = 0), its tip at the origin (44 degrees), its base 1.62 tall at
  // x = 2, where two plates meet it (parts 2 and 3, joined at the base's middle): the base is two
  // seams. Plates above and below (parts 4 and 5) hold its long sides. At size 4 each long side
  // would be one piece, and the tab a fan of two triangles of 22 degrees at its tip. Its long
  // sides get as many pieces as its base instead: a triangle at the tip, then a row of a quad and
  // a triangle.
  FeModel model;
  const double half = 2.0 * std::tan(22.0 * M_PI / 180.0);
  test::addNode(model, 1, 0.0, 0.0);
  test::addNode(model, 2, 2.0, half);
  test::addNode(model, 3, 2.0, 0.0);
  test::addNode(model, 4, 2.0, -half);
  test::addNode(model, 5, 5.0, 0.0);
  test::addNode(model, 6, 5.0, half);
  test::addNode(model, 7, 0.0, 3.0);
  test::addNode(model, 8, 2.0, 3.0);
  test::addNode(model, 9, 2.0, -3.0);
  test::addNode(model, 10, 0.0, -3.0);
  test::addNode(model, 11, 5.0, -half);
  test::addShell(model, 1, 1, {1, 4, 3});
  test::addShell(model, 2, 1, {1, 3, 2});
  test::addShell(model, 3, 2, {3, 5, 6, 2});
  test::addShell(model, 4, 3, {4, 11, 5, 3});
  test::addShell(model, 5, 4, {1, 2, 8, 7});
  test::addShell(model, 6, 5, {1, 10, 9, 4});
  const RemeshReport report = remeshAtSize(model, 4.0);
  const RemeshedPart* tab = partOne(report);
  ASSERT_NE(tab, nullptr);
  EXPECT_EQ(tab->status, PartStatus::Remeshed) << tab->reason;
  EXPECT_EQ(tab->acceptance.failing, 0u) << tab->reason;
  EXPECT_GE(tab->quads, 1u) << tab->reason;
}

TEST(SeamSampling, ASeamFacingSeveralPastThePatchsCornerGetsStationsAtTheirJoints) {
  // freedlm.bdf at its size: part 26 (a fairing) has a strip 1.5 wide along its keel, a curve of
  // its own 54 long, which faces its seams with part 27 (pieces 3.85 long, then 2.15) and, past
  // the keel's end, one more seam round the patch's corner, whose closest points are all the
  // keel's end. That curve left the keel without stations: its even pieces (2.35) slanted the
  // rows up to 6 mm along against the strip's 1.5 across, and 26 and 27 beside it were kept. It
  // counts with the last stretch now, and the keel's nodes face the joints across. Part 7's
  // bottom seam meets curves past both its ends (up the rib's sides), which would crowd its end
  // stretches: they spread over the stretches next to them, and it still passes.
  VOXREMESH_REQUIRE_SHARED_DECK(path, "freedlm.bdf");
  FeModel model = readDeck(path.string());
  const RemeshReport report = remeshDeck(model, RemeshSettings{});
  for (const RemeshedPart& part : report.parts) {
    if (part.plan.part == 7 || part.plan.part == 26 || part.plan.part == 27) {
      EXPECT_NE(part.status, PartStatus::Kept) << part.plan.part << ": " << part.reason;
    }
  }
}
