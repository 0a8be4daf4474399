// Feeds arbitrary bytes as a JSON batch job file (.json) to voxremesh::readBatchFile (parse only).
// Run: build-fuzz/bin/fuzz_batch corpus/ -max_total_time=1800 -rss_limit_mb=2048  (corpus: a copy
// of seeds/batch)
#include <cstddef>
#include <cstdint>
#include <exception>

#include "fuzz_input_file.h"
#include "voxremesh/batch.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = voxremesh_fuzz::writeInput(data, size, ".json");
  try {
    (void)voxremesh::readBatchFile(path);
  } catch (const std::exception&) {
    // a clean refusal of malformed input is fine
  }
  return 0;
}
