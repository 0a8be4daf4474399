// The reader behind the layout check of a .vdb file (vdb_layout.h, vdb_tree_layout.h): the file's
// little-endian fields through a window of its bytes, with every stated length checked against a
// bound before it is skipped. Internal to src/volume.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace voxremesh::volume {

/// Reads the fields of one file in order, seeking freely. Refusals are InputErrors naming the
/// file and a byte offset.
class LayoutReader {
 public:
  /// The most bytes `bytes` returns at once (an internal node's mask takes 4096).
  static constexpr std::size_t kMaxBytes = 8192;

  /// Opens `path`. Throws InputError naming it when it cannot be opened or sized.
  explicit LayoutReader(const std::filesystem::path& path);

  std::uint64_t size() const { return size_; }
  std::uint64_t position() const { return position_; }

  /// The bytes from the position to `end`; 0 when the position is at or past it.
  std::uint64_t left(std::uint64_t end) const { return end > position_ ? end - position_ : 0; }

  /// Moves to `offset` (reading there is refused by the bounds, not by the move).
  void seek(std::uint64_t offset) { position_ = offset; }

  /// Reads a fixed-size value that ends at or before `end` (and the file's end). Returns false,
  /// staying where it was, when it does not.
  template <typename T>
  bool value(T& out, std::uint64_t end) {
    if (sizeof(T) > left(end)) return false;
    const unsigned char* at = window(sizeof(T));
    if (at == nullptr) return false;
    std::memcpy(&out, at, sizeof(T));
    position_ += sizeof(T);
    return true;
  }

  /// Reads a fixed-size value of `what` that must end at or before `end`. Throws InputError at
  /// the position when it does not.
  template <typename T>
  T require(std::uint64_t end, const std::string& what) {
    T out{};
    if (!value(out, end)) tooShort(sizeof(T), end, what);
    return out;
  }

  /// The `count` bytes (at most kMaxBytes) of `what` at the position, which must end at or before
  /// `end`; the reader moves past them. The pointer is valid until the next read. Throws
  /// InputError like require.
  const unsigned char* bytes(std::size_t count, std::uint64_t end, const std::string& what);

  /// Skips `count` bytes that `what` claims (a length the file states). Throws InputError at the
  /// position when fewer than `count` remain before `end`.
  void claim(std::uint64_t count, std::uint64_t end, const std::string& what);

  /// Skips the `count` bytes `what` takes (a size the layout implies). Throws InputError like
  /// require when fewer remain before `end`.
  void skip(std::uint64_t count, std::uint64_t end, const std::string& what) {
    if (count > left(end)) tooShort(count, end, what);
    position_ += count;
  }

  /// A string: its 32-bit length, then its bytes, which must end at or before `end`. Returns false
  /// when the length itself does not fit (the reader stays); throws InputError at the length when
  /// the bytes do not. With `text`, stores the string's first 64 characters there.
  bool string(std::uint64_t end, const std::string& what, std::string* text = nullptr);

  /// Like string, but a length that does not fit before `end` is refused too: throws InputError.
  void requireString(std::uint64_t end, const std::string& what, std::string* text = nullptr) {
    if (!string(end, what, text)) tooShort(sizeof(std::uint32_t), end, "the length of " + what);
  }

  /// Throws InputError: "byte offset <position>: <message> (a damaged .vdb file; nothing read)".
  [[noreturn]] void fail(const std::string& message) const { failAt(position_, message); }

  /// Throws InputError like fail, at `offset`.
  [[noreturn]] void failAt(std::uint64_t offset, const std::string& message) const;

 private:
  /// The `count` (at most kMaxBytes) bytes at the position from the window, refilling it there
  /// when they are not in it; nullptr when the file ends before them.
  const unsigned char* window(std::size_t count);

  /// Throws InputError at the position: `what` needs `count` bytes, fewer remain before `end`.
  [[noreturn]] void tooShort(std::uint64_t count, std::uint64_t end, const std::string& what) const;

  std::string name_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::uint64_t position_ = 0;
  std::vector<unsigned char> window_;
  std::uint64_t windowStart_ = 0;
  std::size_t windowBytes_ = 0;
};

}  // namespace voxremesh::volume
