// Reading a batch job file: structure checks, globs, variants, placeholders (batch.h).
#include <fnmatch.h>
#include <cmath>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "io/text_scan.h"
#include "json/json.h"
#include "voxremesh/batch.h"
#include "voxremesh/errors.h"

namespace voxremesh {

namespace {

namespace fs = std::filesystem;
using json::Json;

class FileReader {
 public:
  FileReader(const fs::path& path, bool allowOutside)
      : path_(path), name_(path.string()), allowOutside_(allowOutside) {}

  BatchFile read() {
    const std::string content = io::loadFile(path_);
    Json root;
    try {
      root = json::parseJson(content);
    } catch (const json::JsonError& error) {
      throw InputError(name_, error.line(), std::string("not a valid job file: ") + error.what());
    }
    if (root.type != Json::Type::Object) fail(root, "the job file must be a JSON object");
    allowKeys(root, {"threads", "defaults", "jobs"}, "the job file");
    BatchFile file;
    if (const Json* threads = root.find("threads")) {
      // Compared as doubles before the cast: a number out of int's range must not reach it.
      if (threads->type != Json::Type::Number || !(threads->number >= 0.0) ||
          threads->number > kMaxBatchThreads || threads->number != std::floor(threads->number))
        fail(*threads,
             "\"threads\" must be a whole number within 0.." + std::to_string(kMaxBatchThreads));
      file.threads = static_cast<int>(threads->number);
    }
    std::vector<std::pair<std::string, const Json*>> defaults;
    if (const Json* given = root.find("defaults")) addSettings(*given, "\"defaults\"", defaults);
    const Json* jobs = root.find("jobs");
    if (!jobs) fail(root, "the job file has no \"jobs\" list");
    if (jobs->type != Json::Type::Array || jobs->items.empty())
      fail(*jobs, "\"jobs\" must be a non-empty list of job objects");
    for (std::size_t j = 0; j < jobs->items.size(); ++j) {
      const std::size_t first = file.jobs.size();
      expand(jobs->items[j], defaults, file.jobs);
      if (!allowOutside_)
        for (std::size_t k = first; k < file.jobs.size(); ++k)
          refuseWritingOutside(jobs->items[j], file.jobs[k]);
    }
    refuseSharedOutputs(*jobs, file.jobs);
    return file;
  }

  /// Fails when two jobs write the same output, or a job writes over its input: the later result
  /// would replace the earlier one (or the input) while every job reported success.
  void refuseSharedOutputs(const Json& where, const std::vector<BatchJob>& jobs) const {
    std::map<fs::path, std::size_t> writer;
    for (const BatchJob& job : jobs) {
      if (!job.problem.empty()) continue;
      const fs::path output = job.output.lexically_normal();
      if (output == job.input.lexically_normal())
        fail(where, "job \"" + job.name + "\" would write over its input " + job.input.string());
      const auto [it, added] = writer.emplace(output, job.index);
      if (!added)
        fail(where, "jobs \"" + jobs[it->second].name + "\" and \"" + job.name + "\" both write " +
                        job.output.string());
    }
  }

  /// Fails when a job writes outside the job file's folder: its output, or a chain's -write
  /// target (relative to the working folder, as the chain reads it).
  void refuseWritingOutside(const Json& where, const BatchJob& job) const {
    if (!job.problem.empty()) return;
    // (target, the member naming it)
    std::vector<std::pair<fs::path, const char*>> written{{job.output, "output"}};
    for (std::size_t i = 0; i + 1 < job.chain.size(); ++i)
      if (job.chain[i] == "-write") written.emplace_back(job.chain[i + 1], "chain");
    std::error_code error;
    const fs::path folder = fs::weakly_canonical(fs::absolute(path_).parent_path(), error);
    for (const auto& [target, member] : written) {
      const fs::path full = fs::weakly_canonical(fs::absolute(target), error);
      const fs::path inside = full.lexically_relative(folder);
      if (error || inside.empty() || *inside.begin() == "..") {
        const Json* at = where.find(member);
        fail(at ? *at : where, "job \"" + job.name + "\" writes " + full.string() +
                                   ", outside the job file's folder " + folder.string() +
                                   " (voxremesh batch --allow-outside allows it)");
      }
    }
  }

