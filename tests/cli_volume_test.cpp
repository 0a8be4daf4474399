// The volume commands of the voxremesh command line, run as a subprocess: voxelize, inspect and
// slice on the shipped sample part and the real decks, and their answers to bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "json/json.h"
#include "support/png.h"
#include "support/test_support.h"

namespace fs = std::filesystem;
using voxremesh::json::Json;
using voxremesh::json::parseJson;
using voxremesh::test::CliRun;
using voxremesh::test::contains;
using voxremesh::test::quoted;
using voxremesh::test::readText;
using voxremesh::test::runCli;
using voxremesh::test::runCliSplit;
using voxremesh::test::samplePart;
using voxremesh::test::scratchDir;
using voxremesh::test::writeText;

using voxremesh::test::runShell;

namespace {

// The default slice colours (slice_image.h, `voxremesh help slice`).
using Colour = std::array<std::uint8_t, 3>;
constexpr Colour kInvalid{255, 210, 0}, kFeature{0, 0, 0}, kInactive{128, 128, 128};

// How many pixels have the colour; and how many are bluish (b > r) or reddish (r > b) besides.
struct ColourCount {
  int matching = 0, bluish = 0, reddish = 0;
};

ColourCount countColour(const voxremesh::test::DecodedPng& png, const Colour& colour) {
  ColourCount count;
  for (std::size_t i = 0; i + 2 < png.rgb.size(); i += 3) {
    const Colour c{png.rgb[i], png.rgb[i + 1], png.rgb[i + 2]};
    count.matching += c == colour ? 1 : 0;
    if (c == kInvalid || c == kFeature || c == kInactive) continue;
    count.bluish += c[2] > c[0] ? 1 : 0;
    count.reddish += c[0] > c[2] ? 1 : 0;
  }
  return count;
}

// Voxelizes the sample part once per test process at --size 5 into a scratch folder.
const fs::path& sampleVolume() {
  static const fs::path path = [] {
    const fs::path dir = scratchDir("cli-volume-sample");
    const fs::path vdb = dir / "rail.vdb";
    const CliRun r =
        // The rail's bends turn by 30 to 40 degrees per edge: feature lines at 30 (not at the
        // default 45), for the feature markers below.
        runCliSplit("voxelize " + quoted(samplePart()) + " -o " + quoted(vdb) +
                    " --size 5 --feature-angle 30");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return vdb;
  }();
  return path;
}

Json inspectJson(const fs::path& vdb) {
  const CliRun r = runCliSplit("inspect " + quoted(vdb) + " --json");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return parseJson(r.out);
}

// A little-endian field of a file's bytes.
template <typename T>
T fieldAt(const std::string& bytes, std::size_t at) {
  T value{};
  if (at + sizeof value <= bytes.size()) std::memcpy(&value, bytes.data() + at, sizeof value);
  return value;
}

// Where the sdf grid of a voxremesh .vdb file keeps counts that OpenVDB 10 allocates or loops
// over as stated (0 when the layout is not the expected one).
struct SdfTreeCounts {
  std::size_t rootCounts = 0;  // the root's tile count; its child count follows
  std::size_t leafBlock = 0;   // the Int64 size of the first leaf's compressed values
};

SdfTreeCounts sdfTreeCounts(const std::string& bytes) {
  // The grid descriptor: name, type, empty instance parent, then the grid's start, data-block
  // start and end positions.
  const std::string descriptor =
      std::string("\x03\0\0\0sdf", 7) + std::string("\x10\0\0\0Tree_float_5_4_3\0\0\0\0", 24);
  const std::size_t at = bytes.find(descriptor);
  if (at == std::string::npos) return {};
  const auto gridPos = fieldAt<std::int64_t>(bytes, at + descriptor.size());
  const auto blockPos = fieldAt<std::int64_t>(bytes, at + descriptor.size() + 8);
  // At the grid's start: compression flags, metadata, the transform (a UniformScaleMap: its name
  // and five Vec3d), then the tree: a buffer count, the background, the tile and child counts.
  const std::string map("\x0f\0\0\0UniformScaleMap", 19);
  const std::size_t transform = bytes.find(map, static_cast<std::size_t>(gridPos));
  if (transform == std::string::npos || transform > static_cast<std::size_t>(blockPos)) return {};
  SdfTreeCounts counts;
  counts.rootCounts = transform + map.size() + 5 * 24 + 4 + 4;
  // The data blocks start with the first leaf's: its value mask, a byte saying what stands for
  // its inactive values (2, 4, 5: one or two values follow; 3, 4, 5: a selection mask), then the
  // compressed values.
  const std::size_t metadataAt = static_cast<std::size_t>(blockPos) + 64;
  const int metadata = metadataAt < bytes.size() ? bytes[metadataAt] : -1;
  counts.leafBlock = metadataAt + 1 +
                     (metadata == 2 || metadata == 4 ? 4
                      : metadata == 5                ? 8
                                                     : 0) +
                     (metadata >= 3 && metadata <= 5 ? 64 : 0);
  return counts;
}

}  // namespace

