// LS-DYNA keyword reading and writing (src/io/lsdyna_read.cpp, lsdyna_write.cpp): the real decks
// of ../shared/data, round trips, every card format, includes, and errors with file and line.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <random>
#include <string>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "support/expect_input_error.h"
#include "support/test_support.h"
#include "voxremesh/errors.h"

using namespace voxremesh;
namespace fs = std::filesystem;

namespace {

/// Bad-input assertion comparing file names (include paths may be spelled differently).
void expectInputError(const std::function<void()>& action, const fs::path& file, std::size_t line,
                      const std::string& text) {
  voxremesh::test::expectInputError(action, file, line, text, voxremesh::test::FileMatch::FileName);
}

FeModel read(const fs::path& path, Warnings* warnings = nullptr) {
  Warnings local;
  return io::readLsDyna(path, warnings ? *warnings : local);
}

std::string write(const FeModel& model, Warnings* warnings = nullptr) {
  Warnings local;
  std::string out;
  io::writeLsDyna(model, out, warnings ? *warnings : local);
  return out;
}

/// Writes `text` as a deck in a scratch folder and reads it.
FeModel readText(const std::string& test, const std::string& text, Warnings* warnings = nullptr) {
  const fs::path path = test::scratchDir(test) / "deck.k";
  io::writeFileAtomically(path, text);
  return read(path, warnings);
}

/// Writes a model, reads the written deck back.
FeModel roundTrip(const std::string& test, const FeModel& model, std::string* written = nullptr) {
  const std::string text = write(model);
  if (written) *written = text;
  return readText(test, text);
}

std::size_t countTrias(const FeModel& model) {
  std::size_t trias = 0;
  for (const Shell& shell : model.shells) trias += shell.nodeCount == 3;
  return trias;
}

bool contains(const Warnings& warnings, const std::string& text) {
  for (const std::string& w : warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

/// Expects same geometry, parts and extras (coordinates to 1e-9 relative).
void expectSameModel(const FeModel& a, const FeModel& b) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    ASSERT_EQ(a.nodes[i].id, b.nodes[i].id) << "node " << i;
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(a.nodes[i].xyz[k], b.nodes[i].xyz[k],
                  1e-9 * std::fabs(a.nodes[i].xyz[k]) + 1e-300)
          << "node " << a.nodes[i].id;
  }
  ASSERT_EQ(a.shells.size(), b.shells.size());
  for (std::size_t i = 0; i < a.shells.size(); ++i) {
    const Shell& x = a.shells[i];
    const Shell& y = b.shells[i];
    ASSERT_EQ(x.id, y.id);
    ASSERT_EQ(x.part, y.part) << "shell " << x.id;
    ASSERT_EQ(x.nodeCount, y.nodeCount) << "shell " << x.id;
    for (int k = 0; k < x.nodeCount; ++k) ASSERT_EQ(x.nodes[k], y.nodes[k]) << "shell " << x.id;
    ASSERT_EQ(a.shellTypes[x.type], b.shellTypes[y.type]) << "shell " << x.id;
    ASSERT_EQ(x.extras < 0, y.extras < 0) << "shell " << x.id;
    if (x.extras >= 0) {
      const ShellExtras& ex = a.shellExtras[static_cast<std::size_t>(x.extras)];
      const ShellExtras& ey = b.shellExtras[static_cast<std::size_t>(y.extras)];
      for (int k = 0; k < 4; ++k) ASSERT_DOUBLE_EQ(ex.thickness[k], ey.thickness[k]);
      ASSERT_DOUBLE_EQ(ex.angle, ey.angle);
      ASSERT_EQ(ex.angleIsMcid, ey.angleIsMcid);
      ASSERT_DOUBLE_EQ(ex.offset, ey.offset);
    }
  }
  ASSERT_EQ(a.parts.size(), b.parts.size());
  for (std::size_t i = 0; i < a.parts.size(); ++i) {
    EXPECT_EQ(a.parts[i].id, b.parts[i].id);
    EXPECT_EQ(a.parts[i].name, b.parts[i].name);
  }
  ASSERT_EQ(a.nodeExtras.size(), b.nodeExtras.size());
  for (const auto& [id, extras] : a.nodeExtras) {
    ASSERT_TRUE(b.nodeExtras.count(id)) << "node " << id;
    EXPECT_EQ(extras.dynaTc, b.nodeExtras.at(id).dynaTc);
    EXPECT_EQ(extras.dynaRc, b.nodeExtras.at(id).dynaRc);
  }
}

/// Expects every verbatim block of `model` byte for byte, in order, in `text`.
void expectBlocksInOrder(const FeModel& model, const std::string& text) {
  std::size_t at = 0;
  for (const DeckBlock& block : model.blocks) {
    if (block.kind != DeckBlock::Kind::Verbatim) continue;
    const std::size_t found = text.find(block.text, at);
    ASSERT_NE(found, std::string::npos) << "block not found in order:\n"
                                        << block.text.substr(0, 200);
    at = found + block.text.size();
  }
}

const DeckBlock* findBlock(const FeModel& model, const std::string& keywordLine) {
  for (const DeckBlock& block : model.blocks)
    if (block.kind == DeckBlock::Kind::Verbatim &&
        block.text.compare(0, keywordLine.size(), keywordLine) == 0)
      return &block;
  return nullptr;
}

/// The source text without its *NODE and *ELEMENT_SHELL blocks (a block runs from its keyword
/// line to the next one).
std::string nonGeometryText(const std::string& source) {
  std::string result;
  bool geometry = false;
  std::size_t begin = 0;
  while (begin < source.size()) {
    std::size_t end = source.find('\n', begin);
    end = end == std::string::npos ? source.size() : end + 1;
    const std::string line = source.substr(begin, end - begin);
    if (line[0] == '*') {
      const std::string keyword = line.substr(0, line.find_first_of(" \r\n"));
      geometry = keyword == "*NODE" || keyword.rfind("*ELEMENT_SHELL", 0) == 0;
    }
    if (!geometry) result += line;
    begin = end;
  }
  return result;
}

/// Reads a real deck, writes it, reads it again: same model, every verbatim block in order, and
/// writing the re-read model gives the same text.
void expectRealRoundTrip(const std::string& test, const fs::path& deck) {
  const FeModel first = read(deck);
  std::string verbatim;
  for (const DeckBlock& block : first.blocks) verbatim += block.text;
  EXPECT_EQ(verbatim, nonGeometryText(test::readText(deck)));  // nothing but geometry left out
  std::string written;
  const FeModel second = roundTrip(test, first, &written);
  expectSameModel(first, second);
  expectBlocksInOrder(first, written);
  EXPECT_EQ(write(second), written);
}

void expectDeckError(const std::string& test, const std::string& text, std::size_t line,
                     const std::string& message) {
  const fs::path path = test::scratchDir(test) / "bad.k";
  io::writeFileAtomically(path, text);
  expectInputError([&] { read(path); }, path, line, message);
}

/// Right-aligns each value in `width` columns (a fixed-format card piece).
std::string cols(int width, std::initializer_list<const char*> values) {
  std::string out;
  for (const char* value : values) {
    const std::string text(value);
    out += std::string(static_cast<std::size_t>(std::max(0, width - static_cast<int>(text.size()))),
                       ' ') +
           text;
  }
  return out;
}

const char* const kTwoQuads =
    "*NODE\n"
    "       1             0.0             0.0             0.0\n"
    "       2             1.0             0.0             0.0\n"
    "       3             1.0             1.0             0.0\n"
    "       4             0.0             1.0             0.0\n"
    "       5             2.0             0.0             0.0\n"
    "       6             2.0             1.0             0.0\n";

}  // namespace

