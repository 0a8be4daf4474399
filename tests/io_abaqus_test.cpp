// Abaqus input: geometry and verbatim content, *INCLUDE, NSET on *NODE, element continuation
// lines, part IDs and names through the writer, refusals and bad input with file and line.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "support/expect_input_error.h"
#include "support/test_support.h"
#include "voxremesh/errors.h"

namespace fs = std::filesystem;
using namespace voxremesh;

namespace {

using voxremesh::test::expectInputError;

fs::path put(const fs::path& dir, const std::string& name, const std::string& content) {
  const fs::path path = dir / name;
  fs::create_directories(path.parent_path());
  io::writeFileAtomically(path, content);
  return path;
}

bool hasWarning(const Warnings& warnings, const std::string& fragment) {
  return std::any_of(warnings.begin(), warnings.end(),
                     [&](const std::string& w) { return w.find(fragment) != std::string::npos; });
}

const std::string kHeading = "*HEADING\r\nSynthetic deck: a panel, a rib and a solid block\r\n";
const std::string kMaterial =
    "** Materials and sections: kept byte for byte\n"
    "*MATERIAL, NAME=STEEL\n"
    "*ELASTIC\n"
    "  210000.,   0.3   \r\n"
    "*DENSITY\n"
    "7.85e-9,\n"
    "*SHELL SECTION, ELSET=PANEL, MATERIAL=STEEL\n"
    "1.5, 5\n"
    "*MEMBRANE SECTION, ELSET=\"Rib Part\", MATERIAL=STEEL\n"
    "0.8,\n";
const std::string kSolid =
    "*ELEMENT, TYPE=C3D8R, ELSET=BLOCK\n"
    "100, 1, 2, 3, 4, 21, 22, 23, 24\n"
    "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL\n";
const std::string kStep =
    "*STEP, NAME=LOAD\n"
    "*STATIC\n"
    "0.1, 1.0\n"
    "*BOUNDARY\n"
    "ALLNODES, ENCASTRE\n"
    "*END STEP\n";

/// A deck with a panel (S4R, S3R with a continued element line), a membrane rib on a panel
/// edge (three faces on edge 2-3), elements without ELSET, a solid, materials and a step.
std::string syntheticDeck() {
  std::string nodes = "*NODE, NSET=ALLNODES\n";
  const double xyz[][3] = {{0, 0, 0},  {1, 0, 0},     {1, 1, 0},  {0, 1, 0}, {2, 0, 0},
                           {2, 1, 0},  {1.5, 1.5, 0}, {1, 0, 1},  {1, 1, 1}, {3, 0, 0},
                           {3, 1, 0},  {4, 0, 0},     {4, 1, 0},  {5, 0, 0}, {5, 1, 0},
                           {6, 0, 0},  {6, 1, 0},     {7, 0, 0},  {7, 1, 0}, {8, 0, 0},
                           {0, 0, -1}, {1, 0, -1},    {1, 1, -1}, {0, 1, -1}};
  for (int i = 0; i < 24; ++i) {
    nodes +=
        std::to_string(i + 1) + ", " + std::to_string(xyz[i][0]) + ", " + std::to_string(xyz[i][1]);
    if (i != 2) nodes += ", " + std::to_string(xyz[i][2]);  // node 3 leaves z out: 0
    nodes += "\n";
  }
  return kHeading + "** the nodes\n" + nodes +
         "*ELEMENT, TYPE=S4R, ELSET=PANEL\n"
         "1, 1, 2, 3, 4\n"
         "2, 2, 5, 6, 3\n"
         "** a comment between element blocks\n"
         "*Element, type=s3r,\n"
         "  elset=Panel\n"
         "3, 3, 6,\n"
         "   7\n"
         "*ELEMENT, TYPE=M3D4, ELSET=\"Rib Part\"\n"
         "10, 2, 3, 9, 8\n"
         "*ELEMENT, TYPE=S4R\n"
         "20, 5, 10, 11, 6\n"
         "21, 10, 12, 13, 11\n" +
         kSolid + kMaterial + kStep;
}

std::map<Id, std::array<double, 3>> coordinates(const FeModel& model) {
  std::map<Id, std::array<double, 3>> xyz;
  for (const Node& n : model.nodes) xyz[n.id] = n.xyz;
  return xyz;
}

void expectSameGeometry(const FeModel& a, const FeModel& b) {
  EXPECT_EQ(coordinates(a), coordinates(b));
  ASSERT_EQ(a.shells.size(), b.shells.size());
  for (std::size_t i = 0; i < a.shells.size(); ++i) {
    EXPECT_EQ(a.shells[i].id, b.shells[i].id);
    EXPECT_EQ(a.shells[i].part, b.shells[i].part);
    EXPECT_EQ(a.shells[i].nodeCount, b.shells[i].nodeCount);
    EXPECT_EQ(a.shells[i].nodes, b.shells[i].nodes);
    EXPECT_EQ(a.shellTypes[a.shells[i].type], b.shellTypes[b.shells[i].type]);
  }
  ASSERT_EQ(a.parts.size(), b.parts.size());
  for (const Part& part : a.parts) {
    const Part* other = b.findPart(part.id);
    ASSERT_NE(other, nullptr) << part.id;
    EXPECT_EQ(other->name, part.name);
  }
}

std::string verbatimText(const FeModel& model) {
  std::string text;
  for (const DeckBlock& block : model.blocks)
    if (block.kind == DeckBlock::Kind::Verbatim) text += block.text;
  return text;
}

}  // namespace