TEST(CliVolume, HelpListsAndDocumentsTheCommands) {
  const CliRun help = runCliSplit("--help");
  ASSERT_EQ(help.exitCode, 0);
  for (const char* command : {"voxelize", "inspect", "slice"})
    EXPECT_TRUE(contains(help.out, command)) << command;
  const CliRun voxelize = runCliSplit("help voxelize");
  EXPECT_EQ(voxelize.exitCode, 0);
  for (const char* option : {"-o PART.vdb", "--size H", "--voxel V", "--part PID", "--band N",
                             "--feature-angle DEG", "--invalid-angle DEG", "--format F"})
    EXPECT_TRUE(contains(voxelize.out, option)) << option << "\n" << voxelize.out;
  const CliRun slice = runCliSplit("slice --help");
  EXPECT_EQ(slice.exitCode, 0);
  for (const char* colour : {"blue", "white", "red", "grey", "yellow", "black"})
    EXPECT_TRUE(contains(slice.out, colour)) << colour << "\n" << slice.out;
  EXPECT_TRUE(contains(runCliSplit("help inspect").out, "--json"));
}

TEST(CliVolume, VoxelizeWritesTheThreeGrids) {
  const fs::path dir = scratchDir("cli-volume-voxelize");
  const fs::path vdb = dir / "rail.vdb";
  const CliRun r =
      runCliSplit("voxelize " + quoted(samplePart()) + " -o " + quoted(vdb) + " --size 5");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_EQ(
      r.out.rfind("wrote " + vdb.string() + ": part 100 (Hat rail), 1 sheet, voxel size 5, ", 0),
      0u)
      << r.out;
  for (const char* what : {" active voxels, ", " invalid voxels, ", " feature cells, ", " s\n"})
    EXPECT_TRUE(contains(r.out, what)) << what << "\n" << r.out;
  ASSERT_TRUE(fs::is_regular_file(vdb));
  // The summary's counts are the file's.
  const Json report = inspectJson(vdb);
  const std::string active = report["grids"].items.at(0)["active_voxels"].text;
  EXPECT_TRUE(contains(r.out, "voxel size 5, " + active + " active voxels, " +
                                  report["invalid_voxels"].text + " invalid voxels, " +
                                  report["feature_cells"].text + " feature cells"))
      << r.out;

  if (!fs::exists("/usr/bin/vdb_print")) GTEST_SKIP() << "/usr/bin/vdb_print not installed";
  const auto print = runShell("/usr/bin/vdb_print " + quoted(vdb));
  ASSERT_EQ(print.exitCode, 0) << print.output;
  for (const char* grid : {"sdf ", "invalid ", "feature "}) {
    bool listed = false;
    for (std::size_t at = 0; at < print.output.size();) {
      std::size_t end = print.output.find('\n', at);
      if (end == std::string::npos) end = print.output.size();
      listed = listed || print.output.compare(at, std::string(grid).size(), grid) == 0;
      at = end + 1;
    }
    EXPECT_TRUE(listed) << grid << "\n" << print.output;
  }
}

