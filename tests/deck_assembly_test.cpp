// Deck assembly: remeshed parts put back into LS-DYNA, Nastran and Abaqus decks; new IDs, seams,
// node reference remapping and what stays byte for byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <vector>

#include "support/test_support.h"
#include "voxremesh/deck_assembly.h"
#include "voxremesh/deck_compare.h"
#include "voxremesh/io.h"

using namespace voxremesh;
using voxremesh::test::readText;
using voxremesh::test::scratchDir;
using voxremesh::test::writeText;

namespace {

// Two unit quads side by side: shell 1 of part 1 (nodes 1 2 5 4) and shell 2 of part 2
// (2 3 6 5); nodes 2 and 5 are the seam.
const char* const kDeck =
    "*KEYWORD\n"
    "*NODE\n"
    "       1             0.0             0.0             0.0\n"
    "       2             1.0             0.0             0.0\n"
    "       3             2.0             0.0             0.0\n"
    "       4             0.0             1.0             0.0\n"
    "       5             1.0             1.0             0.0\n"
    "       6             2.0             1.0             0.0\n"
    "*ELEMENT_SHELL\n"
    "       1       1       1       2       5       4\n"
    "       2       2       2       3       6       5\n"
    "*SET_NODE_LIST\n"
    "$#     sid       da1\n"
    "         7       0.0       0.0       0.0       0.0\n"
    "         1         4         2\n"
    "*SET_NODE_LIST_GENERATE\n"
    "         8\n"
    "         1         1\n"
    "*CONSTRAINED_WIDGET_NODE\n"
    "         4\n"
    "*ELEMENT_MASS\n"
    "   90000       2             1.0       0\n"
    "*DATABASE_HISTORY_NODE\n"
    "1,5\n"
    "*END\n";

/// The new mesh of part 1: two quads over the old one, its first point moved by 0.05.
QuadMesh newPartOne() {
  QuadMesh mesh;
  mesh.part = 1;
  mesh.points = {{0.05, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 1, 0}, {1, 1, 0}};
  mesh.faces = {{0, 1, 4, 3}, {1, 2, 5, 4}};
  return mesh;
}

/// The verbatim block whose text starts with `keyword` followed by a line end.
const DeckBlock& block(const FeModel& model, const std::string& keyword) {
  for (const DeckBlock& b : model.blocks)
    if (b.kind == DeckBlock::Kind::Verbatim && b.text.rfind(keyword + "\n", 0) == 0) return b;
  throw std::runtime_error("no block " + keyword);
}

/// Two unit quads side by side on nodes 1..6 (x = 0, 1, 2; y = 0, 1): shell 1 of `partA`, shell 2
/// of `partB`.
FeModel twoQuads(Id partA, Id partB) {
  FeModel model;
  model.sourceFormat = DeckFormat::LsDyna;
  for (Id i = 1; i <= 6; ++i)
    test::addNode(model, i, static_cast<double>((i - 1) % 3), static_cast<double>((i - 1) / 3));
  test::addShell(model, 1, partA, {1, 2, 5, 4});
  test::addShell(model, 2, partB, {2, 3, 6, 5});
  return model;
}

/// A Nastran deck of a 2 x 2 plate of unit quads in part 1 (grid (i, j): ID 1 + i + 3 j at
/// (i, j, 0); shell (i, j): ID 1 + i + 2 j), with `cards` after its shells.
std::string nastranPlateDeck(const std::string& cards) {
  std::string deck = "BEGIN BULK\n";
  char line[96];
  for (int n = 0; n < 9; ++n) {
    std::snprintf(line, sizeof line, "GRID    %8d        %8.1f%8.1f%8.1f\n", n + 1, double(n % 3),
                  double(n / 3), 0.0);
    deck += line;
  }
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 1 + i + 3 * j;
      std::snprintf(line, sizeof line, "CQUAD4  %8d       1%8d%8d%8d%8d\n", 1 + i + 2 * j, a, a + 1,
                    a + 4, a + 3);
      deck += line;
    }
  return deck + cards +
         "PSHELL         1       1     1.0\nMAT1           1  2.1+5            .3\nENDDATA\n";
}

/// The new mesh of that plate: cells x cells quads over [0, 2] x [0, 2] in part `part` (point
/// (i, j): index i + (cells + 1) j; face (i, j): index i + cells j).
QuadMesh plateMesh(int cells, Id part) {
  QuadMesh mesh;
  mesh.part = part;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) mesh.points.push_back({2.0 * i / cells, 2.0 * j / cells, 0.0});
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const CornerIndex a = CornerIndex(i + (cells + 1) * j), row = CornerIndex(cells + 1);
      mesh.faces.push_back({a, a + 1, a + row + 1, a + row});
    }
  return mesh;
}

std::map<Id, std::array<double, 3>> nodesById(const FeModel& model) {
  std::map<Id, std::array<double, 3>> nodes;
  for (const Node& node : model.nodes) nodes[node.id] = node.xyz;
  return nodes;
}

}  // namespace