// ---------------------------------------------------------------------------------------------
// The real decks

TEST(LsDynaRealDecks, BracketCountsAndPart) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "bracket.k");
  Warnings warnings;
  const FeModel model = read(path, &warnings);
  EXPECT_EQ(model.sourceFormat, DeckFormat::LsDyna);
  EXPECT_EQ(model.nodes.size(), 1972u);  // grep: data lines of the *NODE block
  EXPECT_EQ(model.shells.size(), 1865u);
  EXPECT_EQ(countTrias(model), 54u);
  EXPECT_EQ(model.shells.size() - countTrias(model), 1811u);
  ASSERT_EQ(model.parts.size(), 1u);
  EXPECT_EQ(model.parts[0].id, 4075);
  EXPECT_EQ(model.parts[0].name, "Recliner Bkt i/b");
  EXPECT_TRUE(model.parts[0].definedInBlocks);
  for (const Shell& shell : model.shells) ASSERT_EQ(shell.part, 4075);
  EXPECT_EQ(model.nodes[0].id, 434224);
  EXPECT_DOUBLE_EQ(model.nodes[0].xyz[0], 3266.4460449);
  EXPECT_DOUBLE_EQ(model.nodes[0].xyz[1], -167.3549194);
  EXPECT_DOUBLE_EQ(model.nodes[0].xyz[2], 555.2623901);
  EXPECT_EQ(model.shells[0].id, 479590);
  EXPECT_EQ(model.shells[0].nodes, (std::array<Id, 4>{434225, 434226, 434228, 434692}));
  EXPECT_TRUE(warnings.empty());
  ASSERT_NE(findBlock(model, "*PART"), nullptr);
  EXPECT_NE(findBlock(model, "*PART")->text.find("$HMNAME COMPS    4074Recliner B_817"),
            std::string::npos);
}

TEST(LsDynaRealDecks, WheelCounts) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "wheel.k");
  const FeModel model = read(path);
  EXPECT_EQ(model.nodes.size(), 11825u);
  EXPECT_EQ(model.shells.size(), 11553u);
  ASSERT_EQ(model.parts.size(), 1u);
  EXPECT_EQ(model.parts[0].id, 1);
  EXPECT_EQ(model.parts[0].name, "MC - rim - front- R");
}

TEST(LsDynaRealDecks, BirdCountsPartsAndSph) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "bird.k");
  const FeModel model = read(path);
  EXPECT_EQ(model.nodes.size(), 5185u);
  EXPECT_EQ(model.shells.size(), 960u);
  ASSERT_EQ(model.parts.size(), 3u);  // *PART 1, *PART_INERTIA 2, *PART 101 (SPH)
  EXPECT_EQ(model.parts[0].id, 1);
  EXPECT_EQ(model.parts[1].id, 2);
  EXPECT_EQ(model.parts[2].id, 101);
  for (const Part& part : model.parts) {
    EXPECT_EQ(part.name, "");  // blank titles
    EXPECT_TRUE(part.definedInBlocks);
  }
  const DeckBlock* sph = findBlock(model, "*ELEMENT_SPH");
  ASSERT_NE(sph, nullptr);
  EXPECT_NE(sph->text.find(" 1000001     101   9.9999997e-05"), std::string::npos);
}

