// Feeds arbitrary bytes as a quality criteria file to voxremesh::readCriteriaFile (parse and
// check only). Run: build-fuzz/bin/fuzz_criteria corpus/ -max_total_time=1800 -rss_limit_mb=2048
// (corpus: a copy of seeds/criteria)
#include <cstddef>
#include <cstdint>
#include <exception>

#include "fuzz_input_file.h"
#include "voxremesh/criteria_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = voxremesh_fuzz::writeInput(data, size, ".txt");
  try {
    voxremesh::QualitySettings settings;
    voxremesh::readCriteriaFile(path, settings);
  } catch (const std::exception&) {
    // a clean refusal of malformed input is fine
  }
  return 0;
}
