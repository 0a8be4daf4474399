// A minimal PNG writer for slice images: 8-bit RGB, "Up"-filtered rows compressed with zlib,
// tEXt chunks saying what the image shows (PNG specification, W3C 2003 / ISO 15948).
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "io/atomic_file.h"
#include "voxremesh/slice_image.h"

namespace voxremesh {

namespace {

/// IDAT chunks carry at most this many bytes of the compressed stream each.
constexpr std::size_t kIdatChunkBytes = std::size_t{1} << 20;

void appendBigEndian32(std::string& out, std::uint32_t value) {
  out += char((value >> 24) & 0xff);
  out += char((value >> 16) & 0xff);
  out += char((value >> 8) & 0xff);
  out += char(value & 0xff);
}

/// Appends one chunk: length, type, data, CRC-32 of type and data.
void appendChunk(std::string& out, const char (&type)[5], const char* data, std::size_t size) {
  appendBigEndian32(out, static_cast<std::uint32_t>(size));
  const std::size_t typeAt = out.size();
  out.append(type, 4);
  out.append(data, size);
  const auto* bytes = reinterpret_cast<const Bytef*>(out.data() + typeAt);
  const uLong crc = crc32(crc32(0L, Z_NULL, 0), bytes, static_cast<uInt>(4 + size));
  appendBigEndian32(out, static_cast<std::uint32_t>(crc));
}

void appendText(std::string& out, const std::string& keyword, const std::string& text) {
  const std::string data = keyword + '\0' + text;
  appendChunk(out, "tEXt", data.data(), data.size());
}

std::string describe(const SliceImage& image) {
  char text[512];
  std::snprintf(text, sizeof text,
                "slice %s = %.9g (voxel index %d), voxel size %.9g, %d pixels per voxel; "
                "%s index %d..%d left to right, %s index %d..%d bottom to top",
                axisName(image.axis), image.sliceWorld, image.sliceIndex, image.voxelSize,
                image.pixelsPerVoxel, axisName(image.uAxis), image.uMin, image.uMax,
                axisName(image.vAxis), image.vMin, image.vMax);
  return text;
}

}  // namespace

std::string encodePng(const SliceImage& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw std::invalid_argument("cannot encode an empty image as PNG");
  }
  const std::size_t rowBytes = std::size_t(image.width) * 3;
  if (image.pixels.size() != rowBytes * std::size_t(image.height)) {
    throw std::invalid_argument("image of " + std::to_string(image.width) + " x " +
                                std::to_string(image.height) + " pixels holds " +
                                std::to_string(image.pixels.size()) + " bytes, not " +
                                std::to_string(rowBytes * std::size_t(image.height)));
  }

  // Filtered scanlines: filter type 2 ("Up"), each byte minus the byte above (0 above row 0).
  std::string raw(std::size_t(image.height) * (rowBytes + 1), '\0');
  for (int y = 0; y < image.height; ++y) {
    char* out = raw.data() + std::size_t(y) * (rowBytes + 1);
    const std::uint8_t* row = image.pixels.data() + std::size_t(y) * rowBytes;
    out[0] = 2;
    if (y == 0) {
      std::copy(row, row + rowBytes, out + 1);
    } else {
      const std::uint8_t* above = row - rowBytes;
      for (std::size_t i = 0; i < rowBytes; ++i) out[1 + i] = char(std::uint8_t(row[i] - above[i]));
    }
  }
  uLongf compressedSize = compressBound(static_cast<uLong>(raw.size()));
  std::string compressed(compressedSize, '\0');
  const int status =
      compress2(reinterpret_cast<Bytef*>(compressed.data()), &compressedSize,
                reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size()), 6);
  if (status != Z_OK) {
    throw std::runtime_error(std::string("zlib cannot compress the image: ") + zError(status));
  }
  compressed.resize(compressedSize);

  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string header;
  appendBigEndian32(header, static_cast<std::uint32_t>(image.width));
  appendBigEndian32(header, static_cast<std::uint32_t>(image.height));
  header += char(8);  // bit depth
  header += char(2);  // colour type: RGB
  header += char(0);  // compression: deflate
  header += char(0);  // filter method: adaptive (per-row filter bytes)
  header += char(0);  // no interlace
  appendChunk(png, "IHDR", header.data(), header.size());
  appendText(png, "Software", std::string("voxremesh ") + VOXREMESH_VERSION);
  appendText(png, "Comment", describe(image));
  for (std::size_t at = 0; at < compressed.size(); at += kIdatChunkBytes) {
    appendChunk(png, "IDAT", compressed.data() + at,
                std::min(kIdatChunkBytes, compressed.size() - at));
  }
  appendChunk(png, "IEND", "", 0);
  return png;
}

void writePng(const SliceImage& image, const std::filesystem::path& path) {
  io::writeFileAtomically(path, encodePng(image));
}

}  // namespace voxremesh