TEST(DeckAssembly, LsDynaSeamIdsAndRemaps) {
  const auto dir = scratchDir("assembly_lsdyna");
  writeText(dir / "in.k", kDeck);
  FeModel model = readDeck(dir / "in.k");
  const FeModel before = model;
  const AssemblyReport report = replacePartMeshes(model, {newPartOne()});

  // New nodes from 7; the seam points at (1,0,0) and (1,1,0) are the kept nodes 2 and 5.
  EXPECT_EQ(report.firstNewNodeId, 7);
  EXPECT_EQ(report.newNodes, 4u);
  EXPECT_EQ(report.seamPoints, 2u);
  // Element IDs above the *ELEMENT_MASS ID 90000.
  EXPECT_EQ(report.firstNewElementId, 90001);
  ASSERT_EQ(model.shells.size(), 3u);
  EXPECT_EQ(model.shells[0].id, 2);  // the kept shell first
  EXPECT_EQ(model.shells[1].id, 90001);
  EXPECT_EQ(model.shells[1].part, 1);
  EXPECT_EQ((std::array<Id, 4>{7, 8, 10, 9}), model.shells[1].nodes);
  EXPECT_EQ((std::array<Id, 4>{8, 2, 5, 10}), model.shells[2].nodes);

  // The history node 1 is a point: the nearest new node 7 (at 0.05) takes it. The list of
  // nodes 1, 4 and 2 is a region, the two sides of part 1 from node 1 to 2 and to 4: the new
  // nodes on them join it (7 and 8 on the bottom, 9 at node 4), each from its nearest member.
  ASSERT_EQ(report.remaps.size(), 4u);
  EXPECT_EQ(report.remaps[0].keyword, "*DATABASE_HISTORY_NODE");
  EXPECT_EQ(report.remaps[0].oldNode, 1);
  EXPECT_EQ(report.remaps[0].newNode, 7);
  EXPECT_NEAR(report.remaps[0].distance, 0.05, 1e-15);
  const std::array<std::pair<Id, Id>, 3> setRemaps{{{1, 7}, {1, 8}, {4, 9}}};
  for (std::size_t k = 0; k < setRemaps.size(); ++k) {
    const NodeRemap& remap = report.remaps[k + 1];
    EXPECT_EQ(remap.keyword, "*SET_NODE_LIST");
    EXPECT_EQ(std::make_pair(remap.oldNode, remap.newNode), setRemaps[k]);
    EXPECT_EQ(remap.line, 15u);
    EXPECT_FALSE(remap.blockLine);
  }
  EXPECT_EQ(report.remaps[3].distance, 0.0);
  ASSERT_EQ(report.unmapped.size(), 2u);
  EXPECT_EQ(report.unmapped[0].keyword, "*SET_NODE_LIST_GENERATE");
  EXPECT_EQ(report.unmapped[0].node, 1);
  EXPECT_EQ(report.unmapped[0].line, 18u);
  EXPECT_EQ(report.unmapped[1].keyword, "*CONSTRAINED_WIDGET_NODE");
  EXPECT_EQ(report.unmapped[1].node, 4);
  EXPECT_EQ(report.keptOldNodes, 2u);
  EXPECT_EQ(report.removedNodes, 0u);
  const auto nodes = nodesById(model);
  EXPECT_TRUE(nodes.count(1) && nodes.count(4));

  // Rewritten fields keep their columns; the other blocks are unchanged.
  EXPECT_EQ(block(model, "*SET_NODE_LIST").text,
            "*SET_NODE_LIST\n"
            "$#     sid       da1\n"
            "         7       0.0       0.0       0.0       0.0\n"
            "         7         8         2\n"
            "         9\n");
  EXPECT_EQ(block(model, "*DATABASE_HISTORY_NODE").text, "*DATABASE_HISTORY_NODE\n7,5\n");
  for (const char* keyword :
       {"*SET_NODE_LIST_GENERATE", "*CONSTRAINED_WIDGET_NODE", "*ELEMENT_MASS", "*END"})
    EXPECT_EQ(block(model, keyword).text, block(before, keyword).text) << keyword;

  // The written deck reads back with the new mesh.
  writeDeck(model, dir / "out.k");
  const FeModel back = readDeck(dir / "out.k");
  EXPECT_EQ(back.shells.size(), 3u);
  EXPECT_EQ(back.nodes.size(), model.nodes.size());
  EXPECT_NE(readText(dir / "out.k").find("         7         8         2\n         9\n"),
            std::string::npos);
}

TEST(DeckAssembly, NodeSetsAndInitialVelocitiesCoverTheSameRegionOfTheNewMesh) {
  // A 2 x 2 plate of unit quads (node (i, j): ID 1 + i + 3 j, velocity 10 x its ID) remeshed as
  // 3 x 3 quads of side 2/3. The set of the side x = 0 must become the new nodes on that side;
  // every new node must get one velocity line, with the data of its nearest old node.
  std::string deck = "*KEYWORD\n*NODE\n";
  char line[96];
  for (int n = 0; n < 9; ++n) {
    std::snprintf(line, sizeof line, "%8d%16.3f%16.3f%16.3f\n", n + 1, double(n % 3), double(n / 3),
                  0.0);
    deck += line;
  }
  deck += "*ELEMENT_SHELL\n";
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 1 + i + 3 * j;
      std::snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8d\n", 1 + i + 2 * j, 1, a, a + 1, a + 4,
                    a + 3);
      deck += line;
    }
  deck += "*SET_NODE_LIST\n         3\n         1         4         7\n*INITIAL_VELOCITY_NODE\n";
  for (int n = 1; n <= 9; ++n) {
    std::snprintf(line, sizeof line, "%10d%10.1f%10.1f\n", n, 10.0 * n, -1.0);
    deck += line;
  }
  deck += "*END\n";
  const auto dir = scratchDir("assembly_regions");
  writeText(dir / "in.k", deck);
  FeModel model = readDeck(dir / "in.k");
  const QuadMesh mesh = plateMesh(3, 1);
  const AssemblyReport report = replacePartMeshes(model, {mesh});
  EXPECT_EQ(report.removedNodes, 9u);
  EXPECT_TRUE(report.unmapped.empty());
  writeDeck(model, dir / "out.k");
  const FeModel back = readDeck(dir / "out.k");
  const auto nodes = nodesById(back);
  ASSERT_EQ(nodes.size(), 16u);
  const auto dataLines = [&](const std::string& keyword) {
    std::vector<std::string> lines;
    const std::string& text = block(back, keyword).text;
    std::size_t at = text.find('\n') + 1;
    while (at < text.size()) {
      const std::size_t end = text.find('\n', at);
      lines.push_back(text.substr(at, end - at));
      at = end + 1;
    }
    return lines;
  };
  std::set<Id> members;
  const std::vector<std::string> setLines = dataLines("*SET_NODE_LIST");
  for (std::size_t k = 1; k < setLines.size(); ++k) {  // after the set's ID
    const std::string& row = setLines[k];
    for (std::size_t c = 0; c < row.size(); c += 10) {
      const std::string field = row.substr(c, 10);
      if (field.find_first_not_of(' ') != std::string::npos) members.insert(std::stoll(field));
    }
  }
  std::set<Id> onTheSide;
  for (const auto& [id, xyz] : nodes)
    if (xyz[0] == 0.0) onTheSide.insert(id);
  EXPECT_EQ(onTheSide.size(), 4u);
  EXPECT_EQ(members, onTheSide);
  std::map<Id, double> velocity;
  for (const std::string& row : dataLines("*INITIAL_VELOCITY_NODE")) {
    const Id id = std::stoll(row.substr(0, 10));
    EXPECT_TRUE(velocity.emplace(id, std::stod(row.substr(10, 10))).second) << "twice: " << id;
    EXPECT_EQ(row.substr(20), "      -1.0");
  }
  ASSERT_EQ(velocity.size(), 16u);
  for (const auto& [id, xyz] : nodes) {
    ASSERT_TRUE(velocity.count(id)) << id;
    const long nearestOld = 1 + std::lround(xyz[0]) + 3 * std::lround(xyz[1]);
    EXPECT_EQ(velocity.at(id), 10.0 * double(nearestOld)) << id;
  }
}