 private:
  [[noreturn]] void fail(const Json& where, const std::string& message) const {
    throw InputError(name_, where.line, message);
  }

  void allowKeys(const Json& object, std::initializer_list<const char*> keys,
                 const std::string& what) const {
    for (const auto& [key, value] : object.members) {
      bool known = false;
      std::string list;
      for (const char* allowed : keys) {
        known = known || key == allowed;
        list += (list.empty() ? "" : ", ") + std::string(allowed);
      }
      if (!known) fail(value, "unknown key \"" + key + "\" in " + what + " (known: " + list + ")");
    }
  }

  /// Collects a settings object's members; values must be numbers or strings (checked per job
  /// when it runs is their meaning).
  void addSettings(const Json& object, const std::string& what,
                   std::vector<std::pair<std::string, const Json*>>& into) const {
    if (object.type != Json::Type::Object) fail(object, what + " must be an object of settings");
    for (const auto& member : object.members) {
      const std::string& key = member.first;
      const Json& value = member.second;
      if (value.type != Json::Type::Number && value.type != Json::Type::String)
        fail(value, "setting \"" + key + "\" in " + what + " must be a number or a string");
      into.erase(std::remove_if(into.begin(), into.end(),
                                [&](const auto& entry) { return entry.first == key; }),
                 into.end());
      into.emplace_back(key, &value);
    }
  }

  const std::string& text(const Json& job, const char* key, bool required) const {
    static const std::string kEmpty;
    const Json* value = job.find(key);
    if (!value) {
      if (required) fail(job, std::string("the job has no \"") + key + "\"");
      return kEmpty;
    }
    if (value->type != Json::Type::String || value->text.empty())
      fail(*value, std::string("\"") + key + "\" must be a non-empty string");
    return value->text;
  }

  fs::path resolve(const std::string& text) const {
    const fs::path path(text);
    return path.is_absolute() ? path : path_.parent_path() / path;
  }

  std::vector<fs::path> glob(const Json& job, const std::string& pattern) const {
    const fs::path full = resolve(pattern);
    const fs::path folder = full.parent_path().empty() ? fs::path(".") : full.parent_path();
    const std::string namePattern = full.filename().string();
    std::vector<fs::path> matches;
    std::error_code error;
    if (!fs::is_directory(folder, error))
      fail(job,
           "\"inputs\": no file matches " + full.string() + " (no folder " + folder.string() + ")");
    for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
      if (it->is_regular_file() &&
          ::fnmatch(namePattern.c_str(), it->path().filename().string().c_str(), 0) == 0)
        matches.push_back(it->path());
    if (error) fail(job, "cannot list the folder " + folder.string() + ": " + error.message());
    std::sort(matches.begin(), matches.end());
    if (matches.empty()) fail(job, "\"inputs\": no file matches " + full.string());
    return matches;
  }

  static std::string scalarText(const Json& value) { return value.text; }

  /// Fills {stem} {name} {index} {input} {output} and {KEY} of the settings.
  static std::string fill(const std::string& pattern, const BatchJob& job, bool withPaths,
                          std::string& problem) {
    std::string out;
    std::size_t i = 0;
    while (i < pattern.size()) {
      const std::size_t open = pattern.find('{', i);
      if (open == std::string::npos) {
        out += pattern.substr(i);
        break;
      }
      const std::size_t close = pattern.find('}', open);
      if (close == std::string::npos) {
        out += pattern.substr(i);
        break;
      }
      out += pattern.substr(i, open - i);
      const std::string key = pattern.substr(open + 1, close - open - 1);
      if (key == "stem") {
        out += job.input.stem().string();
      } else if (key == "name") {
        out += job.name;
      } else if (key == "index") {
        out += std::to_string(job.index);
      } else if (withPaths && key == "input") {
        out += job.input.string();
      } else if (withPaths && key == "output") {
        out += job.output.string();
      } else if (job.settings.count(key)) {
        out += job.settings.at(key);
      } else {
        if (problem.empty()) problem = "placeholder {" + key + "} names no setting of the job";
        out += pattern.substr(open, close - open + 1);
      }
      i = close + 1;
    }
    return out;
  }

