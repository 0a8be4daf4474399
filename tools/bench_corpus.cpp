// bench_corpus: the remesh of every real deck of the corpus, at the default size and at twice it.
//
// For each deck of --data (default ../shared/data relative to the working folder: run it from the
// source root; every file ending in .k .key .bdf .nas .dat .inp, sorted by name, sub-folders
// skipped) and each of two sizes (the default, i.e. the deck's median edge length, and twice that
// length), runs `voxremesh remesh DECK -o TMP/out.EXT [--size S] --report TMP/report.json --quiet`
// as a child process (the voxremesh found next to this program), so that its time, peak memory
// (the child's ru_maxrss from wait4) and a crash are its own. A run taking longer than --timeout
// seconds (default 300) is killed and reported as a timeout. Exit codes of the CLI: 0 every part
// accepted, 3 some parts kept (both write the deck and the report), 1 an error, anything else
// (or a signal) a crash.
//
// Prints one table row per run: deck, size, exit code, parts, parts remeshed / retried / kept,
// failing share, worst distance / target size, folded elements and 180-degree quad corners (these
// four over the remeshed and retried parts), nodes inside an edge of a part they share a seam
// with (input -> output, over the deck), seconds and peak MB; then a line of totals. Writes
// the same to --json (default bench_corpus.json) as an array of runs, each with the per-part list
// of the CLI's report, for comparisons between versions. The kernel carries a parent's peak memory
// over fork and exec into the child's, so this program keeps its own small (decks are read in
// forked helpers): its peak, printed with the totals, stays at the ~33 MB any program linking
// OpenVDB starts with, voxremesh included, and does not inflate the children's figures.
//
// usage: bench_corpus [--data DIR] [--json OUT.json] [--decks a.k,b.bdf] [--threads N]
//                     [--timeout S] [--timeout-note]
// --decks names files of DIR (or paths, when they hold a '/'); --threads is passed to the CLI;
// --timeout-note prints below the row of every run that did not end with exit code 0 or 3
// (error, crash, timeout) the last lines of its error output and keeps its temporary folder.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench_timing.h"
#include "json/json.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"

namespace fs = std::filesystem;
using voxremesh::bench::secondsSince;
using voxremesh::json::Json;

namespace {

const char* const kUsage =
    "usage: bench_corpus [--data DIR] [--json OUT.json] [--decks a.k,b.bdf] [--threads N]\n"
    "                    [--timeout S] [--timeout-note]\n";

/// The command line.
struct Options {
  fs::path data = "../shared/data";
  fs::path json = "bench_corpus.json";
  std::vector<std::string> decks;  ///< empty: every deck of `data`
  int threads = 0;                 ///< 0: the CLI's default (all cores)
  double timeout = 300.0;          ///< seconds before a run is killed
  bool timeoutNote = false;
};

/// How one child run ended, from its wait status.
struct ChildEnd {
  int rc = -1;     ///< exit code, -1 when it did not exit
  int signal = 0;  ///< the signal that ended it, 0 when none
  bool timedOut = false;
  double seconds = 0.0;  ///< wall time
  double peakMb = 0.0;   ///< the child's ru_maxrss in MB
};

/// One deck at one size: the child's end and the figures of its report.
struct Run {
  std::string deck;
  int factor = 1;     ///< 1: the default size, 2: twice it
  double size = 0.0;  ///< the size given to the CLI (NaN when the deck's size is unknown)
  ChildEnd end;
  std::string outcome;  ///< ok, kept, error, timeout, crash (signal N), exit N, skipped
  std::string note;     ///< the kept parts, the end of the child's error output, or why skipped
  fs::path folder;      ///< the run's temporary folder
  std::size_t parts = 0, remeshed = 0, retried = 0, kept = 0;
  std::size_t elements = 0, failing = 0, folded = 0, degenerate = 0;  ///< remeshed + retried
  /// Nodes inside an edge of a part they share a seam with, in the input and the output.
  std::size_t hangingIn = 0, hangingOut = 0;
  double worstDistance = 0.0;  ///< max distance / target size over remeshed and retried parts
  std::vector<Json> partList;  ///< the "parts" array of the CLI's report
};

/// Splits "a,b,c" at the commas (empty items dropped).
std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

/// Parses the command line; returns false (after printing the usage) when it is malformed.
bool parseOptions(int argc, char** argv, Options& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--timeout-note") {
      options.timeoutNote = true;
    } else if (arg == "--data" && hasValue) {
      options.data = argv[++i];
    } else if (arg == "--json" && hasValue) {
      options.json = argv[++i];
    } else if (arg == "--decks" && hasValue) {
      options.decks = splitCommas(argv[++i]);
    } else if (arg == "--threads" && hasValue) {
      options.threads = std::atoi(argv[++i]);
    } else if (arg == "--timeout" && hasValue) {
      options.timeout = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr, "%s", kUsage);
      return false;
    }
  }
  if (options.threads < 0 || !(options.timeout > 0)) {
    std::fprintf(stderr, "%s", kUsage);
    return false;
  }
  return true;
}

