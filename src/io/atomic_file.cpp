#include "io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <system_error>

namespace voxremesh::io {

void writeFileAtomically(const std::filesystem::path& path, std::string_view content) {
  // Unique per process and per call, so that threads writing at once never share a temporary.
  static std::atomic<unsigned long> calls{0};
  std::filesystem::path temporary = path;
  temporary += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(calls++);
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (!file) throw std::runtime_error("cannot write " + path.string() + ": cannot create file");
  const bool written = std::fwrite(content.data(), 1, content.size(), file) == content.size();
  const bool closed = std::fclose(file) == 0;
  if (!written || !closed) {
    std::remove(temporary.c_str());
    throw std::runtime_error("cannot write " + path.string() + ": write failed (disk full?)");
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::remove(temporary.c_str());
    throw std::runtime_error("cannot write " + path.string() + ": " + error.message());
  }
}

}  // namespace voxremesh::io
