// Nastran bulk data: reading every field format, keeping everything else verbatim, writing it back
// (src/io/nastran_read.cpp, nastran_write.cpp, nastran_cards.cpp).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <random>
#include <string>
#include <string_view>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/nastran_cards.h"
#include "io/text_scan.h"
#include "support/expect_input_error.h"
#include "support/test_support.h"
#include "voxremesh/errors.h"

namespace fs = std::filesystem;
using namespace voxremesh;

namespace {

using voxremesh::test::expectInputError;

/// A small-field line: each field left-justified in 8 columns (the 10th is the marker).
std::string small(std::initializer_list<std::string_view> fields) {
  std::string line;
  for (const std::string_view f : fields) {
    line.append(f);
    if (f.size() < 8) line.append(8 - f.size(), ' ');
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  return line + "\n";
}

/// A large-field line: field 1 in 8 columns, 4 fields in 16 columns, the marker in 8.
std::string large(std::initializer_list<std::string_view> fields) {
  std::string line;
  std::size_t i = 0;
  for (const std::string_view f : fields) {
    const std::size_t width = (i == 0 || i == 5) ? 8 : 16;
    line.append(f);
    if (f.size() < width) line.append(width - f.size(), ' ');
    ++i;
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  return line + "\n";
}

fs::path put(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  io::writeFileAtomically(path, text);
  return path;
}

FeModel read(const fs::path& path, Warnings* warnings = nullptr) {
  Warnings local;
  return io::readNastran(path, warnings ? *warnings : local);
}

std::string write(const FeModel& model, Warnings* warnings = nullptr) {
  Warnings local;
  std::string out;
  io::writeNastran(model, out, warnings ? *warnings : local);
  return out;
}

std::string verbatim(const FeModel& model) {
  std::string text;
  for (const DeckBlock& block : model.blocks)
    if (block.kind == DeckBlock::Kind::Verbatim) text += block.text;
  return text;
}

const Node& node(const FeModel& model, Id id) {
  for (const Node& n : model.nodes)
    if (n.id == id) return n;
  throw std::runtime_error("no node " + std::to_string(id));
}

const Shell& shell(const FeModel& model, Id id) {
  for (const Shell& s : model.shells)
    if (s.id == id) return s;
  throw std::runtime_error("no shell " + std::to_string(id));
}

const ShellExtras& extrasOf(const FeModel& model, Id id) {
  const Shell& s = shell(model, id);
  if (s.extras < 0) throw std::runtime_error("shell " + std::to_string(id) + " has no extras");
  return model.shellExtras.at(static_cast<std::size_t>(s.extras));
}

const std::string& typeOf(const FeModel& model, Id id) {
  return model.shellTypes.at(shell(model, id).type);
}

/// A unit square of 2x1 quads plus a triangle, in small field, with a header and a property.
const std::string kHeader =
    "SOL 101\n"
    "CEND\n"
    "TITLE = plate\n"
    "SUBCASE 1\n"
    "  SPC = 1\n"
    "BEGIN BULK\n";

std::string plateBulk() {
  return small({"$HMNAME PROP                   7\"Plate inner\""}) +
         small({"PSHELL", "7", "1", "1.5", "1"}) +
         small({"MAT1", "1", "210000.", "", ".3", "7.85-9"}) +
         small({"GRID", "1", "", "0.", "0.", "0."}) + small({"GRID", "2", "", "1.", "0.", "0."}) +
         small({"GRID", "3", "0", "2.", "0.", "0."}) + small({"GRID", "4", "", "0.", "1.", "0."}) +
         small({"GRID", "5", "", "1.", "1.", "0."}) + small({"GRID", "6", "", "2.", "1.", "0."}) +
         small({"GRID", "7", "", "2.", "2.", "0."}) +
         small({"CQUAD4", "10", "7", "1", "2", "5", "4"}) +
         small({"CQUAD4", "11", "7", "2", "3", "6", "5"}) +
         small({"CTRIA3", "12", "7", "5", "6", "7"}) + small({"SPC1", "1", "123456", "1", "4"}) +
         "ENDDATA\n";
}

}  // namespace

// ---- reading the field formats
// -------------------------------------------------------------------

TEST(NastranRead, SmallFieldDeckWithHeader) {
  const fs::path dir = test::scratchDir("nastran-small");
  const fs::path path = put(dir / "plate.bdf", kHeader + plateBulk());
  Warnings warnings;
  const FeModel model = read(path, &warnings);
  EXPECT_EQ(model.sourceFormat, DeckFormat::Nastran);
  ASSERT_EQ(model.nodes.size(), 7u);
  ASSERT_EQ(model.shells.size(), 3u);
  EXPECT_EQ(node(model, 3).xyz, (std::array<double, 3>{2.0, 0.0, 0.0}));
  EXPECT_EQ(node(model, 7).xyz, (std::array<double, 3>{2.0, 2.0, 0.0}));
  EXPECT_EQ(shell(model, 11).nodes, (std::array<Id, 4>{2, 3, 6, 5}));
  EXPECT_EQ(shell(model, 11).nodeCount, 4);
  EXPECT_EQ(shell(model, 12).nodeCount, 3);
  EXPECT_EQ(shell(model, 12).part, 7);
  EXPECT_EQ(typeOf(model, 10), "");
  ASSERT_EQ(model.parts.size(), 1u);
  EXPECT_EQ(model.parts[0].id, 7);
  EXPECT_EQ(model.parts[0].name, "Plate inner");
  EXPECT_TRUE(model.parts[0].definedInBlocks);
  EXPECT_TRUE(model.shellExtras.empty());
  EXPECT_TRUE(model.nodeExtras.empty());
  // Header verbatim first; then property and material; nodes; shells; SPC1; ENDDATA.
  ASSERT_GE(model.blocks.size(), 5u);
  EXPECT_EQ(model.blocks[0].kind, DeckBlock::Kind::Verbatim);
  EXPECT_EQ(model.blocks[0].text.substr(0, kHeader.size()), kHeader);
  EXPECT_EQ(model.blocks[1].kind, DeckBlock::Kind::Nodes);
  EXPECT_EQ(model.blocks[2].kind, DeckBlock::Kind::Shells);
  EXPECT_EQ(verbatim(model), kHeader + small({"$HMNAME PROP                   7\"Plate inner\""}) +
                                 small({"PSHELL", "7", "1", "1.5", "1"}) +
                                 small({"MAT1", "1", "210000.", "", ".3", "7.85-9"}) +
                                 small({"SPC1", "1", "123456", "1", "4"}) + "ENDDATA\n");
  EXPECT_TRUE(warnings.empty()) << warnings.front();
}

TEST(NastranRead, GridsInLocalSystemsAreReadIntoTheBasicSystem) {
  // System 5: rectangular, origin (10, 0, 0), z along basic x, x along basic y (A, B, C given in
  // system 6). System 6: rectangular, shifted by (0, 0, 1) from basic. System 7: cylindrical
  // about basic z; system 8: spherical about basic z. The GRIDs come before the systems.
  const fs::path dir = test::scratchDir("nastran-cp");
  const std::string text =
      "BEGIN BULK\n" + small({"GRID", "1", "5", "1.", "2.", "3."}) +
      small({"GRID", "2", "7", "2.", "90.", "5."}) + small({"GRID", "3", "8", "2.", "90.", "0."}) +
      small({"GRID", "4", "", "1.", "1.", "1.", "5"}) +
      small({"CORD2R", "5", "6", "10.", "0.", "-1.", "11.", "0.", "-1.", "+"}) +
      small({"+", "10.", "1.", "-1."}) +
      small({"CORD2R", "6", "", "0.", "0.", "1.", "0.", "0.", "2.", "+"}) +
      small({"+", "1.", "0.", "1."}) + large({"CORD2C*", "7", "0", "0.", "0.", "+C7"}) +
      large({"*C7", "0.", "0.", "0.", "1.", "+C8"}) + large({"*C8", "1.", "0.", "0."}) +
      small({"CORD2S", "8", "", "0.", "0.", "0.", "0.", "0.", "1.", "+"}) +
      small({"+", "1.", "0.", "0."}) + small({"CQUAD4", "1", "1", "1", "2", "3", "4"}) +
      "ENDDATA\n";
  const FeModel model = read(put(dir / "cp.bdf", text));
  const auto near = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    for (int k = 0; k < 3; ++k)
      if (std::abs(a[std::size_t(k)] - b[std::size_t(k)]) > 1e-12) return false;
    return true;
  };
  // System 5 in basic: origin (10, 0, 0), z = basic x, x = basic y, y = basic z.
  EXPECT_TRUE(near(node(model, 1).xyz, {13.0, 1.0, 2.0}));
  EXPECT_TRUE(near(node(model, 2).xyz, {0.0, 2.0, 5.0}));  // r 2, theta 90, z 5
  EXPECT_TRUE(near(node(model, 3).xyz, {2.0, 0.0, 0.0}));  // r 2, theta 90 (from z), phi 0
  EXPECT_TRUE(near(node(model, 4).xyz, {1.0, 1.0, 1.0}));  // CD 5 is no location system
  EXPECT_EQ(model.nodeExtras.at(4).nastranCd, 5);
  // The systems stay in the deck, written back as they were.
  EXPECT_NE(verbatim(model).find("CORD2C*"), std::string::npos);
  EXPECT_NE(verbatim(model).find(small({"+", "10.", "1.", "-1."})), std::string::npos);
}

TEST(NastranRead, LargeFieldWithContinuations) {
  const fs::path dir = test::scratchDir("nastran-large");
  const std::string deck =
      large({"GRID*", "101", "0", "1.25", "-2.5", "+G101"}) + large({"*G101", "3.75", "", "", ""}) +
      large({"GRID*", "102", "", "1.0000000000001", "2.5E+3", "*A"}) +
      large({"*A", "-1.5D-2", "7", "", "12"}) + large({"GRID*", "103", "", "0.", "1."}) +
      large({"*", ".5"}) + large({"GRID*", "104", "", "1.", "1."}) + large({"*", "1."}) +
      small({"PSHELL", "5", "1", "2."}) +
      large({"CQUAD4*", "900000001", "5", "101", "102", "+Q1"}) +
      large({"*Q1", "103", "104", "12.5", "-.75", "+Q2"}) +
      large({"*Q2", "", "0", "1.1", "1.2", "+Q3"}) + large({"*Q3", "1.3", "1.4"});
  const fs::path path = put(dir / "large.nas", deck);
  const FeModel model = read(path);
  ASSERT_EQ(model.nodes.size(), 4u);
  EXPECT_EQ(node(model, 101).xyz, (std::array<double, 3>{1.25, -2.5, 3.75}));
  EXPECT_EQ(node(model, 102).xyz[0], 1.0000000000001);
  EXPECT_EQ(node(model, 102).xyz[1], 2500.0);
  EXPECT_DOUBLE_EQ(node(model, 102).xyz[2], -0.015);
  EXPECT_EQ(node(model, 103).xyz[2], 0.5);
  ASSERT_EQ(model.nodeExtras.count(102), 1u);
  EXPECT_EQ(model.nodeExtras.at(102).nastranCd, 7);
  EXPECT_EQ(model.nodeExtras.at(102).nastranPs, 0);
  EXPECT_EQ(model.nodeExtras.at(102).nastranSeid, 12);
  ASSERT_EQ(model.shells.size(), 1u);
  const Shell& quad = model.shells[0];
  EXPECT_EQ(quad.id, 900000001);
  EXPECT_EQ(quad.part, 5);
  EXPECT_EQ(quad.nodes, (std::array<Id, 4>{101, 102, 103, 104}));
  const ShellExtras& extras = extrasOf(model, 900000001);
  EXPECT_FALSE(extras.angleIsMcid);
  EXPECT_EQ(extras.angle, 12.5);
  EXPECT_EQ(extras.offset, -0.75);
  EXPECT_EQ(extras.thickness, (std::array<double, 4>{1.1, 1.2, 1.3, 1.4}));
}

TEST(NastranRead, FreeFieldSmallAndLarge) {
  const fs::path dir = test::scratchDir("nastran-free");
  const std::string deck =
      "BEGIN BULK\n"
      "PSHELL,3,1,0.8\n"
      "GRID,1,,0.,0.,0.\n"
      "GRID, 2 , , 1.5 , 0. , 0.   $ blanks around fields do not matter\n"
      "GRID*,3,,1.23456789012345,1.\n"
      "*,-7.5\n"
      "GRID,4,0,0.,1.,0.,3,246,\n"
      "CQUAD4,20,3,1,2,3,4,0.5,,\n"
      ",,,.9,.9,.9,.9\n"
      "CTRIA3,21,,1,2,3,7,1.-2,,+T21\n"
      "+T21,,0,2.,2.,2.\n"
      "ENDDATA\n";
  const fs::path path = put(dir / "free.bdf", deck);
  const FeModel model = read(path);
  ASSERT_EQ(model.nodes.size(), 4u);
  EXPECT_EQ(node(model, 2).xyz[0], 1.5);
  EXPECT_EQ(node(model, 3).xyz[0], 1.23456789012345);
  EXPECT_EQ(node(model, 3).xyz[2], -7.5);
  EXPECT_EQ(model.nodeExtras.at(4).nastranCd, 3);
  EXPECT_EQ(model.nodeExtras.at(4).nastranPs, 246);
  ASSERT_EQ(model.shells.size(), 2u);
  EXPECT_EQ(extrasOf(model, 20).angle, 0.5);
  EXPECT_EQ(extrasOf(model, 20).thickness, (std::array<double, 4>{0.9, 0.9, 0.9, 0.9}));
  // PID blank defaults to the element ID; MCID is an integer in the THETA/MCID field.
  EXPECT_EQ(shell(model, 21).part, 21);
  EXPECT_TRUE(extrasOf(model, 21).angleIsMcid);
  EXPECT_EQ(extrasOf(model, 21).angle, 7.0);
  EXPECT_DOUBLE_EQ(extrasOf(model, 21).offset, 0.01);
  EXPECT_EQ(extrasOf(model, 21).thickness, (std::array<double, 4>{2.0, 2.0, 2.0, 0.0}));
}

TEST(NastranRead, MixedFormatsTabsAndLowerCase) {
  const fs::path dir = test::scratchDir("nastran-mixed");
  // Nastran reads lower-case input as upper case; a tab advances to the next 8-column field.
  const std::string deck = "grid\t1\t\t0.\t0.\t0.\n" + small({"grid", "2", "", "1.", "0.", "0."}) +
                           "GRID,3,,1.,1.,0.\n" + large({"Grid*", "4", "", "0.", "1.", "+"}) +
                           large({"*", "0."}) +
                           small({"cquad4", "1", "9", "1", "2", "3", "4", "", "", "+C"}) +
                           large({"*C", "", "", "2.5", "2.5"}) + large({"*", "2.5", "2.5"});
  const fs::path path = put(dir / "mixed.dat", deck);
  const FeModel model = read(path);
  ASSERT_EQ(model.nodes.size(), 4u);
  EXPECT_EQ(node(model, 1).xyz, (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(node(model, 2).xyz[0], 1.0);
  EXPECT_EQ(node(model, 4).xyz, (std::array<double, 3>{0.0, 1.0, 0.0}));
  ASSERT_EQ(model.shells.size(), 1u);
  EXPECT_EQ(shell(model, 1).part, 9);
  EXPECT_EQ(extrasOf(model, 1).thickness, (std::array<double, 4>{2.5, 2.5, 2.5, 2.5}));
}

TEST(NastranRead, ExponentForms) {
  const fs::path dir = test::scratchDir("nastran-exponents");
  const std::string deck = small({"GRID", "1", "", "1.-3", "1.+2", "1.5D3"}) +
                           small({"GRID", "2", "", "7.", "-.5E+1", "+2.5-1"}) +
                           small({"GRID", "3", "", "-1.25E-2", "3.d0", ".1+1"});
  const FeModel model = read(put(dir / "exp.bdf", deck));
  EXPECT_DOUBLE_EQ(node(model, 1).xyz[0], 1e-3);
  EXPECT_DOUBLE_EQ(node(model, 1).xyz[1], 100.0);
  EXPECT_DOUBLE_EQ(node(model, 1).xyz[2], 1500.0);
  EXPECT_DOUBLE_EQ(node(model, 2).xyz[0], 7.0);
  EXPECT_DOUBLE_EQ(node(model, 2).xyz[1], -5.0);
  EXPECT_DOUBLE_EQ(node(model, 2).xyz[2], 0.25);
  EXPECT_DOUBLE_EQ(node(model, 3).xyz[0], -0.0125);
  EXPECT_DOUBLE_EQ(node(model, 3).xyz[1], 3.0);
  EXPECT_DOUBLE_EQ(node(model, 3).xyz[2], 1.0);
}

TEST(NastranRead, QuadrTriarAndShellExtras) {
  const fs::path dir = test::scratchDir("nastran-extras");
  std::string deck;
  for (int i = 1; i <= 6; ++i)
    deck += small({"GRID", std::to_string(i), "", std::to_string(i % 3) + ".",
                   std::to_string(i / 3) + ".", "0."});
  deck += small({"CQUADR", "1", "4", "1", "2", "5", "4", "30.", "0.2"}) +
          small({"CTRIAR", "2", "4", "2", "3", "6"}) +
          small({"CQUAD4", "3", "4", "1", "2", "5", "4", "5", "", "+"}) +
          small({"+", "", "", "1.", "2.", "3.", "4."}) +
          small({"CQUAD4", "4", "", "2", "3", "6", "5", "0"}) +
          small({"CTRIA3", "5", "4", "1", "2", "4", "-45.", "-1.5"});
  const FeModel model = read(put(dir / "extras.bdf", deck));
  ASSERT_EQ(model.shells.size(), 5u);
  EXPECT_EQ(typeOf(model, 1), "CQUADR");
  EXPECT_EQ(typeOf(model, 2), "CTRIAR");
  EXPECT_EQ(typeOf(model, 3), "");
  EXPECT_EQ(typeOf(model, 5), "");
  EXPECT_EQ(extrasOf(model, 1).angle, 30.0);
  EXPECT_FALSE(extrasOf(model, 1).angleIsMcid);
  EXPECT_EQ(extrasOf(model, 1).offset, 0.2);
  EXPECT_EQ(shell(model, 2).extras, -1);
  EXPECT_TRUE(extrasOf(model, 3).angleIsMcid);
  EXPECT_EQ(extrasOf(model, 3).angle, 5.0);
  EXPECT_EQ(extrasOf(model, 3).thickness, (std::array<double, 4>{1.0, 2.0, 3.0, 4.0}));
  // MCID 0 (the basic system) differs from THETA = 0.0 and must survive.
  EXPECT_EQ(shell(model, 4).part, 4);
  EXPECT_TRUE(extrasOf(model, 4).angleIsMcid);
  EXPECT_EQ(extrasOf(model, 4).angle, 0.0);
  EXPECT_EQ(extrasOf(model, 5).angle, -45.0);
  EXPECT_EQ(extrasOf(model, 5).offset, -1.5);
  // Parts used without a property card are added, undefined, with a warning.
  ASSERT_EQ(model.parts.size(), 1u);
  EXPECT_EQ(model.parts[0].id, 4);
  EXPECT_FALSE(model.parts[0].definedInBlocks);
}

TEST(NastranRead, PartNamesFromHyperMeshAndAnsaComments) {
  const fs::path dir = test::scratchDir("nastran-names");
  const std::string deck =
      "BEGIN BULK\n"
      "$HMNAME PROP                   1\"B-pillar inner\" 4\n"
      "$HWCOLOR PROP                  1      11\n" +
      small({"PSHELL", "1", "1", "1.2"}) + "$ANSA_NAME;2;PSHELL;~\n$Roof_outer\n" +
      small({"PSHELL", "2", "1", "0.7"}) + small({"PSHELL", "3", "1", "0.7"}) +
      small({"PCOMP", "4", "", "", "", "", "", "", "", "+P4"}) +
      small({"+P4", "1", ".5", "0.", "YES"}) + small({"PSHELL", "6", "1", "1."}) +
      small({"GRID", "1", "", "0.", "0.", "0."}) + small({"GRID", "2", "", "1.", "0.", "0."}) +
      small({"GRID", "3", "", "1.", "1.", "0."}) + small({"CTRIA3", "1", "1", "1", "2", "3"}) +
      small({"CTRIA3", "2", "2", "1", "2", "3"}) + small({"CTRIA3", "3", "3", "1", "2", "3"}) +
      small({"CTRIA3", "4", "4", "1", "2", "3"}) + small({"CTRIA3", "5", "5", "1", "2", "3"}) +
      "$ANSA_NAME_COMMENT;3;PSHELL;Floor panel;;NO;NO;NO;NO;\n"
      "$ANSA_NAME_COMMENT;4;PCOMP;Composite lid;;NO;NO;NO;NO;\n"
      "ENDDATA\n";
  Warnings warnings;
  const FeModel model = read(put(dir / "names.bdf", deck), &warnings);
  ASSERT_EQ(model.parts.size(), 6u);
  const auto partNamed = [&](Id id) { return model.findPart(id); };
  ASSERT_NE(partNamed(1), nullptr);
  EXPECT_EQ(partNamed(1)->name, "B-pillar inner");
  EXPECT_EQ(partNamed(2)->name, "Roof_outer");
  EXPECT_EQ(partNamed(3)->name, "Floor panel");
  EXPECT_EQ(partNamed(4)->name, "Composite lid");
  EXPECT_TRUE(partNamed(4)->definedInBlocks);
  EXPECT_EQ(partNamed(6)->name, "");
  EXPECT_TRUE(partNamed(6)->definedInBlocks);
  ASSERT_NE(partNamed(5), nullptr);
  EXPECT_FALSE(partNamed(5)->definedInBlocks);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("property 5"), std::string::npos) << warnings[0];
}

TEST(NastranRead, OtherCardsKeptByteForByteInOrder) {
  const fs::path dir = test::scratchDir("nastran-verbatim");
  const std::string before =
      "$ materials and rigid elements\r\n"
      "PSHELL  1       1       1.\r\n"
      "MAT1    1       210000.         .3      7.85-9\r\n"
      "RBE2    900     1       123456  2       3       4       5       6       +RB1\r\n"
      "+RB1    7       8\r\n";
  const std::string between =
      "CBAR    50      2       1       2       0.      0.      1.\r\n"
      "$ a comment between geometry cards\r\n"
      "SPC1    1       123     1       THRU    4\r\n";
  const std::string after =
      "CHEXA   60      8       1       2       3       4       5       6       +\r\n"
      "+       7       8\r\n"
      "ENDDATA\r\n"
      "anything after ENDDATA stays as it is\r\n";
  const std::string grids =
      "GRID    1               0.      0.      0.\r\n"
      "GRID    2               1.      0.      0.\r\n"
      "GRID    3               1.      1.      0.\r\n";
  const std::string deck = before + grids + between +
                           "GRID    4               0.      1.      0.\r\n" +
                           "CQUAD4  1       1       1       2       3       4\r\n" + after;
  const FeModel model = read(put(dir / "verbatim.bdf", deck));
  ASSERT_EQ(model.nodes.size(), 4u);
  EXPECT_EQ(verbatim(model), before + between + after);
  // Blocks in file order: [before] Nodes [between] Shells [CHEXA] [ENDDATA...].
  ASSERT_EQ(model.blocks.size(), 6u);
  EXPECT_EQ(model.blocks[0].text, before);
  EXPECT_EQ(model.blocks[1].kind, DeckBlock::Kind::Nodes);
  EXPECT_EQ(model.blocks[2].text, between);
  EXPECT_EQ(model.blocks[3].kind, DeckBlock::Kind::Shells);
  // The writer keeps the verbatim text and the deck's CRLF line ends.
  const std::string out = write(model);
  EXPECT_NE(out.find(before), std::string::npos);
  EXPECT_NE(out.find(between), std::string::npos);
  EXPECT_NE(out.find(after), std::string::npos);
  EXPECT_EQ(out.find("\n"), out.find("\r\n") + 1);
  for (std::size_t at = out.find('\n'); at != std::string::npos; at = out.find('\n', at + 1))
    ASSERT_EQ(out[at - 1], '\r') << "a line without CR at " << at;
}

TEST(NastranRead, IncludeInSubfolder) {
  const fs::path dir = test::scratchDir("nastran-include");
  put(dir / "mesh" / "nodes.bdf", small({"GRID", "1", "", "0.", "0.", "0."}) +
                                      small({"GRID", "2", "", "1.", "0.", "0."}) +
                                      "INCLUDE 'more/last.bdf'\n");
  // The included file's last line has no line break: it must not be glued to the next line.
  const std::string mat1 = small({"MAT1", "1", "70000.", "", ".33"});
  put(dir / "mesh" / "more" / "last.bdf",
      small({"GRID", "3", "", "1.", "1.", "0."}) + mat1.substr(0, mat1.size() - 1));
  // A repeated plain BEGIN BULK (some bulk files start with one) is kept and changes nothing.
  put(dir / "elements.bdf", "BEGIN BULK\n" + small({"CTRIA3", "1", "1", "1", "2", "3"}));
  const fs::path main = put(dir / "main.bdf", kHeader + small({"PSHELL", "1", "1", "1."}) +
                                                  "INCLUDE 'mesh/\n"
                                                  "        nodes.bdf'\n"
                                                  "include \"elements.bdf\"\n"
                                                  "ENDDATA\n");
  Warnings warnings;
  const FeModel model = read(main, &warnings);
  ASSERT_EQ(model.nodes.size(), 3u);
  EXPECT_EQ(node(model, 3).xyz, (std::array<double, 3>{1.0, 1.0, 0.0}));
  ASSERT_EQ(model.shells.size(), 1u);
  EXPECT_EQ(verbatim(model), kHeader + small({"PSHELL", "1", "1", "1."}) +
                                 small({"MAT1", "1", "70000.", "", ".33"}) + "BEGIN BULK\n" +
                                 "ENDDATA\n");
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_NE(warnings[0].find("main.bdf:8: INCLUDE 'mesh/nodes.bdf' was read in place"),
            std::string::npos)
      << warnings[0];
  // Errors inside an included file name that file and its line.
  put(dir / "mesh" / "more" / "last.bdf", small({"GRID", "1", "", "1.", "1.", "0."}));
  expectInputError([&] { read(main); }, dir / "mesh" / "more" / "last.bdf", 1,
                   "duplicate node ID 1");
}

// ---- writing
// ---------------------------------------------------------------------------------------

TEST(NastranWrite, RoundTripKeepsEverything) {
  const fs::path dir = test::scratchDir("nastran-roundtrip");
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(-3000.0, 3000.0);
  std::string grids;
  for (int i = 1; i <= 40; ++i) {
    char x[32];
    std::snprintf(x, sizeof x, "%.15g", coordinate(random));
    const std::string y = std::to_string(coordinate(random));
    grids += "GRID," + std::to_string(i) + ",," + x + "," + y + "," + std::to_string(i * 0.001) +
             (i == 5 ? ",2,345,3" : "") + "\n";
  }
  const std::string deck =
      kHeader + "$HMNAME PROP                   1\"Door inner\"\n" +
      small({"PSHELL", "1", "1", "0.8", "1"}) + small({"MAT1", "1", "210000.", "", ".3"}) +
      small({"RBE2", "500", "1", "123456", "2", "3", "4", "5", "6", "+R"}) +
      small({"+R", "7", "8"}) + grids + small({"CBAR", "600", "3", "1", "2", "0.", "0.", "1."}) +
      "CQUAD4,1,1,1,2,12,11,33.3333333,0.25\n" +
      small({"CQUAD4", "2", "1", "2", "3", "13", "12", "", "", "+"}) +
      small({"+", "", "", ".81", ".82", ".83", ".84"}) +
      small({"CQUADR", "3", "2", "3", "4", "14", "13", "9"}) +
      small({"CTRIAR", "4", "2", "4", "5", "15"}) +
      large({"CTRIA3*", "123456789", "1", "5", "6", "+"}) +
      large({"*", "16", "1.23456789012", "-2.", ""}) +
      "$ANSA_NAME_COMMENT;2;PSHELL;Door outer;;NO;NO;NO;NO;\n"
      "ENDDATA\n";
  const fs::path path = put(dir / "deck.bdf", deck);
  const FeModel first = read(path);
  Warnings writeWarnings;
  const std::string text = write(first, &writeWarnings);
  const FeModel second = read(put(dir / "written.bdf", text));

  ASSERT_EQ(second.nodes.size(), first.nodes.size());
  for (std::size_t i = 0; i < first.nodes.size(); ++i) {
    EXPECT_EQ(second.nodes[i].id, first.nodes[i].id);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(second.nodes[i].xyz[k], first.nodes[i].xyz[k],
                  1e-9 * std::fabs(first.nodes[i].xyz[k]))
          << "node " << first.nodes[i].id;
  }
  ASSERT_EQ(second.nodeExtras.size(), 1u);
  EXPECT_EQ(second.nodeExtras.at(5).nastranCd, 2);
  EXPECT_EQ(second.nodeExtras.at(5).nastranPs, 345);
  EXPECT_EQ(second.nodeExtras.at(5).nastranSeid, 3);
  ASSERT_EQ(second.shells.size(), first.shells.size());
  for (std::size_t i = 0; i < first.shells.size(); ++i) {
    const Shell& a = first.shells[i];
    const Shell& b = second.shells[i];
    EXPECT_EQ(b.id, a.id);
    EXPECT_EQ(b.part, a.part);
    EXPECT_EQ(b.nodeCount, a.nodeCount);
    EXPECT_EQ(b.nodes, a.nodes);
    EXPECT_EQ(second.shellTypes.at(b.type), first.shellTypes.at(a.type));
    ASSERT_EQ(b.extras < 0, a.extras < 0) << "shell " << a.id;
    if (a.extras >= 0) {
      const ShellExtras& ea = first.shellExtras[static_cast<std::size_t>(a.extras)];
      const ShellExtras& eb = second.shellExtras[static_cast<std::size_t>(b.extras)];
      EXPECT_EQ(eb.angle, ea.angle) << "shell " << a.id;
      EXPECT_EQ(eb.angleIsMcid, ea.angleIsMcid) << "shell " << a.id;
      EXPECT_EQ(eb.offset, ea.offset) << "shell " << a.id;
      EXPECT_EQ(eb.thickness, ea.thickness) << "shell " << a.id;
    }
  }
  EXPECT_EQ(extrasOf(second, 1).angle, 33.3333333);
  EXPECT_EQ(extrasOf(second, 123456789).angle, 1.23456789012);
  EXPECT_EQ(typeOf(second, 3), "CQUADR");
  ASSERT_EQ(second.parts.size(), first.parts.size());
  for (std::size_t i = 0; i < first.parts.size(); ++i) {
    EXPECT_EQ(second.parts[i].id, first.parts[i].id);
    EXPECT_EQ(second.parts[i].name, first.parts[i].name);
  }
  // Part 2 had no PSHELL: the writer generated one (named) before ENDDATA; read back it is defined.
  ASSERT_NE(second.findPart(2), nullptr);
  EXPECT_EQ(second.findPart(2)->name, "Door outer");
  EXPECT_TRUE(second.findPart(2)->definedInBlocks);
  EXPECT_FALSE(first.findPart(2)->definedInBlocks);
  EXPECT_EQ(second.findPart(1)->name, "Door inner");
  EXPECT_LT(text.find("PSHELL         2"), text.find("ENDDATA"));
  EXPECT_GT(text.find("PSHELL         2"), text.find("CTRIA3*"));
  ASSERT_EQ(writeWarnings.size(), 2u);  // the generated PSHELL; the 9-digit element ID
  // Verbatim content byte for byte (the generated PSHELL is new verbatim text in the second read).
  const std::string firstVerbatim = verbatim(first);
  const std::string secondVerbatim = verbatim(second);
  const std::size_t generated = secondVerbatim.find("$ voxremesh: PSHELL");
  ASSERT_NE(generated, std::string::npos);
  EXPECT_EQ(
      secondVerbatim.substr(0, generated) + secondVerbatim.substr(secondVerbatim.find("ENDDATA")),
      firstVerbatim);
  // Writing the second model gives the same text again.
  const std::string again = write(second);
  const FeModel third = read(put(dir / "again.bdf", again));
  EXPECT_EQ(write(third), again);
}

TEST(NastranWrite, ModelFromAnotherFormatBecomesAFreshDeck) {
  FeModel model;
  model.sourceFormat = DeckFormat::LsDyna;
  model.shellTypes.push_back("_THICKNESS");
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(-1.0e4, 1.0e4);
  const int n = 6;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      model.nodes.push_back(
          Node{1000 + j * n + i, {coordinate(random), coordinate(random), 1e-7 * i}});
  model.nodeExtras[1000].dynaTc = 7;  // LS-DYNA only: nothing for Nastran
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      Shell s;
      s.id = 1 + j * n + i;
      s.part = i < n / 2 ? 11 : 22;
      s.nodes = {1000 + j * n + i, 1000 + j * n + i + 1, 1000 + (j + 1) * n + i + 1,
                 1000 + (j + 1) * n + i};
      if (s.part == 22) {
        s.type = 1;
        s.extras = static_cast<std::int32_t>(model.shellExtras.size());
        ShellExtras extras;
        extras.thickness = {1.5, 1.5, 2.5, 2.5};
        model.shellExtras.push_back(extras);
      }
      model.shells.push_back(s);
    }
  Shell tria;
  tria.id = 99999;
  tria.part = 11;
  tria.nodeCount = 3;
  tria.nodes = {1000, 1001, 1000 + n};
  model.shells.push_back(tria);
  model.parts = {Part{11, "Sill \"reinforcement\"", true}, Part{22, "A-pillar", true}};
  model.blocks.push_back(DeckBlock{DeckBlock::Kind::Verbatim, "*KEYWORD\n"});

  Warnings warnings;
  const std::string text = write(model, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("material 1"), std::string::npos);
  EXPECT_EQ(text.find("*KEYWORD"), std::string::npos);
  EXPECT_NE(text.find("BEGIN BULK\n"), std::string::npos);
  const fs::path dir = test::scratchDir("nastran-fresh");
  const FeModel back = read(put(dir / "fresh.bdf", text));
  ASSERT_EQ(back.nodes.size(), model.nodes.size());
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    EXPECT_EQ(back.nodes[i].id, model.nodes[i].id);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(back.nodes[i].xyz[k], model.nodes[i].xyz[k],
                  1e-9 * std::fabs(model.nodes[i].xyz[k]));
  }
  EXPECT_TRUE(back.nodeExtras.empty());
  ASSERT_EQ(back.shells.size(), model.shells.size());
  for (std::size_t i = 0; i < model.shells.size(); ++i) {
    EXPECT_EQ(back.shells[i].id, model.shells[i].id);
    EXPECT_EQ(back.shells[i].part, model.shells[i].part);
    EXPECT_EQ(back.shells[i].nodeCount, model.shells[i].nodeCount);
    EXPECT_EQ(back.shells[i].nodes, model.shells[i].nodes);
    EXPECT_EQ(back.shellTypes.at(back.shells[i].type), "");
  }
  EXPECT_EQ(extrasOf(back, model.shells[4].id).thickness,
            (std::array<double, 4>{1.5, 1.5, 2.5, 2.5}));
  ASSERT_EQ(back.parts.size(), 2u);
  EXPECT_EQ(back.parts[0].id, 11);
  EXPECT_EQ(back.parts[0].name, "Sill  reinforcement ");
  EXPECT_EQ(back.parts[1].id, 22);
  EXPECT_EQ(back.parts[1].name, "A-pillar");
  EXPECT_TRUE(back.parts[0].definedInBlocks);
  // The PSHELL of part 22 takes the mean element thickness, part 11 the placeholder 1.0.
  EXPECT_NE(text.find("\nPSHELL        22       1      2.       1\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nPSHELL        11       1      1.       1\n"), std::string::npos) << text;
  EXPECT_EQ(text.substr(text.size() - 8), "ENDDATA\n");
}

