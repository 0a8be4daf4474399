// Scripted batch: job files (structure, globs, variants), parallel runs where a broken job does
// not stop the others, --resume, --shard, and the summaries; through the library and the CLI.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "json/json.h"
#include "support/test_support.h"
#include "voxremesh/batch.h"
#include "voxremesh/errors.h"
#include "voxremesh/io.h"
#include "voxremesh/volume.h"

namespace fs = std::filesystem;
using namespace voxremesh;
using voxremesh::test::contains;
using voxremesh::test::quoted;
using voxremesh::test::readText;
using voxremesh::test::runCli;
using voxremesh::test::samplePart;
using voxremesh::test::scratchDir;
using voxremesh::test::writeText;

namespace {

/// A job file with two good conversions, one missing input and one invalid setting.
std::string mixedJobs(const fs::path& sample) {
  return "{\n"
         "  \"threads\": 2,\n"
         "  \"jobs\": [\n"
         "    {\"task\": \"convert\", \"input\": \"" +
         sample.string() +
         "\", \"output\": \"out/{stem}.bdf\"},\n"
         "    {\"task\": \"convert\", \"name\": \"broken\", \"input\": \"missing.k\", "
         "\"output\": \"out/missing.obj\"},\n"
         "    {\"task\": \"voxelize\", \"name\": \"bad-size\", \"input\": \"" +
         sample.string() +
         "\", \"output\": \"out/bad.vdb\", \"settings\": {\"size\": -2}},\n"
         "    {\"task\": \"convert\", \"name\": \"obj\", \"input\": \"" +
         sample.string() +
         "\", \"output\": \"out/{name}.obj\"}\n"
         "  ]\n"
         "}\n";
}

std::string inputErrorOf(const fs::path& file, const std::string& text) {
  writeText(file, text);
  try {
    readBatchFile(file);
  } catch (const InputError& error) {
    return std::to_string(error.line()) + ": " + error.what();
  }
  return "(accepted)";
}

}  // namespace

