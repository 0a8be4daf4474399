#include "support/png.h"

#include <zlib.h>

#include <cstdlib>
#include <stdexcept>

namespace voxremesh::test {

namespace {

std::uint32_t bigEndian32(const std::string& bytes, std::size_t at) {
  if (at + 4 > bytes.size()) throw std::runtime_error("PNG truncated");
  std::uint32_t value = 0;
  for (std::size_t i = 0; i < 4; ++i) value = (value << 8) | std::uint8_t(bytes[at + i]);
  return value;
}

std::uint8_t paeth(int a, int b, int c) {
  const int p = a + b - c;
  const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return std::uint8_t(a);
  return std::uint8_t(pb <= pc ? b : c);
}

}  // namespace

DecodedPng decodePng(const std::string& bytes) {
  if (bytes.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) != 0)
    throw std::runtime_error("not a PNG signature");
  DecodedPng png;
  std::string idat;
  std::size_t at = 8;
  bool ended = false;
  while (at < bytes.size()) {
    if (ended) throw std::runtime_error("data after IEND");
    const std::uint32_t length = bigEndian32(bytes, at);
    if (at + 12 + std::size_t(length) > bytes.size()) throw std::runtime_error("chunk truncated");
    const std::string type = bytes.substr(at + 4, 4);
    const std::string data = bytes.substr(at + 8, length);
    const auto* crcBytes = reinterpret_cast<const Bytef*>(bytes.data() + at + 4);
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), crcBytes, uInt(4 + length));
    if (crc != bigEndian32(bytes, at + 8 + length))
      throw std::runtime_error("CRC mismatch in chunk " + type);
    if (png.chunkTypes.empty() && type != "IHDR") throw std::runtime_error("IHDR is not first");
    png.chunkTypes.push_back(type);
    if (type == "IHDR") {
      if (length != 13) throw std::runtime_error("IHDR of length " + std::to_string(length));
      png.width = bigEndian32(data, 0);
      png.height = bigEndian32(data, 4);
      if (png.width == 0 || png.height == 0) throw std::runtime_error("zero image size");
      if (data[8] != 8 || data[9] != 2 || data[10] != 0 || data[11] != 0 || data[12] != 0)
        throw std::runtime_error("not 8-bit RGB, deflate, adaptive filter, not interlaced");
    } else if (type == "IDAT") {
      idat += data;
    } else if (type == "tEXt") {
      const std::size_t zero = data.find('\0');
      if (zero == std::string::npos || zero == 0 || zero > 79)
        throw std::runtime_error("malformed tEXt keyword");
      png.text[data.substr(0, zero)] = data.substr(zero + 1);
    } else if (type == "IEND") {
      if (length != 0) throw std::runtime_error("IEND with data");
      ended = true;
    }
    at += 12 + std::size_t(length);
  }
  if (!ended) throw std::runtime_error("no IEND chunk");
  if (idat.empty()) throw std::runtime_error("no IDAT chunk");

  const std::size_t rowBytes = std::size_t(png.width) * 3;
  uLongf rawSize = uLongf((rowBytes + 1) * png.height);
  std::string raw(rawSize + 1, '\0');  // one spare byte: a longer stream shows as a wrong size
  uLongf produced = rawSize + 1;
  const int status = uncompress(reinterpret_cast<Bytef*>(raw.data()), &produced,
                                reinterpret_cast<const Bytef*>(idat.data()), uLong(idat.size()));
  if (status != Z_OK) throw std::runtime_error(std::string("zlib: ") + zError(status));
  if (produced != rawSize) throw std::runtime_error("decompressed size does not match IHDR");

  png.rgb.assign(rowBytes * png.height, 0);
  for (std::size_t y = 0; y < png.height; ++y) {
    const auto* in = reinterpret_cast<const std::uint8_t*>(raw.data()) + y * (rowBytes + 1);
    std::uint8_t* out = png.rgb.data() + y * rowBytes;
    const std::uint8_t* above = y ? out - rowBytes : nullptr;
    for (std::size_t i = 0; i < rowBytes; ++i) {
      const int a = i >= 3 ? out[i - 3] : 0, b = above ? above[i] : 0;
      const int c = above && i >= 3 ? above[i - 3] : 0;
      int predictor = 0;
      switch (in[0]) {
        case 0:
          break;
        case 1:
          predictor = a;
          break;
        case 2:
          predictor = b;
          break;
        case 3:
          predictor = (a + b) / 2;
          break;
        case 4:
          predictor = paeth(a, b, c);
          break;
        default:
          throw std::runtime_error("unknown filter type " + std::to_string(in[0]));
      }
      out[i] = std::uint8_t(in[1 + i] + predictor);
    }
  }
  return png;
}

}  // namespace voxremesh::test