TEST(DeckAssembly, UnreferencedOldNodesAreRemoved) {
  const auto dir = scratchDir("assembly_removed");
  std::string deck = kDeck;
  // Without the range and the unknown keyword, nodes 1 and 4 go.
  deck.replace(deck.find("*SET_NODE_LIST_GENERATE"),
               deck.find("*ELEMENT_MASS") - deck.find("*SET_NODE_LIST_GENERATE"), "");
  writeText(dir / "in.k", deck);
  FeModel model = readDeck(dir / "in.k");
  const AssemblyReport report = replacePartMeshes(model, {newPartOne()});
  EXPECT_TRUE(report.unmapped.empty());
  EXPECT_EQ(report.removedNodes, 2u);
  const auto nodes = nodesById(model);
  EXPECT_EQ(nodes.count(1) + nodes.count(4), 0u);
  EXPECT_EQ(nodes.size(), 8u);  // 2 3 5 6 kept, 7..10 new
}

TEST(DeckAssembly, JunctionPointsOfTwoRemeshedPartsBecomeOneNode) {
  FeModel model = twoQuads(1, 2);
  QuadMesh a, b;
  a.part = 1;
  a.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  a.faces = {{0, 1, 2, 3}};
  a.constraints.assign(4, PointConstraint{});
  a.constraints[1].role = a.constraints[2].role = PointRole::Junction;
  b.part = 2;
  b.points = {{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}};
  b.faces = {{0, 1, 2, 3}};
  b.constraints.assign(4, PointConstraint{});
  b.constraints[0].role = b.constraints[3].role = PointRole::Junction;
  const AssemblyReport report = replacePartMeshes(model, {a, b});
  EXPECT_EQ(report.mergedJunctionPoints, 2u);
  EXPECT_EQ(report.newNodes, 6u);
  EXPECT_EQ(report.removedNodes, 6u);
  ASSERT_EQ(model.shells.size(), 2u);
  EXPECT_EQ(model.shells[0].nodes[1], model.shells[1].nodes[0]);
  EXPECT_EQ(model.shells[0].nodes[2], model.shells[1].nodes[3]);
  EXPECT_EQ(model.nodes.size(), 6u);
  EXPECT_EQ(model.nodes.front().id, 7);
  // Without the Junction role, coincident points stay apart.
  FeModel again = twoQuads(1, 2);
  a.constraints.clear();
  EXPECT_EQ(replacePartMeshes(again, {a, b}).mergedJunctionPoints, 0u);
}

TEST(DeckAssembly, TypesAndExtrasComeFromTheOldShells) {
  FeModel model = twoQuads(1, 1);
  const std::uint8_t thick = model.internShellType("_THICKNESS");
  for (Shell& shell : model.shells) shell.type = thick;
  model.shellExtras.resize(2);
  model.shellExtras[0].thickness = {1, 1, 1, 1};
  model.shellExtras[1].thickness = {2, 2, 2, 2};
  model.shells[0].extras = 0;
  model.shells[1].extras = 1;
  QuadMesh mesh;
  mesh.part = 1;
  mesh.points = {{0, 0, 0}, {0.9, 0, 0}, {0.9, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  mesh.faces = {{0, 1, 2, 3}, {1, 4, 5, kNoCorner}};
  replacePartMeshes(model, {mesh});
  ASSERT_EQ(model.shells.size(), 2u);
  EXPECT_EQ(model.shells[0].type, thick);
  EXPECT_EQ(model.shells[0].extras, 0);  // centroid x 0.45: nearer the first old shell
  EXPECT_EQ(model.shells[1].extras, 1);
  EXPECT_EQ(model.shells[1].nodeCount, 3);
}

TEST(DeckAssembly, NastranFieldsAreRewrittenInTheirColumns) {
  const auto dir = scratchDir("assembly_nastran");
  writeText(dir / "in.bdf",
            "BEGIN BULK\n"
            "GRID           1              0.      0.      0.\n"
            "GRID           2              1.      0.      0.\n"
            "GRID           3              1.      1.      0.\n"
            "GRID           4              0.      1.      0.\n"
            "CQUAD4       101       1       1       2       3       4\n"
            "SPC1         100  123456       1       4\n"
            "RBE2        5000    9999  123456       4       1\n"
            "CONM2,6000,3,0,1.5\n"
            "SPC1         200     123       1    THRU       4\n"
            "PSHELL         1       1     1.0\n"
            "MAT1           1  2.1+5            .3\n"
            "ENDDATA\n");
  FeModel model = readDeck(dir / "in.bdf");
  QuadMesh mesh;
  mesh.part = 1;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.25}};
  mesh.faces = {{0, 1, 2, 3}};
  const AssemblyReport report = replacePartMeshes(model, {mesh});
  EXPECT_EQ(report.firstNewNodeId, 5);
  EXPECT_EQ(report.firstNewElementId, 6001);  // above the CONM2 EID 6000
  ASSERT_EQ(report.remaps.size(), 5u);
  ASSERT_EQ(report.unmapped.size(), 4u);  // SPC1 THRU covers 1..4
  EXPECT_EQ(report.unmapped[0].keyword, "SPC1");
  // Every report names the card and its line: the points first, then the SPC1 list of the side
  // from node 1 to 4 (a region: the new nodes 5 and 8 on that side). The Nastran reader does not
  // record where a verbatim block stood in the file (DeckBlock::line 0), so the line is the one
  // within the block (blockLine): the block starts at the SPC1 of file line 7.
  const std::vector<std::pair<std::string, std::size_t>> where = {
      {"RBE2", 2}, {"RBE2", 2}, {"CONM2", 3}, {"SPC1", 1}, {"SPC1", 1}};
  for (std::size_t i = 0; i < where.size(); ++i) {
    EXPECT_EQ(report.remaps[i].keyword, where[i].first) << i;
    EXPECT_EQ(report.remaps[i].line, where[i].second) << i;
    EXPECT_TRUE(report.remaps[i].blockLine) << i;
  }
  for (const UnmappedReference& ref : report.unmapped) {
    EXPECT_EQ(ref.line, 4u);
    EXPECT_TRUE(ref.blockLine);
  }
  writeDeck(model, dir / "out.bdf");
  const std::string out = readText(dir / "out.bdf");
  EXPECT_NE(out.find("SPC1         100  123456       5       8\n"), std::string::npos) << out;
  EXPECT_NE(out.find("RBE2        5000    9999  123456       8       5\n"), std::string::npos)
      << out;
  EXPECT_NE(out.find("CONM2,6000,7,0,1.5\n"), std::string::npos) << out;
  EXPECT_NE(out.find("SPC1         200     123       1    THRU       4\n"), std::string::npos);
  const FeModel back = readDeck(dir / "out.bdf");
  EXPECT_EQ(back.shells.size(), 1u);
}