TEST(Batch, JobFileExpansion) {
  const fs::path dir = scratchDir("batch_expand");
  writeText(dir / "decks" / "a.k", "*KEYWORD\n*END\n");
  writeText(dir / "decks" / "b.k", "*KEYWORD\n*END\n");
  writeText(dir / "decks" / "c.txt", "x\n");
  writeText(dir / "jobs.json",
            R"({"defaults": {"band": 4},
 "jobs": [
  {"task": "voxelize", "inputs": "decks/*.k", "output": "out/{stem}_{size}.vdb",
   "settings": {"size": 2}, "variants": [{"size": 1}, {"size": 3, "format": "k"}]},
  {"task": "chain", "name": "c", "input": "decks/a.k", "output": "x/{name}.vdb",
   "chain": ["-read", "{input}", "-write", "{output}"]}
 ]})");
  const BatchFile file = readBatchFile(dir / "jobs.json");
  ASSERT_EQ(file.jobs.size(), 5u);
  EXPECT_EQ(file.jobs[0].name, "a-1");
  EXPECT_EQ(file.jobs[0].output, dir / "out" / "a_1.vdb");
  EXPECT_EQ(file.jobs[1].output, dir / "out" / "a_3.vdb");
  EXPECT_EQ(file.jobs[1].settings.at("format"), "k");
  EXPECT_EQ(file.jobs[1].settings.at("band"), "4");
  EXPECT_EQ(file.jobs[2].input, dir / "decks" / "b.k");
  EXPECT_EQ(file.jobs[3].name, "b-2");
  EXPECT_EQ(file.jobs[4].task, BatchTask::Chain);
  EXPECT_EQ(file.jobs[4].chain[1], (dir / "decks" / "a.k").string());
  EXPECT_EQ(file.jobs[4].chain[3], (dir / "x" / "c.vdb").string());
  EXPECT_EQ(file.jobs[4].index, 4u);

  const fs::path bad = dir / "bad.json";
  EXPECT_TRUE(contains(inputErrorOf(bad, "{\"jobs\": [}\n"), "1: "));
  EXPECT_TRUE(contains(inputErrorOf(bad, "{\n\"jobs\": []\n}"), "non-empty"));
  EXPECT_TRUE(contains(inputErrorOf(bad,
                                    "{\"jobs\": [\n{\"task\": \"voxelize\", \"input\": "
                                    "\"a.k\", \"output\": \"a.vdb\", \"colour\": 1}]}"),
                       "2: "));
  EXPECT_TRUE(contains(inputErrorOf(bad,
                                    "{\"jobs\": [{\"task\": \"fly\", \"input\": \"a.k\", "
                                    "\"output\": \"a.vdb\"}]}"),
                       "unknown task \"fly\""));
  EXPECT_TRUE(contains(inputErrorOf(bad,
                                    "{\"jobs\": [{\"task\": \"convert\", \"inputs\": "
                                    "\"none/*.k\", \"output\": \"a.bdf\"}]}"),
                       "no file matches"));
  EXPECT_TRUE(contains(inputErrorOf(bad,
                                    "{\"jobs\": [{\"task\": \"convert\", \"input\": "
                                    "\"a.k\"}]}"),
                       "no \"output\""));
  EXPECT_TRUE(contains(inputErrorOf(bad,
                                    "{\"jobs\": [{\"task\": \"convert\", \"input\": "
                                    "\"a.k\", \"output\": \"a.bdf\", \"settings\": "
                                    "{\"size\": [1]}}]}"),
                       "must be a number or a string"));
  EXPECT_THROW(readBatchFile(dir / "nothing.json"), InputError);
  // Two jobs writing one file, or a job writing over its input, would lose a result silently.
  EXPECT_TRUE(contains(inputErrorOf(bad,
                                    "{\"jobs\": [{\"task\": \"convert\", \"inputs\": "
                                    "\"decks/*.k\", \"output\": \"out/all.obj\"}]}"),
                       "jobs \"a\" and \"b\" both write"));
  EXPECT_TRUE(contains(inputErrorOf(bad,
                                    "{\"jobs\": [{\"task\": \"convert\", \"input\": "
                                    "\"decks/a.k\", \"output\": \"decks/./a.k\"}]}"),
                       "would write over its input"));
  // Writing outside the job file's folder: refused unless allowed.
  const std::string outside =
      "{\"jobs\": [{\"task\": \"convert\", \"input\": \"decks/a.k\",\n"
      "  \"output\": \"../../elsewhere.obj\"}]}";
  const std::string refusal = inputErrorOf(bad, outside);
  EXPECT_TRUE(contains(refusal, "2: job \"a\" writes ")) << refusal;
  EXPECT_TRUE(contains(refusal, "elsewhere.obj, outside the job file's folder")) << refusal;
  EXPECT_FALSE(contains(refusal, "..")) << refusal;
  writeText(bad, outside);
  EXPECT_EQ(readBatchFile(bad, true).jobs.size(), 1u);
  EXPECT_TRUE(contains(inputErrorOf(bad,
                                    "{\"jobs\": [{\"task\": \"convert\", \"input\": "
                                    "\"decks/a.k\", \"output\": \"/tmp/a.obj\"}]}"),
                       "outside the job file's folder"));
  EXPECT_TRUE(contains(inputErrorOf(bad,
                                    "{\"jobs\": [{\"task\": \"chain\", \"input\": "
                                    "\"decks/a.k\", \"output\": \"out/a.obj\", \"chain\": "
                                    "[\"-read\", \"{input}\", \"-write\", \"/tmp/b.obj\", "
                                    "\"-write\", \"{output}\"]}]}"),
                       "writes /tmp/b.obj, outside"));
  // Inside, through a folder name with "..": accepted.
  writeText(bad,
            "{\"jobs\": [{\"task\": \"convert\", \"input\": \"decks/a.k\", \"output\": "
            "\"out/../out2/a.obj\"}]}");
  EXPECT_EQ(readBatchFile(bad).jobs.size(), 1u);
}