TEST(CliVolume, PythonOpenVdbReadsTheGrids) {
  const fs::path vdb = sampleVolume();
  // Debian's python3-openvdb imports only under the system interpreter.
  if (runShell("/usr/bin/python3 -c 'import pyopenvdb' 2>/dev/null").exitCode != 0)
    GTEST_SKIP() << "python3-openvdb (pyopenvdb) not installed";
  const auto read = runShell(
      "/usr/bin/python3 -c 'import sys, pyopenvdb as vdb\n"
      "grids, meta = vdb.readAll(sys.argv[1])\n"
      "for g in sorted(grids, key=lambda g: g.name): print(g.name, g.valueTypeName, "
      "g.activeVoxelCount())\n"
      "print(\"part\", meta[\"voxremesh_part_id\"])' " +
      quoted(vdb));
  ASSERT_EQ(read.exitCode, 0) << read.output;
  const Json report = inspectJson(vdb);
  for (const Json& grid : report["grids"].items) {
    const std::string line = grid["name"].text +
                             (grid["name"].text == "sdf" ? " float " : " bool ") +
                             std::to_string(static_cast<long>(grid["active_voxels"].number));
    EXPECT_TRUE(contains(read.output, line)) << line << "\n" << read.output;
  }
  EXPECT_TRUE(contains(read.output, "part 100")) << read.output;
}

TEST(CliVolume, InspectReportsTheGrids) {
  const Json report = inspectJson(sampleVolume());
  EXPECT_EQ(report["part"].number, 100);
  EXPECT_EQ(report["voxel_size"].number, 5);
  EXPECT_EQ(report["band_voxels"].number, 3);
  EXPECT_TRUE(contains(report["source_file"].text, "hat_rail.k"));
  const Json& grids = report["grids"];
  ASSERT_EQ(grids.items.size(), 3u);
  EXPECT_EQ(grids.items[0]["name"].text, "sdf");
  EXPECT_EQ(grids.items[0]["class"].text, "level set");
  EXPECT_GT(grids.items[0]["active_voxels"].number, 0);
  EXPECT_EQ(grids.items[1]["name"].text, "invalid");
  EXPECT_EQ(grids.items[2]["name"].text, "feature");
  // The rail has free flange edges, rail ends and holes (invalid voxels) and bends (features).
  EXPECT_GT(report["invalid_voxels"].number, 0);
  EXPECT_GT(report["feature_cells"].number, 0);
  // The band around a rail of 400 x 150 x 45: -10 .. 410 along x at voxel size 5 and band 3.
  const Json& box = grids.items[0]["world_bbox"];
  EXPECT_EQ(box.items.at(0).items.at(0).number, -10);
  EXPECT_EQ(box.items.at(1).items.at(0).number, 410);

  const CliRun table = runCliSplit("inspect " + quoted(sampleVolume()));
  ASSERT_EQ(table.exitCode, 0) << table.err;
  EXPECT_EQ(table.out.rfind(sampleVolume().string() + "\n\nvolume of part 100", 0), 0u)
      << table.out;
  for (const char* what : {"sdf ", "invalid ", "feature ", "level set", "invalid voxels "})
    EXPECT_TRUE(contains(table.out, what)) << what << "\n" << table.out;
}