TEST(AbaqusRead, GeometryPartsTypesAndContinuationLines) {
  const fs::path path = put(test::scratchDir("abq_read"), "deck.inp", syntheticDeck());
  Warnings warnings;
  const FeModel m = io::readAbaqus(path, warnings);
  EXPECT_EQ(m.sourceFormat, DeckFormat::Abaqus);
  ASSERT_EQ(m.nodes.size(), 24u);
  EXPECT_EQ(m.nodes[2].xyz, (std::array<double, 3>{1, 1, 0}));
  ASSERT_EQ(m.shells.size(), 6u);
  const Shell& tria = m.shells[2];
  EXPECT_EQ(tria.id, 3);
  EXPECT_EQ(tria.nodeCount, 3);
  EXPECT_EQ(tria.nodes[0], 3);
  EXPECT_EQ(tria.nodes[1], 6);
  EXPECT_EQ(tria.nodes[2], 7);
  EXPECT_EQ(m.shellTypes[tria.type], "S3R");
  EXPECT_EQ(m.shellTypes[m.shells[0].type], "S4R");
  EXPECT_EQ(m.shellTypes[m.shells[3].type], "M3D4");
  // Parts: PANEL (and "Panel", the same label), "Rib Part", then S4R for elements without ELSET.
  ASSERT_EQ(m.parts.size(), 3u);
  EXPECT_EQ(m.parts[0].id, 1);
  EXPECT_EQ(m.parts[0].name, "PANEL");
  EXPECT_EQ(m.parts[1].id, 2);
  EXPECT_EQ(m.parts[1].name, "Rib Part");
  EXPECT_EQ(m.parts[2].id, 3);
  EXPECT_EQ(m.parts[2].name, "S4R");
  const std::vector<Id> parts = {1, 1, 1, 2, 3, 3};
  for (std::size_t i = 0; i < parts.size(); ++i) EXPECT_EQ(m.shells[i].part, parts[i]) << i;
  // The blocks: heading, nodes, the NSET and comment, shells, then the rest in order.
  ASSERT_GE(m.blocks.size(), 5u);
  EXPECT_EQ(m.blocks[0].kind, DeckBlock::Kind::Verbatim);
  EXPECT_EQ(m.blocks[0].text, kHeading + "** the nodes\n");
  EXPECT_EQ(m.blocks[1].kind, DeckBlock::Kind::Nodes);
  EXPECT_EQ(m.blocks[2].kind, DeckBlock::Kind::Verbatim);
  EXPECT_EQ(m.blocks[3].kind, DeckBlock::Kind::Shells);
  const std::string rest = verbatimText(m);
  EXPECT_NE(rest.find("** a comment between element blocks\n"), std::string::npos);
  EXPECT_NE(rest.find(kSolid + kMaterial + kStep), std::string::npos);
}

TEST(AbaqusRead, NsetOnNodeBecomesAnEquivalentNsetBlock) {
  const fs::path path = put(test::scratchDir("abq_nset"), "deck.inp", syntheticDeck());
  Warnings warnings;
  const FeModel m = io::readAbaqus(path, warnings);
  const std::string expected =
      "*NSET, NSET=ALLNODES\n"
      "1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16\n"
      "17, 18, 19, 20, 21, 22, 23, 24\n";
  ASSERT_GE(m.blocks.size(), 3u);
  EXPECT_EQ(m.blocks[2].text.substr(0, expected.size()), expected);
  std::string out;
  io::writeAbaqus(m, out, warnings);
  EXPECT_NE(out.find("*NODE\n1, 0, 0, 0\n"), std::string::npos);
  EXPECT_NE(out.find(expected), std::string::npos);
}

