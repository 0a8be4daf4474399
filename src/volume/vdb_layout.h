// A check of a .vdb file's layout before OpenVDB reads it: OpenVDB allocates every string and
// metadata value at the length the file states, so a damaged length asks for gigabytes. Internal
// to src/volume.
#pragma once

#include <filesystem>

namespace voxremesh::volume {

/// Walks the header, the file metadata, the grid descriptors and each grid's metadata and
/// transform type of a .vdb file (format versions 222 to 224, with grid offsets, as voxremesh and
/// OpenVDB 10 write them), checking every stated length and position against the bytes the file
/// holds. Files of other versions or without grid offsets are left to OpenVDB.
/// Throws InputError naming the file and the byte offset of the first length or position that
/// points past the end of the file (or of its grid).
void checkVdbLayout(const std::filesystem::path& path);

}  // namespace voxremesh::volume
