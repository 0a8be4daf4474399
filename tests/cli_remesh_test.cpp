// voxremesh remesh as a subprocess: the sample part, whole real decks (bird.k's other keywords
// byte for byte), the report, and bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "json/json.h"
#include "support/test_support.h"
#include "voxremesh/io.h"

namespace fs = std::filesystem;
using namespace voxremesh;
using voxremesh::test::contains;
using voxremesh::test::quoted;
using voxremesh::test::readText;
using voxremesh::test::runCli;
using voxremesh::test::samplePart;
using voxremesh::test::scratchDir;

namespace {

/// The text of a keyword block: from "\n*KEYWORD\n" to the next keyword line.
std::string blockOf(const std::string& text, const std::string& keyword) {
  const std::size_t begin = text.find("\n" + keyword + "\n");
  if (begin == std::string::npos) return "(missing " + keyword + ")";
  return text.substr(begin, text.find("\n*", begin + 1) - begin);
}

}  // namespace

TEST(RemeshCli, SamplePartWithDefaults) {
  const fs::path dir = scratchDir("remesh_sample");
  const fs::path sample = samplePart();
  const auto run = runCli("remesh " + quoted(sample) + " -o " + quoted(dir / "rail.k"));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "1 parts remeshed")) << run.output;
  const FeModel in = readDeck(sample);
  const FeModel out = readDeck(dir / "rail.k");
  EXPECT_GT(out.shells.size(), in.shells.size() / 2);
  Id maxIn = 0;
  for (const Shell& shell : in.shells) maxIn = std::max(maxIn, shell.id);
  for (const Shell& shell : out.shells) EXPECT_GT(shell.id, maxIn);
}

TEST(RemeshCli, BirdKeepsEveryOtherKeywordByteForByte) {
  VOXREMESH_REQUIRE_SHARED_DECK(bird, "bird.k");
  const fs::path dir = scratchDir("remesh_bird");
  const auto run = runCli("remesh " + quoted(bird) + " -o " + quoted(dir / "bird.k") +
                          " --report " + quoted(dir / "report.json") + " --threads 2");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const std::string in = readText(bird), out = readText(dir / "bird.k");
  for (const char* keyword :
       {"*ELEMENT_SPH", "*SET_NODE_LIST_GENERATE", "*CONSTRAINED_EXTRA_NODES_SET",
        "*BOUNDARY_PRESCRIBED_MOTION_RIGID", "*SECTION_SPH", "*EOS_GRUNEISEN", "*SET_PART_LIST",
        "*CONTACT_AUTOMATIC_NODES_TO_SURFACE_TITLE", "*DEFINE_BOX", "*CONTROL_SPH"})
    EXPECT_EQ(blockOf(out, keyword), blockOf(in, keyword)) << keyword;
  const json::Json report = json::parseJson(readText(dir / "report.json"));
  EXPECT_FALSE(report["remaps"].items.empty());
  const FeModel back = readDeck(dir / "bird.k");
  std::size_t sph = 0;
  for (const Node& node : back.nodes) sph += node.id >= 1000001 && node.id <= 1004160 ? 1 : 0;
  EXPECT_EQ(sph, 4160u);
}

TEST(RemeshCli, BadInputEndsWithAMessageAndNoOutput) {
  const fs::path dir = scratchDir("remesh_bad");
  const fs::path sample = samplePart();
  const auto noPart =
      runCli("remesh " + quoted(sample) + " -o " + quoted(dir / "a.k") + " --parts 5");
  EXPECT_EQ(noPart.exitCode, 1);
  EXPECT_TRUE(contains(noPart.output, "no part 5")) << noPart.output;
  const auto badSize =
      runCli("remesh " + quoted(sample) + " -o " + quoted(dir / "a.k") + " --size abc");
  EXPECT_EQ(badSize.exitCode, 1);
  const auto badExt = runCli("remesh " + quoted(sample) + " -o " + quoted(dir / "a.xyz"));
  EXPECT_EQ(badExt.exitCode, 1);
  const auto missing = runCli("remesh " + quoted(dir / "none.k") + " -o " + quoted(dir / "a.k"));
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_TRUE(contains(missing.output, "none.k")) << missing.output;
  EXPECT_FALSE(fs::exists(dir / "a.k"));
  EXPECT_FALSE(fs::exists(dir / "a.xyz"));
}
