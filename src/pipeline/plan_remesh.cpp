// Planning a remesh: parts, target sizes (pipeline.h).
#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "pipeline/remesh_part.h"
#include "voxremesh/errors.h"
#include "voxremesh/pipeline.h"

namespace voxremesh {

namespace {

std::string listIds(const std::vector<Id>& ids) {
  std::string text;
  for (const Id id : ids) text += (text.empty() ? "" : ", ") + std::to_string(id);
  return text;
}

}  // namespace

std::vector<Id> shellPartIds(const FeModel& model) {
  std::set<Id> parts;
  for (const Shell& shell : model.shells) parts.insert(shell.part);
  return {parts.begin(), parts.end()};
}

Id choosePart(const FeModel& model, Id requested, const std::string& deckName,
              const std::string& option) {
  const std::vector<Id> parts = shellPartIds(model);
  if (parts.empty()) throw std::runtime_error(deckName + " has no shell elements");
  if (requested != 0) {
    if (!std::binary_search(parts.begin(), parts.end(), requested))
      throw std::runtime_error(
          (model.findPart(requested)
               ? "part " + std::to_string(requested) + " of " + deckName + " has no shells"
               : "no part " + std::to_string(requested) + " in " + deckName) +
          "; parts with shells: " + listIds(parts));
    return requested;
  }
  if (parts.size() > 1)
    throw SettingError(deckName + " has " + std::to_string(parts.size()) +
                       " parts with shells; choose one with " + option + " (" + listIds(parts) +
                       ")");
  return parts.front();
}

namespace {

/// The median edge of the shells of `part` (of all shells when part is 0), with the node index
/// given (built once for many parts).
double medianEdge(const FeModel& model, const std::unordered_map<Id, std::size_t>& index, Id part) {
  std::vector<double> lengths;
  for (const Shell& shell : model.shells) {
    if (part != 0 && shell.part != part) continue;
    for (int c = 0; c < shell.nodeCount; ++c) {
      const auto& a = model.nodes[index.at(shell.nodes[static_cast<std::size_t>(c)])].xyz;
      const auto& b =
          model.nodes[index.at(shell.nodes[static_cast<std::size_t>((c + 1) % shell.nodeCount)])]
              .xyz;
      lengths.push_back(std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                  (a[2] - b[2]) * (a[2] - b[2])));
    }
  }
  const std::string what = part != 0 ? "part " + std::to_string(part) : std::string("the deck");
  if (lengths.empty()) throw std::invalid_argument(what + " has no shells");
  const std::size_t middle = lengths.size() / 2;
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(middle),
                   lengths.end());
  double median = lengths[middle];
  if (lengths.size() % 2 == 0)
    median = (median + *std::max_element(lengths.begin(),
                                         lengths.begin() + static_cast<std::ptrdiff_t>(middle))) /
             2;
  if (!(median > 0))
    throw std::invalid_argument("the shells of " + what + " have zero-length sides only");
  if (!std::isfinite(median))
    throw std::invalid_argument("the median side of the shells of " + what +
                                " is too long to measure (coordinates near the largest number "
                                "a double holds); no element size can be chosen for it");
  return median;
}

}  // namespace

double defaultTargetSize(const FeModel& model, Id part) {
  return medianEdge(model, model.nodeIndex(), part);
}

double deckTargetSize(const FeModel& model) {
  return medianEdge(model, model.nodeIndex(), 0);
}

std::vector<PartPlan> planRemesh(const FeModel& model, const RemeshSettings& settings) {
  if (!std::isfinite(settings.targetSize) || settings.targetSize < 0)
    throw SettingError("the target size must be a positive number (got " +
                       std::to_string(settings.targetSize) + ")");
  if (settings.threads < 0)
    throw SettingError("the number of threads must be 0 (all cores) or more");
  checkVolumeSettings(settings.volume);
  if (!(settings.volume.bandWidthVoxels >= kExtractionBandVoxels))
    throw SettingError("the band of the remesh volumes must be at least " +
                       pipeline::formatNumber(kExtractionBandVoxels) +
                       " voxels each side (the extraction reads the distance at cell corners "
                       "up to sqrt(3) voxels from the surface); got " +
                       pipeline::formatNumber(settings.volume.bandWidthVoxels));
  const std::vector<Id> withShells = shellPartIds(model);
  std::vector<Id> chosen = settings.parts.empty() ? withShells : settings.parts;
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  for (const auto& [part, size] : settings.partSizes)
    if (!std::isfinite(size) || size <= 0)
      throw SettingError("the target size of part " + std::to_string(part) +
                         " must be a positive number (got " + std::to_string(size) + ")");
  if (settings.retries < 0 || settings.retries > 8)
    throw SettingError("the number of retries must be within 0..8");
  if (!(settings.narrowFeatureVoxels >= 0 && settings.narrowFeatureVoxels <= 16))
    throw SettingError("the narrow-feature width must be within 0..16 voxels");
  if (!(settings.finestVoxelShare > 0 && settings.finestVoxelShare <= 1))
    throw SettingError("the finest voxel share must be within (0, 1]");
  std::vector<PartPlan> plans;
  const double deckSize = settings.targetSize > 0 ? settings.targetSize : deckTargetSize(model);
  std::unordered_map<Id, std::size_t> shellCount;
  for (const Shell& shell : model.shells) ++shellCount[shell.part];
  for (const Id part : chosen) {
    if (!std::binary_search(withShells.begin(), withShells.end(), part))
      throw SettingError((model.findPart(part) ? "part " + std::to_string(part) + " has no shells"
                                               : "no part " + std::to_string(part)) +
                         " to remesh; parts with shells: " + listIds(withShells));
    PartPlan plan;
    plan.part = part;
    if (const Part* found = model.findPart(part)) plan.name = found->name;
    plan.shells = shellCount[part];
    const auto size = settings.partSizes.find(part);
    plan.targetSize = size != settings.partSizes.end() ? size->second : deckSize;
    plans.push_back(std::move(plan));
  }
  for (const auto& [part, size] : settings.partSizes)
    if (!std::binary_search(chosen.begin(), chosen.end(), part))
      throw SettingError("a size is given for part " + std::to_string(part) +
                         ", which is not remeshed; parts with shells: " + listIds(withShells));
  return plans;
}

std::vector<SheetVolume> partVolumes(const FeModel& model, const PartPlan& plan,
                                     const RemeshSettings& settings) {
  std::vector<Sheet> sheets = buildSheets(model, plan.part, settings.sheets);
  if (sheets.empty())
    throw std::runtime_error("part " + std::to_string(plan.part) +
                             " has no shell with an area to remesh");
  VolumeSettings volume = settings.volume;
  volume.rule = VoxelSizeRule::TargetElementSize;
  volume.targetElementSize = plan.targetSize;
  std::vector<Volume> volumes = buildSheetVolumes(sheets, volume);
  std::vector<SheetVolume> result;
  result.reserve(sheets.size());
  for (std::size_t k = 0; k < sheets.size(); ++k)
    result.push_back({std::move(sheets[k]), std::move(volumes[k])});
  return result;
}

}  // namespace voxremesh