TEST(AbaqusWrite, SameSourceKeepsVerbatimBytesAndRegeneratesGeometry) {
  const fs::path dir = test::scratchDir("abq_same");
  const fs::path path = put(dir, "deck.inp", syntheticDeck());
  Warnings warnings;
  const FeModel first = io::readAbaqus(path, warnings);
  std::string out;
  io::writeAbaqus(first, out, warnings);
  // *MATERIAL / *SHELL SECTION / *STEP (with a CRLF line and trailing blanks) byte for byte.
  EXPECT_NE(out.find(kMaterial), std::string::npos);
  EXPECT_NE(out.find(kSolid + kMaterial + kStep), std::string::npos);
  EXPECT_EQ(out.substr(0, kHeading.size()), kHeading);
  EXPECT_NE(out.find("*ELEMENT, TYPE=S4R, ELSET=PANEL\n1, 1, 2, 3, 4\n2, 2, 5, 6, 3\n"),
            std::string::npos);
  EXPECT_NE(out.find("*ELEMENT, TYPE=S3R, ELSET=PANEL\n3, 3, 6, 7\n"), std::string::npos);
  EXPECT_NE(out.find("** voxremesh part 2 \"Rib Part\"\n*ELEMENT, TYPE=M3D4, ELSET=\"Rib Part\"\n"),
            std::string::npos);
  // Geometry comes before the materials and the step.
  EXPECT_LT(out.find("*NODE\n"), out.find("*MATERIAL"));
  EXPECT_LT(out.find("TYPE=M3D4"), out.find("*STEP"));
  const fs::path again = put(dir, "again.inp", out);
  const FeModel second = io::readAbaqus(again, warnings);
  expectSameGeometry(first, second);
  EXPECT_EQ(verbatimText(second), verbatimText(first));
  // Writing the re-read model gives the same text: nothing accumulates.
  std::string out2;
  io::writeAbaqus(second, out2, warnings);
  EXPECT_EQ(out2, out);
}

TEST(AbaqusWrite, ForeignModelWithTJunctionRoundTripsWithIdsNamesAndExactCoordinates) {
  FeModel model;
  model.sourceFormat = DeckFormat::LsDyna;
  model.shellTypes.push_back("_THICKNESS");
  // A floor of two rows of quads (and a triangle pair), and a fin on the middle line.
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i)
      model.nodes.push_back(
          Node{100 + 10 * j + i, {0.1 * i + 1.0 / 3.0, 0.2 * j - 1e-9 * i, -0.7}});
  for (int i = 0; i < 4; ++i)
    model.nodes.push_back(Node{900000 + i, {0.1 * i + 1.0 / 3.0, 0.2, 1e-3}});
  model.parts = {Part{40, "Floor Panel", true}, Part{7, "rib-2", true}, Part{9, "", false}};
  model.shellExtras.push_back(ShellExtras{{1.2, 1.2, 1.2, 1.2}, 0.0, false, 0.0});
  model.shells.push_back(Shell{1, 40, {100, 101, 111, 110}, 4, 1, 0});
  model.shells.push_back(Shell{2, 40, {101, 102, 112, 0}, 3});
  model.shells.push_back(Shell{3, 40, {101, 112, 111, 0}, 3});
  model.shells.push_back(Shell{4, 40, {110, 111, 121, 120}, 4});
  model.shells.push_back(Shell{5, 40, {111, 112, 122, 121}, 4});
  model.shells.push_back(Shell{6, 7, {110, 111, 900001, 900000}, 4});
  model.shells.push_back(Shell{7, 7, {111, 112, 900002, 900001}, 4});
  model.shells.push_back(Shell{8, 9, {102, 103, 113, 112}, 4});
  Warnings warnings;
  std::string out;
  io::writeAbaqus(model, out, warnings);
  EXPECT_EQ(out.substr(0, 9), "*HEADING\n");
  EXPECT_NE(out.find("*ELEMENT, TYPE=S4R, ELSET=\"Floor Panel\"\n"), std::string::npos);
  EXPECT_NE(out.find("*ELEMENT, TYPE=S3R, ELSET=\"Floor Panel\"\n"), std::string::npos);
  EXPECT_NE(out.find("ELSET=\"rib-2\""), std::string::npos);
  EXPECT_NE(out.find("ELSET=PART_9"), std::string::npos);
  const fs::path path = put(test::scratchDir("abq_foreign"), "out.inp", out);
  const FeModel read = io::readAbaqus(path, warnings);
  EXPECT_EQ(coordinates(read), coordinates(model));
  ASSERT_EQ(read.shells.size(), model.shells.size());
  for (std::size_t i = 0; i < model.shells.size(); ++i) {
    EXPECT_EQ(read.shells[i].id, model.shells[i].id);
    EXPECT_EQ(read.shells[i].part, model.shells[i].part);
    EXPECT_EQ(read.shells[i].nodes, model.shells[i].nodes);
    EXPECT_EQ(read.shellTypes[read.shells[i].type], model.shells[i].nodeCount == 3 ? "S3R" : "S4R");
  }
  ASSERT_EQ(read.parts.size(), 3u);
  EXPECT_EQ(read.findPart(40)->name, "Floor Panel");
  EXPECT_EQ(read.findPart(7)->name, "rib-2");
  EXPECT_EQ(read.findPart(9)->name, "PART_9");
  // The edge 111-112 (and 110-111) carries two floor faces and a fin face.
  std::map<std::pair<Id, Id>, int> uses;
  for (const Shell& s : read.shells)
    for (int k = 0; k < s.nodeCount; ++k) {
      Id a = s.nodes[k], b = s.nodes[(k + 1) % s.nodeCount];
      if (a > b) std::swap(a, b);
      ++uses[{a, b}];
    }
  EXPECT_EQ((uses[{111, 112}]), 3);
  EXPECT_EQ((uses[{110, 111}]), 3);
  EXPECT_TRUE(hasWarning(warnings, "1 element(s) carry thickness"));
}