TEST(NastranWrite, RealsAlwaysFitAndKeepADecimalPoint) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  char buffer[64];
  for (int i = 0; i < 20000; ++i) {
    const double value = mantissa(random) * std::pow(10.0, exponent(random));
    for (const int width : {8, 16}) {
      const std::size_t length = io::nastran::formatReal(value, width, buffer);
      const std::string text(buffer, length);
      ASSERT_LE(length, static_cast<std::size_t>(width)) << text;
      ASSERT_NE(text.find('.'), std::string::npos) << text;
      double back = 0;
      ASSERT_TRUE(io::parseReal(text, back)) << text;
      // Even negative values with two-digit exponents keep 3 significant digits in 8 columns
      // ("-3.50-30") and 11 in 16 columns.
      EXPECT_LE(std::fabs(back - value), (width == 8 ? 5e-3 : 5e-11) * std::fabs(value)) << text;
      if (io::nastran::fitsExactly(value, width)) {
        EXPECT_EQ(back, value) << text;
      }
    }
  }
  const auto format8 = [&](double v) {
    return std::string(buffer, io::nastran::formatReal(v, 8, buffer));
  };
  EXPECT_EQ(format8(0.001), ".001");
  EXPECT_EQ(format8(1.0), "1.");
  EXPECT_EQ(format8(-0.0), "-0.");
  EXPECT_EQ(format8(1e-20), "1.-20");
  EXPECT_EQ(format8(2.5e12), "2.5+12");
  EXPECT_EQ(format8(1.23456789e-7), "1.2346-7");
  EXPECT_EQ(format8(123456.789), "123456.8");
}