TEST(DeckAssembly, ANodeOfAKeptPartThatOnlyCoincidesWithANewPointStaysApart) {
  // Grid 2 (a corner of part 1's quad) and grid 5 (a corner of part 2's quad) lie at the same
  // place, joined by an RBE2 only. Part 1 is remeshed with a point there: the point keeps the
  // hard point's ID 2, not the kept part's node 5, so the parts stay unconnected and the RBE2
  // still joins two nodes.
  const auto dir = scratchDir("assembly_coincident_rbe2");
  writeText(dir / "in.bdf",
            "BEGIN BULK\n"
            "GRID           1              0.      0.      0.\n"
            "GRID           2              1.      0.      0.\n"
            "GRID           3              1.      1.      0.\n"
            "GRID           4              0.      1.      0.\n"
            "GRID           5              1.      0.      0.\n"
            "GRID           6              2.      0.      0.\n"
            "GRID           7              2.      1.      0.\n"
            "GRID           8              1.      1.      1.\n"
            "CQUAD4       101       1       1       2       3       4\n"
            "CQUAD4       102       2       5       6       7       8\n"
            "RBE2        5000       5  123456       2\n"
            "PSHELL         1       1     1.0\n"
            "PSHELL         2       1     1.0\n"
            "MAT1           1  2.1+5            .3\n"
            "ENDDATA\n");
  FeModel model = readDeck(dir / "in.bdf");
  QuadMesh mesh;
  mesh.part = 1;
  mesh.points = {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5, 1, 0}, {0, 1, 0}};
  mesh.faces = {{0, 1, 4, 5}, {1, 2, 3, 4}};
  const AssemblyReport report = replacePartMeshes(model, {mesh}, {2});
  EXPECT_EQ(report.hardPointsKept, 1u);
  EXPECT_EQ(report.seamPoints, 0u);
  for (const Shell& shell : model.shells) {
    if (shell.part != 1) continue;
    const auto end = shell.nodes.begin() + shell.nodeCount;
    EXPECT_EQ(std::find(shell.nodes.begin(), end, Id(5)), end) << "shell " << shell.id;
  }
  writeDeck(model, dir / "out.bdf");
  const std::string out = readText(dir / "out.bdf");
  EXPECT_NE(out.find("RBE2        5000       5  123456       2\n"), std::string::npos) << out;
}

TEST(DeckAssembly, NastranSetAndSpcListsCoverTheSameRegionOfTheNewMesh) {
  // A 2 x 2 plate of unit quads remeshed as 3 x 3 quads of side 2/3: the SET1 of all 9 grids (on
  // a continuation line) must list the 16 new grids, the free-format SPC1 of the side x = 0 the
  // 4 new grids on that side.
  const std::string deck = nastranPlateDeck(
      "SET1          77       1       2       3       4       5       6       7\n"
      "               8       9\n"
      "SPC1,88,123,1,4,7\n");
  const auto dir = scratchDir("assembly_nastran_regions");
  writeText(dir / "in.bdf", deck);
  FeModel model = readDeck(dir / "in.bdf");
  const QuadMesh mesh = plateMesh(3, 1);
  const AssemblyReport report = replacePartMeshes(model, {mesh});
  EXPECT_EQ(report.removedNodes, 9u);
  EXPECT_TRUE(report.unmapped.empty());
  writeDeck(model, dir / "out.bdf");
  const std::string out = readText(dir / "out.bdf");
  const auto nodes = nodesById(readDeck(dir / "out.bdf"));
  ASSERT_EQ(nodes.size(), 16u);
  // The IDs of a card: its lines up to the next card, small fields 2..9 or commas after field 3.
  const auto listed = [&](const std::string& start, bool commas) {
    std::multiset<Id> ids;
    std::size_t at = out.find(start);
    if (at == std::string::npos) return ids;
    for (bool first = true; at < out.size(); first = false) {
      const std::size_t end = out.find('\n', at);
      const std::string row = out.substr(at, end - at);
      if (!first && row[0] != ' ' && row[0] != '+' && row[0] != ',') break;
      if (commas) {
        std::size_t field = 0, begin = 0;
        for (std::size_t c = 0; c <= row.size(); ++c)
          if (c == row.size() || row[c] == ',') {
            const std::string token = row.substr(begin, c - begin);
            if (field >= (first ? 3u : 1u) && token.find_first_not_of(' ') != std::string::npos)
              ids.insert(std::stoll(token));
            ++field;
            begin = c + 1;
          }
      } else {
        for (std::size_t c = first ? 16 : 8; c < std::min<std::size_t>(row.size(), 72); c += 8) {
          const std::string token = row.substr(c, 8);
          if (token.find_first_not_of(' ') != std::string::npos) ids.insert(std::stoll(token));
        }
      }
      at = end + 1;
    }
    return ids;
  };
  std::multiset<Id> all, side;
  for (const auto& [id, xyz] : nodes) {
    all.insert(id);
    if (xyz[0] == 0.0) side.insert(id);
  }
  EXPECT_EQ(listed("SET1          77", false), all) << out;
  EXPECT_EQ(listed("SPC1,88,123,", true), side) << out;
}

