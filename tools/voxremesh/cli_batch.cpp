// voxremesh batch: the jobs of a JSON job file in parallel, with a summary (batch.h).
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/batch.h"
#include "voxremesh/progress.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage =
    "voxremesh batch JOBS.json [--threads N] [--resume] [--shard I/N] [--summary PREFIX] "
    "[--quiet] [--allow-outside]";

const char* const kHelp =
    "Runs the jobs of a JSON job file in parallel within the thread budget. A job that fails\n"
    "(unreadable input, invalid setting, ...) is reported and the others still run; the exit\n"
    "status is 1 when any job failed, else 3 when a remesh job kept parts unchanged (status\n"
    "\"short\"), else 0. Writes PREFIX.csv and PREFIX.json with one row per job:\n"
    "status, message, time, element counts and, for remesh jobs and chains with -quality, the\n"
    "elements failing a quality criterion, their share and the largest distance to the original.\n"
    "\n"
    "job file:\n"
    "  {\"threads\": 2, \"defaults\": {\"size\": 4},\n"
    "   \"jobs\": [{\"task\": \"voxelize\", \"input\": \"bracket.k\", \"output\": "
    "\"b_{size}.vdb\",\n"
    "             \"variants\": [{\"size\": 2}, {\"size\": 4}]},\n"
    "            {\"task\": \"convert\", \"inputs\": \"decks/*.k\", \"output\": "
    "\"out/{stem}.bdf\"},\n"
    "            {\"task\": \"chain\", \"input\": \"a.k\", \"output\": \"a.vdb\",\n"
    "             \"chain\": [\"-read\", \"{input}\", \"-voxelize\", \"-write\", \"{output}\"]}]}\n"
    "  tasks: voxelize (one part into a .vdb), convert (deck to deck), remesh (the deck's\n"
    "  parts, or \"part\", remeshed as voxremesh remesh does), chain (actions, see voxremesh\n"
    "  -help); settings: size voxel part band feature_angle invalid_angle format;\n"
    "  output placeholders: {stem} {name} {index} {SETTING}; paths relative to the job file.\n"
    "  Jobs write inside the job file's folder only (outputs and a chain's -write targets):\n"
    "  a job file that writes elsewhere is refused unless --allow-outside is given.\n"
    "\n"
    "options:\n"
    "  --threads N       thread budget for all jobs (default: the file's \"threads\", else all\n"
    "                    cores)\n"
    "  --resume          skip jobs whose output exists (outputs are written atomically, so an\n"
    "                    existing one is complete)\n"
    "  --shard I/N       run only the jobs whose number is I modulo N (0 <= I < N), e.g.\n"
    "                    --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT with 0-based tasks\n"
    "  --summary PREFIX  where the summary goes (default: JOBS without .json plus \".summary\",\n"
    "                    and \".shardIofN\" when sharded)\n"
    "  --quiet           no progress line (it is shown only on a terminal anyway)\n"
    "  --allow-outside   let jobs write outside the job file's folder\n";

}  // namespace

int runBatchCommand(const std::vector<std::string>& args) {
  if (wantsHelp(args)) {
    std::printf("usage: %s\n\n%s", kUsage, kHelp);
    return 0;
  }
  const ParsedArgs parsed = parseArgs(args,
                                      {{"--threads", true},
                                       {"--resume", false},
                                       {"--shard", true},
                                       {"--summary", true},
                                       {"--quiet", false},
                                       {"--allow-outside", false}},
                                      1, 1, kUsage);
  BatchOptions options;
  options.resume = parsed.has("--resume");
  std::optional<int> threads;
  // A malformed option value is a bad command line (exit 2), unlike a bad job file.
  parseOptionValues(kUsage, [&] {
    if (const auto shard = parsed.value("--shard")) parseShard(*shard, options);
    if (const auto text = parsed.value("--threads"))
      threads = static_cast<int>(parseIntegerInRange("--threads", *text, 0, kMaxBatchThreads));
  });
  const auto summary = parsed.value("--summary");
  if (summary && summary->empty()) throw UsageError("option --summary needs a value", kUsage);
  const std::filesystem::path jobFile = parsed.positional[0];
  const BatchFile file = readBatchFile(jobFile, parsed.has("--allow-outside"));
  options.threads = threads ? *threads : file.threads;
  std::filesystem::path prefix = jobFile;
  if (prefix.extension() == ".json") prefix.replace_extension();
  std::string prefixText = prefix.string() + ".summary";
  if (options.shardCount > 1)
    prefixText = prefix.string() + ".shard" + std::to_string(options.shardIndex) + "of" +
                 std::to_string(options.shardCount) + ".summary";
  if (summary) prefixText = *summary;

  ProgressLine progress(stderr, ProgressLine::isTerminal(stderr) && !parsed.has("--quiet"));
  options.onJobDone = [&](const BatchResult& result, std::size_t done, std::size_t total) {
    progress.clear();
    if (result.status == "failed") {
      std::fprintf(stderr, "FAILED %s: %s\n", result.name.c_str(), result.message.c_str());
    } else {
      std::printf("%-7s %s (%.2f s)\n", result.status.c_str(), result.name.c_str(), result.seconds);
      std::fflush(stdout);
    }
    progress.update("batch", std::to_string(done) + "/" + std::to_string(total) + " jobs",
                    static_cast<double>(done) / static_cast<double>(total));
  };
  std::vector<BatchResult> results = runBatch(file.jobs, options);
  progress.clear();
  // A resumed run keeps the earlier results of the jobs it skips (their summary rows and the
  // exit code), read from the earlier summary before it is replaced.
  if (options.resume) restoreEarlierResults(file.jobs, results, prefixText + ".json");
  writeBatchSummaries(file.jobs, results, prefixText);
  // Jobs run now by status; skipped ones (those restored from the earlier run among them).
  std::size_t ok = 0, failed = 0, skipped = 0, shortJobs = 0, earlier = 0, anyShort = 0;
  for (const BatchResult& result : results) {
    anyShort += result.status == "short" ? 1 : 0;
    if (result.fromEarlierRun || result.status == "skipped") {
      ++skipped;
      earlier += result.fromEarlierRun ? 1 : 0;
      continue;
    }
    ok += result.status == "ok" ? 1 : 0;
    shortJobs += result.status == "short" ? 1 : 0;
    failed += result.status == "failed" ? 1 : 0;
  }
  printOutput(std::to_string(ok) + " ok, " + std::to_string(shortJobs) + " short, " +
              std::to_string(failed) + " failed, " + std::to_string(skipped) + " skipped (" +
              std::to_string(earlier) + " with their earlier result); summary in " + prefixText +
              ".csv and .json\n");
  return failed > 0 ? 1 : (anyShort > 0 ? kExitShortfall : 0);
}

}  // namespace voxremesh::cli
