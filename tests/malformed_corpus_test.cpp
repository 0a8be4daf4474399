// The malformed-input corpus (tests/data/malformed) and the accepted edge cases
// (tests/data/accepted): the CLI is run on every row of the table in each folder's README.md.
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "json/json.h"
#include "support/test_support.h"

namespace {

namespace fs = std::filesystem;
using voxremesh::test::quoted;
using voxremesh::test::readText;
using voxremesh::test::scratchDir;

const fs::path kData = fs::path(VOXREMESH_SOURCE_DIR) / "tests" / "data";

/// The cells of the rows of the Markdown table in `readme` (the lines starting with '|' after
/// the `|---|` line), trimmed, backticks removed. Fails the test for a row with another number
/// of cells than `columns`.
std::vector<std::vector<std::string>> tableRows(const fs::path& readme, std::size_t columns) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(readText(readme));
  std::string line;
  bool inTable = false;
  while (std::getline(lines, line)) {
    if (line.rfind("|---", 0) == 0) {
      inTable = true;
      continue;
    }
    if (!inTable || line.empty() || line[0] != '|') continue;
    std::vector<std::string> cells;
    std::istringstream split(line.substr(1));
    std::string cell;
    while (std::getline(split, cell, '|')) {
      std::string text;
      for (char c : cell)
        if (c != '`') text += c;
      const std::size_t first = text.find_first_not_of(' ');
      const std::size_t last = text.find_last_not_of(' ');
      cells.push_back(first == std::string::npos ? "" : text.substr(first, last - first + 1));
    }
    EXPECT_EQ(cells.size(), columns) << readme << ": " << line;
    if (cells.size() == columns) rows.push_back(cells);
  }
  return rows;
}

/// The names of the files in `dir`.
std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    names.insert(entry.path().filename().string());
  return names;
}

/// A fresh copy of the files of `from` (the CLI runs there, so that outputs land in it).
fs::path copyOf(const fs::path& from, const std::string& name) {
  const fs::path dir = scratchDir(name);
  for (const auto& entry : fs::directory_iterator(from))
    fs::copy_file(entry.path(), dir / entry.path().filename());
  return dir;
}

struct Outcome {
  int exitCode = -1;
  std::string out;
  std::string err;
};

/// Runs `voxremesh ARGS` with `dir` as working folder, within 30 s and 2 GB of address space
/// (a reader that hangs or allocates what the file cannot justify fails the row).
Outcome runIn(const fs::path& dir, const std::string& args) {
  const fs::path logs = scratchDir("malformed-corpus-logs");
  const std::string command = "cd " + quoted(dir) + " && timeout 30 " +
                              voxremesh::test::addressSpaceLimit(2000000000) + VOXREMESH_CLI + " " +
                              args + " >" + quoted(logs / "out") + " 2>" + quoted(logs / "err") +
                              "; exit $?";
  const int code = voxremesh::test::runShell(command).exitCode;
  return {code, readText(logs / "out"), readText(logs / "err")};
}

/// `command` with every "{}" replaced by `file`.
std::string substitute(std::string command, const std::string& file) {
  for (std::size_t at = command.find("{}"); at != std::string::npos; at = command.find("{}", at))
    command.replace(at, 2, file);
  return command;
}

/// The texts an error message must contain for the `at` column of the malformed table (see
/// tests/data/malformed/README.md).
std::vector<std::string> placeTexts(const std::string& file, const std::string& at) {
  if (at == "-") return {};
  if (at == ":") return {file + ": "};
  if (at.size() > 1 && at[0] == ':') return {file + at + ":"};
  if (at.size() > 1 && at[0] == '@') return {file + ": ", "byte offset " + at.substr(1)};
  return {at + ":"};
}

TEST(MalformedCorpus, EveryFileIsRefusedNamingItsPlaceAndLeavesNothing) {
  const fs::path source = kData / "malformed";
  const auto rows = tableRows(source / "README.md", 5);
  ASSERT_GE(rows.size(), 60u);
  const fs::path dir = copyOf(source, "malformed-corpus");
  const std::set<std::string> before = listing(dir);

  std::set<std::string> listed;
  for (const auto& row : rows) {
    const std::string& file = row[0];
    const std::string args = substitute(row[1], file);
    const int expectedExit = std::stoi(row[2]);
    SCOPED_TRACE("voxremesh " + args);
    listed.insert(file);
    ASSERT_TRUE(fs::is_regular_file(source / file)) << "the table names a missing file";

    const Outcome run = runIn(dir, args);
    EXPECT_EQ(run.exitCode, expectedExit) << run.err;
    EXPECT_EQ(run.err.rfind(expectedExit == 1 ? "voxremesh: error: " : "voxremesh: ", 0), 0u)
        << run.err;
    for (const std::string& text : placeTexts(file, row[3]))
      EXPECT_NE(run.err.find(text), std::string::npos) << "no '" << text << "' in: " << run.err;
    EXPECT_NE(run.err.find(row[4]), std::string::npos) << "no '" << row[4] << "' in: " << run.err;

    for (const std::string& name : listing(dir))
      if (!before.count(name)) {
        ADD_FAILURE() << "left behind: " << name;
        fs::remove_all(dir / name);
      }
  }
  // Every file of the corpus has a row.
  for (const std::string& name : listing(source)) {
    if (name != "README.md") {
      EXPECT_TRUE(listed.count(name)) << name << " is not in the table";
    }
  }
}

TEST(MalformedCorpus, AcceptedEdgeCasesGiveTheirDocumentedCounts) {
  const fs::path source = kData / "accepted";
  const auto rows = tableRows(source / "README.md", 7);
  ASSERT_FALSE(rows.empty());
  const fs::path dir = copyOf(source, "accepted-corpus");

  std::set<std::string> listed;
  for (const auto& row : rows) {
    const std::string& file = row[0];
    SCOPED_TRACE("voxremesh info " + file + " --json");
    listed.insert(file);
    const Outcome run = runIn(dir, "info " + file + " --json");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const voxremesh::json::Json report = voxremesh::json::parseJson(run.out);
    EXPECT_EQ(report["model"]["nodes"].number, std::stod(row[1]));
    EXPECT_EQ(report["model"]["shells"].number, std::stod(row[2]));
    EXPECT_EQ(report["model"]["parts"].number, std::stod(row[3]));
    EXPECT_EQ(report["total"]["quads"].number, std::stod(row[4]));
    EXPECT_EQ(report["total"]["trias"].number, std::stod(row[5]));
  }
  for (const std::string& name : listing(source)) {
    if (name != "README.md" && fs::path(name).extension() != ".inc") {
      EXPECT_TRUE(listed.count(name)) << name << " is not in the table";
    }
  }
}

}  // namespace
