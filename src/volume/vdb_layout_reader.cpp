// The reader behind the layout check of a .vdb file (vdb_layout_reader.h).
#include "volume/vdb_layout_reader.h"

#include <algorithm>

#include "voxremesh/errors.h"

namespace voxremesh::volume {

namespace {

constexpr std::size_t kWindowBytes = 1 << 16;  // read ahead: the walk skips mostly short blocks
constexpr std::size_t kKeptCharacters = 64;    // of a string, for recognising names and types

}  // namespace

LayoutReader::LayoutReader(const std::filesystem::path& path)
    : name_(path.string()), in_(path, std::ios::binary), window_(kWindowBytes) {
  std::error_code error;
  size_ = std::filesystem::file_size(path, error);
  if (error || !in_) throw InputError(name_, 0, "cannot read the file");
}

const unsigned char* LayoutReader::window(std::size_t count) {
  if (position_ >= windowStart_ && count <= windowBytes_ &&
      position_ - windowStart_ <= windowBytes_ - count)
    return window_.data() + (position_ - windowStart_);
  if (position_ > size_) return nullptr;
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(position_));
  in_.read(reinterpret_cast<char*>(window_.data()), static_cast<std::streamsize>(kWindowBytes));
  windowStart_ = position_;
  windowBytes_ = static_cast<std::size_t>(std::max<std::streamsize>(in_.gcount(), 0));
  return count <= windowBytes_ ? window_.data() : nullptr;
}

const unsigned char* LayoutReader::bytes(std::size_t count, std::uint64_t end,
                                         const std::string& what) {
  if (count > left(end)) tooShort(count, end, what);
  const unsigned char* at = window(std::min(count, kMaxBytes));
  if (at == nullptr) tooShort(count, end, what);
  position_ += count;
  return at;
}

void LayoutReader::claim(std::uint64_t count, std::uint64_t end, const std::string& what) {
  if (count > left(end))
    fail(what + " claims " + std::to_string(count) + " bytes, but only " +
         std::to_string(left(end)) + " remain before byte " + std::to_string(end));
  position_ += count;
}

bool LayoutReader::string(std::uint64_t end, const std::string& what, std::string* text) {
  const std::uint64_t at = position_;
  std::uint32_t length = 0;
  if (!value(length, end)) return false;
  if (length > left(end)) {
    const std::uint64_t remaining = left(end);
    position_ = at;
    fail("the length of " + what + " is " + std::to_string(length) + " bytes, but only " +
         std::to_string(remaining) + " remain");
  }
  if (text != nullptr) {
    const std::size_t kept = std::min<std::size_t>(length, kKeptCharacters);
    const unsigned char* characters = window(kept);
    text->assign(characters == nullptr ? "" : reinterpret_cast<const char*>(characters),
                 characters == nullptr ? 0 : kept);
  }
  position_ += length;
  return true;
}

void LayoutReader::failAt(std::uint64_t offset, const std::string& message) const {
  throw InputError(name_, 0,
                   "byte offset " + std::to_string(offset) + ": " + message +
                       " (a damaged .vdb file; nothing read)");
}

void LayoutReader::tooShort(std::uint64_t count, std::uint64_t end, const std::string& what) const {
  fail(what + " takes " + std::to_string(count) + " bytes, but only " + std::to_string(left(end)) +
       " remain before byte " + std::to_string(end));
}

}  // namespace voxremesh::volume
