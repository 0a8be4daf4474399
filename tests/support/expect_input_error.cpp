#include "support/expect_input_error.h"

#include <gtest/gtest.h>

#include "voxremesh/errors.h"

namespace voxremesh::test {

void expectInputError(const std::function<void()>& action, const std::filesystem::path& file,
                      std::size_t line, const std::string& fragment, FileMatch match) {
  try {
    action();
    ADD_FAILURE() << "no InputError for " << file << " (expected: " << fragment << ")";
  } catch (const InputError& error) {
    if (match == FileMatch::FileName) {
      EXPECT_EQ(std::filesystem::path(error.file()).filename(), file.filename()) << error.what();
    } else {
      EXPECT_EQ(error.file(), file.string()) << error.what();
    }
    EXPECT_EQ(error.line(), line) << error.what();
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
  }
}

}  // namespace voxremesh::test