TEST(LsDynaRealDecks, RoundTripBracket) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "bracket.k");
  expectRealRoundTrip("rt_bracket", path);
}

TEST(LsDynaRealDecks, RoundTripWheel) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "wheel.k");
  expectRealRoundTrip("rt_wheel", path);
}

TEST(LsDynaRealDecks, RoundTripBirdKeepsSphAndSets) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "bird.k");
  expectRealRoundTrip("rt_bird", path);
  const FeModel model = read(path);
  const std::string written = write(model);
  for (const char* keyword :
       {"*ELEMENT_SPH", "*SET_NODE_LIST\n", "*SET_NODE_LIST_GENERATE", "*PART_INERTIA", "*END"}) {
    const DeckBlock* block = findBlock(model, keyword);
    ASSERT_NE(block, nullptr) << keyword;
    EXPECT_NE(written.find(block->text), std::string::npos) << keyword;
  }
}

// ---------------------------------------------------------------------------------------------
// Shell options

TEST(LsDynaShellOptions, ThicknessBetaMcidOffsetValues) {
  const std::string deck =
      std::string("*KEYWORD\n") + kTwoQuads + "*ELEMENT_SHELL_THICKNESS\n" +
      cols(8, {"1", "7", "1", "2", "3", "4"}) + "\n" + cols(16, {"1.1", "1.2", "1.3", "1.4"}) +
      "\n" + "*ELEMENT_SHELL_BETA\n" + cols(8, {"2", "7", "2", "5", "6", "3"}) + "\n" +
      cols(16, {"2.0", "2.0", "2.0", "2.0", "45.0"}) + "\n" + "*ELEMENT_SHELL_MCID\n" +
      cols(8, {"3", "7", "1", "2", "3"}) + "\n" + cols(16, {"0.5", "0.5", "0.5", "0.5", "12"}) +
      "\n" + "*ELEMENT_SHELL_OFFSET\n" + cols(8, {"4", "7", "2", "5", "6", "3"}) + "\n" +
      cols(16, {"-0.7"}) + "\n" + "*ELEMENT_SHELL_OFFSET_BETA\n" +
      cols(8, {"5", "7", "1", "2", "3", "4"}) + "\n" +
      cols(16, {"3.0", "3.0", "3.0", "3.0", "30.0"}) + "\n" + cols(16, {"0.25"}) + "\n" + "*END\n";
  const FeModel model = readText("options", deck);
  ASSERT_EQ(model.shells.size(), 5u);
  const auto extras = [&](std::size_t i) -> const ShellExtras& {
    EXPECT_GE(model.shells[i].extras, 0);
    return model.shellExtras.at(static_cast<std::size_t>(model.shells[i].extras));
  };
  EXPECT_EQ(model.shellTypes[model.shells[0].type], "_THICKNESS");
  EXPECT_EQ(extras(0).thickness, (std::array<double, 4>{1.1, 1.2, 1.3, 1.4}));
  EXPECT_EQ(model.shellTypes[model.shells[1].type], "_BETA");
  EXPECT_EQ(extras(1).angle, 45.0);
  EXPECT_FALSE(extras(1).angleIsMcid);
  EXPECT_EQ(model.shellTypes[model.shells[2].type], "_MCID");
  EXPECT_EQ(model.shells[2].nodeCount, 3);
  EXPECT_EQ(extras(2).angle, 12.0);
  EXPECT_TRUE(extras(2).angleIsMcid);
  EXPECT_EQ(model.shellTypes[model.shells[3].type], "_OFFSET");
  EXPECT_EQ(extras(3).offset, -0.7);
  EXPECT_EQ(model.shellTypes[model.shells[4].type], "_OFFSET_BETA");
  EXPECT_EQ(extras(4).thickness[0], 3.0);
  EXPECT_EQ(extras(4).angle, 30.0);
  EXPECT_EQ(extras(4).offset, 0.25);

  std::string written;
  const FeModel back = roundTrip("options_rt", model, &written);
  expectSameModel(model, back);
  EXPECT_NE(written.find("*ELEMENT_SHELL_MCID\n"), std::string::npos);
  EXPECT_NE(written.find("*ELEMENT_SHELL_OFFSET_BETA\n"), std::string::npos);
}