/// `path`'s extension in lower case, with the dot.
std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

/// Whether `path` names a deck format the corpus holds.
bool isDeck(const fs::path& path) {
  static const char* const kExtensions[] = {".k", ".key", ".bdf", ".nas", ".dat", ".inp"};
  const std::string ext = lowerExtension(path);
  return std::any_of(std::begin(kExtensions), std::end(kExtensions),
                     [&](const char* known) { return ext == known; });
}

/// The decks to run: those of --decks, or every deck file directly in `data`, sorted by name.
std::vector<fs::path> listDecks(const Options& options) {
  std::vector<fs::path> decks;
  if (!options.decks.empty()) {
    for (const std::string& name : options.decks)
      decks.push_back(name.find('/') == std::string::npos ? options.data / name : fs::path(name));
    return decks;
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(options.data))
    if (entry.is_regular_file() && isDeck(entry.path())) decks.push_back(entry.path());
  std::sort(decks.begin(), decks.end(),
            [](const fs::path& a, const fs::path& b) { return a.filename() < b.filename(); });
  return decks;
}

/// The voxremesh CLI next to this program (both are built into the same bin folder).
fs::path findCli() {
  return fs::read_symlink("/proc/self/exe").parent_path() / "voxremesh";
}

/// The deck's default target size (its median edge length), read in a forked child so that this
/// process stays small: a forked child starts with its parent's peak memory. Returns NaN, with
/// the reason in `error`, when the deck cannot be read.
double deckSizeInChild(const fs::path& deck, std::string& error) {
  int channel[2];
  if (pipe(channel) != 0) {
    error = std::string("pipe: ") + std::strerror(errno);
    return std::nan("");
  }
  const pid_t pid = fork();
  if (pid == 0) {
    close(channel[0]);
    std::string answer;
    try {
      char text[64];
      std::snprintf(text, sizeof text, "%.17g",
                    voxremesh::deckTargetSize(voxremesh::readDeck(deck)));
      answer = text;
    } catch (const std::exception& e) {
      answer = std::string("error: ") + e.what();
    }
    ssize_t written = write(channel[1], answer.data(), answer.size());
    _exit(written == static_cast<ssize_t>(answer.size()) ? 0 : 1);
  }
  close(channel[1]);
  std::string answer;
  char buffer[512];
  for (ssize_t n; (n = read(channel[0], buffer, sizeof buffer)) > 0;) answer.append(buffer, n);
  close(channel[0]);
  int status = 0;
  if (pid > 0) waitpid(pid, &status, 0);
  if (pid < 0 || answer.empty() || answer.rfind("error: ", 0) == 0) {
    error = pid < 0          ? std::string("fork: ") + std::strerror(errno)
            : answer.empty() ? "reading the deck crashed"
                             : answer.substr(7);
    return std::nan("");
  }
  return std::strtod(answer.c_str(), nullptr);
}

/// The command line of one remesh run (argv[0] is the CLI's path).
std::vector<std::string> remeshCommand(const fs::path& cli, const fs::path& deck, double size,
                                       const fs::path& folder, int threads) {
  std::vector<std::string> args = {cli.string(), "remesh", deck.string(), "-o",
                                   (folder / ("out" + lowerExtension(deck))).string()};
  if (size > 0) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", size);
    args.insert(args.end(), {"--size", text});
  }
  args.insert(args.end(), {"--report", (folder / "report.json").string(), "--quiet"});
  if (threads > 0) args.insert(args.end(), {"--threads", std::to_string(threads)});
  return args;
}

