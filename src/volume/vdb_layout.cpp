// The layout check of a .vdb file before OpenVDB reads it (vdb_layout.h). The layout followed is
// OpenVDB's io::Archive (header), MetaMap::readMeta, GridDescriptor::read and Transform::read.
#include "volume/vdb_layout.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "voxremesh/errors.h"

namespace voxremesh::volume {

namespace {

constexpr std::int64_t kVdbMagic = 0x56444220;
constexpr std::uint32_t kFirstCheckedVersion = 222;  // per-grid compression, the current layout
constexpr std::uint32_t kLastCheckedVersion = 224;

/// Reads the little-endian fields of a .vdb file, refusing any length that runs past `end`.
class LayoutReader {
 public:
  explicit LayoutReader(const std::filesystem::path& path)
      : name_(path.string()), in_(path, std::ios::binary) {
    std::error_code error;
    size_ = std::filesystem::file_size(path, error);
    if (error || !in_) throw InputError(name_, 0, "cannot read the file");
  }

  std::uint64_t size() const { return size_; }
  std::uint64_t position() const { return position_; }

  /// Moves to an offset within the file.
  void seek(std::uint64_t offset) {
    position_ = offset;
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset));
  }

  /// A fixed-size value; false when the file ends before it (left to OpenVDB to report).
  template <typename T>
  bool value(T& out, std::uint64_t end) {
    if (sizeof(T) > end - position_) return false;
    char bytes[sizeof(T)];
    if (!in_.read(bytes, sizeof(T))) return false;
    std::memcpy(&out, bytes, sizeof(T));
    position_ += sizeof(T);
    return true;
  }

  /// Skips `count` bytes that `what` claims, refusing them when fewer remain before `end`.
  void claim(std::uint64_t count, std::uint64_t end, const std::string& what) {
    if (count > end - position_)
      fail(what + " claims " + std::to_string(count) + " bytes, but only " +
           std::to_string(end - position_) + " remain");
    seek(position_ + count);
  }

  /// A string: its 32-bit length, then its bytes.
  bool string(std::uint64_t end, const std::string& what) {
    const std::uint64_t at = position_;
    std::uint32_t length = 0;
    if (!value(length, end)) return false;
    if (length > end - position_) {
      const std::uint64_t left = end - position_;
      position_ = at;
      fail("the length of " + what + " is " + std::to_string(length) + " bytes, but only " +
           std::to_string(left) + " remain");
    }
    seek(position_ + length);
    return true;
  }

  /// A metadata map: a count, then per entry a name, a type name and a sized value.
  bool metadata(std::uint64_t end, const std::string& what) {
    std::int32_t count = 0;
    const std::uint64_t at = position_;
    if (!value(count, end)) return false;
    // An entry takes at least 12 bytes (two empty strings and an empty value).
    if (count < 0 || static_cast<std::uint64_t>(count) > (end - position_) / 12) {
      position_ = at;
      fail(what + " claims " + std::to_string(count) + " entries, more than the bytes left hold");
    }
    for (std::int32_t k = 0; k < count; ++k) {
      if (!string(end, "the name of an entry of " + what) ||
          !string(end, "the type of an entry of " + what))
        return false;
      std::uint32_t bytes = 0;
      if (!value(bytes, end)) return false;
      claim(bytes, end, "the value of an entry of " + what);
    }
    return true;
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(name_, 0,
                     "byte offset " + std::to_string(position_) + ": " + message +
                         " (a damaged .vdb file; nothing read)");
  }

 private:
  std::string name_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::uint64_t position_ = 0;
};

