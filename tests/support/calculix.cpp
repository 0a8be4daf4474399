#include "support/calculix.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "support/test_support.h"
#include "voxremesh/io.h"

namespace voxremesh::test {

namespace {

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string_view trimmed(std::string_view text) {
  const char* const blanks = " \t\r";
  const std::size_t begin = text.find_first_not_of(blanks);
  if (begin == std::string_view::npos) return {};
  return text.substr(begin, text.find_last_not_of(blanks) - begin + 1);
}

/// The lines of a text, without their line ends.
std::vector<std::string_view> linesOf(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

/// A keyword line ("*ELEMENT, TYPE=S4R, ELSET=...") split at the commas outside double quotes:
/// the keyword, then the parameters, each trimmed.
std::vector<std::string_view> keywordFields(std::string_view line) {
  std::vector<std::string_view> fields;
  bool quoted = false;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i < line.size() && line[i] == '"') quoted = !quoted;
    if (i == line.size() || (line[i] == ',' && !quoted)) {
      fields.push_back(trimmed(line.substr(start, i - start)));
      start = i + 1;
    }
  }
  return fields;
}

bool isKeywordLine(std::string_view line) {
  line = trimmed(line);
  return line.size() > 1 && line[0] == '*' && line[1] != '*';
}

/// The value of NAME=VALUE among a keyword line's parameters (name case-insensitive, blanks
/// around '=' allowed); false when absent.
bool parameter(const std::vector<std::string_view>& fields, const std::string& name,
               std::string_view& value) {
  for (std::size_t i = 1; i < fields.size(); ++i) {
    const std::size_t equals = fields[i].find('=');
    if (equals == std::string_view::npos) continue;
    if (upper(trimmed(fields[i].substr(0, equals))) != name) continue;
    value = trimmed(fields[i].substr(equals + 1));
    return true;
  }
  return false;
}

/// The solid-shell counterpart ccx is to use for a shell type, or empty when `type` (upper case)
/// is not one of the shell types this support handles.
std::string_view analysisType(const std::string& type) {
  if (type == "S3" || type == "S3R") return "S3";
  if (type == "S4" || type == "S4R") return "S4";
  return {};
}

/// Appends a number in a form ccx reads back exactly enough.
void appendNumber(std::string& out, double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", value);
  out += buffer;
}

/// The lines of `text` that contain `needle` (case-insensitive), each with the two lines after it
/// (ccx continues its messages there), at most `limit` of them.
std::string linesWith(const std::string& text, const std::string& needle, int limit = 5) {
  std::string found;
  int count = 0;
  const std::vector<std::string_view> lines = linesOf(text);
  for (std::size_t i = 0; i < lines.size() && count < limit; ++i) {
    if (upper(lines[i]).find(needle) == std::string::npos) continue;
    ++count;
    for (std::size_t k = i; k < std::min(i + 3, lines.size()); ++k) {
      found += "    ";
      found += trimmed(lines[k]);
      found += '\n';
    }
  }
  return found;
}

}  // namespace

bool ccxAvailable() {
  return runShell("command -v ccx >/dev/null").exitCode == 0;
}

std::vector<std::string> shellElsets(const std::string& inp) {
  std::vector<std::string> elsets;
  for (std::string_view line : linesOf(inp)) {
    if (!isKeywordLine(line)) continue;
    const std::vector<std::string_view> fields = keywordFields(trimmed(line));
    if (upper(fields[0]) != "*ELEMENT") continue;
    std::string_view type, elset;
    if (!parameter(fields, "TYPE", type) || analysisType(upper(type)).empty()) continue;
    if (!parameter(fields, "ELSET", elset))
      throw std::runtime_error("shell block without ELSET: " + std::string(line));
    if (std::find(elsets.begin(), elsets.end(), elset) == elsets.end()) elsets.emplace_back(elset);
  }
  return elsets;
}

std::string frequencyDeck(const std::string& inp, const FrequencySettings& settings) {
  const std::vector<std::string> elsets = shellElsets(inp);
  if (elsets.empty()) throw std::runtime_error("the deck has no *ELEMENT block of shells");
  std::string deck;
  deck.reserve(inp.size() + 1024);
  for (std::string_view line : linesOf(inp)) {
    if (isKeywordLine(line)) {
      const std::vector<std::string_view> fields = keywordFields(trimmed(line));
      const std::string keyword = upper(fields[0]);
      if (keyword == "*STEP")
        throw std::runtime_error("the deck has a step already: " + std::string(line));
      std::string_view type;
      if (keyword == "*ELEMENT" && parameter(fields, "TYPE", type) &&
          !analysisType(upper(type)).empty()) {
        // The same line with the type replaced, the other parameters as written.
        deck += "*ELEMENT, TYPE=";
        deck += analysisType(upper(type));
        for (std::size_t i = 1; i < fields.size(); ++i) {
          if (upper(trimmed(fields[i].substr(0, fields[i].find('=')))) == "TYPE") continue;
          deck += ", ";
          deck += fields[i];
        }
        deck += '\n';
        continue;
      }
    }
    deck += line;
    deck += '\n';
  }
  deck += "** frequency analysis added by the test: steel (mm, tonne, s), one thickness\n";
  deck += "*MATERIAL, NAME=TEST_STEEL\n*ELASTIC\n";
  appendNumber(deck, settings.youngsModulus);
  deck += ", ";
  appendNumber(deck, settings.poissonsRatio);
  deck += "\n*DENSITY\n";
  appendNumber(deck, settings.density);
  deck += '\n';
  for (const std::string& elset : elsets) {
    deck += "*SHELL SECTION, ELSET=" + elset + ", MATERIAL=TEST_STEEL\n";
    appendNumber(deck, settings.thickness);
    deck += '\n';
  }
  deck += "*STEP\n*FREQUENCY\n" + std::to_string(settings.modes) + "\n*END STEP\n";
  return deck;
}