TEST(AbaqusWrite, TypesFollowTheNodeCountAndLabelsStayDistinct) {
  FeModel model;
  model.sourceFormat = DeckFormat::Abaqus;
  const std::uint8_t m3d4 = model.internShellType("M3D4");
  model.nodes = {Node{1, {0, 0, 0}}, Node{2, {1, 0, 0}}, Node{3, {1, 1, 0}}, Node{4, {0, 1, 0}}};
  model.parts = {Part{1, "Door", false}, Part{2, "DOOR", false}};
  model.shells.push_back(Shell{1, 1, {1, 2, 3, 4}, 4, m3d4});
  model.shells.push_back(Shell{2, 2, {1, 3, 4, 0}, 3, m3d4});  // a triangle of an M3D4 part
  Warnings warnings;
  std::string out;
  io::writeAbaqus(model, out, warnings);
  EXPECT_NE(out.find("*ELEMENT, TYPE=M3D4, ELSET=Door\n"), std::string::npos);
  EXPECT_NE(out.find("*ELEMENT, TYPE=M3D3, ELSET=DOOR_2\n"), std::string::npos);
  EXPECT_TRUE(hasWarning(warnings, "Abaqus labels ignore case"));
}

TEST(AbaqusRead, IncludeFilesAreMergedRelativeToTheIncludingFile) {
  const fs::path dir = test::scratchDir("abq_include");
  put(dir, "sub/nodes.inp",
      "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n*INCLUDE, INPUT=more.inp\n3, 1, 1, 0\n");
  put(dir, "sub/more.inp", "*NODE\n4, 0, 1, 0");  // no final newline
  const fs::path main = put(dir, "main.inp",
                            "*HEADING\ninclude test\n*INCLUDE, INPUT=sub/nodes.inp\n"
                            "*ELEMENT, TYPE=S4R, ELSET=P\n1, 1, 2, 3, 4\n"
                            "*INCLUDE, INPUT=sub/step.inp\n");
  put(dir, "sub/step.inp", "*STEP\n*STATIC\n*END STEP\n");
  Warnings warnings;
  // Abaqus reads the merged text: "3, 1, 1, 0" after the nested include continues the *NODE
  // block that more.inp opened.
  const FeModel m = io::readAbaqus(main, warnings);
  ASSERT_EQ(m.nodes.size(), 4u);
  EXPECT_EQ(m.nodes[3].id, 3);
  ASSERT_EQ(m.shells.size(), 1u);
  EXPECT_TRUE(hasWarning(warnings, "*INCLUDE of 'sub/nodes.inp' merged into the deck"));
  EXPECT_TRUE(hasWarning(warnings, "*INCLUDE of 'more.inp' merged into the deck"));
  std::string out;
  io::writeAbaqus(m, out, warnings);
  EXPECT_EQ(out.find("*INCLUDE"), std::string::npos);
  EXPECT_NE(out.find("*STEP\n*STATIC\n*END STEP\n"), std::string::npos);

  const fs::path missing = put(dir, "missing.inp", "*HEADING\nx\n*INCLUDE, INPUT=nowhere.inp\n");
  expectInputError([&] { io::readAbaqus(missing, warnings); }, missing, 3,
                   "file 'nowhere.inp' not found");
  const fs::path cycle = put(dir, "cycle.inp", "*HEADING\n*INCLUDE, INPUT=cycle.inp\n");
  expectInputError([&] { io::readAbaqus(cycle, warnings); }, cycle, 2, "includes itself");
}

