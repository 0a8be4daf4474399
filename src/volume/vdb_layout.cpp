// The layout check of a .vdb file before OpenVDB reads it (vdb_layout.h). The layout followed is
// OpenVDB 10's io::Archive (header), MetaMap::readMeta with the metadata types openvdb::initialize
// registers (io/DelayedLoadMetadata.cc for "__delayedload"), GridDescriptor::read,
// Archive::readGrid (compression flags, metadata, Transform::read and the maps of math/Maps.h)
// and, for the tree, vdb_tree_layout.h.
#include "volume/vdb_layout.h"

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "volume/vdb_layout_reader.h"
#include "volume/vdb_tree_layout.h"

namespace voxremesh::volume {

namespace {

constexpr std::int64_t kVdbMagic = 0x56444220;
constexpr std::uint32_t kFirstCheckedVersion = 222;  // per-grid compression, the current layout
constexpr std::uint32_t kLastCheckedVersion = 224;
constexpr const char* kHalfFloatSuffix = "_HalfFloat";            // of a descriptor's grid type
constexpr const char* kHalfFloatName = "is_saved_as_half_float";  // GridBase::META_SAVE_HALF_FLOAT
constexpr const char* kDelayedLoadType = "__delayedload";         // io::DelayedLoadMetadata
constexpr const char* kSheetCountName = "voxremesh_sheet_count";  // volume_io.cpp, an int64
constexpr std::uint64_t kLeafBytes = 64;         // the least a leaf takes: its value mask
constexpr std::uint64_t kBloscHeaderBytes = 16;  // BLOSC_MIN_HEADER_LENGTH
constexpr std::uint64_t kBloscPadBytes = 128;    // compression::BLOSC_PAD_BYTES

/// A fixed-size metadata type OpenVDB registers: TypedMetadata<T>::readValue reads sizeof(T)
/// bytes, whatever size the entry states.
struct FixedMeta {
  const char* type;
  char element;  ///< 'b' bool, 'i' int32, 'l' int64, 'f' float, 'd' double
  std::uint32_t count;
};

constexpr FixedMeta kFixedMetas[] = {
    {"bool", 'b', 1},   {"int32", 'i', 1}, {"int64", 'l', 1},  {"float", 'f', 1},
    {"double", 'd', 1}, {"vec2i", 'i', 2}, {"vec2s", 'f', 2},  {"vec2d", 'd', 2},
    {"vec3i", 'i', 3},  {"vec3s", 'f', 3}, {"vec3d", 'd', 3},  {"vec4i", 'i', 4},
    {"vec4s", 'f', 4},  {"vec4d", 'd', 4}, {"mat4s", 'f', 16}, {"mat4d", 'd', 16}};

/// The bytes of one element of a fixed-size metadata type.
std::uint32_t elementBytes(char element) {
  return element == 'b' ? 1 : element == 'l' || element == 'd' ? 8 : 4;
}

/// The fixed-size metadata type named `type`; nullptr for the others.
const FixedMeta* findFixedMeta(const std::string& type) {
  for (const FixedMeta& meta : kFixedMetas)
    if (type == meta.type) return &meta;
  return nullptr;
}

/// The little-endian value of type T at `at`.
template <typename T>
T load(const unsigned char* at) {
  T value{};
  std::memcpy(&value, at, sizeof value);
  return value;
}

/// Whether one element of a fixed-size metadata value equals zero (-0.0 does, NaN does not).
bool elementIsZero(char element, const unsigned char* at) {
  switch (element) {
    case 'b':
      return *at == 0;
    case 'i':
      return load<std::int32_t>(at) == 0;
    case 'l':
      return load<std::int64_t>(at) == 0;
    case 'f':
      return load<float>(at) == 0;
    default:
      return load<double>(at) == 0;
  }
}

/// TypedMetadata<T>::asBool of a fixed-size value: true unless every element equals zero.
bool fixedAsBool(const FixedMeta& meta, const unsigned char* value) {
  for (std::uint32_t k = 0; k < meta.count; ++k)
    if (!elementIsZero(meta.element, value + k * elementBytes(meta.element))) return true;
  return false;
}

/// One array of a "__delayedload" value: its 32-bit byte count, then a blosc block of that many
/// bytes or, for a count of 0, `count` plain elements of `bytes` bytes; with `optional`, a count
/// of 0xffffffff stands for no array. Throws InputError for an array or blosc header that does not
/// fit before `end`, or a header whose sizes disagree with `count` and the block (OpenVDB reserves
/// and decompresses what the header says).
void delayedLoadArray(LayoutReader& reader, std::uint64_t end, std::uint32_t count,
                      std::uint32_t bytes, bool optional, const std::string& what) {
  const std::uint64_t at = reader.position();
  const auto stated = reader.require<std::uint32_t>(end, "the size of " + what);
  if (optional && stated == std::numeric_limits<std::uint32_t>::max()) return;
  if (stated == 0) {
    reader.claim(std::uint64_t{count} * bytes, end, what);
    return;
  }
  reader.claim(stated, end, what);
  reader.seek(at + sizeof stated);
  const unsigned char* header = reader.bytes(kBloscHeaderBytes, end, "the blosc header of " + what);
  const auto uncompressed = load<std::uint32_t>(header + 4);  // nbytes
  const auto compressed = load<std::uint32_t>(header + 12);   // cbytes
  // Blosc compresses fewer than 128 bytes padded to 128 (points/StreamCompression.cc).
  const std::uint64_t expected = std::uint64_t{count} * bytes;
  if ((uncompressed != expected &&
       (expected >= kBloscPadBytes || uncompressed != kBloscPadBytes)) ||
      compressed > stated)
    reader.failAt(at, "the blosc header of " + what + " claims " + std::to_string(uncompressed) +
                          " bytes from " + std::to_string(compressed) + ", but " +
                          std::to_string(count) + " elements of " + std::to_string(bytes) +
                          " bytes in " + std::to_string(stated) + " were stated");
  reader.seek(at + sizeof stated + stated);
}

/// A "__delayedload" value (DelayedLoadMetadata::readValue) from the position to `end`: a leaf
/// count, the leaves' mask bytes, then optionally their Int64 block sizes. A grid of
/// `regionBytes` bytes holds at most regionBytes / 64 leaves. Throws InputError as
/// delayedLoadArray does, or for a larger count.
void delayedLoadValue(LayoutReader& reader, std::uint64_t end, std::uint64_t regionBytes,
                      const std::string& what) {
  if (reader.position() == end) return;  // an empty value reads nothing
  const std::uint64_t at = reader.position();
  const auto count = reader.require<std::uint32_t>(end, "the leaf count of " + what);
  if (count > regionBytes / kLeafBytes)
    reader.failAt(at, what + " claims " + std::to_string(count) + " leaf nodes, more than " +
                          std::to_string(regionBytes) + " bytes hold");
  delayedLoadArray(reader, end, count, 1, false, "the leaf masks of " + what);
  delayedLoadArray(reader, end, count, 8, true, "the leaf block sizes of " + what);
}

/// What the walk keeps of a metadata map (the last entry of each name, as MetaMap keeps).
struct MetaFacts {
  bool halfFloat = false;          ///< the asBool of is_saved_as_half_float
  std::int64_t sheetCount = 0;     ///< an int64 voxremesh_sheet_count (0: none)
  std::uint64_t sheetCountAt = 0;  ///< where its value is
};

/// A metadata map (MetaMap::readMeta) from the position to `end`: a count, then per entry a name,
/// a type name, a 32-bit size and the value. `regionBytes` bounds a "__delayedload" entry's leaf
/// count (see delayedLoadValue). Fills `facts`. Throws InputError for a count, length, size or
/// value larger than the bytes left before `end`, or a field that does not fit before it.
void metadata(LayoutReader& reader, std::uint64_t end, std::uint64_t regionBytes,
              const std::string& what, MetaFacts& facts) {
  const std::uint64_t at = reader.position();
  const auto count = reader.require<std::int32_t>(end, "the entry count of " + what);
  // An entry takes at least 12 bytes (two empty strings and an empty value).
  if (count < 0 || static_cast<std::uint64_t>(count) > reader.left(end) / 12)
    reader.failAt(
        at, what + " claims " + std::to_string(count) + " entries, more than the bytes left hold");
  const std::string entry = "the value of an entry of " + what;
  for (std::int32_t k = 0; k < count; ++k) {
    std::string name, type;
    reader.requireString(end, "the name of an entry of " + what, &name);
    reader.requireString(end, "the type of an entry of " + what, &type);
    const auto bytes = reader.require<std::uint32_t>(end, "the size of " + entry);
    const std::uint64_t valueAt = reader.position();
    reader.claim(bytes, end, entry);
    reader.seek(valueAt);
    if (const FixedMeta* fixed = findFixedMeta(type)) {
      const unsigned char* value =
          reader.bytes(fixed->count * elementBytes(fixed->element), end, entry);
      if (name == kHalfFloatName) facts.halfFloat = fixedAsBool(*fixed, value);
      if (name == kSheetCountName && fixed->element == 'l' && fixed->count == 1) {
        facts.sheetCount = load<std::int64_t>(value);
        facts.sheetCountAt = valueAt;
      }
      continue;
    }
    if (type == kDelayedLoadType) delayedLoadValue(reader, valueAt + bytes, regionBytes, entry);
    // StringMetadata and UnknownMetadata::asBool: not empty; DelayedLoadMetadata's: false.
    if (name == kHalfFloatName) facts.halfFloat = bytes > 0 && type != kDelayedLoadType;
    reader.seek(valueAt + bytes);
  }
}

/// The header up to the file metadata; false when the file does not start with the .vdb magic
/// number (left to OpenVDB to say "not a VDB file"). Throws InputError for a header cut short, a
/// format version other than 222..224 or a file without grid offsets (a stream): OpenVDB would
/// read those without the checks here.
bool header(LayoutReader& reader) {
  const std::uint64_t end = reader.size();
  std::int64_t magic = 0;
  if (!reader.value(magic, end) || magic != kVdbMagic) return false;
  const std::uint64_t versionAt = reader.position();
  const auto version = reader.require<std::uint32_t>(end, "the file format version");
  if (version < kFirstCheckedVersion || version > kLastCheckedVersion)
    reader.failAt(versionAt, "file format version " + std::to_string(version) + "; versions " +
                                 std::to_string(kFirstCheckedVersion) + " to " +
                                 std::to_string(kLastCheckedVersion) + " are read");
  reader.skip(2 * sizeof(std::uint32_t), end, "the library version");
  const std::uint64_t offsetsAt = reader.position();
  if (reader.require<char>(end, "the grid offsets flag") == 0)
    reader.failAt(offsetsAt,
                  "a stream without grid offsets; files written by OpenVDB's io::File are read");
  reader.skip(36, end, "the file's UUID");  // written as text, with hyphens
  return true;
}

/// Transform::read from the position to `end`: a map type name, then the map's values (math/Maps.h
/// read(); a NonlinearFrustumMap's bounding box, taper and depth come before a second map).
/// Returns false for a map type OpenVDB does not register (it refuses the grid itself). Throws
/// InputError for a name or map that does not fit before `end`.
bool transform(LayoutReader& reader, std::uint64_t end, const std::string& which) {
  struct MapSize {
    const char* type;
    std::uint32_t bytes;
  };
  static constexpr MapSize kMaps[] = {{"AffineMap", 128},
                                      {"UnitaryMap", 128},
                                      {"ScaleMap", 120},
                                      {"UniformScaleMap", 120},
                                      {"TranslationMap", 24},
                                      {"ScaleTranslateMap", 144},
                                      {"UniformScaleTranslateMap", 144}};
  std::string type;
  reader.requireString(end, "the transform type of " + which, &type);
  while (type == "NonlinearFrustumMap") {
    reader.skip(64, end, "the frustum of the transform of " + which);
    reader.requireString(end, "the second map type of the transform of " + which, &type);
  }
  for (const MapSize& map : kMaps)
    if (type == map.type) {
      reader.skip(map.bytes, end, "the transform of " + which);
      return true;
    }
  return false;
}

/// The grid type of a descriptor without its "_HalfFloat" suffix.
std::string withoutHalfFloatSuffix(std::string type) {
  const std::size_t suffix = std::strlen(kHalfFloatSuffix);
  if (type.size() > suffix && type.compare(type.size() - suffix, suffix, kHalfFloatSuffix) == 0)
    type.erase(type.size() - suffix);
  return type;
}

/// One grid: its descriptor, then at its position its compression flags, metadata, transform
/// and (unless it is an instance of another grid's tree) its tree, all within the grid's bytes.
/// Throws InputError for a descriptor cut short, positions out of order, or anything of the grid
/// that runs past them (see metadata, transform and checkTreeLayout).
void grid(LayoutReader& reader, std::size_t index) {
  TreeGrid tree;
  tree.which = "grid " + std::to_string(index);
  const std::uint64_t size = reader.size();
  std::string type, parent;
  reader.requireString(size, "the name of " + tree.which);
  reader.requireString(size, "the type of " + tree.which, &type);
  reader.requireString(size, "the instance parent of " + tree.which, &parent);
  const bool instance = !parent.empty();  // written without a tree, and with a block position 0
  const std::uint64_t positionsAt = reader.position();
  const auto gridPos = reader.require<std::int64_t>(size, "the positions of " + tree.which);
  const auto blockPos = reader.require<std::int64_t>(size, "the positions of " + tree.which);
  const auto endPos = reader.require<std::int64_t>(size, "the positions of " + tree.which);
  const auto inFile = [&](std::int64_t p) {
    return p >= 0 && static_cast<std::uint64_t>(p) <= size;
  };
  if (!inFile(gridPos) || !inFile(blockPos) || !inFile(endPos) ||
      static_cast<std::uint64_t>(gridPos) < reader.position() || endPos < gridPos ||
      (!instance && (blockPos < gridPos || endPos < blockPos)))
    reader.failAt(positionsAt, "the positions of " + tree.which + " (" + std::to_string(gridPos) +
                                   ", " + std::to_string(blockPos) + ", " + std::to_string(endPos) +
                                   ") are not in order within the file of " + std::to_string(size) +
                                   " bytes");
  tree.blockPosition = static_cast<std::uint64_t>(instance ? endPos : blockPos);
  tree.endPosition = static_cast<std::uint64_t>(endPos);
  const auto start = static_cast<std::uint64_t>(gridPos);
  reader.seek(start);
  tree.compression =
      reader.require<std::uint32_t>(tree.blockPosition, "the compression of " + tree.which);
  MetaFacts facts;
  metadata(reader, tree.blockPosition, tree.endPosition - start, "the metadata of " + tree.which,
           facts);
  tree.halfFloat = facts.halfFloat;
  type = withoutHalfFloatSuffix(type);
  if (transform(reader, tree.blockPosition, tree.which) && !instance && isWalkedTreeType(type))
    checkTreeLayout(reader, type, tree);
  // The next descriptor follows the grid's end, as OpenVDB reads.
  reader.seek(tree.endPosition);
}

}  // namespace

void checkVdbLayout(const std::filesystem::path& path) {
  LayoutReader reader(path);
  if (!header(reader)) return;
  MetaFacts facts;
  metadata(reader, reader.size(), reader.size(), "the file metadata", facts);
  const std::uint64_t countAt = reader.position();
  const auto grids = reader.require<std::int32_t>(reader.size(), "the grid count");
  // A grid takes at least 40 bytes (three empty strings and three positions).
  if (grids < 0 || static_cast<std::uint64_t>(grids) > reader.left(reader.size()) / 40)
    reader.failAt(countAt,
                  "the file claims " + std::to_string(grids) + " grids, more than its bytes hold");
  // readVolumes reserves a volume per sheet: three grids each.
  if (facts.sheetCount > grids / 3)
    reader.failAt(facts.sheetCountAt, std::string("the file metadata ") + kSheetCountName +
                                          " claims " + std::to_string(facts.sheetCount) +
                                          " sheets, but the file holds " + std::to_string(grids) +
                                          " grids (three per sheet)");
  for (std::int32_t k = 0; k < grids; ++k) grid(reader, static_cast<std::size_t>(k));
}

}  // namespace voxremesh::volume
