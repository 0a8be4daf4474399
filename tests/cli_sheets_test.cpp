// A part of several sheets (the wheel: rim front, rim back and disc at a T-junction) through the
// volume commands and the chain, run as a subprocess: voxelize writes one volume per sheet into
// one .vdb, extract joins the sheets' meshes at their junction nodes, the chain does the same;
// a one-sheet part still writes a file every reader opens.
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <string>

#include "support/mesh_topology.h"
#include "support/test_support.h"
#include "voxremesh/io.h"
#include "voxremesh/quad_mesh.h"
#include "voxremesh/sheets.h"
#include "voxremesh/volume.h"

namespace voxremesh {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::contains;
using test::quoted;
using test::runCliSplit;

/// The mesh of part `part` of a deck or mesh file (points: the nodes its shells use).
QuadMesh partMesh(const fs::path& path, Id part) {
  return quadMeshFromModel(readDeck(path), part);
}

/// The number of `Name: NAME` lines of `vdb_print -l FILE` for each grid name.
std::size_t listedGrids(const std::string& output, const std::string& name) {
  std::size_t count = 0;
  for (std::size_t at = output.find("Name: " + name + "\n"); at != std::string::npos;
       at = output.find("Name: " + name + "\n", at + 1))
    ++count;
  return count;
}

TEST(CliSheets, VoxelizeAndExtractJoinTheWheelSheets) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "wheel.k");
  const fs::path dir = test::scratchDir("cli-sheets-wheel");
  const CliRun voxelize = runCliSplit("voxelize " + quoted(deck) + " -o " + quoted(dir / "w.vdb"));
  ASSERT_EQ(voxelize.exitCode, 0) << voxelize.err;
  EXPECT_TRUE(contains(voxelize.out, ", 3 sheets, voxel size ")) << voxelize.out;
  const CliRun extract =
      runCliSplit("extract " + quoted(dir / "w.vdb") + " -o " + quoted(dir / "w.obj"));
  ASSERT_EQ(extract.exitCode, 0) << extract.err;
  EXPECT_TRUE(contains(extract.out, "3 sheets)")) << extract.out;

  // One connected mesh; the sheets' boundary loops are all kept but the three junction rings
  // (one per sheet), which are inner edges of the joined mesh (as junction_test.cpp asserts for
  // the pipeline).
  const QuadMesh mesh = partMesh(dir / "w.obj", 0);
  const test::MeshTopology topology = test::meshTopology(mesh);
  std::size_t inputLoops = 0;
  for (const Sheet& sheet : buildSheets(readDeck(deck), 1))
    inputLoops += sheet.boundaryLoops.size();
  EXPECT_EQ(topology.components, 1u);
  EXPECT_EQ(topology.boundaryLoops, inputLoops - 3);
  EXPECT_GT(topology.nonManifoldEdges, 150u);  // the T-junction ring: three faces per edge

  // inspect and slice read every sheet.
  const CliRun inspect = runCliSplit("inspect " + quoted(dir / "w.vdb"));
  ASSERT_EQ(inspect.exitCode, 0) << inspect.err;
  EXPECT_TRUE(contains(inspect.out, "sheet 2 of 3\n")) << inspect.out;
  const CliRun slice = runCliSplit("slice " + quoted(dir / "w.vdb") +
                                   " --axis y --at -830 --sheet 2 -o " + quoted(dir / "s.png"));
  EXPECT_EQ(slice.exitCode, 0) << slice.err;
  const CliRun beyond = runCliSplit("slice " + quoted(dir / "w.vdb") +
                                    " --axis y --at -830 --sheet 3 -o " + quoted(dir / "t.png"));
  EXPECT_NE(beyond.exitCode, 0);
  EXPECT_TRUE(contains(beyond.err, "--sheet must be a sheet of the volume, 0..2")) << beyond.err;
  EXPECT_FALSE(fs::exists(dir / "t.png"));

  if (!fs::exists("/usr/bin/vdb_print")) GTEST_SKIP() << "/usr/bin/vdb_print not installed";
  const test::CliResult print = test::runShell("/usr/bin/vdb_print -l " + quoted(dir / "w.vdb"));
  ASSERT_EQ(print.exitCode, 0) << print.output;
  for (const std::string grid : {"sdf", "invalid", "feature"})
    for (const std::string suffix : {"", ".sheet1", ".sheet2"})
      EXPECT_EQ(listedGrids(print.output, grid + suffix), 1u) << grid + suffix;
}

