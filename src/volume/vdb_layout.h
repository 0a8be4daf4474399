// A check of a .vdb file's layout before OpenVDB reads it: OpenVDB allocates every string and
// metadata value at the length the file states, so a damaged length asks for gigabytes. Internal
// to src/volume.
#pragma once

#include <filesystem>

namespace voxremesh::volume {

/// Walks the header, the file metadata, the grid descriptors and each grid's metadata and
/// transform type of a .vdb file, checking every stated length and position against the bytes
/// the file holds. A file without the .vdb magic number is left to OpenVDB to refuse.
/// Throws InputError naming the file and the byte offset of the first length or position that
/// points past the end of the file (or of its grid), of a format version other than 222 to 224
/// (those voxremesh and OpenVDB 10 write), or of a file without grid offsets (a stream).
void checkVdbLayout(const std::filesystem::path& path);

}  // namespace voxremesh::volume