std::vector<Eigenmode> parseEigenmodes(const std::string& dat) {
  std::vector<Eigenmode> modes;
  const std::size_t table = dat.find("E I G E N V A L U E   O U T P U T");
  if (table == std::string::npos) return modes;
  // Header lines (words), then one row per mode: number, eigenvalue, rad/time, cycles/time and
  // (ccx 2.x) the imaginary part; the table ends at the first other line after a row.
  bool inRows = false;
  for (std::string_view line : linesOf(std::string_view(dat).substr(table))) {
    std::istringstream fields{std::string(line)};
    Eigenmode mode;
    if (fields >> mode.mode >> mode.eigenvalue >> mode.radians >> mode.hertz) {
      modes.push_back(mode);
      inRows = true;
    } else if (inRows) {
      break;
    }
  }
  return modes;
}

CcxRun runCcx(const std::filesystem::path& dir, const std::string& job, int timeoutSeconds,
              int threads) {
  CcxRun run;
  const auto start = std::chrono::steady_clock::now();
  const CliResult result =
      runShell("cd " + quoted(dir) + " && OMP_NUM_THREADS=" + std::to_string(threads) +
               " timeout " + std::to_string(timeoutSeconds) + " ccx -i " +
               quoted(std::filesystem::path(job)) + " </dev/null");
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.exitCode = result.exitCode;
  run.output = result.output;
  const std::filesystem::path dat = dir / (job + ".dat");
  if (std::filesystem::exists(dat)) run.dat = readText(dat);
  run.modes = parseEigenmodes(run.dat);
  return run;
}

std::string ccxFailure(const CcxRun& run, int modes) {
  std::string failure;
  if (run.exitCode == 124)
    failure += "ccx was ended by the time limit\n";
  else if (run.exitCode != 0)
    failure += "ccx exited with status " + std::to_string(run.exitCode) + "\n";
  for (const char* needle : {"*ERROR", "NONPOSITIVE JACOBIAN"}) {
    const std::string output = linesWith(run.output, needle);
    const std::string dat = linesWith(run.dat, needle);
    if (!output.empty()) failure += std::string("ccx output has ") + needle + ":\n" + output;
    if (!dat.empty()) failure += std::string("the .dat file has ") + needle + ":\n" + dat;
  }
  if (run.modes.size() < static_cast<std::size_t>(modes))
    failure += std::to_string(run.modes.size()) + " eigenmode(s) in the .dat file, " +
               std::to_string(modes) + " asked\n";
  return failure;
}

std::size_t countNearZeroModes(const std::vector<Eigenmode>& modes, double factor) {
  double largest = 0.0;
  for (const Eigenmode& mode : modes) largest = std::max(largest, mode.hertz);
  return static_cast<std::size_t>(
      std::count_if(modes.begin(), modes.end(),
                    [&](const Eigenmode& mode) { return mode.hertz < factor * largest; }));
}

void writeSubdividedAbaqus(const std::filesystem::path& deck, const std::filesystem::path& out) {
  FeModel model = readDeck(deck);
  std::unordered_map<Id, std::size_t> index = model.nodeIndex();
  Id nextNode = 0, nextShell = 0;
  for (const Node& node : model.nodes) nextNode = std::max(nextNode, node.id);
  for (const Shell& shell : model.shells) nextShell = std::max(nextShell, shell.id);
  std::map<std::pair<Id, Id>, Id> midpoints;
  const auto addNode = [&](const std::array<double, 3>& xyz) {
    model.nodes.push_back(Node{++nextNode, xyz});
    index[nextNode] = model.nodes.size() - 1;
    return nextNode;
  };
  const auto at = [&](Id node) { return model.nodes[index.at(node)].xyz; };
  const auto midpoint = [&](Id a, Id b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    const auto found = midpoints.find(key);
    if (found != midpoints.end()) return found->second;
    const std::array<double, 3> p = at(a), q = at(b);
    const Id id = addNode({(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2});
    midpoints.emplace(key, id);
    return id;
  };
  std::vector<Shell> shells;
  for (const Shell& shell : model.shells) {
    const int n = shell.nodeCount;
    std::array<Id, 4> m{};
    for (int c = 0; c < n; ++c)
      m[std::size_t(c)] =
          midpoint(shell.nodes[std::size_t(c)], shell.nodes[std::size_t((c + 1) % n)]);
    const auto piece = [&](std::array<Id, 4> nodes, int count) {
      Shell part = shell;
      part.id = ++nextShell;
      part.nodes = nodes;
      part.nodeCount = static_cast<std::uint8_t>(count);
      shells.push_back(part);
    };
    if (n == 4) {
      std::array<double, 3> centre{};
      for (int c = 0; c < 4; ++c)
        for (int a = 0; a < 3; ++a)
          centre[std::size_t(a)] += at(shell.nodes[std::size_t(c)])[std::size_t(a)] / 4;
      const Id middle = addNode(centre);
      for (int c = 0; c < 4; ++c)
        piece({shell.nodes[std::size_t(c)], m[std::size_t(c)], middle, m[std::size_t((c + 3) % 4)]},
              4);
    } else {
      piece({shell.nodes[0], m[0], m[2], 0}, 3);
      piece({m[0], shell.nodes[1], m[1], 0}, 3);
      piece({m[2], m[1], shell.nodes[2], 0}, 3);
      piece({m[0], m[1], m[2], 0}, 3);
    }
  }
  model.shells = std::move(shells);
  writeDeck(model, out);
}

}  // namespace voxremesh::test