TEST(Batch, BrokenJobsFailAloneAndShardsSplitTheWork) {
  const fs::path dir = scratchDir("batch_run");
  writeText(dir / "jobs.json", mixedJobs(samplePart()));
  const BatchFile file = readBatchFile(dir / "jobs.json");
  BatchOptions options;
  options.threads = 2;
  std::vector<BatchResult> results = runBatch(file.jobs, options);
  ASSERT_EQ(results.size(), 4u);
  EXPECT_EQ(results[0].status, "ok");
  EXPECT_EQ(results[1].status, "failed");
  EXPECT_TRUE(contains(results[1].message, "missing.k")) << results[1].message;
  EXPECT_EQ(results[2].status, "failed");
  EXPECT_TRUE(contains(results[2].message, "size")) << results[2].message;
  EXPECT_EQ(results[3].status, "ok");
  EXPECT_FALSE(fs::exists(dir / "out" / "missing.obj"));
  EXPECT_FALSE(fs::exists(dir / "out" / "bad.vdb"));
  const FeModel converted = readDeck(dir / "out" / "hat_rail.bdf");
  EXPECT_EQ(results[0].elementsIn, converted.shells.size());

  // The summary: one row per job, unknown values empty / null.
  const std::string csv = batchSummaryCsv(file.jobs, results);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
  EXPECT_TRUE(contains(csv, ",failed,")) << csv;
  const json::Json summary = json::parseJson(batchSummaryJson(file.jobs, results));
  EXPECT_EQ(summary["ok"].number, 2);
  EXPECT_EQ(summary["failed"].number, 2);
  EXPECT_EQ(summary["jobs"].items[0]["quality_failures"].type, json::Json::Type::Null);

  // --resume skips the finished jobs; the broken ones fail again.
  options.resume = true;
  results = runBatch(file.jobs, options);
  EXPECT_EQ(results[0].status, "skipped");
  EXPECT_EQ(results[1].status, "failed");
  EXPECT_EQ(results[3].status, "skipped");

  // Shards: every job in exactly one shard.
  options.resume = false;
  parseShard("1/2", options);
  results = runBatch(file.jobs, options);
  EXPECT_EQ(results[0].status, "other-shard");
  EXPECT_EQ(results[1].status, "failed");
  EXPECT_EQ(results[2].status, "other-shard");
  EXPECT_EQ(results[3].status, "ok");
  EXPECT_THROW(parseShard("2/2", options), SettingError);
  EXPECT_THROW(parseShard("-1/2", options), SettingError);
  EXPECT_THROW(parseShard("1", options), SettingError);
}

TEST(Batch, RemeshAndQualityChainsFillTheQualityColumns) {
  const fs::path dir = scratchDir("batch_quality");
  const std::string sample = samplePart().string();
  writeText(dir / "jobs.json",
            "{\"jobs\": [\n"
            "  {\"task\": \"remesh\", \"input\": \"" +
                sample +
                "\", \"output\": \"out/remeshed.k\", \"settings\": {\"size\": 5}},\n"
                "  {\"task\": \"chain\", \"input\": \"" +
                sample +
                "\", \"output\": \"out/chained.k\", \"chain\": [\"-read\", \"{input}\", "
                "\"-voxelize\", \"size=5\", \"-extract\", \"-optimize\", \"-quality\", "
                "\"-write\", \"{output}\"]},\n"
                "  {\"task\": \"remesh\", \"name\": \"voxel\", \"input\": \"" +
                sample +
                "\", \"output\": \"out/voxel.k\", \"settings\": {\"voxel\": 2}}\n"
                "]}\n");
  const BatchFile file = readBatchFile(dir / "jobs.json");
  ASSERT_EQ(file.jobs.size(), 3u);
  EXPECT_EQ(file.jobs[0].task, BatchTask::Remesh);
  BatchOptions options;
  options.threads = 2;
  const std::vector<BatchResult> results = runBatch(file.jobs, options);
  ASSERT_EQ(results[0].status, "ok") << results[0].message;
  ASSERT_EQ(results[1].status, "ok") << results[1].message;
  EXPECT_EQ(results[2].status, "failed");
  EXPECT_TRUE(contains(results[2].message, "not \"voxel\"")) << results[2].message;
  EXPECT_FALSE(fs::exists(dir / "out" / "voxel.k"));
  // The remesh job and the chain that runs the same stages agree.
  const BatchResult& remesh = results[0];
  ASSERT_TRUE(remesh.qualityFailures && remesh.qualityFailureShare && remesh.maxDistance);
  // The optimised rail passes every criterion at its size (its last two failing quads, at the
  // rail's ends, are split into triangle pairs); the chain must count the same.
  EXPECT_LE(*remesh.qualityFailures, 2u);
  EXPECT_EQ(remesh.elementsOut, readDeck(dir / "out" / "remeshed.k").shells.size());
  EXPECT_DOUBLE_EQ(*remesh.qualityFailureShare,
                   double(*remesh.qualityFailures) / double(*remesh.elementsOut));
  EXPECT_GT(*remesh.maxDistance, 0.0);
  EXPECT_LT(*remesh.maxDistance, 0.25 * 5);  // the distance limit at size 5
  EXPECT_EQ(results[1].qualityFailures, remesh.qualityFailures);
  EXPECT_EQ(results[1].qualityFailureShare, remesh.qualityFailureShare);
  ASSERT_TRUE(results[1].maxDistance);
  EXPECT_NEAR(*results[1].maxDistance, *remesh.maxDistance, 1e-9);
  EXPECT_FALSE(results[2].qualityFailures);
  // Summaries: the share column, empty / null where unknown.
  const std::string csv = batchSummaryCsv(file.jobs, results);
  EXPECT_TRUE(contains(csv, ",quality_failures,quality_failure_share,max_distance\n")) << csv;
  EXPECT_TRUE(contains(csv, ",,,\n")) << csv;  // the failed job
  const json::Json summary = json::parseJson(batchSummaryJson(file.jobs, results));
  EXPECT_EQ(summary["jobs"].items[0]["quality_failure_share"].number, *remesh.qualityFailureShare);
  EXPECT_EQ(summary["jobs"].items[0]["quality_failures"].number, double(*remesh.qualityFailures));
  EXPECT_EQ(summary["jobs"].items[2]["quality_failure_share"].type, json::Json::Type::Null);
}