TEST(CliVolume, SliceWritesAPngOfTheSection) {
  const Json report = inspectJson(sampleVolume());
  const Json& world = report["grids"].items.at(0)["world_bbox"];
  const double zMid =
      (world.items.at(0).items.at(2).number + world.items.at(1).items.at(2).number) / 2;
  const fs::path dir = scratchDir("cli-volume-slice");

  // Across the walls: both sides of the sheet, invalid voxels beyond the rail's open ends.
  const fs::path zPng = dir / "z.png";
  const CliRun z = runCliSplit("slice " + quoted(sampleVolume()) + " --axis z --at " +
                               std::to_string(zMid) + " -o " + quoted(zPng));
  ASSERT_EQ(z.exitCode, 0) << z.err;
  const voxremesh::test::DecodedPng zImage = voxremesh::test::decodePng(readText(zPng));
  EXPECT_TRUE(contains(z.out, "wrote " + zPng.string() + ": " + std::to_string(zImage.width) +
                                  " x " + std::to_string(zImage.height) + " pixels, z = "))
      << z.out;
  EXPECT_TRUE(contains(zImage.text.at("Comment"), "slice z = ")) << zImage.text.at("Comment");
  const ColourCount zColours = countColour(zImage, kInvalid);
  EXPECT_GT(zColours.matching, 0);
  EXPECT_GT(zColours.bluish, 0);
  EXPECT_GT(zColours.reddish, 0);

  // The rail's section at mid-length: feature markers at the bends, invalid beyond the flanges.
  const fs::path xPng = dir / "x.png";
  const CliRun x = runCliSplit("slice " + quoted(sampleVolume()) + " --axis x --at 200 -o " +
                               quoted(xPng) + " --scale 4");
  ASSERT_EQ(x.exitCode, 0) << x.err;
  EXPECT_TRUE(contains(x.out,
                       "x = 200 (voxel layer 40), y -10 .. 160 left to right, z -10 .. "
                       "55 bottom to top, 4 pixels per voxel"))
      << x.out;
  const voxremesh::test::DecodedPng xImage = voxremesh::test::decodePng(readText(xPng));
  // y -10..160 and z -10..55 at voxel size 5: 35 x 14 voxels of 4 x 4 pixels.
  EXPECT_EQ(xImage.width, 35u * 4);
  EXPECT_EQ(xImage.height, 14u * 4);
  EXPECT_GT(countColour(xImage, kFeature).matching, 0);
  EXPECT_GT(countColour(xImage, kInvalid).matching, 0);
  EXPECT_GT(countColour(xImage, kInactive).matching, 0);
  // The flange at z = 0 ends at y = 0: the voxel y = -10, z = 0 beyond it is invalid. Its block
  // is column 0, row (55 - 0) / 5 = 11 from the top.
  const std::size_t at = (std::size_t(11 * 4 + 2) * xImage.width + 2) * 3;
  EXPECT_EQ((Colour{xImage.rgb[at], xImage.rgb[at + 1], xImage.rgb[at + 2]}), kInvalid);
}

TEST(CliVolume, BadInputFailsWithoutOutput) {
  const fs::path dir = scratchDir("cli-volume-bad");
  const fs::path vdb = dir / "out.vdb";
  const std::string deck = quoted(samplePart());

  const CliRun missing =
      runCliSplit("voxelize " + quoted(dir / "no-such.k") + " -o " + quoted(vdb));
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_EQ(missing.err.rfind("voxremesh: error: ", 0), 0u) << missing.err;
  EXPECT_TRUE(contains(missing.err, (dir / "no-such.k").string())) << missing.err;

  // Malformed option values are a malformed command line: exit 2 with the usage.
  const CliRun negative = runCliSplit("voxelize " + deck + " -o " + quoted(vdb) + " --voxel -1");
  EXPECT_EQ(negative.exitCode, 2);
  EXPECT_TRUE(contains(negative.err, "voxel size must be a finite number > 0 (got -1)"))
      << negative.err;

  // A voxel size the machine cannot hold is refused before anything is allocated.
  const CliRun tiny = runCliSplit("voxelize " + deck + " -o " + quoted(vdb) + " --voxel 0.0001");
  EXPECT_EQ(tiny.exitCode, 1);
  EXPECT_TRUE(contains(tiny.err, "more than the memory limit")) << tiny.err;
  EXPECT_TRUE(contains(tiny.err, "choose a voxel size of at least")) << tiny.err;

  const CliRun part = runCliSplit("voxelize " + deck + " -o " + quoted(vdb) + " --part 999");
  EXPECT_EQ(part.exitCode, 1);
  EXPECT_TRUE(contains(part.err, "no part 999 in ")) << part.err;
  EXPECT_TRUE(contains(part.err, "parts with shells: 100")) << part.err;

  for (const std::string& bad : {std::string("--size nan"), std::string("--size -2"),
                                 std::string("--band 0"), std::string("--invalid-angle 95"),
                                 std::string("--feature-angle 200"), std::string("--part abc")}) {
    const CliRun r = runCliSplit("voxelize " + deck + " -o " + quoted(vdb) + " " + bad);
    EXPECT_EQ(r.exitCode, 2) << bad;
    EXPECT_TRUE(contains(r.err, "usage: voxremesh voxelize")) << bad << ": " << r.err;
  }
  EXPECT_EQ(runCliSplit("voxelize " + deck + " -o " + quoted(dir / "missing" / "out.vdb")).exitCode,
            1);

  // Slices: outside the volume, of a file that is no volume, an unknown axis, a bad scale.
  const fs::path png = dir / "slice.png";
  const CliRun outside =
      runCliSplit("slice " + quoted(sampleVolume()) + " --axis z --at 100 -o " + quoted(png));
  EXPECT_EQ(outside.exitCode, 1);
  EXPECT_TRUE(contains(outside.err, "z = 100 is outside the volume")) << outside.err;
  EXPECT_TRUE(contains(outside.err, "-10 .. 55")) << outside.err;
  const CliRun notVdb = runCliSplit("slice " + deck + " --axis z --at 0 -o " + quoted(png));
  EXPECT_EQ(notVdb.exitCode, 1);
  EXPECT_TRUE(contains(notVdb.err, samplePart().string())) << notVdb.err;
  EXPECT_EQ(runCliSplit("slice " + quoted(sampleVolume()) + " --axis w --at 0 -o " + quoted(png))
                .exitCode,
            2);
  EXPECT_EQ(runCliSplit("slice " + quoted(sampleVolume()) + " --axis z --at 0 --scale 0 -o " +
                        quoted(png))
                .exitCode,
            2);
  const CliRun inspectMissing = runCliSplit("inspect " + quoted(dir / "none.vdb"));
  EXPECT_EQ(inspectMissing.exitCode, 1);
  EXPECT_TRUE(contains(inspectMissing.err, (dir / "none.vdb").string())) << inspectMissing.err;

  // An existing image stays as it was.
  writeText(dir / "kept.png", "old");
  EXPECT_EQ(runCliSplit("slice " + quoted(sampleVolume()) + " --axis y --at 1000 -o " +
                        quoted(dir / "kept.png"))
                .exitCode,
            1);
  EXPECT_EQ(readText(dir / "kept.png"), "old");

  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename(), "kept.png") << "left behind: " << entry.path();
}

