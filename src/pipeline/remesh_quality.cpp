// The quality of remeshed output: .vtu cell data of a quality report, per-part summaries of a
// remesh, and the .vtu file of all remeshed parts (remesh_quality.h).
#include "voxremesh/remesh_quality.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>

namespace voxremesh {

namespace {

/// A value ParaView can read: non-finite values become +-1e30.
double finiteForVtu(double value) {
  if (std::isnan(value)) return 1e30;
  if (std::isinf(value)) return value > 0 ? 1e30 : -1e30;
  return value;
}

}  // namespace

FeModel partShells(const FeModel& model, Id part, const std::string& deckName) {
  const std::unordered_map<Id, std::size_t> index = model.nodeIndex();
  FeModel out;
  out.sourceFormat = model.sourceFormat;
  std::unordered_set<Id> used;
  for (const Shell& shell : model.shells) {
    if (part != 0 && shell.part != part) continue;
    out.shells.push_back(shell);
    out.shells.back().extras = -1;
    out.shells.back().type = 0;
    for (int k = 0; k < shell.nodeCount; ++k) {
      const Id node = shell.nodes[static_cast<std::size_t>(k)];
      if (!used.insert(node).second) continue;
      const auto found = index.find(node);
      if (found == index.end())
        throw std::runtime_error(deckName + ": shell " + std::to_string(shell.id) + " names node " +
                                 std::to_string(node) + ", which is not defined");
      out.nodes.push_back(model.nodes[found->second]);
    }
  }
  if (out.shells.empty())
    throw std::runtime_error(deckName + (part ? " has no shells of part " + std::to_string(part)
                                              : std::string(" has no shell elements")));
  return out;
}

std::vector<MeshCurve> deckChannelCurves(const FeModel& deck, Id part,
                                         const SheetSettings& sheets) {
  try {
    return channelCurves(part ? buildSheets(deck, part, sheets) : buildAllSheets(deck, sheets));
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception&) {
    return {};  // not split into sheets: judged against the target size
  }
}

std::vector<FieldData> qualityCellFields(const QualityReport& report) {
  std::vector<FieldData> fields = {{"warping_deg", {}},
                                   {"aspect_ratio", {}},
                                   {"min_angle_deg", {}},
                                   {"max_angle_deg", {}},
                                   {"skew_deg", {}},
                                   {"jacobian_ratio", {}},
                                   {"jacobian_ratio_gauss", {}},
                                   {"scaled_jacobian", {}},
                                   {"taper", {}},
                                   {"min_length", {}},
                                   {"judged_size", {}},
                                   {"fail_mask", {}},
                                   {"pass", {}},
                                   {"quality_index", {}}};
  for (FieldData& field : fields) field.values.reserve(report.elements);
  for (std::size_t f = 0; f < report.elements; ++f) {
    const ElementQuality& q = report.elementValues[f];
    const double values[] = {q.warpingDeg,
                             q.aspectRatio,
                             q.minAngleDeg,
                             q.maxAngleDeg,
                             q.skewDeg,
                             q.jacobianRatio,
                             q.jacobianRatioGauss,
                             q.scaledJacobian,
                             q.taper,
                             q.minLength,
                             report.judgedSize[f],
                             double(report.elementFailures[f]),
                             report.elementFailures[f] == 0 ? 1.0 : 0.0,
                             report.qualityIndex[f]};
    for (std::size_t k = 0; k < fields.size(); ++k)
      fields[k].values.push_back(finiteForVtu(values[k]));
  }
  return fields;
}

std::vector<PartQuality> assessRemeshedParts(const FeModel& original, const FeModel& remeshed,
                                             const RemeshReport& remesh,
                                             const QualitySettings& settings,
                                             const SheetSettings& sheets) {
  checkQualitySettings(settings);
  std::vector<PartQuality> out;
  out.reserve(remesh.parts.size());
  for (const RemeshedPart& part : remesh.parts) {
    if (part.status == PartStatus::Kept) continue;
    const Id id = part.plan.part;
    const FeModel before = partShells(original, id, "the original deck");
    const FeModel after = partShells(remeshed, id, "the remeshed deck");
    QualitySettings partSettings = settings;
    partSettings.targetSize = part.voxelSize;
    partSettings.distanceSize = part.plan.targetSize;
    const QuadMesh originalMesh = quadMeshFromModel(before);
    PartQuality quality;
    quality.part = id;
    quality.elementsBefore = before.shells.size();
    quality.elementsAfter = after.shells.size();
    const std::vector<MeshCurve> channels = deckChannelCurves(original, id, sheets);
    quality.report =
        assessQuality(quadMeshFromModel(after), partSettings, &originalMesh, &channels);
    out.push_back(std::move(quality));
  }
  return out;
}

void writeRemeshQualityVtu(const FeModel& remeshed, const std::vector<PartQuality>& parts,
                           const std::filesystem::path& path) {
  FeModel all;
  all.sourceFormat = remeshed.sourceFormat;
  std::vector<FieldData> cells;
  std::unordered_map<Id, std::size_t> nodeOf;  // node ID -> index in all.nodes
  std::vector<double> distance;
  for (const PartQuality& part : parts) {
    const FeModel shells = partShells(remeshed, part.part, "the remeshed deck");
    if (shells.shells.size() != part.report.elements)
      throw std::invalid_argument(
          "part " + std::to_string(part.part) + " has " + std::to_string(shells.shells.size()) +
          " shells but its quality report " + std::to_string(part.report.elements));
    for (std::size_t n = 0; n < shells.nodes.size(); ++n) {
      const double d = part.report.distance ? part.report.distance->pointDistance[n] : 0.0;
      const auto [it, added] = nodeOf.emplace(shells.nodes[n].id, all.nodes.size());
      if (added) {
        all.nodes.push_back(shells.nodes[n]);
        distance.push_back(d);
      } else {
        distance[it->second] = std::max(distance[it->second], d);
      }
    }
    all.shells.insert(all.shells.end(), shells.shells.begin(), shells.shells.end());
    if (const Part* found = remeshed.findPart(part.part))
      all.parts.push_back({found->id, found->name, false});
    std::vector<FieldData> fields = qualityCellFields(part.report);
    if (cells.empty()) {
      cells = std::move(fields);
      continue;
    }
    for (std::size_t k = 0; k < cells.size(); ++k)
      cells[k].values.insert(cells[k].values.end(), fields[k].values.begin(),
                             fields[k].values.end());
  }
  for (double& d : distance) d = finiteForVtu(d);
  writeVtu(all, path, cells, {{"distance", distance}});
}

}  // namespace voxremesh
