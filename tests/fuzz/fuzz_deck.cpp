// Feeds arbitrary bytes as a deck/mesh file of extension FUZZ_EXTENSION to voxremesh::readDeck.
// Built once per extension (fuzz_deck_k, _bdf, _inp, _obj, _off, _stl, _ply); run e.g.
//   build-fuzz/bin/fuzz_deck_k corpus/ -max_total_time=1800 -rss_limit_mb=2048  (corpus: a copy of
//   seeds/deck_k)
#include <cstddef>
#include <cstdint>
#include <exception>

#include "fuzz_input_file.h"
#include "voxremesh/io.h"

#ifndef FUZZ_EXTENSION
#error "compile with -DFUZZ_EXTENSION=\".k\" (or .bdf .inp .obj .off .stl .ply)"
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = voxremesh_fuzz::writeInput(data, size, FUZZ_EXTENSION);
  try {
    voxremesh::Warnings warnings;
    (void)voxremesh::readDeck(path, {}, &warnings);
  } catch (const std::exception&) {
    // a clean refusal of malformed input is fine
  }
  return 0;
}
