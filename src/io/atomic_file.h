// Writing a file so that it either appears complete or not at all.
#pragma once

#include <filesystem>
#include <string_view>

namespace voxremesh::io {

/// Writes `content` to a temporary file beside `path`, then renames it over `path`.
/// On failure the temporary file is removed and `path` is left as it was.
/// Throws std::runtime_error naming the path when the folder is not writable or the disk is full.
void writeFileAtomically(const std::filesystem::path& path, std::string_view content);

}  // namespace voxremesh::io
