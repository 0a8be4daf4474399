// The deck report on the real decks of ../shared/data: the figures their README states.
#include <gtest/gtest.h>

#include <string>

#include "io/text_scan.h"
#include "support/test_support.h"
#include "voxremesh/deck_report.h"
#include "voxremesh/io.h"

using namespace voxremesh;

namespace {

DeckReport reportOf(const std::filesystem::path& path) {
  Warnings warnings;
  const FeModel model = readDeck(path, {}, &warnings);
  return reportDeck(model);
}

// The parts' rows add up to the total where no edge is shared between parts.
void expectPartsAddUp(const DeckReport& r) {
  std::size_t quads = 0, trias = 0;
  for (const PartReport& part : r.parts) {
    quads += part.stats.quads;
    trias += part.stats.trias;
  }
  EXPECT_EQ(quads, r.total.quads);
  EXPECT_EQ(trias, r.total.trias);
}

}  // namespace

TEST(DeckReportDecks, WheelHasTheReadmesTopologyFindings) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "wheel.k");
  const DeckReport r = reportOf(path);
  EXPECT_EQ(r.total.shells(), 11553u);
  EXPECT_EQ(r.total.nonManifoldEdges, 168u);
  // The README's 980 counts every edge on which two shells run the same way: the 168
  // non-manifold edges plus 812 two-shell edges with flipped normals.
  EXPECT_EQ(r.total.inconsistentEdges, 980u);
  EXPECT_EQ(r.total.boundaryEdges, 758u);
  EXPECT_EQ(r.examples.nonManifoldEdges.size(), 10u);
  for (const EdgeExample& example : r.examples.nonManifoldEdges)
    EXPECT_GE(example.shells.size(), 3u);
  expectPartsAddUp(r);
}

TEST(DeckReportDecks, BracketIsAnOpenManifoldConsistentlyOrientedSheet) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "bracket.k");
  const DeckReport r = reportOf(path);
  EXPECT_EQ(r.total.quads, 1811u);
  EXPECT_EQ(r.total.trias, 54u);
  EXPECT_EQ(r.total.boundaryEdges, 288u);
  EXPECT_EQ(r.total.nonManifoldEdges, 0u);
  EXPECT_EQ(r.total.inconsistentEdges, 0u);
  // A manifold sheet's boundary closes: the outer contour and the holes are loops (12, as an
  // independent count of the connected components of its boundary edges gave).
  EXPECT_EQ(r.total.openBoundaryChains, 0u);
  EXPECT_EQ(r.total.boundaryLoops, 12u);
  EXPECT_EQ(r.total.duplicateNodes, 0u);
  EXPECT_EQ(r.total.degenerateElements, 0u);
  EXPECT_EQ(r.total.freeElements, 0u);
  // README: median edge 4.46 mm, min 1.73, max 8.11 (over the element sides).
  EXPECT_NEAR(r.total.edgeLength.median, 4.46, 0.005);
  EXPECT_NEAR(r.total.edgeLength.min, 1.73, 0.005);
  EXPECT_NEAR(r.total.edgeLength.max, 8.11, 0.005);
  const PartReport* bracket = nullptr;
  for (const PartReport& part : r.parts)
    if (part.id == 4075) bracket = &part;
  ASSERT_NE(bracket, nullptr);
  EXPECT_EQ(bracket->stats.shells(), 1865u);
  EXPECT_EQ(bracket->stats.boundaryEdges, 288u);
  // Car coordinates around x = 3000 mm.
  EXPECT_GT(bracket->stats.box.min[0], 2900.0);
  EXPECT_LT(bracket->stats.box.max[0], 3400.0);
  expectPartsAddUp(r);
}

TEST(DeckReportDecks, BirdsSphParticlesAreUnusedNodes) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "bird.k");
  const DeckReport r = reportOf(path);
  EXPECT_EQ(r.total.shells(), 960u);
  // Every *ELEMENT_SPH card names one node that no shell uses.
  const std::string text = test::readText(path);
  io::LineCursor lines(text);
  std::size_t particles = 0;
  bool inSph = false;
  while (lines.next()) {
    const std::string_view line = lines.line();
    if (!line.empty() && line[0] == '*')
      inSph = io::istartsWith(line, "*ELEMENT_SPH");
    else if (inSph && !line.empty() && line[0] != '$')
      ++particles;
  }
  ASSERT_GT(particles, 0u);
  EXPECT_EQ(r.unusedNodes, particles);
  EXPECT_EQ(r.modelNodes, r.total.nodes + particles);
  expectPartsAddUp(r);
  EXPECT_NE(formatReportTable(r).find("SPH particles"), std::string::npos);
}
