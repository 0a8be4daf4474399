// A strict decoder for the PNG images voxremesh writes (8-bit RGB, not interlaced), so that the
// tests can check the file structure (signature, chunk CRCs, IHDR) and look at the pixels.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace voxremesh::test {

/// A decoded PNG image.
struct DecodedPng {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgb;            ///< width x height x 3, rows top to bottom
  std::vector<std::string> chunkTypes;      ///< in file order
  std::map<std::string, std::string> text;  ///< tEXt keyword -> text
};

/// Decodes `bytes` as an 8-bit RGB, non-interlaced PNG, undoing all five row filters.
/// Throws std::runtime_error naming the first problem: a wrong signature, a truncated chunk, a
/// CRC mismatch, IHDR not first or with other parameters, missing IDAT or IEND, data after IEND,
/// a zlib error, a wrong decompressed size or an unknown filter type.
DecodedPng decodePng(const std::string& bytes);

}  // namespace voxremesh::test
