// Conversions between every pair of formats through the public API (readDeck / writeDeck): counts,
// coordinates to the format's precision, part membership and names are kept; the real decks go
// through every format without losing an element.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "support/test_support.h"
#include "voxremesh/errors.h"
#include "voxremesh/fe_model.h"
#include "voxremesh/io.h"

using namespace voxremesh;

namespace {

/// What a format carries, for the assertions.
struct FormatTraits {
  const char* extension;
  bool keepsIds;     ///< node and element IDs as given
  bool keepsParts;   ///< part IDs and membership
  bool keepsNames;   ///< part names
  bool keepsQuads;   ///< quads stay quads (STL splits them)
  double tolerance;  ///< relative coordinate tolerance
};

const FormatTraits kFormats[] = {
    {"k", true, true, true, true, 1e-9},       {"bdf", true, true, true, true, 1e-9},
    {"inp", true, true, true, true, 0.0},      {"obj", false, true, true, true, 0.0},
    {"ply", false, true, false, true, 0.0},    {"off", false, false, false, true, 0.0},
    {"stl", false, false, false, false, 1e-7},
};

/// Two named parts on a 6 x 4 grid with sparse IDs, a few triangles, and a non-manifold
/// T-junction: a fin of two quads standing on an inner edge of part 1.
FeModel makeTwoPartModel() {
  FeModel model;
  model.sourceFormat = DeckFormat::LsDyna;
  auto nodeId = [](int i, int j) { return static_cast<Id>(70001 + 100 * i + j); };
  for (int i = 0; i <= 6; ++i)
    for (int j = 0; j <= 4; ++j)
      model.nodes.push_back({nodeId(i, j), {12.5 * i + 0.1 * j, 9.25 * j, 0.03 * i * j}});
  Id shellId = 9000001;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 4; ++j) {
      const Id part = i < 3 ? 4075 : 4080;
      if ((i + j) % 5 == 0) {  // split into two triangles
        model.shells.push_back(
            {shellId++, part, {nodeId(i, j), nodeId(i + 1, j), nodeId(i + 1, j + 1), 0}, 3});
        model.shells.push_back(
            {shellId++, part, {nodeId(i, j), nodeId(i + 1, j + 1), nodeId(i, j + 1), 0}, 3});
      } else {
        model.shells.push_back(
            {shellId++,
             part,
             {nodeId(i, j), nodeId(i + 1, j), nodeId(i + 1, j + 1), nodeId(i, j + 1)},
             4});
      }
    }
  // The fin on the edge between (2,1) and (2,2), upwards.
  model.nodes.push_back({80001, {25.2, 9.25, 10.0}});
  model.nodes.push_back({80002, {25.1, 18.5, 10.0}});
  model.nodes.push_back({80003, {25.3, 0.0, 10.0}});
  model.shells.push_back({shellId++, 4075, {nodeId(2, 1), nodeId(2, 2), 80002, 80001}, 4});
  model.shells.push_back({shellId++, 4075, {nodeId(2, 0), nodeId(2, 1), 80001, 80003}, 4});
  model.parts.push_back({4075, "Recliner Bkt i/b", false});
  model.parts.push_back({4080, "Rail_inner", false});
  return model;
}

/// Positions of the corners of every shell, as sorted triples: a geometric fingerprint that does
/// not depend on IDs or node order.
std::vector<std::array<double, 3>> cornerPositions(const FeModel& model) {
  std::map<Id, std::array<double, 3>> position;
  for (const Node& node : model.nodes) position[node.id] = node.xyz;
  std::vector<std::array<double, 3>> corners;
  for (const Shell& shell : model.shells)
    for (int k = 0; k < shell.nodeCount; ++k) corners.push_back(position.at(shell.nodes[k]));
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  return corners;
}

std::size_t countQuads(const FeModel& model) {
  return static_cast<std::size_t>(std::count_if(model.shells.begin(), model.shells.end(),
                                                [](const Shell& s) { return s.nodeCount == 4; }));
}

