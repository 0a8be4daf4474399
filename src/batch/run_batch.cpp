// Running batch jobs in parallel within a thread budget (batch.h).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>

#include "voxremesh/action_chain.h"
#include "voxremesh/batch.h"
#include "voxremesh/criteria_file.h"
#include "voxremesh/errors.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/remesh_quality.h"
#include "voxremesh/sheets.h"
#include "voxremesh/volume.h"

namespace voxremesh {

namespace {

/// The settings of one job, checked.
struct JobSettings {
  std::optional<double> size, voxel;
  Id part = 0;
  std::optional<double> band;  ///< unset: VolumeSettings' band, remeshVolumeSettings' for remesh
  double featureAngle = 45.0, invalidAngle = 60.0;
  std::optional<DeckFormat> format;
  std::optional<std::string> criteria;  ///< a criteria file (criteria_file.h), remesh jobs
};

double numberSetting(const BatchJob& job, const std::string& key) {
  const std::string& text = job.settings.at(key);
  if (job.settingIsText.at(key))
    throw SettingError("setting " + key + " must be a number, not \"" + text + "\"");
  return std::strtod(text.c_str(), nullptr);  // a JSON number literal
}

JobSettings checkSettings(const BatchJob& job) {
  JobSettings settings;
  for (const auto& [key, text] : job.settings) {
    if (key == "size" || key == "voxel") {
      const double value = numberSetting(job, key);
      if (!(value > 0) || !std::isfinite(value))
        throw SettingError("setting " + key + " must be a positive size, not " + text);
      (key == "size" ? settings.size : settings.voxel) = value;
    } else if (key == "part") {
      const double value = numberSetting(job, key);
      if (value != std::floor(value) || value <= 0 || value > 9.2e18)
        throw SettingError("setting part must be a positive whole number, not " + text);
      settings.part = static_cast<Id>(value);
    } else if (key == "band") {
      settings.band = numberSetting(job, key);
    } else if (key == "feature_angle") {
      settings.featureAngle = numberSetting(job, key);
    } else if (key == "invalid_angle") {
      settings.invalidAngle = numberSetting(job, key);
    } else if (key == "format") {
      if (!job.settingIsText.at(key)) throw SettingError("setting format must be a string");
      settings.format = formatFromName(text);
    } else if (key == "criteria") {
      if (!job.settingIsText.at(key)) throw SettingError("setting criteria must be a file name");
      settings.criteria = text;
    } else {
      throw SettingError(
          "unknown setting \"" + key +
          "\" (size, voxel, part, band, feature_angle, invalid_angle, format, criteria)");
    }
  }
  if (settings.size && settings.voxel) throw SettingError("give either size or voxel, not both");
  return settings;
}

void runVoxelize(const BatchJob& job, const JobSettings& settings, BatchResult& result) {
  const FeModel model = readDeck(job.input);
  const Id part = choosePart(model, settings.part, job.input.string(), "the setting \"part\"");
  VolumeSettings volume;
  if (settings.band) volume.bandWidthVoxels = *settings.band;
  volume.invalidAngleDeg = settings.invalidAngle;
  if (settings.voxel) {
    volume.rule = VoxelSizeRule::Explicit;
    volume.voxelSize = *settings.voxel;
  } else {
    volume.rule = VoxelSizeRule::TargetElementSize;
    volume.targetElementSize = settings.size ? *settings.size : defaultTargetSize(model, part);
  }
  checkVolumeSettings(volume);
  SheetSettings sheetSettings;
  sheetSettings.featureAngleDeg = settings.featureAngle;
  const std::vector<Sheet> sheets = buildSheets(model, part, sheetSettings);
  if (sheets.empty())
    throw std::runtime_error("part " + std::to_string(part) + " has no shell with an area");
  std::size_t shells = 0;
  for (const Shell& shell : model.shells) shells += shell.part == part ? 1 : 0;
  result.elementsIn = shells;
  writeVolumes(buildSheetVolumes(sheets, volume, VolumeSource{job.input.string()}), job.output);
  result.message = "part " + std::to_string(part) + ", " + std::to_string(sheets.size()) +
                   (sheets.size() == 1 ? " sheet" : " sheets");
}

void runConvert(const BatchJob& job, const JobSettings& settings, BatchResult& result) {
  const FeModel model = readDeck(job.input);
  WriteOptions options;
  options.format = settings.format;
  writeDeck(model, job.output, options);
  result.elementsIn = result.elementsOut = model.shells.size();
}

void runRemesh(const BatchJob& job, const JobSettings& settings, BatchResult& result) {
  if (settings.voxel)
    throw SettingError("a remesh job takes the target element size \"size\", not \"voxel\"");
  FeModel deck = readDeck(job.input);
  const FeModel original = deck;
  RemeshSettings remesh;
  if (settings.size) remesh.targetSize = *settings.size;
  if (settings.part) remesh.parts = {settings.part};
  remesh.sheets.featureAngleDeg = settings.featureAngle;
  if (settings.band) remesh.volume.bandWidthVoxels = *settings.band;
  remesh.volume.invalidAngleDeg = settings.invalidAngle;
  if (settings.criteria) readCriteriaFile(*settings.criteria, remesh.optimizeSettings.quality);
  const RemeshReport report = remeshDeck(deck, remesh);
  std::size_t assessed = 0, failing = 0;
  double distance = 0.0;
  for (const PartQuality& part : assessRemeshedParts(
           original, deck, report, remesh.optimizeSettings.quality, remesh.sheets)) {
    assessed += part.elementsAfter;
    failing += part.failing();
    distance = std::max(distance, part.maxDistance());
  }
  WriteOptions options;
  options.format = settings.format;
  writeDeck(deck, job.output, options);
  result.elementsIn = original.shells.size();
  result.elementsOut = deck.shells.size();
  result.qualityFailures = failing;
  result.qualityFailureShare = assessed ? double(failing) / double(assessed) : 0.0;
  result.maxDistance = distance;
  result.partsKept = report.count(PartStatus::Kept);
  result.message = std::to_string(report.count(PartStatus::Remeshed)) + " parts remeshed, " +
                   std::to_string(report.count(PartStatus::Retried)) + " retried, " +
                   std::to_string(report.count(PartStatus::Kept)) + " kept";
  for (const RemeshedPart& part : report.parts)
    if (part.status == PartStatus::Kept)
      result.message += "; part " + std::to_string(part.plan.part) + " kept: " + part.reason;
  result.moreHangingNodes = report.moreHangingNodes();
  if (result.moreHangingNodes)
    result.message += "; nodes inside an edge of a part they share a seam with: " +
                      std::to_string(report.seamsAfter.hangingNodes) + " (" +
                      std::to_string(report.seamsBefore.hangingNodes) + " in the input)";
}

void runChainJob(const BatchJob& job, BatchResult& result) {
  if (!job.settings.empty())
    throw SettingError("a chain job takes its settings in the chain; use them as {KEY} there");
  const chain::Chain parsed = chain::parseChain(job.chain);
  chain::ChainState state;
  chain::runChain(parsed, state);
  for (const chain::ChainItem& item : state.stack)
    if (item.kind == chain::ChainItem::Kind::Deck) {
      result.elementsIn = item.deck.shells.size();
      break;
    }
  if (!state.stack.empty()) {
    const chain::ChainItem& top = state.stack.back();
    if (top.kind == chain::ChainItem::Kind::Deck) result.elementsOut = top.deck.shells.size();
    if (top.kind == chain::ChainItem::Kind::Mesh) result.elementsOut = top.mesh.faces.size();
  }
  if (state.quality) {
    result.qualityFailures = state.quality->failingAny;
    result.qualityFailureShare = state.quality->failingAnyShare;
    if (state.quality->distance) result.maxDistance = state.quality->distance->max();
  }
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(job.output, ignored))
    throw std::runtime_error("the chain did not write the job's output " + job.output.string());
}

BatchResult runJob(const BatchJob& job, const BatchOptions& options) {
  BatchResult result;
  result.index = job.index;
  result.name = job.name;
  const auto start = std::chrono::steady_clock::now();
  std::error_code ignored;
  if (options.resume && std::filesystem::is_regular_file(job.output, ignored) &&
      std::filesystem::file_size(job.output, ignored) > 0) {
    result.status = "skipped";
    result.message = "output exists (--resume)";
    return result;
  }
  try {
    if (!job.problem.empty()) throw SettingError(job.problem);
    if (job.output.has_parent_path()) std::filesystem::create_directories(job.output.parent_path());
    switch (job.task) {
      case BatchTask::Voxelize:
        runVoxelize(job, checkSettings(job), result);
        break;
      case BatchTask::Convert:
        runConvert(job, checkSettings(job), result);
        break;
      case BatchTask::Remesh:
        runRemesh(job, checkSettings(job), result);
        break;
      case BatchTask::Chain:
        runChainJob(job, result);
        break;
    }
    result.status = result.partsKept.value_or(0) > 0 || result.moreHangingNodes ? "short" : "ok";
  } catch (const std::bad_alloc&) {
    result.status = "failed";
    result.message = "out of memory";
  } catch (const std::exception& error) {
    result.status = "failed";
    result.message = error.what();
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

void parseShard(const std::string& text, BatchOptions& options) {
  const std::size_t slash = text.find('/');
  const auto whole = [](const std::string& part, unsigned long long& value) {
    errno = 0;
    char* end = nullptr;
    value = std::strtoull(part.c_str(), &end, 10);
    return !part.empty() && part[0] != '-' && end == part.c_str() + part.size() && errno == 0;
  };
  unsigned long long index = 0, count = 0;
  if (slash == std::string::npos || !whole(text.substr(0, slash), index) ||
      !whole(text.substr(slash + 1), count) || count == 0 || index >= count)
    throw SettingError("--shard expects I/N with 0 <= I < N (e.g. 0/4), not '" + text + "'");
  options.shardIndex = static_cast<std::size_t>(index);
  options.shardCount = static_cast<std::size_t>(count);
}

std::vector<BatchResult> runBatch(const std::vector<BatchJob>& jobs, const BatchOptions& options) {
  if (options.threads < 0) throw SettingError("--threads must be 0 (all cores) or more");
  if (options.shardCount == 0 || options.shardIndex >= options.shardCount)
    throw SettingError("the shard index must be below the shard count");
  std::vector<BatchResult> results(jobs.size());
  std::vector<std::size_t> mine;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (j % options.shardCount == options.shardIndex) {
      mine.push_back(j);
    } else {
      results[j].index = jobs[j].index;
      results[j].name = jobs[j].name;
      results[j].status = "other-shard";
    }
  }
  std::mutex doneMutex;
  std::size_t done = 0;
  const int threads =
      options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mine.size(), 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t k = range.begin(); k < range.end(); ++k) {
                          const std::size_t j = mine[k];
                          results[j] = runJob(jobs[j], options);
                          std::lock_guard<std::mutex> lock(doneMutex);
                          ++done;
                          if (options.onJobDone) options.onJobDone(results[j], done, mine.size());
                        }
                      });
  });
  return results;
}

}  // namespace voxremesh