TEST(CliVolume, DamagedLengthsInAVdbAreRefusedBeforeOpenVdbAllocatesThem) {
  // OpenVDB allocates a string at the length the file states. A grid name said to be 4 GB long
  // once made `inspect` allocate it; now the length is checked against the file first, within
  // 600 MB of address space, naming the byte offset, and nothing is written.
  const fs::path dir = scratchDir("cli-volume-damaged");
  std::string bytes = readText(sampleVolume());
  const std::size_t name = bytes.find(std::string("\x03\0\0\0sdf", 7));
  ASSERT_NE(name, std::string::npos);
  bytes.replace(name, 4, std::string("\xf0\xff\xff\xff", 4));
  writeText(dir / "damaged.vdb", bytes);
  // Also the fuzzer's findings (tests/fuzz/findings: a 2 GB metadata name in a second grid, a
  // garbage format version whose OpenVDB read took 4 GB or hung building its message, a leaf's
  // blosc block said to hold 70 TB, 4294967296 sheets, an internal node's blosc block of other
  // values whose refusal by OpenVDB leaked the root's child).
  std::vector<fs::path> files = {dir / "damaged.vdb"};
  for (const auto& entry :
       fs::directory_iterator(fs::path(VOXREMESH_SOURCE_DIR) / "tests" / "fuzz" / "findings"))
    if (entry.path().extension() == ".vdb") files.push_back(entry.path());
  std::sort(files.begin() + 1, files.end());
  ASSERT_GE(files.size(), 4u);
  for (const char* reproducer : {"malformed/fuzzed_5gb.vdb", "malformed/bitflipped_8gb.vdb"})
    if (fs::exists(voxremesh::test::sharedDeck(reproducer)))
      files.push_back(voxremesh::test::sharedDeck(reproducer));
  for (const fs::path& file : files)
    for (const std::string& command :
         {"inspect " + quoted(file), "extract " + quoted(file) + " -o " + quoted(dir / "x.obj")}) {
      const voxremesh::test::CliResult run =
          runShell(voxremesh::test::addressSpaceLimit(600000000) + std::string(VOXREMESH_CLI) +
                   " " + command + " 2>&1");
      EXPECT_EQ(run.exitCode, 1) << command << ": " << run.output;
      EXPECT_TRUE(contains(run.output, file.string() + ": byte offset ")) << run.output;
      EXPECT_TRUE(contains(run.output, "a damaged .vdb file")) << run.output;
    }
  EXPECT_TRUE(contains(
      runShell(std::string(VOXREMESH_CLI) + " inspect " + quoted(dir / "damaged.vdb") + " 2>&1")
          .output,
      ": byte offset " + std::to_string(name) +
          ": the length of the name of grid 0 is 4294967280 bytes"));
  EXPECT_FALSE(fs::exists(dir / "x.obj"));
}

