// The voxremesh command line, run as a subprocess: help, version, usage errors, info and convert.
#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/text_scan.h"
#include "json/json.h"
#include "support/test_support.h"

namespace fs = std::filesystem;
using voxremesh::test::CliRun;
using voxremesh::test::quoted;
using voxremesh::test::readText;
using voxremesh::test::runCli;
using voxremesh::test::runCliSplit;
using voxremesh::test::scratchDir;
using voxremesh::test::writeText;

namespace {

void appendField(std::string& line, const std::string& text, std::size_t width) {
  line += std::string(width > text.size() ? width - text.size() : 0, ' ') + text;
}

// An LS-DYNA deck: part 1 a 4 x 3 grid of quads, part 2 two trias (n3 = n4) beside it.
std::string sampleDeck() {
  std::string deck = "*KEYWORD\n*PART\nplate\n         1         1         1\n";
  deck += "*PART\ngusset\n         2         1         1\n*NODE\n";
  auto node = [&](int id, double x, double y) {
    std::string line;
    appendField(line, std::to_string(id), 8);
    for (const double value : {x, y, 0.0}) {
      std::string number;
      voxremesh::io::appendRealFixedWidth(number, value, 16);
      line += number;
    }
    deck += line + "\n";
  };
  for (int j = 0; j <= 3; ++j)
    for (int i = 0; i <= 4; ++i) node(j * 5 + i + 1, 10.0 * i, 10.0 * j);
  node(21, 50.0, 0.0);
  node(22, 50.0, 10.0);
  deck += "*ELEMENT_SHELL\n";
  auto shell = [&](int id, int part, std::vector<int> n) {
    std::string line;
    appendField(line, std::to_string(id), 8);
    appendField(line, std::to_string(part), 8);
    for (const int v : n) appendField(line, std::to_string(v), 8);
    deck += line + "\n";
  };
  int id = 0;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      const int a = j * 5 + i + 1;
      shell(++id, 1, {a, a + 1, a + 6, a + 5});
    }
  shell(++id, 2, {5, 21, 22, 22});
  shell(++id, 2, {5, 22, 10, 10});
  deck += "*END\n";
  return deck;
}

// The deck with the x coordinate of node 2 (line 10) replaced by a malformed number.
std::string malformedDeck() {
  std::string deck = sampleDeck();
  std::size_t line = 0;
  for (int n = 1; n < 10; ++n) line = deck.find('\n', line) + 1;
  if (deck.compare(line, 8, "       2") != 0) throw std::logic_error("line 10 is not node 2");
  deck.replace(line + 8, 16, "       1.2.3e+x4");
  return deck;
}

// Value of "key": <number> in a JSON text (first occurrence after `from`).
double jsonNumber(const std::string& json, const std::string& key, std::size_t from = 0) {
  const std::size_t at = json.find("\"" + key + "\":", from);
  if (at == std::string::npos) throw std::runtime_error("no key " + key);
  return std::strtod(json.c_str() + at + key.size() + 3, nullptr);
}

}  // namespace

TEST(Cli, HelpListsTheCommands) {
  const CliRun r = runCliSplit("--help");
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.out.find("usage: voxremesh COMMAND"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("info"), std::string::npos);
  EXPECT_NE(r.out.find("convert"), std::string::npos);
  EXPECT_TRUE(r.err.empty());
  const CliRun info = runCliSplit("help info");
  EXPECT_EQ(info.exitCode, 0);
  EXPECT_NE(info.out.find("usage: voxremesh info DECK"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("--tolerance"), std::string::npos);
  const CliRun convert = runCliSplit("convert --help");
  EXPECT_EQ(convert.exitCode, 0);
  EXPECT_NE(convert.out.find("--ascii"), std::string::npos) << convert.out;
  EXPECT_EQ(runCliSplit("help nonsense").exitCode, 2);
}

TEST(Cli, VersionPrintsTheProjectVersion) {
  const CliRun r = runCliSplit("--version");
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_EQ(r.out, std::string("voxremesh ") + VOXREMESH_VERSION + "\n");
}

TEST(Cli, UsageErrorsExitWithTwo) {
  const CliRun unknown = runCliSplit("frobnicate");
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_NE(unknown.err.find("unknown command 'frobnicate'"), std::string::npos) << unknown.err;
  EXPECT_NE(unknown.err.find("usage:"), std::string::npos);
  EXPECT_TRUE(unknown.out.empty());
  EXPECT_EQ(runCliSplit("").exitCode, 2);
  const CliRun option = runCliSplit("info deck.k --bogus");
  EXPECT_EQ(option.exitCode, 2);
  EXPECT_NE(option.err.find("unknown option '--bogus'"), std::string::npos) << option.err;
  EXPECT_NE(option.err.find("usage: voxremesh info DECK"), std::string::npos) << option.err;
  const CliRun missing = runCliSplit("info");
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("missing argument"), std::string::npos) << missing.err;
  EXPECT_EQ(runCliSplit("convert only-one.k").exitCode, 2);
  EXPECT_EQ(runCliSplit("info a.k b.k").exitCode, 2);
  EXPECT_EQ(runCliSplit("info a.k --format").exitCode, 2);  // option without its value
}

