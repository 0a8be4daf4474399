// compareDecks and `voxremesh compare`: what a remeshed deck kept and lost, with losses planted in
// small decks and a real deck remeshed end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "support/test_support.h"
#include "voxremesh/deck_compare.h"
#include "voxremesh/io.h"

using namespace voxremesh;
using voxremesh::test::contains;
using voxremesh::test::quoted;
using voxremesh::test::runCli;
using voxremesh::test::scratchDir;
using voxremesh::test::writeText;

namespace {

/// An LS-DYNA deck of two unit quads side by side (parts 1 and 2 sharing nodes 2 and 5), a node
/// set of part 1's nodes, a velocity on every node and a mass on node 3. `part2Left` is the x of
/// part 2's left side (1: the seam is shared through nodes 2 and 5; else part 2 has its own
/// nodes 7 and 8 there); `velocityNodes` lists the nodes with a velocity; `massX` the x of node 3.
std::string twoPartDeck(double part2Left, const std::vector<int>& velocityNodes, double massX) {
  std::string deck = "*KEYWORD\n*NODE\n";
  char line[96];
  const double xs[] = {0, 1, massX, 0, 1, 2, part2Left, part2Left};
  const double ys[] = {0, 0, 0, 1, 1, 1, 0, 1};
  for (int n = 0; n < 8; ++n) {
    std::snprintf(line, sizeof line, "%8d%16.3f%16.3f%16.3f\n", n + 1, xs[n], ys[n], 0.0);
    deck += line;
  }
  const bool shared = part2Left == 1.0;
  deck += "*ELEMENT_SHELL\n       1       1       1       2       5       4\n";
  deck += shared ? "       2       2       2       3       6       5\n"
                 : "       2       2       7       3       6       8\n";
  deck += "*SET_NODE_LIST\n         3\n         1         2         4         5\n";
  deck += "*INITIAL_VELOCITY_NODE\n";
  for (const int node : velocityNodes) {
    std::snprintf(line, sizeof line, "%8d%10.1f%10.1f%10.1f\n", node, 1.0, 0.0, 0.0);
    deck += line;
  }
  return deck + "*ELEMENT_MASS\n       1       3     1.000\n*END\n";
}

DeckComparison compareTexts(const std::string& name, const std::string& before,
                            const std::string& after) {
  const auto dir = scratchDir(name);
  writeText(dir / "in.k", before);
  writeText(dir / "out.k", after);
  return compareDecks(readDeck(dir / "in.k"), readDeck(dir / "out.k"));
}

bool anyLossMentions(const DeckComparison& comparison, const std::string& words) {
  for (const std::string& loss : comparison.losses)
    if (contains(loss, words)) return true;
  return false;
}

}  // namespace

TEST(DeckCompare, ADeckComparedWithItselfLosesNothing) {
  const std::string deck = twoPartDeck(1.0, {1, 2, 3, 4, 5, 6}, 2.0);
  const DeckComparison same = compareTexts("compare_same", deck, deck);
  EXPECT_TRUE(same.losses.empty()) << formatComparisonTable(same);
  ASSERT_EQ(same.parts.size(), 2u);
  EXPECT_DOUBLE_EQ(same.parts[0].areaBefore, 1.0);
  ASSERT_EQ(same.seams.size(), 1u);
  EXPECT_EQ(same.seams[0].before, 2u);
  EXPECT_EQ(same.hardPoints, 1u);
  ASSERT_EQ(same.sets.size(), 1u);
  EXPECT_EQ(same.sets[0].membersBefore, 4u);
  EXPECT_DOUBLE_EQ(same.sets[0].areaBefore, 1.0);  // part 1's quad: all its nodes are members
}

TEST(DeckCompare, PlantedLossesAreEachReported) {
  const std::string before = twoPartDeck(1.0, {1, 2, 3, 4, 5, 6}, 2.0);
  // Part 2 detached (its own nodes on the seam), node 6 without velocity, the mass node moved.
  const std::string after = twoPartDeck(1.0 + 1e-3, {1, 2, 3, 4, 5, 7, 8}, 2.5);
  const DeckComparison lost = compareTexts("compare_lost", before, after);
  EXPECT_TRUE(anyLossMentions(lost, "parts 1 and 2 shared 2 nodes and share none"))
      << formatComparisonTable(lost);
  EXPECT_TRUE(anyLossMentions(lost, "*INITIAL_VELOCITY_NODE on part 2"));
  EXPECT_TRUE(anyLossMentions(lost, "hard points moved"));
  EXPECT_EQ(lost.hardPointsMoved, 1u);
  EXPECT_DOUBLE_EQ(lost.largestHardPointMove, 0.5);
}

