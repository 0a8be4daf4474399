// What the voxremesh subcommands share: the command functions main.cpp dispatches to, argument
// parsing, usage errors, and printing warnings and output.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "voxremesh/errors.h"
#include "voxremesh/io.h"

namespace voxremesh::cli {

/// The exit code of a command that did its work but fell short: `remesh` kept parts unchanged
/// (or `batch` had such jobs), `quality` found the mesh failing its criteria.
constexpr int kExitShortfall = 3;

/// A subcommand: receives the arguments after its name; returns the exit code. Throws UsageError
/// for a malformed command line, anything else derived from std::exception for a failure.
using CommandFunction = int (*)(const std::vector<std::string>& args);

/// `voxremesh info` (cli_info.cpp).
int runInfo(const std::vector<std::string>& args);
/// `voxremesh convert` (cli_convert.cpp).
int runConvert(const std::vector<std::string>& args);
/// `voxremesh voxelize` (cli_voxelize.cpp).
int runVoxelize(const std::vector<std::string>& args);
/// `voxremesh inspect` (cli_inspect.cpp).
int runInspect(const std::vector<std::string>& args);
/// `voxremesh slice` (cli_slice.cpp).
int runSlice(const std::vector<std::string>& args);
/// `voxremesh extract` (cli_extract.cpp).
int runExtract(const std::vector<std::string>& args);
/// `voxremesh remesh` (cli_remesh.cpp).
int runRemesh(const std::vector<std::string>& args);
/// `voxremesh batch` (cli_batch.cpp).
int runBatchCommand(const std::vector<std::string>& args);
/// `voxremesh -ACTION ...`, an action chain (cli_chain.cpp); receives all arguments.
int runChain(const std::vector<std::string>& args);
/// `voxremesh quality` (cli_quality.cpp).
int runQuality(const std::vector<std::string>& args);
/// `voxremesh compare` (cli_compare.cpp).
int runCompare(const std::vector<std::string>& args);

/// A malformed command line (unknown option, missing argument, ...): main prints the message and
/// the command's usage line on stderr and exits with 2.
class UsageError : public std::runtime_error {
 public:
  /// @param message what is wrong; @param usage the command's usage line ("voxremesh info DECK
  /// ...")
  UsageError(const std::string& message, std::string usage)
      : std::runtime_error(message), usage_(std::move(usage)) {}
  /// The usage line of the command the error is about.
  const std::string& usage() const noexcept { return usage_; }

 private:
  std::string usage_;
};

/// An option a command accepts: its name ("--json") and whether a value follows it.
struct OptionSpec {
  const char* name;
  bool takesValue;
};

/// A parsed command line: positional arguments in order, options by name.
struct ParsedArgs {
  std::vector<std::string> positional;
  std::map<std::string, std::string> options;  ///< flags map to ""