TEST(CliVolume, DamagedTreeCountsInAVdbAreRefusedBeforeOpenVdbAllocatesThem) {
  // OpenVDB allocates the size a compressed block of a tree states (a fuzzed file asked
  // bloscFromStream for 70 TB), reads a block stored uncompressed before checking its size, and
  // loops over the tiles and children the root states. Each is now checked against the grid's
  // bytes first: refused within 600 MB of address space, naming the byte offset, and nothing is
  // written.
  const fs::path dir = scratchDir("cli-volume-damaged-tree");
  const std::string bytes = readText(sampleVolume());
  const SdfTreeCounts sdf = sdfTreeCounts(bytes);
  ASSERT_NE(sdf.rootCounts, 0u) << "the sdf grid's layout was not found";
  ASSERT_EQ(fieldAt<std::int32_t>(bytes, sdf.rootCounts - 8), 1);  // the tree's buffer count
  ASSERT_GE(fieldAt<std::uint32_t>(bytes, sdf.rootCounts + 4), 1u);
  const auto blockBytes = fieldAt<std::int64_t>(bytes, sdf.leafBlock);
  ASSERT_GT(blockBytes, 16);  // a blosc block of at most 512 floats
  ASSERT_LT(blockBytes, 2100);

  struct Damage {
    const char* file;
    std::size_t at;
    std::string value;  // the bytes written at `at`
    std::string message;
  };
  const std::int64_t huge = 70000000000000, minusHuge = -huge, minus4000 = -4000;
  const std::string allOnes("\xff\xff\xff\xff", 4);
  const std::vector<Damage> damages = {
      {"leaf_block.vdb", sdf.leafBlock, std::string(reinterpret_cast<const char*>(&huge), 8),
       " claims 70000000000000 bytes, but only "},
      {"leaf_block_raw.vdb", sdf.leafBlock,
       std::string(reinterpret_cast<const char*>(&minusHuge), 8),
       " claims 70000000000000 bytes, but only "},
      // Stored uncompressed, larger than its values: OpenVDB 10 reads it into their buffer.
      {"leaf_block_raw_4000.vdb", sdf.leafBlock,
       std::string(reinterpret_cast<const char*>(&minus4000), 8),
       " claims 4000 bytes, but its values take "},
      {"root_tiles.vdb", sdf.rootCounts, allOnes, " claims 4294967295 tiles of 17 bytes each"},
      {"root_children.vdb", sdf.rootCounts + 4, allOnes,
       " claims 4294967295 child nodes of at least 8205 bytes each"}};
  for (const Damage& damage : damages) {
    std::string damaged = bytes;
    damaged.replace(damage.at, damage.value.size(), damage.value);
    const fs::path file = dir / damage.file;
    writeText(file, damaged);
    for (const std::string& command :
         {"inspect " + quoted(file), "extract " + quoted(file) + " -o " + quoted(dir / "x.obj")}) {
      const voxremesh::test::CliResult run =
          runShell(voxremesh::test::addressSpaceLimit(600000000) + std::string(VOXREMESH_CLI) +
                   " " + command + " 2>&1");
      EXPECT_EQ(run.exitCode, 1) << command << ": " << run.output;
      EXPECT_TRUE(
          contains(run.output, file.string() + ": byte offset " + std::to_string(damage.at) + ": "))
          << run.output;
      EXPECT_TRUE(contains(run.output, damage.message)) << run.output;
      EXPECT_TRUE(contains(run.output, "a damaged .vdb file")) << run.output;
    }
  }
  EXPECT_FALSE(fs::exists(dir / "x.obj"));
}

