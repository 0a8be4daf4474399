// buildSheets and buildAllSheets: the steps of sheet_internal.h, per part.
#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <utility>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "sheets/sheet_internal.h"
#include "voxremesh/errors.h"
#include "voxremesh/sheets.h"

namespace voxremesh {

namespace {

using sheets::Index;
using sheets::kNoIndex;

void checkAngle(double value, const char* name) {
  if (!(value >= 0.0 && value <= 180.0))
    throw SettingError(std::string("SheetSettings::") + name +
                       " must be an angle from 0 to 180 degrees, not " + std::to_string(value));
}

void checkSettings(const SheetSettings& settings) {
  checkAngle(settings.featureAngleDeg, "featureAngleDeg");
  checkAngle(settings.cornerAngleDeg, "cornerAngleDeg");
}

std::vector<Sheet> partSheets(const sheets::ModelContext& context, const sheets::PartMesh& part,
                              const SheetSettings& settings) {
  const sheets::Orientation orientation = sheets::orientComponents(context, part);
  std::vector<sheets::SheetDraft> drafts = sheets::splitSheets(context, part, orientation);
  // The curves of each sheet depend on that sheet only.
  tbb::parallel_for(std::size_t{0}, drafts.size(), [&](std::size_t i) {
    sheets::findBoundaryLoops(drafts[i]);
    sheets::findFeatures(drafts[i], settings);
    sheets::findJunctions(drafts[i], context, part);
  });
  std::vector<Sheet> result;
  result.reserve(drafts.size());
  for (sheets::SheetDraft& draft : drafts) result.push_back(std::move(draft.sheet));
  return result;
}

}  // namespace

std::vector<Sheet> buildSheets(const FeModel& model, Id part, const SheetSettings& settings) {
  checkSettings(settings);
  sheets::ModelContext context = sheets::makeModelContext(model);
  for (Index entry = 0; entry < context.partIds.size(); ++entry)
    if (context.partIds[entry] == part) {
      sheets::setSheetCuts(context, settings);
      std::vector<Index> localOf(model.nodes.size(), kNoIndex);
      return partSheets(context, sheets::makePartMesh(context, entry, localOf), settings);
    }
  return {};
}

std::vector<std::array<Id, 2>> findSheetCuts(const FeModel& model) {
  const sheets::ModelContext context = sheets::makeModelContext(model);
  std::vector<std::array<Id, 2>> cuts;
  for (const auto& [a, b] : sheets::findSheetCuts(context)) {
    const Id u = model.nodes[a].id, v = model.nodes[b].id;
    cuts.push_back({std::min(u, v), std::max(u, v)});
  }
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

std::vector<Sheet> buildAllSheets(const FeModel& model, const SheetSettings& settings) {
  checkSettings(settings);
  sheets::ModelContext context = sheets::makeModelContext(model);
  const std::size_t parts = context.partIds.size();
  // Each part's faces once: for its cuts (unless given), then for its sheets.
  std::vector<sheets::PartMesh> meshes(parts);
  tbb::enumerable_thread_specific<std::vector<Index>> scratch(
      [&] { return std::vector<Index>(model.nodes.size(), kNoIndex); });
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t entry) {
    meshes[entry] = sheets::makePartMesh(context, Index(entry), scratch.local());
  });
  if (settings.sheetCuts) {
    sheets::setSheetCuts(context, settings);
  } else {
    std::vector<std::vector<std::array<Index, 2>>> cuts(parts);
    tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t entry) {
      cuts[entry] = sheets::partCuts(context, meshes[entry]);
    });
    for (const auto& list : cuts)
      context.sheetCuts.insert(context.sheetCuts.end(), list.begin(), list.end());
    std::sort(context.sheetCuts.begin(), context.sheetCuts.end());
    context.sheetCuts.erase(std::unique(context.sheetCuts.begin(), context.sheetCuts.end()),
                            context.sheetCuts.end());
  }
  std::vector<std::vector<Sheet>> perPart(parts);
  std::vector<std::exception_ptr> errors(parts);
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t entry) {
    try {
      perPart[entry] = partSheets(context, meshes[entry], settings);
    } catch (...) {
      errors[entry] = std::current_exception();
    }
  });
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
  std::vector<Sheet> result;
  for (std::vector<Sheet>& sheetsOfPart : perPart)
    for (Sheet& sheet : sheetsOfPart) result.push_back(std::move(sheet));
  return result;
}

}  // namespace voxremesh