  /// The option was given.
  bool has(const std::string& name) const { return options.count(name) != 0; }
  /// The option's value, or nothing when it was not given.
  std::optional<std::string> value(const std::string& name) const {
    const auto it = options.find(name);
    return it == options.end() ? std::nullopt : std::optional<std::string>(it->second);
  }
};

/// The arguments ask for the command's help (-h or --help anywhere).
inline bool wantsHelp(const std::vector<std::string>& args) {
  for (const std::string& arg : args)
    if (arg == "-h" || arg == "--help") return true;
  return false;
}

/// Splits `args` into positional arguments and the given options ("--name value" or
/// "--name=value"; "--" ends the options). Throws UsageError (with `usage`) for an unknown option,
/// an option given twice, a missing or unexpected value, or a number of positional arguments
/// outside [minPositional, maxPositional].
inline ParsedArgs parseArgs(const std::vector<std::string>& args,
                            std::initializer_list<OptionSpec> specs, std::size_t minPositional,
                            std::size_t maxPositional, const std::string& usage) {
  ParsedArgs parsed;
  bool optionsEnded = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (optionsEnded || arg.size() < 2 || arg[0] != '-') {
      parsed.positional.push_back(arg);
      continue;
    }
    if (arg == "--") {
      optionsEnded = true;
      continue;
    }
    const std::size_t equals = arg.find('=');
    const std::string name = arg.substr(0, equals);
    const OptionSpec* spec = nullptr;
    for (const OptionSpec& candidate : specs)
      if (name == candidate.name) spec = &candidate;
    if (!spec) throw UsageError("unknown option '" + name + "'", usage);
    if (parsed.has(name)) throw UsageError("option " + name + " given twice", usage);
    std::string value;
    if (spec->takesValue) {
      if (equals != std::string::npos)
        value = arg.substr(equals + 1);
      else if (i + 1 < args.size())
        value = args[++i];
      else
        throw UsageError("option " + name + " needs a value", usage);
    } else if (equals != std::string::npos) {
      throw UsageError("option " + name + " takes no value", usage);
    }
    parsed.options[name] = value;
  }
  if (parsed.positional.size() < minPositional) throw UsageError("missing argument", usage);
  if (parsed.positional.size() > maxPositional)
    throw UsageError("unexpected argument '" + parsed.positional[maxPositional] + "'", usage);
  return parsed;
}

/// Parses the value of a numeric option. Throws SettingError naming the option when `text` is not
/// a finite number.
inline double parseNumber(const std::string& option, const std::string& text);

/// The value of an angle option (degrees, 0..180). Throws SettingError naming the option
/// otherwise.
inline double parseAngle(const std::string& option, const std::string& text) {
  const double value = parseNumber(option, text);
  if (!(value >= 0.0 && value <= 180.0))
    throw SettingError(option + " must be an angle from 0 to 180 degrees, not " + text);
  return value;
}

/// Throws SettingError when `output` (given with `what`, as "-o") names the file `input`: the
/// input would be replaced by the output without a word.
inline void refuseOverwritingInput(const std::string& input, const std::string& output,
                                   const std::string& what) {
  std::error_code error;
  if (std::filesystem::equivalent(input, output, error))
    throw SettingError(what + " " + output + " is the input " + input + ": write to another file");
}

inline double parseNumber(const std::string& option, const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
    throw SettingError(option + " expects a number, not '" + text + "'");
  return value;
}

/// Parses the value of an integer option (a part ID, a pixel count). Throws SettingError naming
/// the option when `text` is not a whole number within the range of a 64-bit integer.
inline long long parseInteger(const std::string& option, const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
    throw SettingError(option + " expects a whole number, not '" + text + "'");
  return value;
}

/// Parses the value of an integer option that must lie within [low, high] (a count of threads or
/// retries). Throws SettingError naming the option when `text` is not a whole number or lies
/// outside the range.
inline long long parseIntegerInRange(const std::string& option, const std::string& text,
                                     long long low, long long high) {
  const long long value = parseInteger(option, text);
  if (value < low || value > high)
    throw SettingError(option + " must be within " + std::to_string(low) + ".." +
                       std::to_string(high) + ", not " + text);
  return value;
}

/// Runs `parseValues`, the parsing of a command's option values, and turns a SettingError it
/// throws (a value that is not a number of the right kind, or out of its range) into a UsageError
/// with `usage`: a malformed option value is a malformed command line (exit 2), unlike bad input
/// (exit 1). Call it before any input is read, so that nothing is read or written.
template <typename ParseValues>
void parseOptionValues(const std::string& usage, ParseValues&& parseValues) {
  try {
    std::forward<ParseValues>(parseValues)();
  } catch (const SettingError& error) {
    throw UsageError(error.what(), usage);
  }
}

/// Prints each warning on stderr as "warning: <text>".
inline void printWarnings(const Warnings& warnings) {
  for (const std::string& warning : warnings)
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
}

/// Writes `text` to stdout. Throws std::runtime_error when it cannot be written.
inline void printOutput(const std::string& text) {
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0)
    throw std::runtime_error("cannot write to standard output");
}

}  // namespace voxremesh::cli