/// The header up to the file metadata; false when the file is no .vdb file (left to OpenVDB to
/// say so). Throws InputError for a format version other than 222..224 or a file without grid
/// offsets (a stream): OpenVDB would read those without the checks here.
bool header(LayoutReader& reader) {
  const std::uint64_t end = reader.size();
  std::int64_t magic = 0;
  std::uint32_t version = 0, libraryMajor = 0, libraryMinor = 0;
  char hasGridOffsets = 0;
  if (!reader.value(magic, end) || magic != kVdbMagic) return false;
  const std::uint64_t versionAt = reader.position();
  if (!reader.value(version, end)) return false;
  if (version < kFirstCheckedVersion || version > kLastCheckedVersion) {
    reader.seek(versionAt);
    reader.fail("file format version " + std::to_string(version) + "; versions " +
                std::to_string(kFirstCheckedVersion) + " to " +
                std::to_string(kLastCheckedVersion) + " are read");
  }
  if (!reader.value(libraryMajor, end) || !reader.value(libraryMinor, end)) return false;
  const std::uint64_t offsetsAt = reader.position();
  if (!reader.value(hasGridOffsets, end)) return false;
  if (hasGridOffsets == 0) {
    reader.seek(offsetsAt);
    reader.fail("a stream without grid offsets; files written by OpenVDB's io::File are read");
  }
  constexpr std::uint64_t kUuidCharacters = 36;  // written as text, with hyphens
  if (kUuidCharacters > end - reader.position()) return false;
  reader.seek(reader.position() + kUuidCharacters);
  return true;
}

/// One grid: its descriptor, then at its position its compression flags, metadata and transform
/// type. False when the file ends inside the descriptor (OpenVDB reports that).
bool grid(LayoutReader& reader, std::size_t index) {
  const std::string which = "grid " + std::to_string(index);
  const std::uint64_t size = reader.size();
  if (!reader.string(size, "the name of " + which) ||
      !reader.string(size, "the type of " + which) ||
      !reader.string(size, "the instance parent of " + which))
    return false;
  std::int64_t gridPos = 0, blockPos = 0, endPos = 0;
  const std::uint64_t positionsAt = reader.position();
  if (!reader.value(gridPos, size) || !reader.value(blockPos, size) || !reader.value(endPos, size))
    return false;
  const auto inFile = [&](std::int64_t p) {
    return p >= 0 && static_cast<std::uint64_t>(p) <= size;
  };
  if (!inFile(gridPos) || !inFile(blockPos) || !inFile(endPos) ||
      static_cast<std::uint64_t>(gridPos) < reader.position() || blockPos < gridPos ||
      endPos < blockPos) {
    reader.seek(positionsAt);
    reader.fail("the positions of " + which + " (" + std::to_string(gridPos) + ", " +
                std::to_string(blockPos) + ", " + std::to_string(endPos) +
                ") are not in order within the file of " + std::to_string(size) + " bytes");
  }
  // Its compression flags, metadata and transform type lie before its blocks (a grid too short
  // for them is left to OpenVDB); then the next descriptor follows its end, as OpenVDB reads.
  reader.seek(static_cast<std::uint64_t>(gridPos));
  const std::uint64_t blocks = static_cast<std::uint64_t>(blockPos);
  std::uint32_t compression = 0;
  if (reader.value(compression, blocks) && reader.metadata(blocks, "the metadata of " + which))
    reader.string(blocks, "the transform type of " + which);
  reader.seek(static_cast<std::uint64_t>(endPos));
  return true;
}

}  // namespace

void checkVdbLayout(const std::filesystem::path& path) {
  LayoutReader reader(path);
  if (!header(reader)) return;
  if (!reader.metadata(reader.size(), "the file metadata")) return;
  std::int32_t grids = 0;
  const std::uint64_t countAt = reader.position();
  if (!reader.value(grids, reader.size())) return;
  // A grid takes at least 40 bytes (three empty strings and three positions).
  if (grids < 0 || static_cast<std::uint64_t>(grids) > (reader.size() - reader.position()) / 40) {
    reader.seek(countAt);
    reader.fail("the file claims " + std::to_string(grids) + " grids, more than its bytes hold");
  }
  for (std::int32_t k = 0; k < grids; ++k)
    if (!grid(reader, static_cast<std::size_t>(k))) return;
}

}  // namespace voxremesh::volume
