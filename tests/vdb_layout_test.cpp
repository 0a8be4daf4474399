// The layout check of a .vdb file's trees (src/volume/vdb_tree_layout.cpp) on files OpenVDB 10
// writes here, each damaged at one compressed block or one byte read into a bool: `voxremesh
// inspect` refuses them naming the file and byte offset before OpenVDB reads the grid, and lets
// the undamaged files through to the grid lookup.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "support/test_support.h"

namespace fs = std::filesystem;
using voxremesh::test::CliResult;
using voxremesh::test::contains;
using voxremesh::test::quoted;
using voxremesh::test::readText;
using voxremesh::test::runShell;
using voxremesh::test::scratchDir;
using voxremesh::test::writeText;

namespace {

constexpr std::uint32_t kZip = openvdb::io::COMPRESS_ZIP;
constexpr std::uint32_t kBlosc = openvdb::io::COMPRESS_BLOSC;
constexpr std::uint32_t kActive = openvdb::io::COMPRESS_ACTIVE_MASK;

/// Writes `grid` alone to `path` with the compression flags `compression`; returns the bytes.
std::string writeGrid(const fs::path& path, const openvdb::GridBase::Ptr& grid,
                      std::uint32_t compression) {
  openvdb::initialize();
  openvdb::io::File file(path.string());
  file.setCompression(compression);
  file.write(openvdb::GridPtrVec{grid});
  file.close();
  return readText(path);
}

/// `voxremesh inspect FILE` within 600 MB of address space.
CliResult inspect(const fs::path& file) {
  return runShell(voxremesh::test::addressSpaceLimit(600000000) + std::string(VOXREMESH_CLI) +
                  " inspect " + quoted(file) + " 2>&1");
}

/// The file passes the layout check: the grid lookup refuses it for want of voxremesh's grids.
void expectPasses(const fs::path& file) {
  const CliResult run = inspect(file);
  EXPECT_EQ(run.exitCode, 1) << file << ": " << run.output;
  EXPECT_TRUE(contains(run.output, "no grid named 'sdf'")) << file << ": " << run.output;
  EXPECT_FALSE(contains(run.output, "byte offset")) << file << ": " << run.output;
}

/// The file is refused by the layout check at byte `at` with a message containing `message`.
void expectRefusedAt(const fs::path& file, std::size_t at, const std::string& message) {
  const CliResult run = inspect(file);
  EXPECT_EQ(run.exitCode, 1) << file << ": " << run.output;
  EXPECT_TRUE(contains(run.output, file.string() + ": byte offset " + std::to_string(at) + ": "))
      << file << ": " << run.output;
  EXPECT_TRUE(contains(run.output, message)) << file << ": " << run.output;
  EXPECT_TRUE(contains(run.output, "a damaged .vdb file")) << file << ": " << run.output;
}

/// Where the first block of `bytes` starts (its Int64 size) whose stated size is positive and
/// fits the file and whose bytes start with `start`; npos when there is none.
std::size_t firstBlock(const std::string& bytes, const std::string& start) {
  for (std::size_t at = bytes.find(start, 8); at != std::string::npos;
       at = bytes.find(start, at + 1)) {
    std::int64_t size = 0;
    std::memcpy(&size, bytes.data() + at - 8, sizeof size);
    if (size > 0 && static_cast<std::uint64_t>(size) <= bytes.size() - at) return at - 8;
  }
  return std::string::npos;
}

/// The only byte at which two files of the same size differ besides the file's UUID (written as
/// 36 characters after the 21 bytes of magic number, versions and grid offsets flag); npos when
/// they do not differ in exactly one byte.
std::size_t onlyDifference(const std::string& a, const std::string& b) {
  constexpr std::size_t kUuidAt = 21, kUuidBytes = 36;
  if (a.size() != b.size()) return std::string::npos;
  std::size_t found = std::string::npos;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (a[k] == b[k] || (k >= kUuidAt && k < kUuidAt + kUuidBytes)) continue;
    if (found != std::string::npos) return std::string::npos;
    found = k;
  }
  return found;
}