TEST(Cli, InfoOnAMissingFileNamesIt) {
  const fs::path missing = scratchDir("cli-missing") / "no-such-deck.k";
  const CliRun r = runCliSplit("info " + quoted(missing));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err.rfind("voxremesh: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST(Cli, InfoOnAMalformedDeckNamesFileAndLine) {
  const fs::path dir = scratchDir("cli-malformed");
  writeText(dir / "bad.k", malformedDeck());
  const CliRun r = runCliSplit("info " + quoted(dir / "bad.k"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find((dir / "bad.k").string() + ":10"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST(Cli, InfoPrintsTheTableAndValidJson) {
  const fs::path dir = scratchDir("cli-info");
  writeText(dir / "deck.k", sampleDeck());
  const CliRun table = runCliSplit("info " + quoted(dir / "deck.k"));
  ASSERT_EQ(table.exitCode, 0) << table.err;
  EXPECT_NE(table.out.find("plate"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("gusset"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("total"), std::string::npos);
  EXPECT_NE(table.out.find("Findings"), std::string::npos);

  const CliRun json = runCliSplit("info " + quoted(dir / "deck.k") + " --json");
  ASSERT_EQ(json.exitCode, 0) << json.err;
  EXPECT_NO_THROW(voxremesh::json::parseJson(json.out)) << json.out;
  for (const char* key :
       {"\"model\"", "\"parts\"", "\"total\"", "\"examples\"", "\"boundaryEdges\"",
        "\"nonManifoldEdges\"", "\"inconsistentEdges\"", "\"edgeLength\""})
    EXPECT_NE(json.out.find(key), std::string::npos) << key;
  EXPECT_EQ(jsonNumber(json.out, "nodes"), 22);
  EXPECT_EQ(jsonNumber(json.out, "shells"), 14);
  const std::size_t total = json.out.find("\"total\"");
  EXPECT_EQ(jsonNumber(json.out, "quads", total), 12);
  EXPECT_EQ(jsonNumber(json.out, "trias", total), 2);
  // The trias share the grid's right edge nodes 5 and 10: boundary of the union 2 x (4 + 3) + 2.
  EXPECT_EQ(jsonNumber(json.out, "boundaryEdges", total), 16);
  EXPECT_EQ(jsonNumber(json.out, "boundaryLoops", total), 1);

  // --tolerance is honoured and checked; --format reads a deck whatever its extension.
  const CliRun tolerance =
      runCliSplit("info " + quoted(dir / "deck.k") + " --json --tolerance 0.125");
  ASSERT_EQ(tolerance.exitCode, 0) << tolerance.err;
  EXPECT_EQ(jsonNumber(tolerance.out, "tolerance"), 0.125);
  const CliRun badTolerance = runCliSplit("info " + quoted(dir / "deck.k") + " --tolerance abc");
  EXPECT_EQ(badTolerance.exitCode, 2);
  EXPECT_NE(badTolerance.err.find("--tolerance expects a number, not 'abc'"), std::string::npos)
      << badTolerance.err;
  EXPECT_EQ(runCliSplit("info " + quoted(dir / "deck.k") + " --tolerance -1").exitCode, 2);
  fs::copy_file(dir / "deck.k", dir / "deck.txt");
  EXPECT_EQ(runCliSplit("info " + quoted(dir / "deck.txt")).exitCode, 1);  // unknown extension
  EXPECT_EQ(runCliSplit("info " + quoted(dir / "deck.txt") + " --format=k").exitCode, 0);
}

TEST(Cli, ConvertToObjAndBackKeepsTheCounts) {
  const fs::path dir = scratchDir("cli-convert");
  writeText(dir / "deck.k", sampleDeck());
  const CliRun toObj =
      runCliSplit("convert " + quoted(dir / "deck.k") + " " + quoted(dir / "mesh.obj"));
  ASSERT_EQ(toObj.exitCode, 0) << toObj.err;
  EXPECT_NE(toObj.out.find("wrote " + (dir / "mesh.obj").string() + ": 22 nodes, 14 shells"),
            std::string::npos)
      << toObj.out;
  ASSERT_TRUE(fs::exists(dir / "mesh.obj"));
  const CliRun back =
      runCliSplit("convert " + quoted(dir / "mesh.obj") + " " + quoted(dir / "back.k"));
  ASSERT_EQ(back.exitCode, 0) << back.err;

  const CliRun original = runCliSplit("info --json " + quoted(dir / "deck.k"));
  const CliRun roundTrip = runCliSplit("info --json " + quoted(dir / "back.k"));
  ASSERT_EQ(roundTrip.exitCode, 0) << roundTrip.err;
  const std::size_t a = original.out.find("\"total\""), b = roundTrip.out.find("\"total\"");
  for (const char* key : {"nodes", "quads", "trias", "edges", "boundaryEdges"})
    EXPECT_EQ(jsonNumber(original.out, key, a), jsonNumber(roundTrip.out, key, b)) << key;

  // --ascii is for STL and PLY only: a warning, on stderr, for OBJ.
  const CliRun ascii = runCliSplit("convert " + quoted(dir / "deck.k") + " " +
                                   quoted(dir / "ascii.obj") + " --ascii");
  EXPECT_EQ(ascii.exitCode, 0);
  EXPECT_NE(ascii.err.find("warning: --ascii only affects STL and PLY"), std::string::npos)
      << ascii.err;
}

TEST(Cli, AnOutputThatIsTheInputIsRefusedAndTheInputStays) {
  const fs::path dir = scratchDir("cli-overwrite-input");
  writeText(dir / "in.k", sampleDeck());
  for (const std::string& command :
       {"convert " + quoted(dir / "in.k") + " " + quoted(dir / "in.k"),
        "convert " + quoted(dir / "in.k") + " " + quoted(dir / "." / "in.k"),
        "remesh " + quoted(dir / "in.k") + " -o " + quoted(dir / "in.k"),
        "remesh " + quoted(dir / "in.k") + " -o " + quoted(dir / "out.k") + " --report " +
            quoted(dir / "in.k")}) {
    const CliRun run = runCliSplit(command);
    EXPECT_EQ(run.exitCode, 1) << command;
    EXPECT_NE(run.err.find("is the input"), std::string::npos) << run.err;
    EXPECT_EQ(readText(dir / "in.k"), sampleDeck());
  }
}

TEST(Cli, AFeatureAngleOutsideZeroTo180IsRefusedBeforeTheDeckIsRead) {
  const fs::path dir = scratchDir("cli-feature-angle");
  // remesh: a malformed command line (exit 2, the usage line), as its other numeric options.
  const CliRun remesh = runCliSplit("remesh " + quoted(dir / "missing.k") + " -o " +
                                    quoted(dir / "out.k") + " --feature-angle 400");
  EXPECT_EQ(remesh.exitCode, 2) << remesh.err;
  EXPECT_NE(remesh.err.find("usage: voxremesh remesh IN -o OUT"), std::string::npos) << remesh.err;
  // voxelize too.
  const CliRun voxelize = runCliSplit("voxelize " + quoted(dir / "missing.k") + " -o " +
                                      quoted(dir / "out.vdb") + " --feature-angle -5");
  EXPECT_EQ(voxelize.exitCode, 2) << voxelize.err;
  for (const CliRun& run : {remesh, voxelize}) {
    EXPECT_NE(run.err.find("--feature-angle must be an angle from 0 to 180 degrees"),
              std::string::npos)
        << run.err;
    EXPECT_EQ(run.err.find("missing.k"), std::string::npos) << run.err;  // not read
  }
  EXPECT_FALSE(fs::exists(dir / "out.k"));
  EXPECT_FALSE(fs::exists(dir / "out.vdb"));
}

/// Writes each deck {name, text, expected} into `dir` and expects `info` on it to exit 1 with an
/// error holding the deck's name followed by `expected` (":LINE:" and the message).
void expectInfoRefuses(const fs::path& dir, const std::vector<std::array<std::string, 3>>& decks) {
  for (const auto& [name, text, expected] : decks) {
    writeText(dir / name, text);
    const CliRun run = runCliSplit("info " + quoted(dir / name));
    EXPECT_EQ(run.exitCode, 1) << name << ": " << run.out;
    EXPECT_NE(run.err.find(name + expected), std::string::npos) << run.err;
  }
}

TEST(Cli, NonFiniteCoordinatesAreRefusedAtTheirLine) {
  const fs::path dir = scratchDir("cli-nan");
  // Each deck and the line of its bad node.
  const std::vector<std::array<std::string, 3>> decks{
      {"nan.k", "*KEYWORD\n*NODE\n1,0,0,0\n2,nan,0,0\n3,1,1,0\n*ELEMENT_SHELL\n1,1,1,2,3\n*END\n",
       ":4:"},
      {"inf.inp",
       "*NODE\n1, 0., 0., 0.\n2, 1., inf, 0.\n3, 1., 1., 0.\n*ELEMENT, TYPE=S3\n1, 1, 2, 3\n",
       ":3:"},
      {"nan.obj", "v 0 0 0\nv 1 0 NaN\nv 1 1 0\nf 1 2 3\n", ":2:"}};
  expectInfoRefuses(dir, decks);
}

TEST(Cli, AFolderOrDeviceGivenAsAFileIsRefusedByName) {
  const fs::path dir = scratchDir("cli-not-a-file");
  fs::create_directories(dir / "folder");
  fs::create_directories(dir / "folder.k");
  writeText(dir / "zero.inp", "*INCLUDE, INPUT=/dev/zero\n*NODE\n1, 0., 0., 0.\n");
  writeText(dir / "zero.k", "*KEYWORD\n*INCLUDE\n/dev/zero\n*END\n");
  for (const std::string& command :
       {"batch " + quoted(dir / "folder"), "-config " + quoted(dir / "folder"),
        "info " + quoted(dir / "folder.k"), "info " + quoted(dir / "zero.inp"),
        "info " + quoted(dir / "zero.k")}) {
    const CliRun run = runCliSplit(command);
    EXPECT_EQ(run.exitCode, 1) << command;
    EXPECT_TRUE(run.err.find("not a regular file") != std::string::npos ||
                run.err.find("not found as a regular file") != std::string::npos ||
                run.err.find("is a folder, not a file") != std::string::npos)
        << command << ": " << run.err;
  }
}

TEST(Cli, IdsThatAreNotPositiveAreRefusedAtTheirLine) {
  const fs::path dir = scratchDir("cli-negative-ids");
  const std::string nodes = "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n*ELEMENT_SHELL\n";
  const std::vector<std::array<std::string, 3>> decks{
      {"element.k", nodes + "-5,1,1,2,3\n*END\n", ":7: element ID -5 is not positive"},
      {"part.k", nodes + "5,-1,1,2,3\n*END\n", ":7: part ID -1 of element 5 is not positive"},
      {"element.bdf", "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,1.,1.,0.\nCTRIA3,-4,1,1,2,3\n",
       ":4: element ID -4 is not positive"}};
  expectInfoRefuses(dir, decks);
}

TEST(Cli, CoordinatesTooLargeToMeasureAreSaidSo) {
  const fs::path dir = scratchDir("cli-huge-coordinates");
  writeText(dir / "big.k",
            "*KEYWORD\n*NODE\n1,0,0,0\n2,1e307,0,0\n3,1,1,0\n4,0,1,0\n*ELEMENT_SHELL\n"
            "1,1,1,2,3,4\n*END\n");
  const CliRun run = runCliSplit("remesh " + quoted(dir / "big.k") + " -o " + quoted(dir / "o.k"));
  EXPECT_EQ(run.exitCode, 1) << run.out;
  EXPECT_NE(run.err.find("too long to measure"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "o.k"));
}

TEST(Cli, FailedConvertLeavesNoOutputFile) {
  const fs::path dir = scratchDir("cli-convert-fail");
  writeText(dir / "bad.k", malformedDeck());
  const CliRun bad =
      runCliSplit("convert " + quoted(dir / "bad.k") + " " + quoted(dir / "out.obj"));
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_EQ(bad.err.rfind("voxremesh: error: ", 0), 0u) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
  // An existing target stays as it was.
  writeText(dir / "kept.obj", "old content\n");
  EXPECT_EQ(
      runCliSplit("convert " + quoted(dir / "bad.k") + " " + quoted(dir / "kept.obj")).exitCode, 1);
  EXPECT_EQ(readText(dir / "kept.obj"), "old content\n");
  // A target folder that does not exist.
  writeText(dir / "good.k", sampleDeck());
  const CliRun noFolder =
      runCliSplit("convert " + quoted(dir / "good.k") + " " + quoted(dir / "missing" / "out.obj"));
  EXPECT_EQ(noFolder.exitCode, 1);
  EXPECT_FALSE(fs::exists(dir / "missing" / "out.obj"));
  // An unknown target format fails before anything is read or written (a malformed command line).
  const CliRun format =
      runCliSplit("convert " + quoted(dir / "good.k") + " " + quoted(dir / "out.xyz"));
  EXPECT_EQ(format.exitCode, 2);
  EXPECT_NE(format.err.find("xyz"), std::string::npos) << format.err;
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_TRUE(entry.path().extension() == ".k" || entry.path().filename() == "kept.obj")
        << "left behind: " << entry.path();
}
