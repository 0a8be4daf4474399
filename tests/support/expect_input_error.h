// The assertion every reader test uses for bad input: an InputError naming file and line.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>

namespace voxremesh::test {

/// How expectInputError compares the file an error names.
enum class FileMatch {
  Path,      ///< the whole path as given
  FileName,  ///< the file name only (the path may be spelled differently, e.g. via includes)
};

/// Runs `action` and records a test failure unless it throws voxremesh::InputError naming `file`
/// and `line` with `fragment` in its message.
void expectInputError(const std::function<void()>& action, const std::filesystem::path& file,
                      std::size_t line, const std::string& fragment,
                      FileMatch match = FileMatch::Path);

}  // namespace voxremesh::test
