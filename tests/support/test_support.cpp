#include "support/test_support.h"

#include <unistd.h>

#include <sys/wait.h>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace voxremesh::test {

std::filesystem::path sharedDataDir() {
  return std::filesystem::path(VOXREMESH_SOURCE_DIR).parent_path() / "shared" / "data";
}

std::filesystem::path sharedDeck(const std::string& name) {
  return sharedDataDir() / name;
}

std::filesystem::path samplePart() {
  return std::filesystem::path(VOXREMESH_SOURCE_DIR) / "tools" / "samples" / "hat_rail.k";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

namespace {

struct ScratchRoot {
  std::filesystem::path path;
  ScratchRoot() {
    path =
        std::filesystem::temp_directory_path() / ("voxremesh-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
  }
  ~ScratchRoot() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

}  // namespace

std::filesystem::path scratchDir(const std::string& name) {
  static ScratchRoot root;
  const std::filesystem::path dir = root.path / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void writeText(const std::filesystem::path& path, const std::string& text) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream content;
  content << in.rdbuf();
  return content.str();
}

std::string addressSpaceLimit(std::size_t bytes) {
#if defined(__SANITIZE_ADDRESS__)
  constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  constexpr bool kAddressSanitizer = true;
#else
  constexpr bool kAddressSanitizer = false;
#endif
#else
  constexpr bool kAddressSanitizer = false;
#endif
  return kAddressSanitizer ? std::string() : "prlimit --as=" + std::to_string(bytes) + " -- ";
}

CliResult runShell(const std::string& command) {
  CliResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

CliResult runCli(const std::string& args) {
  return runShell(std::string(VOXREMESH_CLI) + " " + args);
}

CliRun runCliSplit(const std::string& args) {
  static int runs = 0;
  const std::filesystem::path dir = scratchDir("cli-run-" + std::to_string(++runs));
  const std::filesystem::path out = dir / "stdout", err = dir / "stderr";
  // runCli appends "2>&1"; after "; exit $?" it applies to the exit only.
  const CliResult result =
      runCli(args + " >'" + out.string() + "' 2>'" + err.string() + "'; exit $?");
  return {result.exitCode, readText(out), readText(err)};
}

std::string quoted(const std::filesystem::path& path) {
  return "'" + path.string() + "'";
}

void addNode(FeModel& model, Id id, double x, double y, double z) {
  model.nodes.push_back(Node{id, {x, y, z}});
}

void addShell(FeModel& model, Id id, Id part, const std::vector<Id>& nodes) {
  Shell shell;
  shell.id = id;
  shell.part = part;
  shell.nodeCount = static_cast<std::uint8_t>(nodes.size());
  for (std::size_t k = 0; k < nodes.size() && k < 4; ++k) shell.nodes[k] = nodes[k];
  model.shells.push_back(shell);
}

FeModel coneModel(int around, int rings, double halfAngleDeg) {
  constexpr double kPi = 3.14159265358979323846;
  FeModel model;
  model.partOrAdd(1, "cone");
  const double a = halfAngleDeg * kPi / 180.0;
  addNode(model, 1, 0.0, 0.0, 0.0);
  const auto ring = [&](int r, int k) { return Id(2 + r * around + (k % around)); };
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < around; ++k) {
      const double turn = 2.0 * kPi * k / around, slant = 10.0 * (r + 1) / rings;
      addNode(model, ring(r, k), slant * std::sin(a) * std::cos(turn),
              slant * std::sin(a) * std::sin(turn), slant * std::cos(a));
    }
  Id shell = 1;
  for (int k = 0; k < around; ++k) addShell(model, shell++, 1, {1, ring(0, k), ring(0, k + 1)});
  for (int r = 0; r + 1 < rings; ++r)
    for (int k = 0; k < around; ++k)
      addShell(model, shell++, 1, {ring(r, k), ring(r + 1, k), ring(r + 1, k + 1), ring(r, k + 1)});
  return model;
}

}  // namespace voxremesh::test