TEST(DeckAssembly, ALongSetListCoversTheNewMeshPastItsFourthLine) {
  // A SET1 as a spline's structural grids are listed: 40 grids off the plate (101..140) on its
  // first five lines, then the plate's 9 grids on the sixth and seventh (data fields 40 to 48).
  // The plate is remeshed: the set must list the 40 grids and the 16 new ones, and no old grid
  // of the plate may stay behind, kept for a reference that could not be rewritten.
  std::string cards;
  char line[96];
  for (int n = 101; n <= 140; ++n) {
    std::snprintf(line, sizeof line, "GRID    %8d        %8.1f%8.1f%8.1f\n", n, double(n), 5.0,
                  0.0);
    cards += line;
  }
  std::string set = "SET1          77";
  for (int k = 0; k < 49; ++k) {
    if (k > 0 && k % 8 == 7) set += "\n        ";
    std::snprintf(line, sizeof line, "%8d", k < 40 ? 101 + k : k - 39);
    set += line;
  }
  const auto dir = scratchDir("assembly_nastran_long_set");
  writeText(dir / "in.bdf", nastranPlateDeck(cards + set + "\n"));
  FeModel model = readDeck(dir / "in.bdf");
  const AssemblyReport report = replacePartMeshes(model, {plateMesh(3, 1)});
  EXPECT_EQ(report.removedNodes, 9u);
  EXPECT_TRUE(report.unmapped.empty());
  EXPECT_EQ(report.keptOldNodes, 0u);
  writeDeck(model, dir / "out.bdf");
  const FeModel back = readDeck(dir / "out.bdf");
  std::set<Id> expected;
  for (const Node& node : back.nodes) expected.insert(node.id);
  // The set's members in the written deck: the integers of its lines after the card's name
  // and ID, up to the next card.
  const std::string out = readText(dir / "out.bdf");
  std::set<Id> listed;
  std::size_t at = out.find("SET1          77");
  ASSERT_NE(at, std::string::npos) << out;
  for (bool first = true; at < out.size(); first = false) {
    const std::size_t end = out.find('\n', at);
    const std::string row = out.substr(at, end - at);
    if (!first && row[0] != ' ') break;
    for (std::size_t c = first ? 16 : 8; c < std::min<std::size_t>(row.size(), 72); c += 8) {
      const std::string token = row.substr(c, 8);
      if (token.find_first_not_of(' ') != std::string::npos) listed.insert(std::stoll(token));
    }
    at = end + 1;
  }
  EXPECT_EQ(listed, expected) << out;
  EXPECT_EQ(listed.size(), 56u);
}

TEST(DeckAssembly, PressureLoadsOnRemovedShellsGoToTheNewShellsOnThem) {
  // A 2 x 2 plate of unit quads (shells 1..4) remeshed as 4 x 4 quads of side 1/2. PLOAD4 of 5.0
  // on shell 1 and of 7.0 (with a continuation line) on shell 4: each new shell whose centroid
  // lies on shell 1 or 4 gets that card with its own ID, and no card names a removed shell.
  const std::string deck = nastranPlateDeck(
      "PLOAD4         9       1     5.0\n"
      "PLOAD4         9       4     7.0                                        +\n"
      "+              0      0.      0.     -1.\n");
  const auto dir = scratchDir("assembly_nastran_loads");
  writeText(dir / "in.bdf", deck);
  FeModel model = readDeck(dir / "in.bdf");
  const QuadMesh mesh = plateMesh(4, 1);
  const AssemblyReport report = replacePartMeshes(model, {mesh});
  EXPECT_EQ(report.elementLoadsRewritten, 2u);
  EXPECT_TRUE(report.unmapped.empty()) << "an element ID is no node reference";
  writeDeck(model, dir / "out.bdf");
  const std::string out = readText(dir / "out.bdf");
  // The expected cards: new shell (i, j) has ID first + i + 4 j and its centroid at
  // (0.5 i + 0.25, 0.5 j + 0.25): on old shell 1 when both are below 1, on 4 when both above.
  std::multiset<std::string> expected, found;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const Id id = report.firstNewElementId + i + 4 * j;
      if (i < 2 && j < 2) expected.insert(std::to_string(id) + " 5.0");
      if (i >= 2 && j >= 2) expected.insert(std::to_string(id) + " 7.0 -1.");
    }
  const auto field = [](const std::string& row, std::size_t k) {
    const std::string text = row.size() > 8 * k ? row.substr(8 * k, 8) : std::string();
    const std::size_t first = text.find_first_not_of(' ');
    return first == std::string::npos ? std::string()
                                      : text.substr(first, text.find(' ', first) - first);
  };
  std::vector<std::string> rows;
  for (std::size_t at = 0; at < out.size();) {
    const std::size_t end = out.find('\n', at);
    rows.push_back(out.substr(at, end - at));
    at = end + 1;
  }
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (rows[r].rfind("PLOAD4", 0) != 0) continue;
    std::string entry = field(rows[r], 2) + " " + field(rows[r], 3);
    if (r + 1 < rows.size() && rows[r + 1][0] == '+') entry += " " + field(rows[r + 1], 4);
    found.insert(entry);
  }
  EXPECT_EQ(found, expected) << out;
}

TEST(DeckAssembly, PressuresOnShellsANewShellStraddlesAreSharedSoTheTotalForceStays) {
  // A 2 x 2 plate of unit quads with pressures 1, 2, 3 and 4 (the last in large fields, the
  // third in free format) remeshed as 3 x 3 quads of side 2/3: the middle row and column
  // straddle two or four old shells. Each new shell gets one card per old shell under it, its
  // pressure times the share of the shell on it, so that the total force (10) stays.
  const std::string deck = nastranPlateDeck(
      "PLOAD4         9       1     1.0\n"
      "PLOAD4         9       2     2.0     2.0     2.0     2.0\n"
      "PLOAD4,9,3,3.0\n"
      "PLOAD4*                9               4             4.0\n");
  const auto dir = scratchDir("assembly_nastran_shared_loads");
  writeText(dir / "in.bdf", deck);
  FeModel model = readDeck(dir / "in.bdf");
  const FeModel before = model;
  const AssemblyReport report = replacePartMeshes(model, {plateMesh(3, 1)});
  EXPECT_EQ(report.elementLoadsRewritten, 4u);
  writeDeck(model, dir / "out.bdf");
  const DeckComparison comparison = compareDecks(before, readDeck(dir / "out.bdf"));
  EXPECT_EQ(comparison.loadCardsBefore, 4u);
  EXPECT_EQ(comparison.loadCardsAfter, 16u);  // 4 corner + 4 x 2 edge + 4 centre cards
  EXPECT_NEAR(comparison.forceBefore[2], 10.0, 1e-12);
  EXPECT_NEAR(comparison.forceAfter[2], 10.0, 1e-6) << readText(dir / "out.bdf");
  EXPECT_TRUE(comparison.dangling.empty())
      << formatComparisonTable(comparison) << readText(dir / "out.bdf");
}

