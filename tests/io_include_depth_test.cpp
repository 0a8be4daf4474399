// Include chains: every deck reader follows a chain of io::kMaxIncludeDepth files and refuses a
// longer one at the include that would exceed it, naming that file and line.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

#include "io/formats.h"
#include "support/expect_input_error.h"
#include "support/test_support.h"
#include "voxremesh/io.h"

namespace voxremesh {
namespace {

namespace fs = std::filesystem;

/// One deck format: its extension, its include lines for a file name (the file name is on line
/// `nameLine` of them), and a mesh of one triangle in it.
struct IncludeFormat {
  std::string extension;
  std::function<std::string(const std::string&)> includeLines;
  std::size_t nameLine = 1;
  std::string triangle;
};

void PrintTo(const IncludeFormat& format, std::ostream* out) {
  *out << format.extension;
}

const IncludeFormat kLsDyna{
    ".k", [](const std::string& name) { return "*INCLUDE\n" + name + "\n"; }, 2,
    "*NODE\n1,0.,0.,0.\n2,1.,0.,0.\n3,0.,1.,0.\n*ELEMENT_SHELL\n1,1,1,2,3,3\n*END\n"};
const IncludeFormat kNastran{
    ".bdf", [](const std::string& name) { return "INCLUDE '" + name + "'\n"; }, 1,
    "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nCTRIA3,1,1,1,2,3\n"};
const IncludeFormat kAbaqus{
    ".inp", [](const std::string& name) { return "*INCLUDE, INPUT=" + name + "\n"; }, 1,
    "*NODE\n1,0.,0.,0.\n2,1.,0.,0.\n3,0.,1.,0.\n*ELEMENT, TYPE=S3, ELSET=P1\n1,1,2,3\n"};

/// Writes files level0 .. level(depth-1) into `dir`, each including the next;
/// the last holds the triangle. Returns the path of level0.
fs::path writeChain(const fs::path& dir, const IncludeFormat& format, std::size_t depth) {
  const auto name = [&](std::size_t level) {
    return "level" + std::to_string(level) + format.extension;
  };
  for (std::size_t level = 0; level + 1 < depth; ++level)
    test::writeText(dir / name(level), format.includeLines(name(level + 1)));
  test::writeText(dir / name(depth - 1), format.triangle);
  return dir / name(0);
}

class IncludeDepth : public ::testing::TestWithParam<IncludeFormat> {};

TEST_P(IncludeDepth, AChainOfTheLimitIsReadAndALongerOneIsRefusedAtTheIncludeTooMany) {
  const IncludeFormat& format = GetParam();
  const fs::path dir = test::scratchDir("include_depth" + format.extension.substr(1));
  const fs::path full = writeChain(dir / "full", format, io::kMaxIncludeDepth);
  EXPECT_EQ(readDeck(full).shells.size(), 1u);

  const fs::path deep = writeChain(dir / "deep", format, io::kMaxIncludeDepth + 1);
  const std::string last = "level" + std::to_string(io::kMaxIncludeDepth - 1) + format.extension;
  test::expectInputError([&] { readDeck(deep); }, dir / "deep" / last, format.nameLine,
                         "nested deeper than 32", test::FileMatch::FileName);
}

INSTANTIATE_TEST_SUITE_P(DeckFormats, IncludeDepth, ::testing::Values(kLsDyna, kNastran, kAbaqus),
                         [](const auto& parameter) { return parameter.param.extension.substr(1); });

}  // namespace
}  // namespace voxremesh