TEST(Batch, ARemeshJobTakesACriteriaFileBesideTheJobFile) {
  // The sample rail at size 5, once with the default criteria and once with a file (named
  // relative to the job file's folder) that fails a skew past 5 degrees (the default: 40), which
  // no optimisation brings every quad of a bent part under, and accepts any failing share (the
  // part is not retried): the summary's failing count follows the file. A file that is not there
  // fails its job alone.
  const fs::path dir = scratchDir("batch_criteria");
  const std::string sample = samplePart().string();
  writeText(dir / "criteria" / "strict.txt", "skew 0 2 4 5 60\nfailing_share 1\n");
  writeText(dir / "jobs.json",
            "{\"jobs\": [\n"
            "  {\"task\": \"remesh\", \"input\": \"" +
                sample +
                "\", \"output\": \"default.k\", \"settings\": {\"size\": 5}},\n"
                "  {\"task\": \"remesh\", \"input\": \"" +
                sample +
                "\", \"output\": \"strict.k\", \"settings\": {\"size\": 5, \"criteria\": "
                "\"criteria/strict.txt\"}},\n"
                "  {\"task\": \"remesh\", \"input\": \"" +
                sample +
                "\", \"output\": \"missing.k\", \"settings\": {\"size\": 5, \"criteria\": "
                "\"criteria/missing.txt\"}}\n"
                "]}\n");
  const BatchFile file = readBatchFile(dir / "jobs.json");
  ASSERT_EQ(file.jobs.size(), 3u);
  EXPECT_EQ(file.jobs[1].settings.at("criteria"), (dir / "criteria" / "strict.txt").string());
  BatchOptions options;
  options.threads = 2;
  const std::vector<BatchResult> results = runBatch(file.jobs, options);
  ASSERT_EQ(results[0].status, "ok") << results[0].message;
  ASSERT_TRUE(results[0].qualityFailures && results[1].qualityFailures);
  EXPECT_GT(*results[1].qualityFailures, *results[0].qualityFailures) << results[1].message;
  EXPECT_EQ(results[2].status, "failed");
  EXPECT_TRUE(contains(results[2].message, "missing.txt")) << results[2].message;
  EXPECT_FALSE(fs::exists(dir / "missing.k"));
}