// ---- bad input
// ---------------------------------------------------------------------------------------

TEST(NastranErrors, EachNamesFileAndLine) {
  const fs::path dir = test::scratchDir("nastran-errors");
  const std::string grids = small({"GRID", "1", "", "0.", "0.", "0."}) +
                            small({"GRID", "2", "", "1.", "0.", "0."}) +
                            small({"GRID", "3", "", "1.", "1.", "0."});
  const auto check = [&](const std::string& name, const std::string& text, std::size_t line,
                         const std::string& message) {
    const fs::path path = put(dir / name, text);
    expectInputError([&] { read(path); }, path, line, message);
  };
  check("number.bdf", grids + small({"GRID", "4", "", "1.2.3", "0.", "0."}), 4,
        "malformed X1 coordinate '1.2.3' in GRID 4");
  check("element-number.bdf", grids + small({"CTRIA3", "7", "1", "1", "2x", "3"}), 4,
        "malformed G2 '2x' in CTRIA3 7");
  check("truncated.bdf", grids + large({"GRID*", "4", "", "0.", "1.", "+G4"}), 4,
        "truncated GRID 4: its continuation line '+G4' (X3, CD, PS, SEID) is missing");
  check("no-id.bdf", grids + "GRID\n", 4, "GRID without an ID");
  check("missing-node.bdf", grids + small({"CQUAD4", "1", "1", "1", "2", "3", "44"}), 4,
        "element 1 names node 44, which the deck does not define");
  check("duplicate-grid.bdf", grids + small({"GRID", "2", "", "5.", "0.", "0."}), 4,
        "duplicate node ID 2");
  check("duplicate-element.bdf",
        grids + small({"CTRIA3", "1", "1", "1", "2", "3"}) + "$\n" +
            small({"CTRIA3", "1", "1", "3", "2", "1"}),
        6, "duplicate element ID 1");
  check("cquad8.bdf", grids + small({"CQUAD8", "1", "1", "1", "2", "3", "4", "5", "6"}), 4,
        "CQUAD8 elements");
  check("cp.bdf", grids + "$ local system\n" + small({"GRID", "9", "5", "0.", "0.", "0."}), 5,
        "GRID 9 is given in coordinate system CP = 5, which the deck does not define");
  const std::string inFive = small({"GRID", "9", "5", "0.", "0.", "0."});
  check("rid.bdf",
        grids + inFive + small({"CORD2R", "5", "6", "0.", "0.", "0.", "0.", "0.", "1.", "+"}) +
            small({"+", "1.", "0.", "0."}),
        5, "CORD2R 5 refers to coordinate system 6, which the deck does not define");
  check("rid-cycle.bdf",
        grids + inFive + small({"CORD2R", "5", "6", "0.", "0.", "0.", "0.", "0.", "1.", "+"}) +
            small({"+", "1.", "0.", "0."}) +
            small({"CORD2R", "6", "5", "0.", "0.", "0.", "0.", "0.", "1.", "+"}) +
            small({"+", "1.", "0.", "0."}),
        5, "returns to itself");
  check("axes.bdf",
        grids + inFive + small({"CORD2C", "5", "", "0.", "0.", "0.", "0.", "0.", "1.", "+"}) +
            small({"+", "0.", "0.", "2."}),
        5, "CORD2C 5: its points A, B and C do not define axes");
  check("grdset.bdf", small({"GRDSET", "", "4"}) + grids, 1, "GRDSET sets the default CP = 4");
  check("tflag.bdf",
        grids + small({"CTRIA3", "1", "1", "1", "2", "3", "", "", "", "+"}) +
            small({"+", "", "1", ".5", ".5", ".5"}),
        5, "TFLAG = 1");
  check("marker.bdf",
        grids + small({"CTRIA3", "1", "1", "1", "2", "3", "", "", "", "+A"}) +
            small({"+B", "", "", ".5", ".5", ".5"}),
        5, "continuation marker '+B' does not match '+A'");
  check("super.bdf", grids + "BEGIN SUPER=2\n" + small({"GRID", "9", "", "0.", "0.", "0."}), 5,
        "after BEGIN SUPER");
  check("empty.bdf", "  \n\n", 0, "empty file");
  check("binary.bdf", grids + std::string("GRID\0\0\x01", 7), 4, "binary data");
  const fs::path main = put(dir / "include.bdf", grids + "$\nINCLUDE 'sub/missing.bdf'\n");
  expectInputError([&] { read(main); }, main, 5, "INCLUDE file 'sub/missing.bdf' not found");
  const fs::path cycle = put(dir / "cycle.bdf", "INCLUDE 'cycle.bdf'\n");
  expectInputError([&] { read(cycle); }, cycle, 1, "cycle");
}

