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

std::vector<Sheet> partSheets(const sheets::ModelContext& context, Index entry,
                              const SheetSettings& settings, std::vector<Index>& localOf) {
  const sheets::PartMesh part = sheets::makePartMesh(context, entry, localOf);
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
  const sheets::ModelContext context = sheets::makeModelContext(model, settings);
  for (Index entry = 0; entry < context.partIds.size(); ++entry)
    if (context.partIds[entry] == part) {
      std::vector<Index> localOf(model.nodes.size(), kNoIndex);
      return partSheets(context, entry, settings, localOf);
    }
  return {};
}

std::vector<std::array<Id, 2>> findFoldCuts(const FeModel& model) {
  const sheets::ModelContext context = sheets::makeModelContext(model, SheetSettings{});
  std::vector<std::array<Id, 2>> cuts;
  cuts.reserve(context.foldCuts.size());
  for (const auto& [a, b] : context.foldCuts) {
    const Id u = model.nodes[a].id, v = model.nodes[b].id;
    cuts.push_back({std::min(u, v), std::max(u, v)});
  }
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

std::vector<Sheet> buildAllSheets(const FeModel& model, const SheetSettings& settings) {
  checkSettings(settings);
  const sheets::ModelContext context = sheets::makeModelContext(model, settings);
  const std::size_t parts = context.partIds.size();
  std::vector<std::vector<Sheet>> perPart(parts);
  std::vector<std::exception_ptr> errors(parts);
  // makePartMesh leaves its scratch as it found it before the per-sheet parallel loop starts, so
  // a part task that TBB runs on this thread inside that loop may use the same scratch.
  tbb::enumerable_thread_specific<std::vector<Index>> scratch(
      [&] { return std::vector<Index>(model.nodes.size(), kNoIndex); });
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t entry) {
    try {
      perPart[entry] = partSheets(context, Index(entry), settings, scratch.local());
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