/// The integers of the data lines of `text` after its first `skipLines` lines (comments, those
/// starting with '$' or "**", left out), in order.
std::vector<Id> integersAfter(const std::string& text, std::size_t skipLines) {
  std::vector<Id> values;
  std::size_t line = 0;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    const std::string row = text.substr(at, end - at);
    at = end + 1;
    if (row.empty() || row[0] == '$' || row.rfind("**", 0) == 0) continue;
    if (line++ < skipLines) continue;
    std::string token;
    for (const char c : row + ",") {
      if (c == ',' || c == ' ') {
        if (!token.empty() && token.find_first_not_of("0123456789") == std::string::npos)
          values.push_back(std::stoll(token));
        token.clear();
      } else {
        token += c;
      }
    }
  }
  return values;
}

/// The IDs of the new shells of plateMesh(4, ...) whose face (i, j) satisfies `inside`.
std::vector<Id> newShellsWhere(Id firstNew, const std::function<bool(int, int)>& inside) {
  std::vector<Id> ids;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      if (inside(i, j)) ids.push_back(firstNew + i + 4 * j);
  std::sort(ids.begin(), ids.end());
  return ids;
}

TEST(DeckAssembly, LsDynaShellSetsAndShellLoadsCoverTheSameRegionOfTheNewMesh) {
  // A 2 x 2 plate of unit quads (shells 1..4, shell (i, j) = 1 + i + 2 j) remeshed as 4 x 4:
  // the set of the bottom row (shells 1 and 2) lists the 8 new shells on it, the pressure on
  // shell 4 goes to the 4 new shells on it, and the GENERATE range cannot be rewritten.
  std::string deck = "*KEYWORD\n*NODE\n";
  char line[96];
  for (int n = 0; n < 9; ++n) {
    std::snprintf(line, sizeof line, "%8d%16.1f%16.1f%16.1f\n", n + 1, double(n % 3), double(n / 3),
                  0.0);
    deck += line;
  }
  deck += "*ELEMENT_SHELL\n";
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 1 + i + 3 * j;
      std::snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8d\n", 1 + i + 2 * j, 1, a, a + 1, a + 4,
                    a + 3);
      deck += line;
    }
  deck +=
      "*SET_SHELL_LIST\n"
      "         5\n"
      "         1         2\n"
      "*SET_SHELL_LIST_GENERATE\n"
      "         6\n"
      "         3         4\n"
      "*LOAD_SHELL_ELEMENT\n"
      "$#     eid      lcid        sf        at\n"
      "         4         1       2.5       0.0\n"
      "*DATABASE_HISTORY_SHELL\n"
      "         3         4\n"
      "*DATABASE_HISTORY_SHELL_ID\n"
      "         1corner\n"
      "*SET_SEGMENT\n"
      "         7\n"
      "         1         2         5         4\n"
      "*END\n";
  const auto dir = scratchDir("assembly_lsdyna_shell_sets");
  writeText(dir / "in.k", deck);
  FeModel model = readDeck(dir / "in.k");
  const AssemblyReport report = replacePartMeshes(model, {plateMesh(4, 1)});
  EXPECT_EQ(report.elementSetMembersRewritten, 4u);  // 2 in the set, 2 in the history list
  EXPECT_EQ(report.elementLoadsRewritten, 2u);       // the pressure and the history record
  // Shells 3 and 4 in the GENERATE range; the segment's four nodes (segments are not rewritten:
  // their nodes are kept, and each is reported; its set ID 7 is no node).
  ASSERT_EQ(report.unmapped.size(), 6u);
  std::map<std::string, std::set<Id>> unmapped;
  for (const auto& u : report.unmapped) unmapped[u.keyword].insert(u.node);
  EXPECT_EQ(unmapped["*SET_SHELL_LIST_GENERATE"], (std::set<Id>{3, 4}));
  EXPECT_EQ(unmapped["*SET_SEGMENT"], (std::set<Id>{1, 2, 4, 5}));

  std::vector<Id> members = integersAfter(block(model, "*SET_SHELL_LIST").text, 2);
  std::sort(members.begin(), members.end());
  EXPECT_EQ(members, newShellsWhere(report.firstNewElementId, [](int, int j) { return j < 2; }));
  const std::string loads = block(model, "*LOAD_SHELL_ELEMENT").text;
  std::vector<Id> loaded;
  const std::vector<Id> values = integersAfter(loads, 1);  // eid, lcid per line (2.5 is no integer)
  for (std::size_t k = 0; k < values.size(); k += 2) loaded.push_back(values[k]);
  std::sort(loaded.begin(), loaded.end());
  EXPECT_EQ(loaded,
            newShellsWhere(report.firstNewElementId, [](int i, int j) { return i >= 2 && j >= 2; }))
      << loads;
  EXPECT_EQ(std::count(loads.begin(), loads.end(), '\n'), 6) << loads;  // keyword, comment, 4
  // The history list of the top row lists the new shells on it; the history record of shell 1
  // is repeated, heading and all, for the 4 new shells on it.
  std::vector<Id> history = integersAfter(block(model, "*DATABASE_HISTORY_SHELL").text, 1);
  std::sort(history.begin(), history.end());
  EXPECT_EQ(history, newShellsWhere(report.firstNewElementId, [](int, int j) { return j >= 2; }));
  const std::string records = block(model, "*DATABASE_HISTORY_SHELL_ID").text;
  std::vector<Id> recorded;  // the I10 field before each heading
  for (std::size_t at = records.find('\n') + 1; at < records.size();) {
    recorded.push_back(std::stoll(records.substr(at, 10)));
    at = records.find('\n', at) + 1;
    if (at == 0) break;
  }
  std::sort(recorded.begin(), recorded.end());
  EXPECT_EQ(recorded,
            newShellsWhere(report.firstNewElementId, [](int i, int j) { return i < 2 && j < 2; }))
      << records;
  EXPECT_EQ(std::count(records.begin(), records.end(), 'c'), 4) << records;  // "corner" 4 times
}