// ---- performance (run with --gtest_also_run_disabled_tests) -------------------------------------

TEST(NastranPerformance, DISABLED_MillionElementDeck) {
  const int n = 1000;  // n x n quads
  FeModel model;
  model.sourceFormat = DeckFormat::Abaqus;
  model.nodes.reserve(static_cast<std::size_t>((n + 1) * (n + 1)));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      model.nodes.push_back(
          Node{1 + j * (n + 1) + i,
               {2.5 * i + 0.123456789 * j, 2.5 * j - 1e-3 * i, std::sin(0.01 * i) * 50.0}});
  model.shells.reserve(static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      Shell s;
      s.id = 1 + j * n + i;
      s.part = 1 + j / 100;
      const Id a = 1 + j * (n + 1) + i;
      s.nodes = {a, a + 1, a + n + 2, a + n + 1};
      model.shells.push_back(s);
    }
  for (Id p = 1; p <= 10; ++p) model.parts.push_back(Part{p, "part " + std::to_string(p), true});
  const fs::path dir = test::scratchDir("nastran-perf");
  Warnings warnings;
  const auto t0 = std::chrono::steady_clock::now();
  std::string text;
  io::writeNastran(model, text, warnings);
  const auto t1 = std::chrono::steady_clock::now();
  io::writeFileAtomically(dir / "big.bdf", text);
  const auto t2 = std::chrono::steady_clock::now();
  const FeModel back = io::readNastran(dir / "big.bdf", warnings);
  const auto t3 = std::chrono::steady_clock::now();
  std::string again;
  io::writeNastran(back, again, warnings);
  const auto t4 = std::chrono::steady_clock::now();
  const auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  std::printf("deck: %zu MB, %zu nodes, %zu shells\n", text.size() >> 20, back.nodes.size(),
              back.shells.size());
  std::printf("write (fresh) %.3f s, save %.3f s, read %.3f s, write (back) %.3f s\n",
              seconds(t0, t1), seconds(t1, t2), seconds(t2, t3), seconds(t3, t4));
  EXPECT_EQ(back.nodes.size(), model.nodes.size());
  EXPECT_EQ(back.shells.size(), model.shells.size());
  EXPECT_LT(seconds(t2, t3), 5.0);
  EXPECT_LT(seconds(t0, t1), 5.0);
}
