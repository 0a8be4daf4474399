// The batch summary as CSV and JSON (batch.h).
#include <charconv>
#include <cmath>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>

#include "io/atomic_file.h"
#include "io/text_scan.h"
#include "json/json.h"
#include "voxremesh/batch.h"

namespace voxremesh {

namespace {

std::string shortest(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// The summary fields of one job in order, as text; `present` false where unknown.
struct Field {
  const char* name;
  std::string text;
  bool present = true;
  bool number = false;
};

std::vector<Field> fields(const BatchJob& job, const BatchResult& result) {
  const auto count = [](const std::optional<std::size_t>& value) {
    return Field{"", value ? std::to_string(*value) : "", value.has_value(), true};
  };
  std::vector<Field> out = {
      {"index", std::to_string(job.index), true, true},
      {"name", job.name},
      {"task", taskName(job.task)},
      {"input", job.input.string()},
      {"output", job.output.string()},
      {"status", result.status},
      {"message", result.message},
      {"seconds", shortest(result.seconds), true, true},
      {"from_earlier_run", result.fromEarlierRun ? "true" : "false", true, true},
  };
  const char* names[] = {"elements_in", "elements_out", "quality_failures"};
  const std::optional<std::size_t>* values[] = {&result.elementsIn, &result.elementsOut,
                                                &result.qualityFailures};
  for (int k = 0; k < 3; ++k) {
    Field field = count(*values[k]);
    field.name = names[k];
    out.push_back(field);
  }
  out.push_back(Field{"quality_failure_share",
                      result.qualityFailureShare ? shortest(*result.qualityFailureShare) : "",
                      result.qualityFailureShare.has_value(), true});
  out.push_back(Field{"max_distance", result.maxDistance ? shortest(*result.maxDistance) : "",
                      result.maxDistance.has_value(), true});
  return out;
}

}  // namespace

std::string batchSummaryCsv(const std::vector<BatchJob>& jobs,
                            const std::vector<BatchResult>& results) {
  std::string text =
      "index,name,task,input,output,status,message,seconds,from_earlier_run,elements_in,elements_"
      "out,"
      "quality_failures,quality_failure_share,max_distance\n";
  for (std::size_t j = 0; j < jobs.size() && j < results.size(); ++j) {
    if (results[j].status == "other-shard") continue;
    std::string line;
    for (const Field& field : fields(jobs[j], results[j]))
      line += (line.empty() ? "" : ",") + csvField(field.text);
    text += line + "\n";
  }
  return text;
}

std::string batchSummaryJson(const std::vector<BatchJob>& jobs,
                             const std::vector<BatchResult>& results) {
  std::size_t ok = 0, shortJobs = 0, failed = 0, skipped = 0;
  std::string items;
  for (std::size_t j = 0; j < jobs.size() && j < results.size(); ++j) {
    const std::string& status = results[j].status;
    if (status == "other-shard") continue;
    ok += status == "ok" ? 1 : 0;
    shortJobs += status == "short" ? 1 : 0;
    failed += status == "failed" ? 1 : 0;
    skipped += status == "skipped" ? 1 : 0;
    std::string object;
    for (const Field& field : fields(jobs[j], results[j])) {
      object += (object.empty() ? "{" : ", ") + json::quote(field.name) + ": ";
      object += !field.present ? "null" : field.number ? field.text : json::quote(field.text);
    }
    items += (items.empty() ? "\n    " : ",\n    ") + object + "}";
  }
  return "{\n  \"jobs\": [" + items + (items.empty() ? "" : "\n  ") +
         "],\n  \"ok\": " + std::to_string(ok) + ",\n  \"short\": " + std::to_string(shortJobs) +
         ",\n  \"failed\": " + std::to_string(failed) +
         ",\n  \"skipped\": " + std::to_string(skipped) + "\n}\n";
}

void writeBatchSummaries(const std::vector<BatchJob>& jobs, const std::vector<BatchResult>& results,
                         const std::string& prefix) {
  io::writeFileAtomically(prefix + ".csv", batchSummaryCsv(jobs, results));
  io::writeFileAtomically(prefix + ".json", batchSummaryJson(jobs, results));
}

namespace {

/// A JSON number as a count: a whole number from 0 to 2^53 (where doubles still count by one),
/// else none (checked before the cast, which is undefined for numbers out of range).
std::optional<std::size_t> wholeCount(const json::Json* value) {
  if (!value || value->type != json::Json::Type::Number) return std::nullopt;
  const double number = value->number;
  if (!(number >= 0.0) || number > 9007199254740992.0 || number != std::floor(number))
    return std::nullopt;
  return static_cast<std::size_t>(number);
}

/// A count field of a summary entry, when it holds one.
std::optional<std::size_t> countOf(const json::Json& entry, const char* key) {
  return wholeCount(entry.find(key));
}

std::optional<double> numberOf(const json::Json& entry, const char* key) {
  const json::Json* value = entry.find(key);
  if (!value || value->type != json::Json::Type::Number) return std::nullopt;
  return value->number;
}

}  // namespace

void restoreEarlierResults(const std::vector<BatchJob>& jobs, std::vector<BatchResult>& results,
                           const std::filesystem::path& earlierSummary) {
  json::Json earlier;
  try {
    if (!std::filesystem::exists(earlierSummary)) return;
    earlier = json::parseJson(io::loadFile(earlierSummary));
  } catch (const std::exception&) {
    return;
  }
  const json::Json* entries = earlier.find("jobs");
  if (!entries || entries->type != json::Json::Type::Array) return;
  for (const json::Json& entry : entries->items) {
    const json::Json* index = entry.find("index");
    const json::Json* output = entry.find("output");
    const json::Json* status = entry.find("status");
    const std::optional<std::size_t> at = wholeCount(index);
    if (!at || !output || !status) continue;
    const std::size_t j = *at;
    if (j >= jobs.size() || j >= results.size() || results[j].status != "skipped" ||
        jobs[j].output.string() != output->text ||
        (status->text != "ok" && status->text != "short"))
      continue;
    BatchResult& result = results[j];
    result.status = status->text;
    if (const json::Json* message = entry.find("message")) result.message = message->text;
    result.seconds = numberOf(entry, "seconds").value_or(0.0);
    result.elementsIn = countOf(entry, "elements_in");
    result.elementsOut = countOf(entry, "elements_out");
    result.qualityFailures = countOf(entry, "quality_failures");
    result.qualityFailureShare = numberOf(entry, "quality_failure_share");
    result.maxDistance = numberOf(entry, "max_distance");
    result.fromEarlierRun = true;
  }
}

}  // namespace voxremesh