/// Starts `args` as a child with its output in folder/stdout.txt and folder/stderr.txt; returns
/// its pid (-1 when fork fails). Between fork and exec only async-signal-safe calls are made.
pid_t startChild(const std::vector<std::string>& args, const fs::path& folder) {
  std::vector<char*> argv;
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  const std::string out = (folder / "stdout.txt").string(), err = (folder / "stderr.txt").string();
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid != 0) return pid;
  const int outFd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int errFd = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (outFd >= 0) dup2(outFd, STDOUT_FILENO);
  if (errFd >= 0) dup2(errFd, STDERR_FILENO);
  execv(argv[0], argv.data());
  _exit(127);
}

/// Waits for the child, killing it once `timeout` seconds have passed; its wall time and its
/// peak memory (wait4's ru_maxrss) come back with its exit code or signal.
ChildEnd waitChild(pid_t pid, double timeout) {
  ChildEnd end;
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, WNOHANG, &usage) == 0) {
    if (secondsSince(start) > timeout) {
      kill(pid, SIGKILL);
      wait4(pid, &status, 0, &usage);
      end.timedOut = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  end.seconds = secondsSince(start);
  end.peakMb = static_cast<double>(usage.ru_maxrss) / 1024.0;
  if (WIFEXITED(status)) end.rc = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) end.signal = WTERMSIG(status);
  return end;
}

/// The outcome's name: ok, kept, error, timeout, crash (signal N) or exit N.
std::string outcomeName(const ChildEnd& end) {
  if (end.timedOut) return "timeout";
  if (end.signal) return "crash (signal " + std::to_string(end.signal) + ")";
  switch (end.rc) {
    case 0:
      return "ok";
    case 3:
      return "kept";
    case 1:
      return "error";
    default:
      return "exit " + std::to_string(end.rc);
  }
}

/// The whole text of a file ("" when it cannot be read).
std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The last `count` non-empty lines of `text`, joined by " | ".
std::string lastLines(const std::string& text, std::size_t count) {
  std::vector<std::string> lines;
  std::stringstream stream(text);
  for (std::string line; std::getline(stream, line);)
    if (!line.empty()) lines.push_back(line);
  std::string joined;
  for (std::size_t i = lines.size() > count ? lines.size() - count : 0; i < lines.size(); ++i)
    joined += (joined.empty() ? "" : " | ") + lines[i];
  return joined;
}

/// `text` with the non-finite numbers printf writes (nan, -nan, inf, -inf) outside strings
/// replaced by null, so that the strict parser takes it.
std::string nonFiniteToNull(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      out += c;
      if (c == '\\' && i + 1 < text.size())
        out += text[++i];
      else if (c == '"')
        inString = false;
      continue;
    }
    if (c == '"') inString = true;
    const std::size_t word = i + (c == '-' ? 1 : 0);
    if (text.compare(word, 3, "nan") == 0 || text.compare(word, 3, "inf") == 0) {
      out += "null";
      i = word + 2;
      continue;
    }
    out += c;
  }
  return out;
}

/// A member's number (NaN when it is missing or not a number).
double number(const Json& object, const char* key) {
  const Json* value = object.find(key);
  return value && value->type == Json::Type::Number ? value->number : std::nan("");
}

/// A member's count (0 when it is missing or not a number).
std::size_t count(const Json& object, const char* key) {
  const double value = number(object, key);
  return std::isfinite(value) && value > 0 ? static_cast<std::size_t>(value) : 0;
}

/// A member's string ("" when it is missing or not a string).
std::string text(const Json& object, const char* key) {
  const Json* value = object.find(key);
  return value && value->type == Json::Type::String ? value->text : std::string();
}

