// Feeds arbitrary bytes as an action chain config file to voxremesh::chain::parseConfig.
// Run: build-fuzz/bin/fuzz_chain_config corpus/ -max_total_time=1800 -rss_limit_mb=2048  (corpus: a
// copy of seeds/chain_config)
#include <cstddef>
#include <cstdint>
#include <exception>

#include "fuzz_input_file.h"
#include "voxremesh/action_chain.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = voxremesh_fuzz::writeInput(data, size, ".cfg");
  try {
    (void)voxremesh::chain::parseConfig(path);
  } catch (const std::exception&) {
    // a clean refusal of malformed input is fine
  }
  return 0;
}