/// A sphere's level set of radius 1 at voxel size 0.1 named "sphere", of grid class `gridClass`
/// (OpenVDB 10 writes level sets and fog volumes without zip compression).
openvdb::GridBase::Ptr sphere(openvdb::GridClass gridClass) {
  openvdb::initialize();
  openvdb::FloatGrid::Ptr grid =
      openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(0.0f), 0.1f);
  grid->setName("sphere");
  grid->setGridClass(gridClass);
  return grid;
}

/// A grid of `GridT` with background `background` and one active tile of `value` at `level`
/// (1: a value of an internal node of 16^3, 3: of the root; 0: no tile), named "tiles".
template <typename GridT>
openvdb::GridBase::Ptr gridWithTile(bool background, int level, bool value, bool active = true) {
  openvdb::initialize();
  typename GridT::Ptr grid = GridT::create(background);
  if (level > 0) grid->tree().addTile(level, openvdb::Coord(0), value, active);
  grid->setName("tiles");
  return grid;
}

/// One byte that OpenVDB reads into a bool: two grids whose files differ only in that byte.
struct BoolByte {
  std::string name;
  openvdb::GridBase::Ptr zero, one;  ///< the byte 0 and 1
};

/// The bool bytes of bool and mask grids: a root's background and tile, an internal node's tile.
std::vector<BoolByte> boolBytes() {
  std::vector<BoolByte> bytes;
  bytes.push_back({"bool_background", gridWithTile<openvdb::BoolGrid>(false, 0, false),
                   gridWithTile<openvdb::BoolGrid>(true, 0, false)});
  for (int level : {3, 1}) {
    const std::string where = level == 3 ? "root" : "internal";
    bytes.push_back({"bool_" + where + "_tile",
                     gridWithTile<openvdb::BoolGrid>(false, level, false),
                     gridWithTile<openvdb::BoolGrid>(false, level, true)});
    bytes.push_back({"mask_" + where + "_tile",
                     gridWithTile<openvdb::MaskGrid>(false, level, false),
                     gridWithTile<openvdb::MaskGrid>(false, level, true)});
  }
  return bytes;
}

}  // namespace

TEST(VdbLayout, ADamagedZipBlockIsRefusedBeforeOpenVdbReadsTheTree) {
  // OpenVDB 10 allocates a child of the root, then throws when a zip block of its values does
  // not decompress, which leaks the child (fuzz_vdb ran out of memory on these). Zip without the
  // active mask stores every value of an internal node: the first zip block (zlib's 78 9c) is
  // the values of the root's first child, in the tree's topology. A level set would be written
  // without zip: the sphere is written as a grid of no class.
  const fs::path dir = scratchDir("vdb-layout-zip");
  const std::string bytes = writeGrid(dir / "zip.vdb", sphere(openvdb::GRID_UNKNOWN), kZip);
  expectPasses(dir / "zip.vdb");
  const std::size_t block = firstBlock(bytes, "\x78\x9c");
  ASSERT_NE(block, std::string::npos) << "no zip block found";

  std::string damaged = bytes;
  damaged.replace(block + 8, 2, std::string("\0\0", 2));
  writeText(dir / "zip_header.vdb", damaged);
  expectRefusedAt(dir / "zip_header.vdb", block,
                  "the zip block of an internal node of grid 0 does not decompress to the 131072 "
                  "bytes of its values (zlib: unknown compression method)");
}

