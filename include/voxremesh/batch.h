// Scripted batch: a JSON job file lists inputs, outputs and per-job settings; the jobs run in
// parallel within a thread budget, a failing job is reported while the others still run, and a
// summary (CSV and JSON) says per job what happened.
//
// Job file (JSON; relative paths are relative to the job file's folder; unknown keys are errors):
//   {
//     "threads": 2,                          optional: thread budget (--threads overrides it)
//     "defaults": { SETTINGS },              optional: settings every job starts from
//     "jobs": [ JOB, ... ]                   required, at least one
//   }
//   JOB = {
//     "name": "bracket",                     optional; default: the input file's stem, plus
//                                            "-" and the variant number for variants
//     "task": "voxelize",                    required: "voxelize" (a part into a .vdb file,
//                                            one volume per sheet as `voxremesh voxelize`),
//                                            "convert" (deck to deck by extension), "remesh"
//                                            (the deck's parts remeshed, pipeline.h) or "chain"
//     "input": "decks/bracket.k",            the input file, or
//     "inputs": "decks/*.k",                 a glob: one job per matching file, sorted by name
//                                            (wildcards * ? [...] in the file name only)
//     "output": "out/{stem}_s{size}.vdb",    required; {stem} is the input's stem, {name} the
//                                            job's name, {index} its number, {KEY} a setting
//     "settings": { SETTINGS },              optional: over the defaults
//     "variants": [ { SETTINGS }, ... ],     optional: one job per variant, over the settings
//     "chain": ["-read", "{input}", "-voxelize", "size={size}", "-write", "{output}"]
//                                            task "chain": the actions (action_chain.h), with the
//                                            placeholders above and {input}
//   }
//   SETTINGS = { "size": 4, "voxel": 1.5, "part": 4075, "band": 3, "feature_angle": 30,
//                "invalid_angle": 60, "format": "k", "criteria": "oem.txt" }
//              (all optional; format: of the output; band: voxels each side, default 3, for
//              remesh jobs kExtractionBandVoxels (extract.h), the least they take)
//   remesh jobs: size is the target element size (default: per part its median edge), part the
//   one part to remesh (default: all parts with shells), voxel is refused, criteria a quality
//   criteria file (criteria_file.h; relative to the job file's folder) for the optimisation,
//   the acceptance and the summary's failing share.
// Jobs are numbered from 0 in the order of the file after expanding globs and variants.
// A job file that is not valid JSON or breaks this structure is refused as a whole
// (InputError naming the file and line); a setting of the wrong type or out of range, a missing
// or unreadable input and any failure while running fail that job only.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace voxremesh {

/// What a job does.
enum class BatchTask { Voxelize, Convert, Remesh, Chain };

/// One job after expanding globs and variants.
struct BatchJob {
  std::size_t index = 0;
  std::string name;
  BatchTask task = BatchTask::Voxelize;
  std::filesystem::path input;
  std::filesystem::path output;
  /// The merged settings (defaults, job settings, variant) as JSON scalar texts: numbers as
  /// written, strings unquoted.
  std::map<std::string, std::string> settings;
  /// For settings given as strings: their keys (so that a number given as text is refused).
  std::map<std::string, bool> settingIsText;
  std::vector<std::string> chain;  ///< task chain: the arguments, placeholders filled in
  std::string problem;  ///< set when the job cannot run as written (e.g. unknown placeholder)
};

/// A parsed job file.
/// The largest thread budget a job file or --threads may give.
inline constexpr int kMaxBatchThreads = 4096;

struct BatchFile {
  std::vector<BatchJob> jobs;
  int threads = 0;  ///< 0 when the file does not say
};

/// Reads a job file (see the schema above).
/// @param allowOutside  jobs may write outside the job file's folder (their output, or a chain's
///                      -write target, relative to the working folder); by default such a job
///                      refuses the file, so that a job file from elsewhere cannot overwrite files
///                      anywhere
/// Throws InputError naming the file and line for unreadable files, invalid JSON and structure
/// errors (missing or unknown keys, wrong types of the structure, an empty job list, a glob that
/// matches no file, two jobs writing one file, a job writing over its input or outside the
/// folder).
BatchFile readBatchFile(const std::filesystem::path& path, bool allowOutside = false);

