// remeshPart: one part through its sheets and volumes, at finer voxels until its mesh passes the
// acceptance, else kept (remesh_part.h).
#include <algorithm>
#include <chrono>
#include <exception>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "pipeline/remesh_part.h"
#include "voxremesh/errors.h"

namespace voxremesh::pipeline {

namespace {

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// One attempt's mesh: every sheet written into a volume of the given voxel size, extracted and
/// optimised (one sheet's volume alive at a time), then joined at the junctions; the faces
/// folded against their sheet flagged in `folded`.
QuadMesh meshAtVoxel(const std::vector<Sheet>& sheets, double voxel, const PartPlan& plan,
                     const RemeshSettings& settings, double junctionSpacing, RemeshedPart& part,
                     std::vector<std::uint8_t>& folded, const StageCallback& stage) {
  std::vector<QuadMesh> sheetMeshes;
  folded.clear();
  VolumeSettings volumeSettings = settings.volume;
  volumeSettings.rule = VoxelSizeRule::TargetElementSize;
  volumeSettings.targetElementSize = voxel;
  ExtractSettings extractSettings = settings.extract;
  if (extractSettings.junctionSpacing <= 0.0) extractSettings.junctionSpacing = junctionSpacing;
  for (std::size_t k = 0; k < sheets.size(); ++k) {
    const std::string where = sheets.size() > 1 ? "sheet " + std::to_string(k) + ": " : "";
    if (stage) stage("volume");
    auto start = std::chrono::steady_clock::now();
    const Volume volume = buildVolume({sheets[k]}, volumeSettings);
    part.volumeSeconds += since(start);
    if (stage) stage("extract");
    start = std::chrono::steady_clock::now();
    ExtractStats stats;
    try {
      sheetMeshes.push_back(extractQuadMesh(volume, extractSettings, &stats));
    } catch (const std::runtime_error& error) {
      throw std::runtime_error(where + error.what());
    }
    addExtractStats(part.extract, stats);
    part.extractSeconds += since(start);
    const QuadMesh surface = sheetSurface(sheets[k]);
    const ReferenceSurface original(surface);
    if (settings.optimize) {
      if (stage) stage("optimize");
      start = std::chrono::steady_clock::now();
      OptimizeSettings optimizeSettings = settings.optimizeSettings;
      optimizeSettings.quality.targetSize = voxel;
      optimizeQuadMesh(sheetMeshes.back(), original, optimizeSettings);
      part.optimizeSeconds += since(start);
    }
    const std::vector<std::uint8_t> sheetFolds =
        foldedAgainstSheet(sheetMeshes.back(), surface, original);
    folded.insert(folded.end(), sheetFolds.begin(), sheetFolds.end());
  }
  QuadMesh mesh = joinAtJunctions(sheetMeshes);
  mesh.part = plan.part;
  return mesh;
}

/// The voxel that resolves every sheet: the target size, or narrowFeatureVoxels times finer than
/// the narrowest sheet's width when that is smaller (never below the finest voxel). `note`
/// receives the reduction in words.
double resolvingVoxel(const std::vector<Sheet>& sheets, const PartPlan& plan,
                      const RemeshSettings& settings, std::string& note) {
  const double finest = settings.finestVoxelShare * plan.targetSize;
  double narrowest = std::numeric_limits<double>::infinity();
  std::size_t narrowSheet = 0;
  for (std::size_t k = 0; k < sheets.size(); ++k) {
    const double width = sheetWidth(sheets[k]);
    if (width < narrowest) {
      narrowest = width;
      narrowSheet = k;
    }
  }
  if (!(settings.narrowFeatureVoxels > 0) ||
      !(narrowest < settings.narrowFeatureVoxels * plan.targetSize))
    return plan.targetSize;
  const double voxel = std::max(finest, narrowest / settings.narrowFeatureVoxels);
  note = "voxel reduced to " + formatNumber(voxel) + ": sheet " + std::to_string(narrowSheet) +
         " is " + formatNumber(narrowest) + " wide, narrower than " +
         formatNumber(settings.narrowFeatureVoxels) + " voxels of " + formatNumber(plan.targetSize);
  return voxel;
}

}  // namespace

RemeshedPart remeshPart(const FeModel& model, const PartPlan& plan, const RemeshSettings& settings,
                        double junctionSpacing, QuadMesh& mesh, const StageCallback& stage) {
  RemeshedPart part;
  part.plan = plan;
  part.status = PartStatus::Kept;
  mesh = QuadMesh{};
  std::vector<Sheet> sheets;
  try {
    sheets = buildSheets(model, plan.part, settings.sheets);
  } catch (const std::bad_alloc&) {
    part.reason = "out of memory while splitting it into sheets";
    return part;
  } catch (const std::exception& error) {
    part.reason = error.what();
    return part;
  }
  if (sheets.empty()) {
    part.reason = "no shell with an area to remesh";
    return part;
  }
  std::string sizeNote;
  double voxel = resolvingVoxel(sheets, plan, settings, sizeNote);
  const QuadMesh original = quadMeshFromModel(model, plan.part);
  const double finest = settings.finestVoxelShare * plan.targetSize;
  std::vector<std::string> failures;
  for (int attempt = 0; attempt <= settings.retries; ++attempt, voxel /= 2) {
    if (attempt > 0 && voxel < finest * (1 - 1e-9)) break;
    ++part.attempts;
    part.voxelSize = voxel;
    part.extract = ExtractStats{};  // the counts of the attempt that ends the part
    const std::string at = "size " + formatNumber(voxel) + ": ";
    try {
      std::vector<std::uint8_t> folded;
      QuadMesh candidate =
          meshAtVoxel(sheets, voxel, plan, settings, junctionSpacing, part, folded, stage);
      part.acceptance = acceptPartMesh(candidate, original, folded, voxel, plan.targetSize,
                                       settings.optimizeSettings.quality);
      if (part.acceptance.accepted) {
        part.status = attempt == 0 ? PartStatus::Remeshed : PartStatus::Retried;
        part.reason = sizeNote;
        part.quads = part.acceptance.quads;
        part.trias = part.acceptance.trias;
        mesh = std::move(candidate);
        return part;
      }
      failures.push_back(at + part.acceptance.reason);
    } catch (const std::bad_alloc&) {
      failures.push_back(at + "out of memory");
      break;
    } catch (const SettingError& error) {  // the memory budget or the grid's index range
      failures.push_back(at + error.what());
      break;
    } catch (const std::exception& error) {
      failures.push_back(at + error.what());
    }
  }
  for (const std::string& failure : failures)
    part.reason += (part.reason.empty() ? "" : "; ") + failure;
  if (!sizeNote.empty()) part.reason += " (" + sizeNote + ")";
  return part;
}

}  // namespace voxremesh::pipeline