TEST(VdbLayout, ABloscBlockOfOtherValuesIsRefusedBeforeOpenVdbReadsTheTree) {
  // A blosc block (header: format version 2, LZ4's version 1) whose header states 4 bytes of
  // values fewer than the node has: blosc_decompress gives them and OpenVDB 10 throws, leaking.
  const fs::path dir = scratchDir("vdb-layout-blosc");
  const std::string bytes = writeGrid(dir / "blosc.vdb", sphere(openvdb::GRID_LEVEL_SET), kBlosc);
  expectPasses(dir / "blosc.vdb");
  const std::size_t block = firstBlock(bytes, "\x02\x01");
  ASSERT_NE(block, std::string::npos) << "no blosc block found";
  std::uint32_t valueBytes = 0;
  std::memcpy(&valueBytes, bytes.data() + block + 8 + 4, sizeof valueBytes);
  ASSERT_EQ(valueBytes, 131072u);  // 32768 floats

  std::string damaged = bytes;
  const std::uint32_t fewer = valueBytes - 4;
  damaged.replace(block + 8 + 4, 4, std::string(reinterpret_cast<const char*>(&fewer), 4));
  writeText(dir / "blosc_values.vdb", damaged);
  expectRefusedAt(dir / "blosc_values.vdb", block,
                  "the header of a blosc block of an internal node of grid 0 claims 131068 bytes "
                  "of values, but they take 131072");
}

TEST(VdbLayout, BoolBytesOtherThanZeroOrOneAreRefused) {
  // OpenVDB 10 reads a bool or mask grid's background, tiles and internal-node values into
  // bools: a byte of 2 is undefined behaviour (UBSan, NodeUnion.h). The byte is found by
  // comparing the files of a grid with a 0 and with a 1 there. An internal node's one active
  // value is stored plain, as a zip block stored uncompressed, or in a blosc block (too few bytes
  // to compress: blosc copies them after its header, and the walk decompresses the block).
  const fs::path dir = scratchDir("vdb-layout-bool");
  const std::vector<std::uint32_t> compressions = {0, kZip | kActive, kBlosc | kActive};
  for (const BoolByte& byte : boolBytes())
    for (const std::uint32_t compression : compressions) {
      const std::string name = byte.name + "_" + std::to_string(compression);
      const std::string zero = writeGrid(dir / (name + "_0.vdb"), byte.zero, compression);
      const std::string one = writeGrid(dir / (name + "_1.vdb"), byte.one, compression);
      expectPasses(dir / (name + "_1.vdb"));
      const std::size_t at = onlyDifference(zero, one);
      ASSERT_NE(at, std::string::npos) << name << ": the files differ in more than one byte";
      ASSERT_EQ(one[at], 1) << name;

      std::string damaged = one;
      damaged[at] = 2;
      writeText(dir / (name + "_2.vdb"), damaged);
      // A blosc block is refused at its start: its Int64 size, then a 16-byte header.
      const bool blosc = compression == (kBlosc | kActive) && contains(name, "internal");
      expectRefusedAt(dir / (name + "_2.vdb"), blosc ? at - 24 : at,
                      " is 2, but it is read into a bool (0 or 1)");
    }
}

TEST(VdbLayout, ARootTileActiveFlagOtherThanZeroOrOneIsRefused) {
  // RootNode::readTopology reads each tile's active flag into a bool, of every value type. A
  // root tile is stored as its origin, its value and that flag.
  const fs::path dir = scratchDir("vdb-layout-active");
  openvdb::initialize();
  const openvdb::Coord origin(4096, -8192, 12288);
  const float value = 1.5f;
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->tree().addTile(3, origin, value, true);
  grid->setName("tiles");
  const std::string bytes = writeGrid(dir / "active_1.vdb", grid, kBlosc | kActive);
  expectPasses(dir / "active_1.vdb");
  const std::string tile = std::string(reinterpret_cast<const char*>(origin.data()), 12) +
                           std::string(reinterpret_cast<const char*>(&value), 4) + "\x01";
  const std::size_t at = bytes.find(tile);
  ASSERT_NE(at, std::string::npos) << "the root tile was not found";
  ASSERT_EQ(bytes.find(tile, at + 1), std::string::npos) << "the root tile was found twice";

  std::string damaged = bytes;
  damaged[at + 16] = 2;
  writeText(dir / "active_2.vdb", damaged);
  expectRefusedAt(dir / "active_2.vdb", at + 16,
                  "a byte of the active flag of a tile of the root of grid 0 is 2, but it is read "
                  "into a bool (0 or 1)");
}