TEST(BatchCli, OneBrokenJobThenResume) {
  const fs::path dir = scratchDir("batch_cli");
  writeText(dir / "jobs.json", mixedJobs(samplePart()));
  const auto first = runCli("batch " + quoted(dir / "jobs.json") + " --threads 2");
  EXPECT_EQ(first.exitCode, 1) << first.output;
  EXPECT_TRUE(contains(first.output, "FAILED broken")) << first.output;
  EXPECT_TRUE(
      contains(first.output, "2 ok, 0 short, 2 failed, 0 skipped (0 with their earlier result)"))
      << first.output;
  EXPECT_FALSE(contains(first.output, "\r"));  // no progress line off a terminal
  EXPECT_TRUE(fs::exists(dir / "out" / "hat_rail.bdf"));
  EXPECT_TRUE(fs::exists(dir / "out" / "obj.obj"));
  const std::string csv = readText(dir / "jobs.summary.csv");
  EXPECT_TRUE(contains(csv, "broken")) << csv;
  EXPECT_NO_THROW(json::parseJson(readText(dir / "jobs.summary.json")));

  const auto resumed = runCli("batch " + quoted(dir / "jobs.json") + " --resume");
  EXPECT_EQ(resumed.exitCode, 1);
  EXPECT_TRUE(
      contains(resumed.output, "0 ok, 0 short, 2 failed, 2 skipped (2 with their earlier result)"))
      << resumed.output;
  // The skipped jobs keep their earlier results in the new summary.
  const json::Json resumedSummary = json::parseJson(readText(dir / "jobs.summary.json"));
  std::size_t restored = 0;
  for (const json::Json& job : resumedSummary["jobs"].items) {
    if (job["from_earlier_run"].type != json::Json::Type::Bool || !job["from_earlier_run"].boolean)
      continue;
    ++restored;
    EXPECT_EQ(job["status"].text, "ok");
    EXPECT_EQ(job["elements_out"].type, json::Json::Type::Number);
  }
  EXPECT_EQ(restored, 2u);

  // Sharded runs write their own summaries.
  const auto shard = runCli("batch " + quoted(dir / "jobs.json") + " --shard 0/2 --resume");
  EXPECT_TRUE(fs::exists(dir / "jobs.shard0of2.summary.csv")) << shard.output;

  // A broken job file: message with file and line, exit 1, no summary.
  writeText(dir / "bad.json", "{\"jobs\": [\n  {\"task\": \"convert\",}\n]}\n");
  const auto bad = runCli("batch " + quoted(dir / "bad.json"));
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_TRUE(contains(bad.output, "bad.json:2")) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "bad.summary.csv"));
  const auto usage = runCli("batch " + quoted(dir / "jobs.json") + " --shard 3");
  EXPECT_EQ(usage.exitCode, 2);
  EXPECT_TRUE(contains(usage.output, "--shard expects I/N")) << usage.output;
}

TEST(BatchCli, MalformedOptionValuesAreUsageErrors) {
  const fs::path dir = scratchDir("batch_cli_usage");
  writeText(dir / "jobs.json", mixedJobs(samplePart()));
  const fs::path summary = dir / "jobs.summary.csv";
  for (const char* options : {"--threads x", "--threads -1", "--threads 5000", "--threads=",
                              "--shard 2/2", "--shard 0/0", "--shard x/2", "--summary="}) {
    SCOPED_TRACE(options);
    const auto run = runCli("batch " + quoted(dir / "jobs.json") + " " + options);
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_TRUE(contains(run.output, "usage: voxremesh batch JOBS.json")) << run.output;
    EXPECT_FALSE(fs::exists(summary));  // refused before any job ran
  }
  const auto threads = runCli("batch " + quoted(dir / "jobs.json") + " --threads x");
  EXPECT_TRUE(contains(threads.output, "--threads expects a whole number, not 'x'"))
      << threads.output;
}

TEST(Batch, VoxelizeJobWritesOneVolumePerSheet) {
  VOXREMESH_REQUIRE_SHARED_DECK(wheel, "wheel.k");
  const fs::path dir = scratchDir("batch_sheets");
  writeText(dir / "jobs.json", "{\"jobs\": [{\"task\": \"voxelize\", \"input\": \"" +
                                   wheel.string() + "\", \"output\": \"out/wheel.vdb\"}]}\n");
  const std::vector<BatchResult> results = runBatch(readBatchFile(dir / "jobs.json").jobs, {});
  ASSERT_EQ(results.at(0).status, "ok") << results[0].message;
  EXPECT_EQ(results[0].message, "part 1, 3 sheets");
  const std::vector<Volume> volumes = readVolumes(dir / "out" / "wheel.vdb");
  ASSERT_EQ(volumes.size(), 3u);  // rim front, rim back, disc
  for (const Volume& volume : volumes) EXPECT_EQ(volume.junctionCurves().size(), 1u);
}
