// Feeds arbitrary bytes as a .vdb file to voxremesh::readVolumes.
// Run: build-fuzz/bin/fuzz_vdb corpus/ -max_total_time=1800 -rss_limit_mb=2048  (corpus: a copy of
// seeds/vdb)
#include <cstddef>
#include <cstdint>
#include <exception>

#include "fuzz_input_file.h"
#include "voxremesh/volume.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = voxremesh_fuzz::writeInput(data, size, ".vdb");
  try {
    (void)voxremesh::readVolumes(path);
  } catch (const std::exception&) {
    // a clean refusal of malformed input is fine
  }
  return 0;
}