TEST(LsDynaShellOptions, DegenerateQuadsAreTriangles) {
  const std::string deck = std::string(kTwoQuads) +
                           "*ELEMENT_SHELL\n"
                           "       1       1       1       2       3       3\n"
                           "       2       1       2       5       6       0\n"
                           "       3       1       2       5       6\n"
                           "       4       1       1       2       3       4\n";
  const FeModel model = readText("degenerate", deck);
  ASSERT_EQ(model.shells.size(), 4u);
  EXPECT_EQ(model.shells[0].nodeCount, 3);
  EXPECT_EQ(model.shells[1].nodeCount, 3);
  EXPECT_EQ(model.shells[2].nodeCount, 3);
  EXPECT_EQ(model.shells[3].nodeCount, 4);
  std::string written;
  expectSameModel(model, roundTrip("degenerate_rt", model, &written));
  EXPECT_NE(written.find("       1       1       1       2       3       3\n"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Card formats

TEST(LsDynaFormats, LongFormatGlobally) {
  const std::string deck =
      "*KEYWORD LONG=Y\n*NODE\n" +
      cols(20, {"123456789012", "1.5", "-2.5", "3.14159265358979", "5", "6"}) + "\n" +
      cols(20, {"123456789013", "2.5", "-2.5", "0.0"}) + "\n" +
      cols(20, {"123456789014", "2.5", "-1.5", "0.0"}) + "\n*ELEMENT_SHELL\n" +
      cols(20, {"99999999999", "4444444444", "123456789012", "123456789013", "123456789014"}) +
      "\n*PART\nlong part\n" + cols(20, {"4444444444", "1", "1"}) + "\n*END\n";
  const FeModel model = readText("long", deck);
  ASSERT_EQ(model.nodes.size(), 3u);
  EXPECT_EQ(model.nodes[0].id, 123456789012);
  EXPECT_DOUBLE_EQ(model.nodes[0].xyz[2], 3.14159265358979);
  EXPECT_EQ(model.nodeExtras.at(123456789012).dynaTc, 5);
  EXPECT_EQ(model.nodeExtras.at(123456789012).dynaRc, 6);
  ASSERT_EQ(model.shells.size(), 1u);
  EXPECT_EQ(model.shells[0].id, 99999999999);
  EXPECT_EQ(model.shells[0].part, 4444444444);
  EXPECT_EQ(model.shells[0].nodeCount, 3);
  ASSERT_EQ(model.parts.size(), 1u);
  EXPECT_EQ(model.parts[0].name, "long part");
  // The deck is long: the writer keeps it so (no suffix, 20-column fields).
  std::string written;
  expectSameModel(model, roundTrip("long_rt", model, &written));
  EXPECT_NE(written.find("*NODE\n"), std::string::npos);
  EXPECT_NE(written.find("        123456789012"), std::string::npos);
}

TEST(LsDynaFormats, PlusSuffixPerKeyword) {
  const std::string deck = "*KEYWORD\n*NODE +\n" + cols(20, {"1", "0.0", "0.0", "0.0"}) + "\n" +
                           cols(20, {"2", "1.0", "0.0", "0.0"}) + "\n*NODE+\n" +
                           cols(20, {"3", "1.0", "1.0", "0.0"}) + "\n*NODE\n" + cols(8, {"4"}) +
                           cols(16, {"0.0", "1.0", "0.0"}) + "\n*ELEMENT_SHELL +\n" +
                           cols(20, {"10", "1", "1", "2", "3", "4"}) + "\n";
  const FeModel model = readText("plus", deck);
  ASSERT_EQ(model.nodes.size(), 4u);
  EXPECT_EQ(model.nodes[2].id, 3);
  EXPECT_EQ(model.nodes[2].xyz[1], 1.0);
  EXPECT_EQ(model.nodes[3].id, 4);
  ASSERT_EQ(model.shells.size(), 1u);
  EXPECT_EQ(model.shells[0].nodes, (std::array<Id, 4>{1, 2, 3, 4}));
  // Later *NODE blocks add nodes but no block.
  int nodeBlocks = 0;
  for (const DeckBlock& block : model.blocks) nodeBlocks += block.kind == DeckBlock::Kind::Nodes;
  EXPECT_EQ(nodeBlocks, 1);
}

TEST(LsDynaFormats, PercentI10) {
  const std::string deck =
      "*KEYWORD\n*NODE %\n" + cols(10, {"1234567890"}) + cols(16, {"0.0", "0.0", "0.0"}) + "\n" +
      cols(10, {"1234567891"}) + cols(16, {"1.0", "0.0", "0.0"}) + cols(10, {"7", "0"}) + "\n" +
      cols(10, {"1234567892"}) + cols(16, {"1.0", "1.0", "0.0"}) + "\n*ELEMENT_SHELL %\n" +
      cols(10, {"9876543210", "5", "1234567890", "1234567891", "1234567892", "1234567892"}) + "\n";
  const FeModel model = readText("i10", deck);
  ASSERT_EQ(model.nodes.size(), 3u);
  EXPECT_EQ(model.nodes[1].id, 1234567891);
  EXPECT_EQ(model.nodeExtras.at(1234567891).dynaTc, 7);
  ASSERT_EQ(model.shells.size(), 1u);
  EXPECT_EQ(model.shells[0].id, 9876543210);
  EXPECT_EQ(model.shells[0].part, 5);
  EXPECT_EQ(model.shells[0].nodeCount, 3);
  EXPECT_EQ(model.shells[0].nodes[2], 1234567892);

  const FeModel global = readText("i10_global",
                                  "*KEYWORD I10=Y\n"
                                  "*NODE\n"
                                  "1234567890             0.0             0.0             0.0\n");
  ASSERT_EQ(global.nodes.size(), 1u);
  EXPECT_EQ(global.nodes[0].id, 1234567890);
}

TEST(LsDynaFormats, CommaFreeFormat) {
  const FeModel model = readText("comma",
                                 "*NODE\n"
                                 "1,0.5,1.5,2.5\n"
                                 "2, 1.0 , , 3.0,,\n"
                                 "3,1e1,2.,-1.5D+1,4,5\n"
                                 "*ELEMENT_SHELL_THICKNESS\n"
                                 "1,9,1,2,3\n"
                                 "0.5,0.6,0.7,,10.0\n");
  ASSERT_EQ(model.nodes.size(), 3u);
  EXPECT_EQ(model.nodes[0].xyz, (std::array<double, 3>{0.5, 1.5, 2.5}));
  EXPECT_EQ(model.nodes[1].xyz, (std::array<double, 3>{1.0, 0.0, 3.0}));
  EXPECT_EQ(model.nodes[2].xyz, (std::array<double, 3>{10.0, 2.0, -15.0}));
  EXPECT_EQ(model.nodeExtras.at(3).dynaTc, 4);
  EXPECT_EQ(model.nodeExtras.at(3).dynaRc, 5);
  ASSERT_EQ(model.shells.size(), 1u);
  EXPECT_EQ(model.shells[0].part, 9);
  const ShellExtras& extras =
      model.shellExtras.at(static_cast<std::size_t>(model.shells[0].extras));
  EXPECT_EQ(extras.thickness, (std::array<double, 4>{0.5, 0.6, 0.7, 0.0}));
  EXPECT_EQ(extras.angle, 10.0);
}

TEST(LsDynaFormats, WhitespaceSeparated) {
  const FeModel model = readText("blanks",
                                 "*NODE\n"
                                 "1 0.5 1.5 2.5\n"
                                 "\t2\t1.0\t-2.0\t3.0\n"
                                 "123456789 1 2 3\n"
                                 "*ELEMENT_SHELL\n"
                                 "1 2 1 2 123456789\n");
  ASSERT_EQ(model.nodes.size(), 3u);
  EXPECT_EQ(model.nodes[0].xyz, (std::array<double, 3>{0.5, 1.5, 2.5}));
  EXPECT_EQ(model.nodes[1].id, 2);
  EXPECT_EQ(model.nodes[1].xyz, (std::array<double, 3>{1.0, -2.0, 3.0}));
  EXPECT_EQ(model.nodes[2].id, 123456789);
  ASSERT_EQ(model.shells.size(), 1u);
  EXPECT_EQ(model.shells[0].nodes[2], 123456789);
  EXPECT_EQ(model.shells[0].nodeCount, 3);
}

TEST(LsDynaFormats, LowerCaseKeywordsAndCrLf) {
  const std::string deck =
      "*keyword\r\n"
      "*part\r\n"
      "$# title\r\n"
      "Lower Part  \r\n"
      "         3         1         1\r\n"
      "*node\r\n"
      "       1             0.0             0.0             0.0\r\n"
      "       2             1.0             0.0             0.0\r\n"
      "       3             1.0             1.0             0.0\r\n"
      "*element_shell_thickness\r\n"
      "       1       3       1       2       3\r\n"
      "             1.0             1.0             1.0\r\n"
      "*end\r\n";
  const FeModel model = readText("lower", deck);
  ASSERT_EQ(model.nodes.size(), 3u);
  ASSERT_EQ(model.shells.size(), 1u);
  EXPECT_EQ(model.shellTypes[model.shells[0].type], "_THICKNESS");
  ASSERT_EQ(model.parts.size(), 1u);
  EXPECT_EQ(model.parts[0].name, "Lower Part");
  ASSERT_NE(findBlock(model, "*part\r\n"), nullptr);
  std::string written;
  expectSameModel(model, roundTrip("lower_rt", model, &written));
  EXPECT_NE(written.find("*NODE\r\n"),
            std::string::npos);  // generated lines follow the deck's CRLF
  EXPECT_EQ(written.find("*ELEMENT_SHELL_THICKNESS\n"), std::string::npos);
  EXPECT_NE(written.find("*end\r\n"), std::string::npos);
}

TEST(LsDynaFormats, LargeIdsRoundTripThroughI10AndLong) {
  FeModel model;
  model.blocks.push_back({DeckBlock::Kind::Verbatim, "*KEYWORD\n"});
  model.blocks.push_back({DeckBlock::Kind::Nodes, {}});
  model.blocks.push_back({DeckBlock::Kind::Shells, {}});
  model.blocks.push_back({DeckBlock::Kind::Verbatim, "*END\n"});
  model.nodes = {{12345678, {0.1, 0.2, 0.3}}, {99999999, {1.0 / 3.0, 0, 0}}, {5, {0, 1, 0}}};
  model.shells.push_back(Shell{1, 1, {12345678, 99999999, 5, 0}, 3, 0, -1});
  model.parts.push_back(Part{1, "p", false});
  std::string written;
  expectSameModel(model, roundTrip("ids8", model, &written));
  EXPECT_NE(written.find("*NODE\n"), std::string::npos);  // 8 digits still fit the standard format

  model.nodes[2].id = 1234567890;  // 10 digits: I10
  model.shells[0].nodes[2] = 1234567890;
  expectSameModel(model, roundTrip("ids10", model, &written));
  EXPECT_NE(written.find("*NODE %\n"), std::string::npos);
  EXPECT_NE(written.find("*ELEMENT_SHELL %\n"), std::string::npos);

  model.nodes[2].id = 123456789012345;  // 15 digits: long
  model.shells[0].nodes[2] = 123456789012345;
  model.shells[0].id = 99999999999;
  model.parts[0].id = 77777777777;
  model.shells[0].part = 77777777777;
  expectSameModel(model, roundTrip("ids15", model, &written));
  EXPECT_NE(written.find("*NODE +\n"), std::string::npos);
  EXPECT_NE(written.find("*ELEMENT_SHELL +\n"), std::string::npos);
  EXPECT_NE(written.find("*PART +\n"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Includes and parts

TEST(LsDynaInclude, RelativePathInSubfolderIsInlined) {
  const fs::path dir = test::scratchDir("include");
  test::writeText(dir / "main.k",
                  "*KEYWORD\n"
                  "*TITLE\n"
                  "main deck\n"
                  "*INCLUDE\n"
                  "sub/mesh.k\n"
                  "*CONTROL_TERMINATION\n"
                  "       1.0\n"
                  "*END\n");
  test::writeText(dir / "sub" / "mesh.k",
                  "*KEYWORD\n"
                  "$ the mesh of the part\n"
                  "*NODE\n"
                  "       1             0.0             0.0             0.0\n"
                  "       2             1.0             0.0             0.0\n"
                  "*INCLUDE\n"
                  "more/nodes3.k\n"
                  "*SET_NODE_LIST\n"
                  "         1\n"
                  "         1         2         3\n"
                  "*PART\n"
                  "included part\n"
                  "         8         1         1\n"
                  "*ELEMENT_SHELL\n"
                  "       1       8       1       2       3\n"
                  "*END\n");
  test::writeText(dir / "sub" / "more" / "nodes3.k",
                  "*NODE\n"
                  "       3             1.0             1.0             0.0");  // no final newline
  Warnings warnings;
  const FeModel model = read(dir / "main.k", &warnings);
  ASSERT_EQ(model.nodes.size(), 3u);
  ASSERT_EQ(model.shells.size(), 1u);
  ASSERT_EQ(model.parts.size(), 1u);
  EXPECT_EQ(model.parts[0].name, "included part");
  EXPECT_TRUE(contains(warnings, "inlined *INCLUDE 'sub/mesh.k'"));
  EXPECT_TRUE(contains(warnings, "inlined *INCLUDE 'more/nodes3.k'"));
  const std::string written = write(model);
  EXPECT_EQ(written.find("*INCLUDE"), std::string::npos);
  EXPECT_EQ(written.find("*END"), written.rfind("*END"));  // the include's *END is not inlined
  EXPECT_EQ(written.find("*KEYWORD"), written.rfind("*KEYWORD"));
  const std::size_t set =
      written.find("*SET_NODE_LIST\n         1\n         1         2         3\n");
  ASSERT_NE(set, std::string::npos);
  EXPECT_LT(written.find("*TITLE\nmain deck\n"), set);
  EXPECT_LT(set, written.find("*CONTROL_TERMINATION\n       1.0\n"));
  EXPECT_NE(written.find("$ the mesh of the part\n"), std::string::npos);
  expectSameModel(model, readText("include_rt", written));
}

TEST(LsDynaInclude, LongIncludeGetsSuffixWhenInlined) {
  const fs::path dir = test::scratchDir("include_long");
  test::writeText(dir / "main.k", "*KEYWORD\n*INCLUDE +\nlong.k\n*END\n");
  test::writeText(dir / "long.k", "*NODE\n" + cols(20, {"1", "0.0", "0.0", "0.0"}) +
                                      "\n*SET_NODE_LIST\n" + cols(20, {"1"}) + "\n");
  const FeModel model = read(dir / "main.k");
  ASSERT_EQ(model.nodes.size(), 1u);
  EXPECT_NE(findBlock(model, "*SET_NODE_LIST +\n"), nullptr);
}

TEST(LsDynaParts, SeveralPartsInOneBlockAndInertiaCards) {
  const std::string deck =
      std::string(kTwoQuads) +
      "*PART\n"
      "$HMNAME COMPS       1first\n"
      "first part\n"
      "         1         1         1\n"
      "second part\n"
      "         2         1         1\n"
      "*PART_INERTIA\n"
      "inertia one\n"
      "         3         1         1\n"
      "       0.0       0.0       0.0       1.0         1\n"
      "       1.0       0.0       0.0       1.0       0.0       1.0\n"
      "       0.0       0.0       0.0       0.0       0.0       0.0\n"
      "       1.0       0.0       0.0       0.0       1.0       0.0         0\n"
      "inertia two\n"
      "         4         1         1\n"
      "       0.0       0.0       0.0       1.0\n"
      "       1.0       0.0       0.0       1.0       0.0       1.0\n"
      "       0.0       0.0       0.0       0.0       0.0       0.0\n"
      "*PART_DUPLICATE\n"
      "PART              1         0\n"
      "*ELEMENT_SHELL\n"
      "       1       1       1       2       3       4\n"
      "       2       9       2       5       6       3\n";
  Warnings warnings;
  const FeModel model = readText("parts", deck, &warnings);
  ASSERT_EQ(model.parts.size(), 5u);
  EXPECT_EQ(model.parts[0].name, "first part");
  EXPECT_EQ(model.parts[1].id, 2);
  EXPECT_EQ(model.parts[1].name, "second part");
  EXPECT_EQ(model.parts[2].id, 3);
  EXPECT_EQ(model.parts[3].id, 4);
  EXPECT_EQ(model.parts[3].name, "inertia two");
  EXPECT_TRUE(model.parts[3].definedInBlocks);
  EXPECT_EQ(model.parts[4].id, 9);  // used by a shell, defined nowhere
  EXPECT_EQ(model.parts[4].name, "");
  EXPECT_FALSE(model.parts[4].definedInBlocks);
  EXPECT_TRUE(contains(warnings, "not defined by any *PART (9)"));

  std::string written;
  const FeModel back = roundTrip("parts_rt", model, &written);
  ASSERT_EQ(back.parts.size(), 5u);
  EXPECT_EQ(back.parts[4].id, 9);
  EXPECT_TRUE(back.parts[4].definedInBlocks);  // the writer generated its *PART
  EXPECT_NE(written.find("SECID and MID of part 9"), std::string::npos);
}

TEST(LsDynaWrite, FreshDeckFromAnotherFormat) {
  FeModel model;
  model.sourceFormat = DeckFormat::Nastran;
  model.blocks.push_back({DeckBlock::Kind::Verbatim, "PARAM,POST,-1\n"});
  model.nodes = {{1, {0, 0, 0}}, {2, {1, 0, 0}}, {3, {1, 1, 0}}, {4, {0, 1, 0}}};
  model.nodeExtras[2].dynaTc = 7;
  model.nodeExtras[3].nastranCd = 5;  // not LS-DYNA's: not written
  model.shellExtras.push_back(ShellExtras{{1.5, 1.5, 1.5, 1.5}, 0.0, false, 0.0});
  model.shellExtras.push_back(ShellExtras{{0, 0, 0, 0}, 4.0, true, 0.5});
  model.shellTypes.push_back("CQUAD4");
  model.shells.push_back(Shell{10, 1, {1, 2, 3, 4}, 4, 1, 0});
  model.shells.push_back(Shell{11, 1, {1, 3, 4, 0}, 3, 1, 1});
  model.shells.push_back(Shell{12, 2, {1, 2, 3, 0}, 3, 1, -1});
  model.parts = {{1, "skin", false}, {2, "", false}};
  const std::string written = write(model);
  EXPECT_EQ(written.find("PARAM"), std::string::npos);
  EXPECT_LT(written.find("*KEYWORD\n"), written.find("*PART\n"));
  EXPECT_NE(written.find("*ELEMENT_SHELL_THICKNESS\n"), std::string::npos);
  EXPECT_NE(written.find("*ELEMENT_SHELL_MCID_OFFSET\n"), std::string::npos);
  EXPECT_EQ(written.substr(written.size() - 5), "*END\n");
  const FeModel back = readText("fresh", written);
  ASSERT_EQ(back.nodes.size(), 4u);
  EXPECT_EQ(back.nodeExtras.size(), 1u);
  EXPECT_EQ(back.nodeExtras.at(2).dynaTc, 7);
  ASSERT_EQ(back.shells.size(), 3u);
  const ShellExtras& mcid = back.shellExtras.at(static_cast<std::size_t>(back.shells[1].extras));
  EXPECT_TRUE(mcid.angleIsMcid);
  EXPECT_EQ(mcid.angle, 4.0);
  EXPECT_EQ(mcid.offset, 0.5);
  EXPECT_EQ(back.shells[2].extras, -1);
  ASSERT_EQ(back.parts.size(), 2u);
  EXPECT_EQ(back.parts[0].name, "skin");
  EXPECT_TRUE(back.parts[0].definedInBlocks);
}

TEST(LsDynaWrite, GeometryWithoutItsBlocksFollowsKeyword) {
  FeModel model;
  model.blocks.push_back({DeckBlock::Kind::Verbatim, "$ header\n*KEYWORD LONG=Y\n"});
  model.blocks.push_back({DeckBlock::Kind::Verbatim, "*CONTROL_TERMINATION\n       1.0\n"});
  model.blocks.push_back({DeckBlock::Kind::Verbatim, "*END"});  // no final newline
  model.nodes = {{1, {0, 0, 0}}, {2, {1, 0, 0}}, {3, {1, 1, 0}}};
  model.shells.push_back(Shell{1, 4, {1, 2, 3, 0}, 3, 0, -1});
  model.parts.push_back(Part{4, "new part", false});
  std::string written;
  const FeModel back = roundTrip("no_blocks", model, &written);
  expectSameModel(model, back);
  const std::size_t keyword = written.find("*KEYWORD LONG=Y\n");
  const std::size_t nodes = written.find("*NODE\n");  // the deck is long: no suffix needed
  const std::size_t shells = written.find("*ELEMENT_SHELL\n");
  const std::size_t control = written.find("*CONTROL_TERMINATION\n");
  const std::size_t part = written.find("*PART\n");
  EXPECT_LT(keyword, nodes);
  EXPECT_LT(nodes, shells);
  EXPECT_LT(shells, control);
  EXPECT_LT(control, part);
  EXPECT_LT(part, written.find("*END"));
  EXPECT_NE(written.find("\nnew part\n"), std::string::npos);
  EXPECT_NE(written.find(std::string(19, ' ') + "1" + std::string(19, ' ') + "4"),
            std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Bad input: each an InputError with file and line

TEST(LsDynaErrors, MalformedNumber) {
  expectDeckError("e_number",
                  "*KEYWORD\n*NODE\n       1             0.0             0.0             0.0\n"
                  "       2           1.2.3             0.0             0.0\n",
                  4, "malformed x coordinate '1.2.3' in *NODE");
  expectDeckError("e_number2", "*ELEMENT_SHELL\n       1       1       1       2      x3\n", 2,
                  "malformed node N3 'x3'");
}

TEST(LsDynaErrors, TruncatedCards) {
  expectDeckError("e_trunc",
                  std::string(kTwoQuads) +
                      "*ELEMENT_SHELL_THICKNESS\n"
                      "       1       1       1       2       3       4\n"
                      "             1.0             1.0             1.0             1.0\n"
                      "       2       1       2       5       6       3\n"
                      "$ comment\n"
                      "*END\n",
                  11, "element 2 has no thickness card (card 2)");
  expectDeckError("e_trunc2",
                  std::string(kTwoQuads) + "*ELEMENT_SHELL\n       1       1       1       2\n", 9,
                  "fewer than 3 nodes");
  expectDeckError("e_trunc3", "*PART\ntitle only\n", 2, "has no card with its PID");
}

TEST(LsDynaErrors, MissingNodeDuplicateIds) {
  expectDeckError(
      "e_missing",
      std::string(kTwoQuads) + "*ELEMENT_SHELL\n       1       1       1       2       3      44\n",
      9, "names node 44, which the deck does not define");
  expectDeckError(
      "e_dupnode",
      std::string(kTwoQuads) + "*NODE\n       3             5.0             5.0             0.0\n",
      9, "duplicate node ID 3");
  expectDeckError("e_dupelem",
                  std::string(kTwoQuads) +
                      "*ELEMENT_SHELL\n"
                      "       1       1       1       2       3       4\n"
                      "       1       1       2       5       6       3\n",
                  10, "duplicate element ID 1");
}

TEST(LsDynaErrors, UnsupportedShellOptions) {
  expectDeckError("e_option", std::string(kTwoQuads) + "*ELEMENT_SHELL_COMPOSITE\n", 8,
                  "option _COMPOSITE is not supported");
  expectDeckError("e_option2", std::string(kTwoQuads) + "*ELEMENT_SHELL_BETA_MCID\n", 8,
                  "exclude each other");
  expectDeckError("e_8node",
                  std::string(kTwoQuads) +
                      "*ELEMENT_SHELL\n       1       1       1       2       3       4       5    "
                      "   6       0       0\n",
                  9, "8-node shell");
}

TEST(LsDynaErrors, MissingIncludeAndCycle) {
  const fs::path dir = test::scratchDir("e_include");
  io::writeFileAtomically(dir / "main.k",
                          "*KEYWORD\n*INCLUDE\n$ the mesh\nparts/missing.k\n*END\n");
  expectInputError([&] { read(dir / "main.k"); }, dir / "main.k", 4,
                   "include file 'parts/missing.k' not found");
  io::writeFileAtomically(dir / "a.k", "*KEYWORD\n*INCLUDE\nb.k\n");
  io::writeFileAtomically(dir / "b.k", "*INCLUDE\na.k\n");
  expectInputError([&] { read(dir / "a.k"); }, dir / "b.k", 2, "include cycle");
  // An error inside an include names the include file and its line.
  io::writeFileAtomically(dir / "c.k", "*KEYWORD\n*INCLUDE\nd.k\n");
  io::writeFileAtomically(dir / "d.k", "$\n*NODE\n       1             0.0             abc\n");
  expectInputError([&] { read(dir / "c.k"); }, dir / "d.k", 3, "malformed y coordinate 'abc'");
}

TEST(LsDynaErrors, EmptyAndBinaryFiles) {
  expectDeckError("e_empty", "  \n\n", 0, "empty file");
  expectDeckError("e_binary", std::string("*KEYWORD\n*NODE\n\x01\x02", 17) + std::string(3, '\0'),
                  3, "binary data");
}

// ---------------------------------------------------------------------------------------------
// Performance (run with --gtest_also_run_disabled_tests; Release build)

namespace {

/// A quad grid deck of n x n elements in standard format.
std::string gridDeck(int n) {
  std::string deck = "*KEYWORD\n*PART\ngrid\n         1         1         1\n*NODE\n";
  char line[128];
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = i * 0.5;
      const double y = j * 0.5;
      std::snprintf(line, sizeof line, "%8d%16.9g%16.9g%16.9g\n", j * (n + 1) + i + 1, x, y, 0.0);
      deck += line;
    }
  deck += "*ELEMENT_SHELL\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i + 1;
      std::snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8d\n", j * n + i + 1, 1, a, a + 1,
                    a + n + 2, a + n + 1);
      deck += line;
    }
  deck += "*END\n";
  return deck;
}

double seconds(const std::function<void()>& action) {
  const auto start = std::chrono::steady_clock::now();
  action();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST(LsDynaPerformance, DISABLED_MillionElements) {
  const fs::path path = test::scratchDir("perf") / "grid.k";
  io::writeFileAtomically(path, gridDeck(1000));
  FeModel model;
  const double readTime = seconds([&] { model = read(path); });
  ASSERT_EQ(model.shells.size(), 1000000u);
  EXPECT_LT(readTime, 5.0);
  std::printf("read 1,000,000 quads (%.1f MB): %.2f s\n",
              static_cast<double>(fs::file_size(path)) / 1e6, readTime);
  for (const bool arbitrary : {false, true}) {
    if (arbitrary) {  // coordinates whose shortest form does not fit 16 columns
      std::mt19937 random(5);
      std::uniform_real_distribution<double> offset(0.0, 1.0);
      for (Node& node : model.nodes)
        for (double& c : node.xyz) c = c * 1.0000001 + offset(random) / 3.0;
    }
    std::string out;
    Warnings warnings;
    const double writeTime = seconds([&] { io::writeLsDyna(model, out, warnings); });
    std::printf("write 1,000,000 quads (%s coordinates): %.2f s\n",
                arbitrary ? "arbitrary double" : "as read", writeTime);
    EXPECT_LT(writeTime, 5.0);
  }
}