TEST(DeckAssembly, AbaqusElementSetsAndDloadsCoverTheSameRegionOfTheNewMesh) {
  std::string deck = "*NODE\n";
  for (int n = 0; n < 9; ++n)
    deck += std::to_string(n + 1) + ", " + std::to_string(n % 3) + ".0, " + std::to_string(n / 3) +
            ".0, 0.0\n";
  deck += "*ELEMENT, TYPE=S4, ELSET=PLATE\n";
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 1 + i + 3 * j;
      deck += std::to_string(1 + i + 2 * j) + ", " + std::to_string(a) + ", " +
              std::to_string(a + 1) + ", " + std::to_string(a + 4) + ", " + std::to_string(a + 3) +
              "\n";
    }
  deck +=
      "*ELSET, ELSET=LEFT\n"
      "1, 3\n"
      "*DLOAD\n"
      "2, P, 0.5\n";
  const auto dir = scratchDir("assembly_abaqus_elsets");
  writeText(dir / "in.inp", deck);
  FeModel model = readDeck(dir / "in.inp");
  ASSERT_EQ(model.shells.size(), 4u);
  const AssemblyReport report = replacePartMeshes(model, {plateMesh(4, model.shells[0].part)});
  EXPECT_EQ(report.elementSetMembersRewritten, 2u);
  EXPECT_EQ(report.elementLoadsRewritten, 1u);
  EXPECT_TRUE(report.unmapped.empty());
  writeDeck(model, dir / "out.inp");
  const std::string out = readText(dir / "out.inp");
  const std::size_t elset = out.find("*ELSET, ELSET=LEFT\n");
  const std::size_t dload = out.find("*DLOAD\n");
  ASSERT_NE(elset, std::string::npos) << out;
  ASSERT_NE(dload, std::string::npos) << out;
  std::vector<Id> members = integersAfter(out.substr(elset, dload - elset), 1);
  std::sort(members.begin(), members.end());
  EXPECT_EQ(members, newShellsWhere(report.firstNewElementId, [](int i, int) { return i < 2; }))
      << out;
  std::vector<Id> loaded = integersAfter(out.substr(dload), 1);
  std::sort(loaded.begin(), loaded.end());
  EXPECT_EQ(loaded,
            newShellsWhere(report.firstNewElementId, [](int i, int j) { return i >= 2 && j < 2; }))
      << out;
}

/// The hard points (hardPointNodes over all its grids) of the plate of nastranPlateDeck with
/// `cards`, written in a scratch folder `name`.
std::unordered_set<Id> plateHardPoints(const std::string& name, const std::string& cards) {
  const auto dir = scratchDir(name);
  writeText(dir / "in.bdf", nastranPlateDeck(cards));
  const FeModel model = readDeck(dir / "in.bdf");
  std::unordered_set<Id> all;
  for (const Node& node : model.nodes) all.insert(node.id);
  return hardPointNodes(model, all);
}

TEST(DeckAssembly, OnlyTheGridFieldsOfANastranCardAreHardPoints) {
  // CONM2 5 on grid 1, SPC 3 on grid 2: the element ID 5 and the set ID 3 are also grid IDs of
  // the plate, but no grids of these cards.
  EXPECT_EQ(plateHardPoints("assembly_nastran_grid_fields",
                            "CONM2          5       1             1.0\n"
                            "SPC            3       2     123\n"),
            (std::unordered_set<Id>{1, 2}));
}

TEST(DeckAssembly, TheGridsOfSupportsAreHardPointsButNotTheirComponents) {
  // SUPORT1 set 7 on grids 3 (components 12) and 4 (components 6), SUPORT on grid 5 (components
  // 1): a free body's supports stay on its structure. The set ID 7 and the components 1, 6
  // are grid IDs of the plate too, but no grids of these cards.
  EXPECT_EQ(plateHardPoints("assembly_nastran_supports",
                            "SUPORT1        7       3      12       4       6\n"
                            "SUPORT         5       1\n"),
            (std::unordered_set<Id>{3, 4, 5}));
}

TEST(DeckAssembly, AbaqusNsetAndBoundary) {
  const auto dir = scratchDir("assembly_abaqus");
  writeText(dir / "in.inp",
            "*NODE\n"
            "1, 0., 0., 0.\n"
            "2, 1., 0., 0.\n"
            "3, 1., 1., 0.\n"
            "4, 0., 1., 0.\n"
            "*ELEMENT, TYPE=S4R, ELSET=PLATE\n"
            "1, 1, 2, 3, 4\n"
            "*NSET, NSET=FIX\n"
            "1, 2, FIXSET\n"
            "*BOUNDARY\n"
            "3, 1, 6\n"
            "*NSET, NSET=GEN, GENERATE\n"
            "1, 4, 1\n");
  FeModel model = readDeck(dir / "in.inp");
  ASSERT_EQ(model.parts.size(), 1u);
  QuadMesh mesh;
  mesh.part = model.parts[0].id;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.faces = {{0, 1, 2, 3}};
  const AssemblyReport report = replacePartMeshes(model, {mesh});
  // The point first (*BOUNDARY), then the set of the side from node 1 to 2 (a region: the new
  // nodes 5 and 6 on it).
  ASSERT_EQ(report.remaps.size(), 3u);
  EXPECT_EQ(report.remaps[0].keyword, "*BOUNDARY");
  EXPECT_EQ(report.remaps[1].keyword, "*NSET");
  EXPECT_EQ(report.remaps[2].keyword, "*NSET");
  // Lines within the block (the Abaqus reader does not record where it stood; it starts at
  // the *NSET of file line 8).
  EXPECT_EQ(report.remaps[0].line, 4u);
  EXPECT_EQ(report.remaps[1].line, 2u);
  EXPECT_EQ(report.remaps[2].line, 2u);
  for (const NodeRemap& remap : report.remaps) EXPECT_TRUE(remap.blockLine);
  EXPECT_EQ(report.unmapped.size(), 4u);
  for (const UnmappedReference& ref : report.unmapped) {
    EXPECT_EQ(ref.keyword, "*NSET");
    EXPECT_EQ(ref.line, 6u);
    EXPECT_TRUE(ref.blockLine);
  }
  writeDeck(model, dir / "out.inp");
  const std::string out = readText(dir / "out.inp");
  EXPECT_NE(out.find("5, 6, FIXSET\n"), std::string::npos) << out;
  EXPECT_NE(out.find("7, 1, 6\n"), std::string::npos) << out;
  EXPECT_NE(out.find("1, 4, 1\n"), std::string::npos) << out;
  EXPECT_EQ(readDeck(dir / "out.inp").shells.size(), 1u);
}