TEST(DeckCompare, ADanglingReferenceAndAnEmptiedSetAreLosses) {
  const std::string before = twoPartDeck(1.0, {1, 2, 3, 4, 5, 6}, 2.0);
  std::string after = before;
  const std::string set = "         1         2         4         5\n";
  after.replace(after.find(set), set.size(), "        91        92\n");
  const DeckComparison lost = compareTexts("compare_dangling", before, after);
  EXPECT_FALSE(anyLossMentions(lost, "dangling"));
  EXPECT_TRUE(anyLossMentions(lost, "*SET_NODE_LIST (line 3): its 4 nodes are gone"))
      << formatComparisonTable(lost);
  // A velocity naming node 9, a free node of the first deck the second does not have.
  std::string withNode9 = before;
  withNode9.insert(withNode9.find("*ELEMENT_SHELL"),
                   "       9           5.000           5.000           0.000\n");
  after = before;
  after.replace(after.find("       6       1.0"), 17, "       9       1.0");
  const DeckComparison dangling = compareTexts("compare_dangling2", withNode9, after);
  ASSERT_EQ(dangling.dangling.size(), 1u) << formatComparisonTable(dangling);
  EXPECT_EQ(dangling.dangling[0].id, 9);
  EXPECT_TRUE(anyLossMentions(dangling, "references name a node or shell"));
}

TEST(DeckCompare, ThePressureForceOfPload4CardsIsComparedAsAVector) {
  // One unit plate: as one quad with 4.0 before; as two half quads (3 and 5) after, or with the
  // pressure lost on one half.
  const std::string grids =
      "BEGIN BULK\n"
      "GRID           1              0.      0.      0.\n"
      "GRID           2              1.      0.      0.\n"
      "GRID           3              1.      1.      0.\n"
      "GRID           4              0.      1.      0.\n"
      "GRID           5              .5      0.      0.\n"
      "GRID           6              .5      1.      0.\n";
  const std::string before = grids +
                             "CQUAD4         1       1       1       2       3       4\n"
                             "PLOAD4         9       1     4.0\nENDDATA\n";
  const std::string halves = grids +
                             "CQUAD4         2       1       1       5       6       4\n"
                             "CQUAD4         3       1       5       2       3       6\n"
                             "PLOAD4         9       2     4.0\n";
  const auto dir = scratchDir("compare_pload4");
  writeText(dir / "in.bdf", before);
  writeText(dir / "same.bdf", halves + "PLOAD4         9       3     4.0\nENDDATA\n");
  writeText(dir / "half.bdf", halves + "PLOAD4         9       3     0.0\nENDDATA\n");
  const FeModel in = readDeck(dir / "in.bdf");
  const DeckComparison same = compareDecks(in, readDeck(dir / "same.bdf"));
  EXPECT_EQ(same.loadCardsBefore, 1u);
  EXPECT_EQ(same.loadCardsAfter, 2u);
  EXPECT_DOUBLE_EQ(same.forceBefore[2], 4.0);
  EXPECT_DOUBLE_EQ(same.forceAfter[2], 4.0);
  EXPECT_TRUE(same.losses.empty()) << formatComparisonTable(same);
  const DeckComparison half = compareDecks(in, readDeck(dir / "half.bdf"));
  EXPECT_TRUE(anyLossMentions(half, "the total pressure force changed by 2"))
      << formatComparisonTable(half);
  const auto cli = runCli("compare " + quoted(dir / "in.bdf") + " " + quoted(dir / "half.bdf"));
  EXPECT_EQ(cli.exitCode, 3) << cli.output;
  EXPECT_TRUE(contains(cli.output, "lost:")) << cli.output;
}

TEST(DeckCompare, Car5RemeshedLosesNothingAndTheCliSaysSo) {
  VOXREMESH_REQUIRE_SHARED_DECK(car5, "car5.k");
  const auto dir = scratchDir("compare_car5");
  const auto remeshed = runCli("remesh " + quoted(car5) + " -o " + quoted(dir / "out.k"));
  ASSERT_TRUE(remeshed.exitCode == 0 || remeshed.exitCode == 3) << remeshed.output;
  const auto compared = runCli("compare " + quoted(car5) + " " + quoted(dir / "out.k"));
  EXPECT_EQ(compared.exitCode, 0) << compared.output;
  EXPECT_TRUE(contains(compared.output, "nothing lost")) << compared.output;
  const auto json = runCli("compare " + quoted(car5) + " " + quoted(dir / "out.k") + " --json");
  EXPECT_TRUE(contains(json.output, "\"losses\": []")) << json.output;
}