/// Map part name -> number of shells (or part ID -> number, when names are not kept). A part
/// without a name is keyed by its ID: formats that need a label (Abaqus ELSET, OBJ group) write
/// it as "PART_<id>", which maps to the same key.
std::map<std::string, std::size_t> membership(const FeModel& model, bool byName) {
  std::map<std::string, std::size_t> count;
  for (const Shell& shell : model.shells) {
    const Part* part = model.findPart(shell.part);
    std::string key = std::to_string(shell.part);
    if (byName && part) {
      std::string upper = part->name;
      for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      const bool labelOfId = upper.rfind("PART_", 0) == 0;
      key = part->name.empty() ? "#" + std::to_string(part->id)
            : labelOfId        ? "#" + upper.substr(5)
                               : part->name;
    }
    count[key]++;
  }
  return count;
}

void expectSameGeometry(const FeModel& a, const FeModel& b, const FormatTraits& traits) {
  const auto ca = cornerPositions(a), cb = cornerPositions(b);
  ASSERT_EQ(ca.size(), cb.size()) << traits.extension;
  for (std::size_t i = 0; i < ca.size(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(ca[i][c], cb[i][c], traits.tolerance * (std::fabs(ca[i][c]) + 1.0))
          << traits.extension << " corner " << i;
}

}  // namespace

TEST(RoundTrip, EveryFormatKeepsCountsCoordinatesAndParts) {
  const FeModel model = makeTwoPartModel();
  const auto dir = test::scratchDir("roundtrip-every-format");
  for (const FormatTraits& traits : kFormats) {
    SCOPED_TRACE(traits.extension);
    const auto file = dir / (std::string("model.") + traits.extension);
    writeDeck(model, file);
    const FeModel back = readDeck(file);
    const std::size_t quads = countQuads(model), trias = model.shells.size() - quads;
    if (traits.keepsQuads) {
      EXPECT_EQ(back.shells.size(), model.shells.size());
      EXPECT_EQ(countQuads(back), quads);
    } else {
      EXPECT_EQ(back.shells.size(), 2 * quads + trias);
    }
    EXPECT_EQ(back.nodes.size(), model.nodes.size());
    expectSameGeometry(model, back, traits);
    if (traits.keepsIds) {
      std::map<Id, std::array<double, 3>> original;
      for (const Node& node : model.nodes) original[node.id] = node.xyz;
      for (const Node& node : back.nodes) ASSERT_TRUE(original.count(node.id)) << node.id;
      for (std::size_t i = 0; i < model.shells.size(); ++i) {
        EXPECT_EQ(back.shells[i].id, model.shells[i].id);
        EXPECT_EQ(back.shells[i].nodes, model.shells[i].nodes);
      }
    }
    if (traits.keepsNames) {
      EXPECT_EQ(membership(back, true), membership(model, true));
    }
    if (traits.keepsParts && traits.keepsIds) {
      EXPECT_EQ(membership(back, false), membership(model, false));
    }
    if (traits.keepsParts) {
      EXPECT_EQ(back.parts.size(), model.parts.size());
    }
  }
}

TEST(RoundTrip, ChainOfDeckFormatsKeepsIdsPartsAndNames) {
  const FeModel model = makeTwoPartModel();
  const auto dir = test::scratchDir("roundtrip-chain");
  FeModel current = model;
  for (const char* extension : {"bdf", "inp", "k", "inp", "bdf", "k"}) {
    const auto file = dir / (std::string("step.") + extension);
    writeDeck(current, file);
    current = readDeck(file);
  }
  ASSERT_EQ(current.nodes.size(), model.nodes.size());
  ASSERT_EQ(current.shells.size(), model.shells.size());
  std::map<Id, std::array<double, 3>> original;
  for (const Node& node : model.nodes) original[node.id] = node.xyz;
  for (const Node& node : current.nodes)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(node.xyz[c], original.at(node.id)[c], 1e-9 * (std::fabs(node.xyz[c]) + 1.0));
  for (std::size_t i = 0; i < model.shells.size(); ++i) {
    EXPECT_EQ(current.shells[i].id, model.shells[i].id);
    EXPECT_EQ(current.shells[i].part, model.shells[i].part);
    EXPECT_EQ(current.shells[i].nodes, model.shells[i].nodes);
  }
  for (const Part& part : model.parts) {
    const Part* back = current.findPart(part.id);
    ASSERT_NE(back, nullptr) << part.id;
    EXPECT_EQ(back->name, part.name);
  }
}

TEST(RoundTrip, RealDecksGoThroughEveryFormatWithoutLosingAnElement) {
  for (const char* name : {"bracket.k", "wheel.k", "bird.k"}) {
    VOXREMESH_REQUIRE_SHARED_DECK(deck, name);
    SCOPED_TRACE(name);
    const FeModel model = readDeck(deck);
    const auto dir = test::scratchDir(std::string("roundtrip-real-") + name);
    for (const FormatTraits& traits : kFormats) {
      SCOPED_TRACE(traits.extension);
      const auto file = dir / (std::string("deck.") + traits.extension);
      Warnings warnings;
      writeDeck(model, file, {}, &warnings);
      const FeModel back = readDeck(file);
      const std::size_t quads = countQuads(model), trias = model.shells.size() - quads;
      EXPECT_EQ(back.shells.size(), traits.keepsQuads ? model.shells.size() : 2 * quads + trias);
      expectSameGeometry(model, back, traits);
      if (traits.keepsNames) {
        EXPECT_EQ(membership(back, true), membership(model, true));
      }
    }
  }
}

TEST(RoundTrip, SameFormatKeepsEveryOtherKeywordByteForByte) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "bird.k");
  const FeModel model = readDeck(deck);
  const auto file = test::scratchDir("roundtrip-bird") / "bird.k";
  writeDeck(model, file);
  const std::string written = test::readText(file);
  std::size_t verbatimBlocks = 0;
  for (const DeckBlock& block : model.blocks) {
    if (block.kind != DeckBlock::Kind::Verbatim) continue;
    ++verbatimBlocks;
    EXPECT_NE(written.find(block.text), std::string::npos) << block.text.substr(0, 80);
  }
  EXPECT_GT(verbatimBlocks, 20u);
  // *ELEMENT_SPH with its 4160 particles is passed through untouched.
  const std::string source = test::readText(deck);
  const auto sph = source.find("*ELEMENT_SPH");
  ASSERT_NE(sph, std::string::npos);
  const std::string sphBlock = source.substr(sph, source.find("\n*", sph) + 1 - sph);
  EXPECT_NE(written.find(sphBlock), std::string::npos);
}

TEST(RoundTrip, FailedWriteLeavesNoFileBehind) {
  const FeModel model = makeTwoPartModel();
  const auto dir = test::scratchDir("roundtrip-failed-write");
  // A folder that does not exist: the write fails and nothing is created.
  EXPECT_THROW(writeDeck(model, dir / "missing" / "out.k"), std::runtime_error);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  // A model whose shell names a node it does not have cannot be written as a surface mesh.
  FeModel broken = model;
  broken.shells[0].nodes[0] = 123456789;
  for (const char* extension : {"obj", "off", "ply", "stl", "vtu"}) {
    EXPECT_ANY_THROW(writeDeck(broken, dir / (std::string("broken.") + extension))) << extension;
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(RoundTrip, UnknownExtensionIsRefusedWithTheAcceptedOnes) {
  try {
    formatFromPath("part.xyz");
    FAIL() << "no exception";
  } catch (const SettingError& e) {
    EXPECT_NE(std::string(e.what()).find(".bdf"), std::string::npos);
  }
  EXPECT_EQ(formatFromName("nastran"), DeckFormat::Nastran);
  EXPECT_EQ(formatFromPath("A.KEY"), DeckFormat::LsDyna);
}
