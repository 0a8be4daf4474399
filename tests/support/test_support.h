// Helpers shared by the test suites: where the real decks are, scratch folders, running the CLI.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "voxremesh/fe_model.h"

namespace voxremesh::test {

/// ../shared/data relative to the project root (may not exist in a user's clone).
std::filesystem::path sharedDataDir();

/// The path of a deck in ../shared/data; the calling test is skipped (GTEST_SKIP) by the macro
/// below when it is missing.
std::filesystem::path sharedDeck(const std::string& name);

/// The sample part shipped with the sources (tools/samples/hat_rail.k).
std::filesystem::path samplePart();

/// `text` contains `part`.
bool contains(const std::string& text, const std::string& part);

/// A fresh, empty folder for one test, removed when the process exits.
std::filesystem::path scratchDir(const std::string& name);

/// Writes text to a file (creating folders); throws std::runtime_error on failure.
void writeText(const std::filesystem::path& path, const std::string& text);

/// Reads a whole file; throws std::runtime_error on failure.
std::string readText(const std::filesystem::path& path);

/// Result of running the voxremesh CLI as a subprocess.
struct CliResult {
  int exitCode = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs a /bin/sh command line and captures its output (stdout and stderr together) and exit
/// code. Throws std::runtime_error when the shell cannot be started.
CliResult runShell(const std::string& command);

/// Runs `voxremesh ARGS` (arguments are passed to /bin/sh as written) and captures its output.
CliResult runCli(const std::string& args);

/// The prefix of a shell command that runs it under an address-space limit of `bytes`
/// ("prlimit --as=BYTES -- "), or nothing in a build with AddressSanitizer, whose shadow memory
/// takes terabytes of address space (the limit would stop every program before it starts): the
/// test then checks the outcome without the limit.
std::string addressSpaceLimit(std::size_t bytes);

/// Result of a CLI run with standard output and standard error kept apart.
struct CliRun {
  int exitCode = -1;
  std::string out;
  std::string err;
};

/// Runs `voxremesh ARGS` like runCli, keeping stdout and stderr apart.
CliRun runCliSplit(const std::string& args);

/// A path in single quotes, for the shell command lines of runCli.
std::string quoted(const std::filesystem::path& path);

/// Appends a node to a model under construction.
void addNode(FeModel& model, Id id, double x, double y, double z = 0.0);

/// Appends a shell (3 or 4 node IDs) of `part` to a model under construction.
void addShell(FeModel& model, Id id, Id part, const std::vector<Id>& nodes);

/// Part 1: a cone 10 long on its slant, tip (node 1) at the origin, axis along +z, with the given
/// half angle (90: a flat disk), in `around` triangles at the tip and rings - 1 rows of quads;
/// node 2 + r around + k is point k of ring r (0 next to the tip).
FeModel coneModel(int around, int rings, double halfAngleDeg);

}  // namespace voxremesh::test

/// Skips the current test with a clear message when ../shared/data/NAME is missing.
#define VOXREMESH_REQUIRE_SHARED_DECK(var, name)                         \
  const std::filesystem::path var = ::voxremesh::test::sharedDeck(name); \
  if (!std::filesystem::exists(var))                                     \
  GTEST_SKIP() << "real deck " << var                                    \
               << " not found (../shared/data is not beside "            \
                  "the project); skipping"