TEST(DeckAssembly, AbaqusNodeSetsCoverTheSameRegionWithoutEmptyEntries) {
  // A 2 x 2 plate of unit quads remeshed finer (3 x 3 quads) and coarser (1 quad). The set of the
  // side x = 0 and the set of all nodes must list exactly the new nodes there; Abaqus reads no
  // empty entry, so a field left over (the coarser mesh) repeats a member.
  std::string deck = "*NODE\n";
  for (int n = 0; n < 9; ++n)
    deck += std::to_string(n + 1) + ", " + std::to_string(n % 3) + "., " + std::to_string(n / 3) +
            "., 0.\n";
  deck +=
      "*ELEMENT, TYPE=S4R, ELSET=PLATE\n1, 1, 2, 5, 4\n2, 2, 3, 6, 5\n3, 4, 5, 8, 7\n"
      "4, 5, 6, 9, 8\n*NSET, NSET=SIDE\n1, 4, 7\n*NSET, NSET=ALL\n1, 2, 3, 4, 5, 6, 7, 8, 9\n";
  const auto dir = scratchDir("assembly_abaqus_regions");
  writeText(dir / "in.inp", deck);
  for (const int cells : {3, 1}) {
    FeModel model = readDeck(dir / "in.inp");
    const QuadMesh mesh = plateMesh(cells, model.parts[0].id);
    replacePartMeshes(model, {mesh});
    writeDeck(model, dir / "out.inp");
    const std::string out = readText(dir / "out.inp");
    // The entries of a set's data lines (up to the next keyword), each non-empty.
    const auto members = [&](const std::string& name) {
      std::set<Id> ids;
      std::size_t at = out.find("*NSET, NSET=" + name + "\n");
      at = out.find('\n', at) + 1;
      while (at < out.size() && out[at] != '*') {
        const std::size_t end = out.find('\n', at);
        std::size_t begin = at;
        for (std::size_t c = at; c <= end; ++c)
          if (c == end || out[c] == ',') {
            const std::string token = out.substr(begin, c - begin);
            EXPECT_NE(token.find_first_not_of(' '), std::string::npos) << "an empty entry:\n"
                                                                       << out;
            if (token.find_first_not_of(' ') != std::string::npos) ids.insert(std::stoll(token));
            begin = c + 1;
          }
        at = end + 1;
      }
      return ids;
    };
    std::set<Id> all, side;
    for (const auto& [id, xyz] : nodesById(model)) {
      all.insert(id);
      if (xyz[0] == 0.0) side.insert(id);
    }
    EXPECT_EQ(all.size(), std::size_t((cells + 1) * (cells + 1)));
    EXPECT_EQ(members("SIDE"), side) << out;
    EXPECT_EQ(members("ALL"), all) << out;
  }
}

TEST(DeckAssembly, BadMeshesLeaveTheModelUnchanged) {
  FeModel model;
  model.sourceFormat = DeckFormat::LsDyna;
  for (Id i = 1; i <= 4; ++i)
    test::addNode(model, i, static_cast<double>((i - 1) % 2), static_cast<double>((i - 1) / 2));
  test::addShell(model, 1, 1, {1, 2, 4, 3});
  QuadMesh good;
  good.part = 1;
  good.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  good.faces = {{0, 1, 2, kNoCorner}};
  const auto expectRefused = [&](std::vector<QuadMesh> meshes, const std::string& text) {
    FeModel copy = model;
    try {
      replacePartMeshes(copy, meshes);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(text), std::string::npos) << error.what();
    }
    EXPECT_EQ(copy.shells.size(), 1u);
    EXPECT_EQ(copy.nodes.size(), 4u);
  };
  QuadMesh noPart = good;
  noPart.part = 0;
  expectRefused({noPart}, "part 0");
  QuadMesh missing = good;
  missing.part = 7;
  expectRefused({missing}, "part 7 has no shells");
  expectRefused({good, good}, "given twice");
  QuadMesh outOfRange = good;
  outOfRange.faces[0][2] = 3;
  expectRefused({outOfRange}, "names point 3");
  QuadMesh nan = good;
  nan.points[0][1] = std::numeric_limits<double>::quiet_NaN();
  expectRefused({nan}, "non-finite");
}

TEST(DeckAssembly, BirdKeepsSphAndEveryOtherKeyword) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "bird.k");
  FeModel model = readDeck(path);
  const FeModel before = model;
  std::set<Id> shellParts;
  for (const Shell& shell : model.shells) shellParts.insert(shell.part);
  std::vector<QuadMesh> meshes;
  for (const Id part : shellParts) meshes.push_back(quadMeshFromModel(model, part));
  const AssemblyReport report = replacePartMeshes(model, meshes);
  // The same surfaces again: every reference moves to a new node at distance 0.
  for (const NodeRemap& remap : report.remaps) EXPECT_EQ(remap.distance, 0.0);
  EXPECT_TRUE(report.unmapped.empty());
  // Only the keywords naming plate nodes change: the node set and the initial velocities.
  std::set<std::string> changed;
  ASSERT_EQ(model.blocks.size(), before.blocks.size());
  for (std::size_t b = 0; b < model.blocks.size(); ++b)
    if (model.blocks[b].text != before.blocks[b].text)
      changed.insert(model.blocks[b].text.substr(0, model.blocks[b].text.find('\n')));
  EXPECT_EQ(changed, (std::set<std::string>{"*INITIAL_VELOCITY_NODE", "*SET_NODE_LIST"}));
  EXPECT_FALSE(report.remaps.empty());
  EXPECT_EQ(model.shells.size(), before.shells.size());
  EXPECT_EQ(model.nodes.size(), before.nodes.size());
  const auto dir = scratchDir("assembly_bird");
  writeDeck(model, dir / "bird.k");
  const std::string out = readText(dir / "bird.k");
  const std::string in = readText(path);
  const auto blockOf = [](const std::string& text, const std::string& keyword) {
    const std::size_t begin = text.find("\n" + keyword + "\n");
    const std::size_t end = text.find("\n*", begin + 1);
    return text.substr(begin, end - begin);
  };
  EXPECT_EQ(blockOf(out, "*ELEMENT_SPH"), blockOf(in, "*ELEMENT_SPH"));
  EXPECT_EQ(blockOf(out, "*SET_NODE_LIST_GENERATE"), blockOf(in, "*SET_NODE_LIST_GENERATE"));
  EXPECT_EQ(blockOf(out, "*CONSTRAINED_EXTRA_NODES_SET"),
            blockOf(in, "*CONSTRAINED_EXTRA_NODES_SET"));
  EXPECT_EQ(readDeck(dir / "bird.k").shells.size(), before.shells.size());
}