TEST(AbaqusRead, DataFromInputFilesAndNotesOnGeneratorsAndFileReferences) {
  const fs::path dir = test::scratchDir("abq_input");
  put(dir, "data/nodes.txt", "1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0");
  put(dir, "data/elements.txt", "** quads\n5, 1, 2, 3, 4\n");
  const fs::path main = put(dir, "main.inp",
                            "*NODE, INPUT=data/nodes.txt\n"
                            "*ELEMENT, TYPE=S4R, ELSET=P, INPUT=data/elements.txt\n"
                            "*NGEN, NSET=LINE\n1, 2\n"
                            "*AMPLITUDE, NAME=A, INPUT=amp.txt\n");
  Warnings w;
  const FeModel m = io::readAbaqus(main, w);
  ASSERT_EQ(m.nodes.size(), 4u);
  EXPECT_EQ(m.nodes[3].xyz, (std::array<double, 3>{0, 1, 0}));
  ASSERT_EQ(m.shells.size(), 1u);
  EXPECT_EQ(m.shells[0].id, 5);
  EXPECT_TRUE(hasWarning(w, "*NGEN generates nodes or elements"));
  EXPECT_TRUE(hasWarning(w, "*AMPLITUDE reads INPUT=amp.txt"));
  EXPECT_EQ(verbatimText(m), "*NGEN, NSET=LINE\n1, 2\n*AMPLITUDE, NAME=A, INPUT=amp.txt\n");
  const fs::path bad = put(dir, "bad.inp", "*NODE\n1, 0, 0, 0\n*NODE, INPUT=data/none.txt\n");
  expectInputError([&] { io::readAbaqus(bad, w); }, bad, 3, "file 'data/none.txt' not found");
  put(dir, "data/badnodes.txt", "1, 0, 0, 0\n2, 1, 0, zero\n");
  const fs::path badData = put(dir, "baddata.inp", "*NODE, INPUT=data/badnodes.txt\n");
  expectInputError([&] { io::readAbaqus(badData, w); }, dir / "data/badnodes.txt", 2,
                   "malformed z coordinate 'zero'");
}

