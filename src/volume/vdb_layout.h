// A check of a .vdb file's layout before OpenVDB reads it: OpenVDB allocates every string,
// metadata value, node and compressed block at the size the file states, so a damaged size asks
// for gigabytes (or terabytes). Internal to src/volume.
#pragma once

#include <filesystem>

namespace voxremesh::volume {

/// Walks a .vdb file as OpenVDB 10's io::File reads it: the header, the file metadata, the grid
/// descriptors, and per grid its compression flags, metadata, transform and (for the tree types
/// vdb_tree_layout.h names) its tree, checking every stated length, count, position and
/// compressed block size against the bytes the file (or the grid) holds, and voxremesh's
/// voxremesh_sheet_count against the grids (three per sheet). A file without the .vdb magic
/// number is left to OpenVDB to refuse, and so is what OpenVDB refuses by itself (an unregistered
/// grid or map type). Throws InputError naming the file and the byte offset of the first length,
/// count, position or field that points or runs past the end of the file (or of its grid: OpenVDB
/// would read on into the next one, or at the file's end take a string length it never read), of
/// a format version other than 222 to 224 (those voxremesh and OpenVDB 10 write), or of a file
/// without grid offsets (a stream).
void checkVdbLayout(const std::filesystem::path& path);

}  // namespace voxremesh::volume