/// Adds one part of the report to the run's figures: its status (a kept part's ID goes to the
/// note), and for a remeshed or retried part its elements, failing elements, distance / target
/// size, folds and 180-degree corners.
void addPart(const Json& part, Run& run) {
  ++run.parts;
  const std::string status = text(part, "status");
  if (status == "kept") {
    ++run.kept;
    char id[32];
    std::snprintf(id, sizeof id, "%.0f", number(part, "part"));
    run.note += (run.note.empty() ? "kept parts " : ", ") + std::string(id);
    return;
  }
  if (status == "remeshed") ++run.remeshed;
  if (status == "retried") ++run.retried;
  if (status != "remeshed" && status != "retried") return;
  run.elements += count(part, "quads") + count(part, "trias");
  run.failing += count(part, "failing");
  run.folded += count(part, "folded");
  run.degenerate += count(part, "degenerate_corners");
  const double ratio = number(part, "distance") / number(part, "target_size");
  run.worstDistance = std::isfinite(ratio) ? std::max(run.worstDistance, ratio)
                                           : std::numeric_limits<double>::infinity();
}

/// Reads the CLI's report of the run into its figures; a missing or unreadable report goes to
/// the run's note.
void readReport(Run& run) {
  const std::string raw = readText(run.folder / "report.json");
  if (raw.empty()) {
    run.note = "no report written";
    return;
  }
  try {
    const Json report = voxremesh::json::parseJson(nonFiniteToNull(raw));
    const Json& parts = report["parts"];
    for (const Json& part : parts.items) addPart(part, run);
    run.partList = parts.items;
    run.hangingIn = count(report, "hanging_nodes_in");
    run.hangingOut = count(report, "hanging_nodes_out");
  } catch (const std::exception& e) {
    run.note = std::string("report not readable: ") + e.what();
  }
}

/// Runs the CLI on one deck at one size in `folder` and gathers its figures.
Run remeshRun(const fs::path& cli, const fs::path& deck, int factor, double size,
              const fs::path& folder, const Options& options) {
  Run run;
  run.deck = deck.filename().string();
  run.factor = factor;
  run.size = size;
  run.folder = folder;
  fs::create_directories(folder);
  const pid_t pid = startChild(
      remeshCommand(cli, deck, factor == 1 ? 0.0 : size, folder, options.threads), folder);
  if (pid < 0) {
    run.outcome = "skipped";
    run.note = std::string("fork: ") + std::strerror(errno);
    return run;
  }
  run.end = waitChild(pid, options.timeout);
  run.outcome = outcomeName(run.end);
  if (run.end.rc == 0 || run.end.rc == 3) readReport(run);
  if (run.end.timedOut)
    run.note = "killed after " + std::to_string(static_cast<int>(options.timeout)) + " s";
  if (run.note.empty() && run.outcome != "ok")
    run.note = lastLines(readText(folder / "stderr.txt"), 3);
  return run;
}

/// A run that was not started, with the reason.
Run skippedRun(const fs::path& deck, int factor, const std::string& reason) {
  Run run;
  run.deck = deck.filename().string();
  run.factor = factor;
  run.size = std::nan("");
  run.outcome = "skipped";
  run.note = lastLines(reason, 3);
  return run;
}

/// The exit-code column: the code, "sigN" for a signal, "T/O" for a timeout, "-" when not run.
std::string rcColumn(const Run& run) {
  if (run.outcome == "skipped") return "-";
  if (run.end.timedOut) return "T/O";
  if (run.end.signal) return "sig" + std::to_string(run.end.signal);
  return std::to_string(run.end.rc);
}

/// The table's header line.
void printHeader(std::size_t deckWidth) {
  std::printf("%-*s %12s %4s %5s %8s %7s %5s %8s %9s %6s %6s %8s %8s %8s\n",
              static_cast<int>(deckWidth), "deck", "size", "rc", "parts", "remeshed", "retried",
              "kept", "failing", "dist/size", "folded", "180deg", "hanging", "seconds", "peak MB");
}