TEST(CliVolume, ASheetCountBeyondTheGridsIsRefusedBeforeItIsReserved) {
  // readVolumes reserves a volume per sheet the file metadata states (fuzz_vdb: 4294967296
  // sheets, a 32 GB reservation); three grids per sheet bound it before anything is read.
  const fs::path dir = scratchDir("cli-volume-sheet-count");
  std::string bytes = readText(sampleVolume());
  const std::string entry("\x15\0\0\0voxremesh_sheet_count\x05\0\0\0int64\x08\0\0\0", 38);
  const std::size_t at = bytes.find(entry);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(fieldAt<std::int64_t>(bytes, at + entry.size()), 1);
  const std::int64_t sheets = std::int64_t{1} << 32;
  bytes.replace(at + entry.size(), 8, std::string(reinterpret_cast<const char*>(&sheets), 8));
  const fs::path file = dir / "sheets.vdb";
  writeText(file, bytes);
  const voxremesh::test::CliResult run =
      runShell(voxremesh::test::addressSpaceLimit(600000000) + std::string(VOXREMESH_CLI) +
               " inspect " + quoted(file) + " 2>&1");
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_TRUE(contains(run.output, file.string() + ": byte offset " +
                                       std::to_string(at + entry.size()) +
                                       ": the file metadata voxremesh_sheet_count claims "
                                       "4294967296 sheets, but the file holds 3 grids"))
      << run.output;
}

TEST(CliVolume, VdbFilesOfOtherWritersPassTheLayoutCheck) {
  // vdb_tool (Debian's libopenvdb-tools) writes level sets with each compression, as half floats,
  // and a vector grid: the layout check walks their trees and lets them through to the grid
  // lookup, which refuses them for want of voxremesh's grids. vdb_print reads voxremesh's file.
  if (runShell("command -v vdb_tool >/dev/null && command -v vdb_print >/dev/null").exitCode != 0)
    GTEST_SKIP() << "vdb_tool or vdb_print (libopenvdb-tools) not installed";
  const fs::path dir = scratchDir("cli-volume-vdb-tool");
  const std::vector<std::string> writes = {"codec=none",          "codec=zip", "codec=blosc",
                                           "codec=active",        "bits=16",   "bits=16 codec=none",
                                           "bits=16 codec=active"};
  for (std::size_t k = 0; k <= writes.size(); ++k) {
    const fs::path file = dir / ("sphere" + std::to_string(k) + ".vdb");
    const std::string make = k < writes.size() ? "-sphere r=1.0 voxel=0.1 -write " + writes[k]
                                               : "-sphere r=1.0 voxel=0.1 -grad -write";
    ASSERT_EQ(runShell("vdb_tool -quiet " + make + " " + quoted(file)).exitCode, 0) << make;
    const voxremesh::test::CliResult run =
        runShell(std::string(VOXREMESH_CLI) + " inspect " + quoted(file) + " 2>&1");
    EXPECT_EQ(run.exitCode, 1) << make << ": " << run.output;
    EXPECT_TRUE(contains(run.output, "no grid named 'sdf'")) << make << ": " << run.output;
    EXPECT_FALSE(contains(run.output, "byte offset")) << make << ": " << run.output;
  }
  const voxremesh::test::CliResult print = runShell("vdb_print -l " + quoted(sampleVolume()));
  EXPECT_EQ(print.exitCode, 0) << print.output;
  EXPECT_TRUE(contains(print.output, "Tree_float_5_4_3")) << print.output;
}

TEST(CliVolume, UsageErrorsExitWithTwo) {
  const fs::path dir = scratchDir("cli-volume-usage");
  const std::string deck = quoted(samplePart());
  const CliRun noOutput = runCliSplit("voxelize " + deck);
  EXPECT_EQ(noOutput.exitCode, 2);
  EXPECT_TRUE(contains(noOutput.err, "missing -o PART.vdb")) << noOutput.err;
  EXPECT_TRUE(contains(noOutput.err, "usage: voxremesh voxelize DECK")) << noOutput.err;
  EXPECT_EQ(runCliSplit("voxelize " + deck + " -o " + quoted(dir / "a.vdb") + " --size 5 --voxel 5")
                .exitCode,
            2);
  EXPECT_EQ(runCliSplit("slice " + quoted(dir / "a.vdb") + " --at 0 -o " + quoted(dir / "a.png"))
                .exitCode,
            2);
  EXPECT_EQ(runCliSplit("slice " + quoted(dir / "a.vdb") + " --axis x -o " + quoted(dir / "a.png"))
                .exitCode,
            2);
  EXPECT_EQ(runCliSplit("slice " + quoted(dir / "a.vdb") + " --axis x --at 0").exitCode, 2);
  EXPECT_EQ(runCliSplit("inspect").exitCode, 2);
  EXPECT_EQ(runCliSplit("inspect a.vdb --bogus").exitCode, 2);

  // Two parts with shells and no --part: the message lists them; --part picks one.
  writeText(dir / "two.obj",
            "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv 20 0 0\nv 20 10 0\n"
            "g plate\nf 1 2 3 4\ng gusset\nf 2 5 6 3\n");
  const CliRun two =
      runCliSplit("voxelize " + quoted(dir / "two.obj") + " -o " + quoted(dir / "two.vdb"));
  EXPECT_EQ(two.exitCode, 2);
  EXPECT_TRUE(contains(two.err, "2 parts with shells; choose one with --part (1, 2)")) << two.err;
  EXPECT_FALSE(fs::exists(dir / "two.vdb"));
  const CliRun picked = runCliSplit("voxelize " + quoted(dir / "two.obj") + " -o " +
                                    quoted(dir / "two.vdb") + " --part 2 --voxel 1");
  EXPECT_EQ(picked.exitCode, 0) << picked.err;
  EXPECT_TRUE(contains(picked.out, "part 2 (gusset), 1 sheet, voxel size 1, ")) << picked.out;
}