TEST(AbaqusRead, RefusesWhatItCannotCarryThrough) {
  const fs::path dir = test::scratchDir("abq_refuse");
  Warnings w;
  const auto read = [&](const fs::path& p) { return [&w, p] { io::readAbaqus(p, w); }; };
  const std::string nodes = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n";
  fs::path p = put(dir, "part.inp", "*HEADING\nx\n*PART, NAME=P1\n" + nodes + "*END PART\n");
  expectInputError(read(p), p, 3, "part-instance input (*PART): node and element IDs are local");
  expectInputError(read(p), p, 3, "export a flat input file");
  p = put(dir, "s8r.inp", nodes + "*ELEMENT, TYPE=S8R, ELSET=X\n1, 1, 2, 3, 4, 1, 2, 3, 4\n");
  expectInputError(read(p), p, 6, "element type S8R has midside nodes");
  p = put(dir, "stri65.inp", nodes + "*ELEMENT, TYPE=STRI65\n1, 1, 2, 3, 4, 1, 2\n");
  expectInputError(read(p), p, 6, "element type STRI65 has midside nodes");
  p = put(dir, "foo.inp", nodes + "*ELEMENT, TYPE=FOO, ELSET=X\n1, 1, 2, 3, 4\n");
  expectInputError(read(p), p, 6, "unknown element type 'FOO'");
  p = put(dir, "notype.inp", nodes + "*ELEMENT, ELSET=X\n1, 1, 2, 3, 4\n");
  expectInputError(read(p), p, 6, "*ELEMENT without TYPE=");
  p = put(dir, "cyl.inp", "*NODE, SYSTEM=C\n1, 1, 90, 0\n");
  expectInputError(read(p), p, 1, "SYSTEM=C");
  p = put(dir, "normals.inp", "*NODE\n1, 0, 0, 0, 0, 0, 1\n");
  expectInputError(read(p), p, 2, "normal direction cosines");
  // An element line continued with ',' past the end of the deck (it once read before its buffer:
  // ../shared/data/malformed/continuation_at_eof.inp).
  p = put(dir, "continued.inp",
          "*NODE\n1, 0., 0., 0.\n2, 1., 0., 0.\n3, 1., 1., 0.\n*ELEMENT, TYPE=S3\n1, 1,\n2,\n");
  expectInputError(read(p), p, 7, "element 1 has 2 node(s); type S3 needs 3");
}

TEST(AbaqusRead, KeepsOtherElementTypesVerbatim) {
  const fs::path dir = test::scratchDir("abq_other");
  const std::string others =
      "*ELEMENT, TYPE=B31, ELSET=BEAMS\n1, 1, 2\n"
      "*ELEMENT, TYPE=T3D2\n2, 2, 3\n"
      "*ELEMENT, TYPE=SPRINGA, ELSET=SPR\n3, 3, 4\n"
      "*ELEMENT, TYPE=MASS, ELSET=M\n4, 4\n";
  const fs::path p = put(dir, "others.inp",
                         "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n" + others +
                             "*ELEMENT, TYPE=S4RS, ELSET=SHELL\n5, 1, 2, 3, 4\n");
  Warnings w;
  const FeModel m = io::readAbaqus(p, w);
  ASSERT_EQ(m.shells.size(), 1u);
  EXPECT_EQ(m.shellTypes[m.shells[0].type], "S4RS");
  EXPECT_EQ(verbatimText(m), others);
}

TEST(AbaqusRead, BadInputNamesFileAndLine) {
  const fs::path dir = test::scratchDir("abq_bad");
  Warnings w;
  const auto read = [&](const fs::path& p) { return [&w, p] { io::readAbaqus(p, w); }; };
  fs::path p = put(dir, "coord.inp", "*HEADING\nx\n*NODE\n1, 0, 0, 0\n2, 1.2.3, 0, 0\n");
  expectInputError(read(p), p, 5, "malformed x coordinate '1.2.3' in *NODE");
  p = put(dir, "nodeid.inp", "*NODE\n1, 0, 0, 0\nA2, 1, 0, 0\n");
  expectInputError(read(p), p, 3, "malformed node ID 'A2'");
  p = put(dir, "missing.inp",
          "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n*ELEMENT, TYPE=S3R, ELSET=P\n"
          "7, 1, 2, 3\n8, 1, 3, 99\n");
  expectInputError(read(p), p, 7, "element 8 names node 99, which the deck does not define");
  p = put(dir, "duplicate.inp", "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n1, 1, 1, 0\n");
  expectInputError(read(p), p, 4, "duplicate node ID 1");
  p = put(dir, "short.inp",
          "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n"
          "*ELEMENT, TYPE=S4R, ELSET=P\n7, 1, 2, 3\n*STEP\n");
  expectInputError(read(p), p, 6, "element 7 has 3 node(s); type S4R needs 4");
  p = put(dir, "long.inp",
          "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n"
          "*ELEMENT, TYPE=S3R, ELSET=P\n7, 1, 2, 3, 4\n");
  expectInputError(read(p), p, 6, "too many nodes for element type S3R");
  p = put(dir, "elemid.inp",
          "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n"
          "*ELEMENT, TYPE=S3R, ELSET=P\n7, 1, 2,\n x3\n");
  expectInputError(read(p), p, 7, "malformed node ID 'x3'");
  p = put(dir, "empty.inp", "\n  \n");
  expectInputError(read(p), p, 0, "empty file");
  p = put(dir, "binary.inp", std::string("*HEADING\n\0\x7f", 11));
  expectInputError(read(p), p, 2, "NUL");
}