/// How runBatch runs.
struct BatchOptions {
  int threads = 0;             ///< 0: all cores
  bool resume = false;         ///< skip jobs whose output exists (outputs are written atomically)
  std::size_t shardIndex = 0;  ///< run the jobs with index % shardCount == shardIndex
  std::size_t shardCount = 1;
  /// Called when a job ends (from worker threads, one call at a time), with the number of
  /// jobs of this shard finished so far and their count.
  std::function<void(const struct BatchResult&, std::size_t done, std::size_t total)> onJobDone;
};

/// Parses "I/N" (0 <= I < N). Throws SettingError naming the text otherwise.
void parseShard(const std::string& text, BatchOptions& options);

/// What happened to one job.
struct BatchResult {
  std::size_t index = 0;
  std::string name;
  /// "ok", "short" (output written, but a remesh kept parts unchanged), "failed", "skipped"
  /// (resume), "other-shard"
  std::string status;
  std::string message;
  double seconds = 0.0;
  std::optional<std::size_t> elementsIn;   ///< shells of the input (of the part for voxelize)
  std::optional<std::size_t> elementsOut;  ///< shells written (deck outputs)
  /// Remesh jobs (over the remeshed parts, remesh_quality.h) and chain jobs with a -quality
  /// action (its last report): the elements failing a quality criterion at the default limits,
  /// their share of all assessed elements, and the largest two-sided distance to the original
  /// (chain jobs: when -quality measured one).
  std::optional<std::size_t> qualityFailures;
  std::optional<double> qualityFailureShare;
  std::optional<double> maxDistance;
  std::optional<std::size_t> partsKept;  ///< remesh jobs: parts kept unchanged
  /// Remesh jobs: more nodes hang on seams than in the input (RemeshReport::moreHangingNodes).
  bool moreHangingNodes = false;
  /// A skipped job (resume) whose earlier result was restored from the earlier summary.
  bool fromEarlierRun = false;
};

/// Runs the jobs of this shard in parallel within the thread budget; every job runs to its own
/// end whatever the others do. Returns one result per job of `jobs` (jobs of other shards with
/// status "other-shard"), in job order; deterministic apart from times.
/// Throws SettingError for threads < 0 or a shard outside its count.
std::vector<BatchResult> runBatch(const std::vector<BatchJob>& jobs, const BatchOptions& options);

/// The summary as CSV: a header line, then one line per job that ran or was skipped (other
/// shards left out): index,name,task,input,output,status,message,seconds,from_earlier_run,
/// elements_in,elements_out,quality_failures,quality_failure_share,max_distance (empty where
/// unknown; RFC 4180 quoting).
std::string batchSummaryCsv(const std::vector<BatchJob>& jobs,
                            const std::vector<BatchResult>& results);

/// The summary as JSON: {"jobs": [...], "ok": n, "short": n, "failed": n, "skipped": n} with the
/// CSV's fields per job (null where unknown).
std::string batchSummaryJson(const std::vector<BatchJob>& jobs,
                             const std::vector<BatchResult>& results);

/// Writes batchSummaryCsv to PREFIX.csv and batchSummaryJson to PREFIX.json, each atomically.
/// Throws std::runtime_error naming the path when one cannot be written.
void writeBatchSummaries(const std::vector<BatchJob>& jobs, const std::vector<BatchResult>& results,
                         const std::string& prefix);

/// On --resume: gives each skipped job the result the earlier summary (the JSON file
/// writeBatchSummaries wrote) holds for the job with the same index and output, when it ended
/// "ok" or "short": its status, message, time and figures, with fromEarlierRun set. Jobs without
/// such an entry stay skipped. A missing, unreadable or invalid summary restores nothing.
void restoreEarlierResults(const std::vector<BatchJob>& jobs, std::vector<BatchResult>& results,
                           const std::filesystem::path& earlierSummary);

/// The name of a task ("voxelize", "convert", "remesh", "chain").
const char* taskName(BatchTask task);

}  // namespace voxremesh
