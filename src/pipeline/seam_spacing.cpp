// Node spacing per seam from the sheets on its sides (seam_spacing.h).
#include "pipeline/seam_spacing.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <exception>
#include <limits>

#include "pipeline/remesh_part.h"

namespace voxremesh::pipeline {

namespace {

/// The longest piece of a boundary cut into pieces about one spacing long, in spacings: a length
/// just under 1.5 spacings stays one piece.
constexpr double kLongestPiece = 1.5;

}  // namespace

double rowLength(const Sheet& sheet, const RemeshSettings& settings) {
  return settings.optimizeSettings.quality.maxAspectRatio * stripWidth(sheet) / kLongestPiece;
}

double sheetNodeSpacing(const Sheet& sheet, double targetSize, const RemeshSettings& settings) {
  const double width = sheetWidth(sheet);
  const bool narrow =
      settings.narrowFeatureVoxels > 0 && width < settings.narrowFeatureVoxels * targetSize;
  return narrow ? std::min(targetSize, rowLength(sheet, settings)) : targetSize;
}

namespace {

/// Lowers spacing[node] to `value` (adding the node when absent).
void lower(std::unordered_map<Id, double>& spacing, Id node, double value) {
  const auto [it, added] = spacing.emplace(node, value);
  if (!added) it->second = std::min(it->second, value);
}

}  // namespace

std::unordered_map<Id, double> seamNodeSpacing(const std::vector<FeModel>& models,
                                               const std::vector<PartPlan>& plans,
                                               const std::vector<double>& junctionSpacing,
                                               const std::vector<std::uint8_t>& skip,
                                               const RemeshSettings& settings) {
  std::vector<std::unordered_map<Id, double>> perPlan(plans.size());
  tbb::parallel_for(std::size_t(0), plans.size(), [&](std::size_t i) {
    if (skip[i]) return;
    std::vector<Sheet> sheets;
    try {
      sheets = buildSheets(models[i], plans[i].part, settings.sheets);
    } catch (const std::exception&) {
      return;  // remeshPart builds them again and reports why they cannot be
    }
    for (const Sheet& sheet : sheets) {
      const double spacing =
          std::min(sheetNodeSpacing(sheet, plans[i].targetSize, settings), junctionSpacing[i]);
      for (const Polyline& curve : sheet.junctionCurves)
        for (const PointIndex p : curve.points) lower(perPlan[i], sheet.pointNodeIds[p], spacing);
    }
  });
  std::unordered_map<Id, double> spacing;
  for (const std::unordered_map<Id, double>& part : perPlan)
    for (const auto& [node, value] : part) lower(spacing, node, value);
  return spacing;
}

void setSeamSpacing(std::vector<Sheet>& sheets, const std::unordered_map<Id, double>& nodeSpacing,
                    double partSpacing) {
  for (Sheet& sheet : sheets) {
    for (Polyline& curve : sheet.junctionCurves) {
      const std::size_t n = curve.points.size();
      const bool inner = !curve.closed && n > 2;
      double smallest = std::numeric_limits<double>::infinity();
      for (std::size_t k = inner ? 1 : 0; k < (inner ? n - 1 : n); ++k) {
        const auto it = nodeSpacing.find(sheet.pointNodeIds[curve.points[k]]);
        if (it != nodeSpacing.end()) smallest = std::min(smallest, it->second);
      }
      curve.nodeSpacing = smallest < partSpacing ? smallest : 0.0;
    }
  }
}

}  // namespace voxremesh::pipeline