TEST(CliSheets, ChainGivesTheMeshOfTheCommands) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "wheel.k");
  const fs::path dir = test::scratchDir("cli-sheets-chain");
  // The same size on both routes (their defaults differ: the mean edge for the command, the
  // median edge for the chain).
  ASSERT_EQ(
      runCliSplit("voxelize " + quoted(deck) + " --size 6 -o " + quoted(dir / "c.vdb")).exitCode,
      0);
  const CliRun extract =
      runCliSplit("extract " + quoted(dir / "c.vdb") + " -o " + quoted(dir / "c.obj"));
  ASSERT_EQ(extract.exitCode, 0) << extract.err;
  const CliRun chain =
      runCliSplit("-read " + quoted(deck) + " -voxelize size=6 -write " + quoted(dir / "v.vdb") +
                  " -print -extract -write " + quoted(dir / "w.k"));
  ASSERT_EQ(chain.exitCode, 0) << chain.err;
  EXPECT_TRUE(contains(chain.out, "3 sheets")) << chain.out;
  EXPECT_TRUE(contains(chain.out, "sheet 2 of 3\n")) << chain.out;

  const QuadMesh commands = partMesh(dir / "c.obj", 0);
  const QuadMesh chained = partMesh(dir / "w.k", 1);  // part 1 replaced in the deck
  EXPECT_EQ(chained.points.size(), commands.points.size());
  EXPECT_EQ(chained.faces.size(), commands.faces.size());

  // The chain reads its own multi-sheet file back, and optimises the joined mesh against the
  // whole part; slice takes sheet=.
  const CliRun again = runCliSplit("-read " + quoted(dir / "v.vdb") + " -slice axis=y at=-830 " +
                                   "sheet=1 file=" + quoted(dir / "s.png") + " -extract -write " +
                                   quoted(dir / "again.obj"));
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_TRUE(contains(again.out, "volume of part 1, 3 sheets")) << again.out;
  EXPECT_EQ(partMesh(dir / "again.obj", 0).faces.size(), commands.faces.size());
  const CliRun optimized = runCliSplit("-read " + quoted(deck) + " -voxelize size=6 -extract " +
                                       "-optimize -write " + quoted(dir / "o.k"));
  EXPECT_EQ(optimized.exitCode, 0) << optimized.err;
}

TEST(CliSheets, OneSheetPartFileOpensEverywhere) {
  const fs::path dir = test::scratchDir("cli-sheets-rail");
  const fs::path vdb = dir / "rail.vdb";
  const CliRun r =
      runCliSplit("voxelize " + quoted(test::samplePart()) + " -o " + quoted(vdb) + " --size 5");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, ", 1 sheet, ")) << r.out;
  const Volume volume = readVolume(vdb);
  EXPECT_EQ(volume.info().part, 100);
  EXPECT_FALSE(volume.boundaryLoops().empty());

  if (!fs::exists("/usr/bin/vdb_print")) GTEST_SKIP() << "/usr/bin/vdb_print not installed";
  const test::CliResult print = test::runShell("/usr/bin/vdb_print -l " + quoted(vdb));
  ASSERT_EQ(print.exitCode, 0) << print.output;
  for (const char* grid : {"sdf", "invalid", "feature"})
    EXPECT_EQ(listedGrids(print.output, grid), 1u) << grid;
  EXPECT_FALSE(contains(print.output, ".sheet")) << print.output;
}

}  // namespace
}  // namespace voxremesh