/// One table row for the run (and with --timeout-note, its note below it when it failed).
void printRow(const Run& run, std::size_t deckWidth, bool timeoutNote) {
  char size[32];
  if (std::isfinite(run.size))
    std::snprintf(size, sizeof size, "%.4g x%d", run.size, run.factor);
  else
    std::snprintf(size, sizeof size, "- x%d", run.factor);
  const bool measured = run.remeshed + run.retried > 0;
  char failing[32] = "-", distance[32] = "-";
  if (measured) {
    std::snprintf(failing, sizeof failing, "%.2f %%",
                  run.elements
                      ? 100.0 * static_cast<double>(run.failing) / static_cast<double>(run.elements)
                      : 0.0);
    std::snprintf(distance, sizeof distance, "%.3f", run.worstDistance);
  }
  char hanging[48];  // in the input -> in the output
  std::snprintf(hanging, sizeof hanging, "%zu->%zu", run.hangingIn, run.hangingOut);
  std::printf("%-*s %12s %4s %5zu %8zu %7zu %5zu %8s %9s %6zu %6zu %8s %8.1f %8.0f\n",
              static_cast<int>(deckWidth), run.deck.c_str(), size, rcColumn(run).c_str(), run.parts,
              run.remeshed, run.retried, run.kept, failing, distance, run.folded, run.degenerate,
              hanging, run.end.seconds, run.end.peakMb);
  const bool failed = run.outcome != "ok" && run.outcome != "kept";
  if (failed && (timeoutNote || run.outcome == "skipped")) {
    const std::string where =
        timeoutNote && !run.folder.empty() ? " (kept in " + run.folder.string() + ")" : "";
    std::printf("%*s  -> %s: %s%s\n", static_cast<int>(deckWidth), "", run.outcome.c_str(),
                run.note.c_str(), where.c_str());
  }
  std::fflush(stdout);
}

/// The totals line: runs by outcome, parts remeshed or retried over all parts, time, peaks.
void printTotals(const std::vector<Run>& runs) {
  std::size_t parts = 0, accepted = 0, failedRuns = 0;
  double seconds = 0.0, peak = 0.0;
  for (const Run& run : runs) {
    parts += run.parts;
    accepted += run.remeshed + run.retried;
    seconds += run.end.seconds;
    peak = std::max(peak, run.end.peakMb);
    if (run.outcome != "ok" && run.outcome != "kept") ++failedRuns;
  }
  rusage self{};
  getrusage(RUSAGE_SELF, &self);
  std::printf(
      "total: %zu runs (%zu error, crash, timeout or skipped), %zu of %zu parts remeshed or "
      "retried (%.1f %%), %.1f s, largest peak %.0f MB (bench_corpus itself %.0f MB)\n",
      runs.size(), failedRuns, accepted, parts,
      parts ? 100.0 * static_cast<double>(accepted) / static_cast<double>(parts) : 0.0, seconds,
      peak, static_cast<double>(self.ru_maxrss) / 1024.0);
}

/// Appends a number as JSON (null when it is not finite).
void appendNumber(std::string& out, double value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  char text[64];
  std::snprintf(text, sizeof text, "%.10g", value);
  out += text;
}

/// Appends a parsed value as compact JSON (numbers as they were written).
void appendJson(std::string& out, const Json& value) {
  switch (value.type) {
    case Json::Type::Null:
      out += "null";
      break;
    case Json::Type::Bool:
      out += value.boolean ? "true" : "false";
      break;
    case Json::Type::Number:
      if (value.text.empty())
        appendNumber(out, value.number);
      else
        out += value.text;
      break;
    case Json::Type::String:
      voxremesh::json::appendJsonString(out, value.text);
      break;
    case Json::Type::Array:
      out += '[';
      for (std::size_t i = 0; i < value.items.size(); ++i) {
        if (i) out += ", ";
        appendJson(out, value.items[i]);
      }
      out += ']';
      break;
    case Json::Type::Object:
      out += '{';
      for (std::size_t i = 0; i < value.members.size(); ++i) {
        if (i) out += ", ";
        voxremesh::json::appendJsonString(out, value.members[i].first);
        out += ": ";
        appendJson(out, value.members[i].second);
      }
      out += '}';
      break;
  }
}