TEST(CliVolume, VoxelizesTheRealBracket) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "bracket.k");
  const fs::path dir = scratchDir("cli-volume-bracket");
  const CliRun r = runCliSplit("voxelize " + quoted(deck) + " -o " + quoted(dir / "bracket.vdb") +
                               " --size 4.5");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "part 4075 (Recliner Bkt i/b), 1 sheet, voxel size 4.5, ")) << r.out;
  const Json report = inspectJson(dir / "bracket.vdb");
  EXPECT_GT(report["grids"].items.at(0)["active_voxels"].number, 0);
  EXPECT_GT(report["invalid_voxels"].number, 0);  // outer contour and holes
  EXPECT_GT(report["boundary_loops"].number, 1);
  // The bracket sits around x = 3000 in car coordinates: slice it there.
  const Json& world = report["grids"].items.at(0)["world_bbox"];
  const double xMid =
      (world.items.at(0).items.at(0).number + world.items.at(1).items.at(0).number) / 2;
  const CliRun slice = runCliSplit("slice " + quoted(dir / "bracket.vdb") + " --axis x --at " +
                                   std::to_string(xMid) + " -o " + quoted(dir / "x.png"));
  ASSERT_EQ(slice.exitCode, 0) << slice.err;
  EXPECT_NO_THROW(voxremesh::test::decodePng(readText(dir / "x.png")));
}

TEST(CliVolume, VoxelizesTheRealWheel) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "wheel.k");
  const fs::path dir = scratchDir("cli-volume-wheel");
  // No size: the mean edge length; the wheel's non-manifold T-junctions give three sheets, each
  // in a volume of its own (one united volume has no consistent sign at the T-junction).
  const CliRun r = runCliSplit("voxelize " + quoted(deck) + " -o " + quoted(dir / "wheel.vdb"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "part 1 (MC - rim - front- R), 3 sheets, ")) << r.out;
  const Json report = inspectJson(dir / "wheel.vdb");
  ASSERT_EQ(report["sheet_count"].number, 3);
  ASSERT_EQ(report["sheets"].items.size(), 3u);
  for (const Json& sheet : report["sheets"].items) {
    EXPECT_GT(sheet["grids"].items.at(0)["active_voxels"].number, 0);
    EXPECT_GT(sheet["feature_cells"].number, 0);
    EXPECT_EQ(sheet["junction_curves"].number, 1);
  }
}

TEST(CliVolume, VoxelizesTheBirdStrikePlate) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "bird.k");
  const fs::path dir = scratchDir("cli-volume-bird");
  // Part 1 is the shell plate; the SPH bird (part 101) has no shells and is not a choice.
  const CliRun r = runCliSplit("voxelize " + quoted(deck) + " -o " + quoted(dir / "bird.vdb"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "part 1")) << r.out;
  const Json report = inspectJson(dir / "bird.vdb");
  EXPECT_GT(report["grids"].items.at(0)["active_voxels"].number, 0);
  EXPECT_GT(report["invalid_voxels"].number, 0);  // the plate has free edges all round
}