  void expand(const Json& job, const std::vector<std::pair<std::string, const Json*>>& defaults,
              std::vector<BatchJob>& out) const {
    if (job.type != Json::Type::Object) fail(job, "each job must be an object");
    allowKeys(job, {"name", "task", "input", "inputs", "output", "settings", "variants", "chain"},
              "a job");
    const std::string& taskText = text(job, "task", true);
    BatchTask task;
    if (taskText == "voxelize") {
      task = BatchTask::Voxelize;
    } else if (taskText == "convert") {
      task = BatchTask::Convert;
    } else if (taskText == "remesh") {
      task = BatchTask::Remesh;
    } else if (taskText == "chain") {
      task = BatchTask::Chain;
    } else {
      fail(*job.find("task"),
           "unknown task \"" + taskText + "\" (one of voxelize, convert, remesh, chain)");
    }
    std::vector<std::string> chain;
    if (const Json* given = job.find("chain")) {
      if (task != BatchTask::Chain) fail(*given, "\"chain\" belongs to jobs of task \"chain\"");
      if (given->type != Json::Type::Array || given->items.empty())
        fail(*given, "\"chain\" must be a non-empty list of strings");
      for (const Json& word : given->items) {
        if (word.type != Json::Type::String) fail(word, "\"chain\" must be a list of strings");
        chain.push_back(word.text);
      }
    } else if (task == BatchTask::Chain) {
      fail(job, "a job of task \"chain\" needs a \"chain\" list");
    }
    std::vector<fs::path> inputs;
    const bool single = job.find("input") != nullptr, many = job.find("inputs") != nullptr;
    if (single == many) fail(job, "a job needs either \"input\" or \"inputs\" (a glob)");
    if (single) {
      inputs.push_back(resolve(text(job, "input", true)));
    } else {
      inputs = glob(job, text(job, "inputs", true));
    }
    const std::string& outputPattern = text(job, "output", true);
    std::vector<std::pair<std::string, const Json*>> base = defaults;
    if (const Json* settings = job.find("settings")) addSettings(*settings, "\"settings\"", base);
    std::vector<std::vector<std::pair<std::string, const Json*>>> variants;
    if (const Json* given = job.find("variants")) {
      if (given->type != Json::Type::Array || given->items.empty())
        fail(*given, "\"variants\" must be a non-empty list of settings objects");
      for (const Json& variant : given->items) {
        variants.push_back(base);
        addSettings(variant, "a variant", variants.back());
      }
    } else {
      variants.push_back(base);
    }
    const Json* nameGiven = job.find("name");
    const std::string name = nameGiven ? text(job, "name", true) : std::string();
    for (const fs::path& input : inputs) {
      for (std::size_t v = 0; v < variants.size(); ++v) {
        BatchJob expanded;
        expanded.index = out.size();
        expanded.task = task;
        expanded.input = input;
        for (const auto& [key, value] : variants[v]) {
          expanded.settings[key] = scalarText(*value);
          expanded.settingIsText[key] = value->type == Json::Type::String;
          // A file a setting names lies, as the inputs do, relative to the job file's folder.
          if (key == "criteria" && expanded.settingIsText[key])
            expanded.settings[key] = resolve(expanded.settings[key]).string();
        }
        std::string jobName = name.empty() ? input.stem().string() : name;
        if (inputs.size() > 1 && !name.empty()) jobName += "-" + input.stem().string();
        expanded.name = variants.size() > 1 ? jobName + "-" + std::to_string(v + 1) : jobName;
        expanded.output = resolve(fill(outputPattern, expanded, false, expanded.problem));
        for (const std::string& word : chain)
          expanded.chain.push_back(fill(word, expanded, true, expanded.problem));
        out.push_back(std::move(expanded));
      }
    }
  }

  fs::path path_;
  std::string name_;
  bool allowOutside_ = false;
};

}  // namespace

BatchFile readBatchFile(const std::filesystem::path& path, bool allowOutside) {
  return FileReader(path, allowOutside).read();
}

const char* taskName(BatchTask task) {
  switch (task) {
    case BatchTask::Voxelize:
      return "voxelize";
    case BatchTask::Convert:
      return "convert";
    case BatchTask::Remesh:
      return "remesh";
    case BatchTask::Chain:
      break;
  }
  return "chain";
}

}  // namespace voxremesh