/// Appends one run as a JSON object: the row's figures, the note and the report's parts.
void appendRun(std::string& out, const Run& run) {
  const auto field = [&out](const char* name) { out += std::string(",\n    \"") + name + "\": "; };
  out += "  {\n    \"deck\": ";
  voxremesh::json::appendJsonString(out, run.deck);
  field("size_factor"), out += std::to_string(run.factor);
  field("size"), appendNumber(out, run.size);
  field("rc"), out += run.end.rc >= 0 ? std::to_string(run.end.rc) : "null";
  field("signal"), out += std::to_string(run.end.signal);
  field("outcome"), voxremesh::json::appendJsonString(out, run.outcome);
  field("parts"), out += std::to_string(run.parts);
  field("remeshed"), out += std::to_string(run.remeshed);
  field("retried"), out += std::to_string(run.retried);
  field("kept"), out += std::to_string(run.kept);
  field("elements"), out += std::to_string(run.elements);
  field("failing"), out += std::to_string(run.failing);
  field("failing_share"), appendNumber(out, run.elements ? static_cast<double>(run.failing) /
                                                               static_cast<double>(run.elements)
                                                         : 0.0);
  field("worst_distance_per_size"), appendNumber(out, run.worstDistance);
  field("folded"), out += std::to_string(run.folded);
  field("degenerate_corners"), out += std::to_string(run.degenerate);
  field("hanging_nodes_in"), out += std::to_string(run.hangingIn);
  field("hanging_nodes_out"), out += std::to_string(run.hangingOut);
  field("seconds"), appendNumber(out, run.end.seconds);
  field("peak_mb"), appendNumber(out, run.end.peakMb);
  field("note"), voxremesh::json::appendJsonString(out, run.note);
  field("part_reports"), out += '[';
  for (std::size_t i = 0; i < run.partList.size(); ++i) {
    out += i ? ",\n      " : "\n      ";
    appendJson(out, run.partList[i]);
  }
  out += run.partList.empty() ? "]" : "\n    ]";
  out += "\n  }";
}

/// Writes every run to `path` as a JSON array.
void writeJson(const std::vector<Run>& runs, const fs::path& path) {
  std::string out = "[";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    out += i ? ",\n" : "\n";
    appendRun(out, runs[i]);
  }
  out += "\n]\n";
  std::ofstream(path, std::ios::binary) << out;
}

/// A fresh temporary folder for the runs.
fs::path makeTempFolder() {
  std::string pattern = (fs::temp_directory_path() / "voxremesh-bench-corpus-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder");
  return pattern;
}

/// Whether the run ended with the deck written (exit code 0 or 3).
bool succeeded(const Run& run) {
  return run.outcome == "ok" || run.outcome == "kept";
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!parseOptions(argc, argv, options)) return 2;
  try {
    const fs::path cli = findCli();
    if (access(cli.c_str(), X_OK) != 0) {
      std::fprintf(stderr,
                   "bench_corpus: no voxremesh next to it (%s); build the voxremesh "
                   "target too\n",
                   cli.c_str());
      return 1;
    }
    const std::vector<fs::path> decks = listDecks(options);
    if (decks.empty()) {
      std::fprintf(stderr, "bench_corpus: no decks in %s\n", options.data.c_str());
      return 1;
    }
    std::size_t deckWidth = 4;
    for (const fs::path& deck : decks)
      deckWidth = std::max(deckWidth, deck.filename().string().size());
    const fs::path temp = makeTempFolder();
    printHeader(deckWidth);
    std::vector<Run> runs;
    bool keepTemp = false;
    for (std::size_t d = 0; d < decks.size(); ++d) {
      std::string error;
      const double size = deckSizeInChild(decks[d], error);
      for (int factor = 1; factor <= 2; ++factor) {
        const fs::path folder = temp / (std::to_string(d) + "-x" + std::to_string(factor));
        if (factor == 2 && !(size > 0)) {
          runs.push_back(skippedRun(decks[d], factor, "no default size: " + error));
        } else {
          runs.push_back(remeshRun(cli, decks[d], factor, size * factor, folder, options));
        }
        Run& run = runs.back();
        printRow(run, deckWidth, options.timeoutNote);
        if (options.timeoutNote && !succeeded(run) && !run.folder.empty())
          keepTemp = true;
        else if (!run.folder.empty())
          fs::remove_all(run.folder);
      }
    }
    printTotals(runs);
    writeJson(runs, options.json);
    std::printf("wrote %s\n", options.json.c_str());
    if (!keepTemp) fs::remove_all(temp);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_corpus: %s\n", e.what());
    return 1;
  }
}
