// Shared by the harnesses: writes the fuzzer's bytes to a fixed per-process file under /tmp
// (/tmp/voxremesh_fuzz_<pid><ext>, rewritten on each call) for the readers that take a path.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace voxremesh_fuzz {

inline std::string writeInput(const uint8_t* data, size_t size, const char* extension) {
  const std::string path =
      "/tmp/voxremesh_fuzz_" + std::to_string(static_cast<long>(getpid())) + extension;
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) std::abort();  // the harness itself is broken, not the reader
  if (size > 0 && std::fwrite(data, 1, size, file) != size) std::abort();
  std::fclose(file);
  return path;
}

}  // namespace voxremesh_fuzz