TEST(DeckCompare, WingboxRemeshedAtTwiceItsSizeKeepsItsPressureForce) {
  // Its 1,632 PLOAD4 cards each carry their own pressure; the remeshed skin's shells are about
  // four times larger: the total force must stay within 1 %.
  VOXREMESH_REQUIRE_SHARED_DECK(wingbox, "wingbox_stitched_together-000.bdf");
  const auto dir = scratchDir("compare_wingbox");
  const auto remeshed =
      runCli("remesh " + quoted(wingbox) + " --size 6 -o " + quoted(dir / "out.bdf"));
  ASSERT_TRUE(remeshed.exitCode == 0 || remeshed.exitCode == 3) << remeshed.output;
  const DeckComparison comparison = compareDecks(readDeck(wingbox), readDeck(dir / "out.bdf"));
  ASSERT_GT(comparison.loadCardsAfter, 0u);
  const double before =
      std::hypot(comparison.forceBefore[0], comparison.forceBefore[1], comparison.forceBefore[2]);
  const double change = std::hypot(comparison.forceAfter[0] - comparison.forceBefore[0],
                                   comparison.forceAfter[1] - comparison.forceBefore[1],
                                   comparison.forceAfter[2] - comparison.forceBefore[2]);
  EXPECT_LT(change, 0.01 * before);
  EXPECT_TRUE(comparison.losses.empty()) << formatComparisonTable(comparison);
}

TEST(DeckCompare, FreedlmRibsRemeshedNextToTheirRigidLinksLoseNothing) {
  // freedlm.bdf parts 13 and 19 hold grids 24005 and 28041, which RBE2 9 and 10 join to grids of
  // other parts at the same coordinates. Those parts are not remeshed: the new nodes there must
  // keep the hard points' IDs, not take the other parts' coincident nodes (which would leave the
  // RBE2s joining a node to itself and connect the parts directly).
  VOXREMESH_REQUIRE_SHARED_DECK(freedlm, "freedlm.bdf");
  const auto dir = scratchDir("compare_freedlm");
  const auto remeshed =
      runCli("remesh " + quoted(freedlm) + " --parts 13,19 -o " + quoted(dir / "out.bdf"));
  ASSERT_TRUE(remeshed.exitCode == 0 || remeshed.exitCode == 3) << remeshed.output;
  const DeckComparison comparison = compareDecks(readDeck(freedlm), readDeck(dir / "out.bdf"));
  EXPECT_GT(comparison.hardPoints, 0u);
  EXPECT_TRUE(comparison.losses.empty()) << formatComparisonTable(comparison);
  const std::string out = test::readText(dir / "out.bdf");
  EXPECT_NE(out.find("RBE2     10      19506   123     24005"), std::string::npos);
}

TEST(DeckCompare, ANodeLeftInsideANeighboursEdgeIsALoss) {
  // Two unit quads sharing the edge x = 1 (nodes 2 and 5). After, part 2 has a node (9) in the
  // middle of that edge, which part 1 lacks: the seam no longer conforms.
  FeModel before;
  const double xs[] = {0, 1, 2, 0, 1, 2}, ys[] = {0, 0, 0, 1, 1, 1};
  for (int n = 0; n < 6; ++n) test::addNode(before, n + 1, xs[n], ys[n], 0.0);
  FeModel after = before;
  test::addShell(before, 1, 1, {1, 2, 5, 4});
  test::addShell(before, 2, 2, {2, 3, 6, 5});
  test::addNode(after, 9, 1.0, 0.5, 0.0);
  test::addNode(after, 10, 2.0, 0.5, 0.0);
  test::addShell(after, 1, 1, {1, 2, 5, 4});
  test::addShell(after, 2, 2, {2, 3, 10, 9});
  test::addShell(after, 3, 2, {9, 10, 6, 5});
  EXPECT_TRUE(compareDecks(before, before).losses.empty());
  const DeckComparison comparison = compareDecks(before, after);
  EXPECT_EQ(comparison.hangingNodesBefore, 0u);
  EXPECT_EQ(comparison.hangingNodesAfter, 1u);
  EXPECT_TRUE(anyLossMentions(
      comparison, "nodes inside an edge of a part they share a seam with: 1 (0 before)"))
      << formatComparisonTable(comparison);
}
