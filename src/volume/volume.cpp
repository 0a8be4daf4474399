// The Volume handle and buildVolume: settings, voxel size, budget, then the grids.
#include <openvdb/openvdb.h>

#include <mutex>
#include <utility>

#include "volume/surface_mesh.h"
#include "volume/volume_build.h"
#include "volume/volume_grids.h"
#include "volume/voxel_budget.h"
#include "voxremesh/volume.h"

namespace voxremesh {

namespace volume {

void initializeOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

}  // namespace volume

Volume::Volume() : impl_(std::make_unique<Impl>()) {}
Volume::~Volume() = default;
Volume::Volume(Volume&& other) noexcept : impl_(std::make_unique<Impl>()) {
  std::swap(impl_, other.impl_);
}
Volume& Volume::operator=(Volume&& other) noexcept {
  std::swap(impl_, other.impl_);
  return *this;
}

Volume::Volume(const Volume& other) : impl_(std::make_unique<Impl>(*other.impl_)) {
  // Deep copies of the grids, all on one new transform.
  Impl& self = *impl_;
  if (self.transform) self.transform = self.transform->copy();
  if (self.sdf) self.sdf = self.sdf->deepCopy(), self.sdf->setTransform(self.transform);
  if (self.invalid) {
    self.invalid = self.invalid->deepCopy();
    self.invalid->setTransform(self.transform);
  }
  if (self.feature) {
    self.feature = self.feature->deepCopy();
    self.feature->setTransform(self.transform);
  }
}

Volume& Volume::operator=(const Volume& other) {
  if (this != &other) *this = Volume(other);
  return *this;
}

bool Volume::empty() const {
  return !impl_->sdf;
}
const VolumeInfo& Volume::info() const {
  return impl_->info;
}
const std::vector<VolumeCurve>& Volume::featureLines() const {
  return impl_->featureLines;
}
const std::vector<VolumeCurve>& Volume::boundaryLoops() const {
  return impl_->boundaryLoops;
}
const std::vector<std::array<double, 3>>& Volume::featurePoints() const {
  return impl_->featurePoints;
}
const std::vector<VolumeCurve>& Volume::junctionCurves() const {
  return impl_->junctionCurves;
}

VolumeCurve worldCurve(const Sheet& sheet, const Polyline& line) {
  VolumeCurve curve;
  curve.closed = line.closed;
  curve.keepPoints = line.keepPoints;
  curve.nodeSpacing = line.nodeSpacing;
  curve.nodeCount = line.nodeCount;
  curve.points.reserve(line.points.size());
  for (PointIndex p : line.points) {
    if (p >= sheet.points.size()) {
      throw std::invalid_argument("a curve refers to point " + std::to_string(p) + " of " +
                                  std::to_string(sheet.points.size()));
    }
    curve.points.push_back(sheet.points[p]);
  }
  for (const auto& [index, ratio] : line.grading)
    curve.grading.emplace_back(curve.points.at(index), ratio);
  curve.stations = line.stations;
  curve.stationPieces = line.stationPieces;
  return curve;
}

Volume buildVolume(const std::vector<Sheet>& sheets, const VolumeSettings& settings,
                   const VolumeSource& source) {
  checkVolumeSettings(settings);
  volume::initializeOpenVdb();
  const volume::SurfaceMesh mesh = volume::buildSurfaceMesh(sheets);
  const double voxelSize = volume::chooseVoxelSize(mesh, settings);
  const VolumeEstimate estimate = volume::estimateVolume(mesh, voxelSize, settings);
  volume::checkVolumeBudget(mesh, voxelSize, estimate, settings);

  Volume result;
  Volume::Impl& out = result.impl();
  out.info.voxelSize = voxelSize;
  out.info.bandWidthVoxels = settings.bandWidthVoxels;
  out.info.invalidAngleDeg = settings.invalidAngleDeg;
  out.info.tieToleranceVoxels = settings.tieToleranceVoxels;
  out.info.sourceFile = source.sourceFile;
  out.info.part = sheets.empty() ? 0 : sheets.front().part;
  out.info.toolVersion = VOXREMESH_VERSION;

  for (const Sheet& sheet : sheets) {
    for (const Polyline& line : sheet.featureLines)
      out.featureLines.push_back(worldCurve(sheet, line));
    for (const Polyline& loop : sheet.boundaryLoops) {
      out.boundaryLoops.push_back(worldCurve(sheet, loop));
    }
    for (const Polyline& junction : sheet.junctionCurves)
      out.junctionCurves.push_back(worldCurve(sheet, junction));
    for (PointIndex p : sheet.featurePoints) {
      if (p >= sheet.points.size()) {
        throw std::invalid_argument("a feature point refers to point " + std::to_string(p) +
                                    " of " + std::to_string(sheet.points.size()));
      }
      out.featurePoints.push_back(sheet.points[p]);
    }
  }

  out.transform = openvdb::math::Transform::createLinearTransform(voxelSize);
  volume::computeSignedDistance(mesh, out.transform, settings, out.sdf, out.invalid);
  out.feature = volume::buildFeatureMask(out.featureLines, out.featurePoints, out.transform);
  return result;
}

}  // namespace voxremesh
