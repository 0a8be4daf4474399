// Choosing the voxel size and refusing settings the machine cannot hold.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "volume/surface_mesh.h"
#include "volume/voxel_budget.h"
#include "voxremesh/errors.h"
#include "voxremesh/volume.h"

namespace voxremesh {

namespace {

/// Peak bytes per active voxel while building: meshToVolume's distance and index trees with their
/// partly filled leaves and per-thread scratch trees, the final sdf and the masks.
/// `bench_voxelize --rss` measures about 36 bytes per active voxel (2 threads, 2 million voxels);
/// twice that leaves room for more threads' scratch trees and less favourable leaf filling.
constexpr double kPeakBytesPerActiveVoxel = 72.0;

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

/// The memory this process may use: the physical memory, or the address-space limit
/// (ulimit -v, prlimit --as) when that is lower.
std::uint64_t usableMemory() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long pageSize = ::sysconf(_SC_PAGE_SIZE);
  std::uint64_t memory = pages <= 0 || pageSize <= 0 ? std::uint64_t{8} << 30
                                                     : static_cast<std::uint64_t>(pages) *
                                                           static_cast<std::uint64_t>(pageSize);
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    memory = std::min<std::uint64_t>(memory, limit.rlim_cur);
  return memory;
}

void requirePositive(double value, const char* name) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw SettingError(std::string(name) + " must be a finite number > 0 (got " + number(value) +
                       ")");
  }
}

}  // namespace

void checkVolumeSettings(const VolumeSettings& settings) {
  switch (settings.rule) {
    case VoxelSizeRule::Explicit:
      requirePositive(settings.voxelSize, "voxel size");
      break;
    case VoxelSizeRule::TargetElementSize:
      if (!std::isfinite(settings.targetElementSize) || settings.targetElementSize < 0.0) {
        throw SettingError(
            "target element size must be a finite number > 0, or 0 for the mean "
            "edge length of the input (got " +
            number(settings.targetElementSize) + ")");
      }
      break;
    case VoxelSizeRule::MinEdgeLength:
      requirePositive(settings.minEdgeFactor, "minimal edge length factor");
      if (settings.minEdgeFactor > 100.0) {
        throw SettingError("minimal edge length factor must be at most 100 (got " +
                           number(settings.minEdgeFactor) + ")");
      }
      break;
    default:
      throw SettingError("unknown voxel size rule");
  }
  if (!(settings.bandWidthVoxels >= 1.0 && settings.bandWidthVoxels <= 64.0)) {
    throw SettingError("narrow band width must be between 1 and 64 voxels (got " +
                       number(settings.bandWidthVoxels) + ")");
  }
  if (!(settings.invalidAngleDeg >= 0.0 && settings.invalidAngleDeg <= 90.0)) {
    throw SettingError("invalid-voxel angle must be between 0 and 90 degrees (got " +
                       number(settings.invalidAngleDeg) + ")");
  }
  if (!(settings.tieToleranceVoxels >= 0.0 && settings.tieToleranceVoxels <= 0.01)) {
    throw SettingError("tie tolerance must be between 0 and 0.01 voxels (got " +
                       number(settings.tieToleranceVoxels) + ")");
  }
}

namespace volume {

double chooseVoxelSize(const SurfaceMesh& mesh, const VolumeSettings& settings) {
  checkVolumeSettings(settings);
  switch (settings.rule) {
    case VoxelSizeRule::Explicit:
      return settings.voxelSize;
    case VoxelSizeRule::TargetElementSize:
      if (settings.targetElementSize > 0.0) return settings.targetElementSize;
      if (!(mesh.meanEdgeLength > 0.0)) {
        throw SettingError(
            "no target element size given and the sheets have no edges to take "
            "the mean edge length from: give a target size or a voxel size");
      }
      return mesh.meanEdgeLength;
    case VoxelSizeRule::MinEdgeLength:
      if (!(mesh.minEdgeLength > 0.0)) {
        throw SettingError(
            "the minimal-edge-length rule needs edges, and the sheets have none "
            "that are not degenerate: give a target size or a voxel size");
      }
      return settings.minEdgeFactor * mesh.minEdgeLength;
  }
  throw SettingError("unknown voxel size rule");
}

VolumeEstimate estimateVolume(const SurfaceMesh& mesh, double voxelSize,
                              const VolumeSettings& settings) {
  requirePositive(voxelSize, "voxel size");
  VolumeEstimate estimate;
  estimate.surfaceArea = mesh.area;
  const double slab = 2.0 * settings.bandWidthVoxels + 1.0;
  estimate.activeVoxels = mesh.area / (voxelSize * voxelSize) * slab;
  estimate.peakBytes = estimate.activeVoxels * kPeakBytesPerActiveVoxel;
  estimate.memoryLimit =
      settings.memoryLimitBytes > 0 ? settings.memoryLimitBytes : usableMemory() / 2;
  estimate.smallestVoxelSize =
      std::sqrt(mesh.area * slab * kPeakBytesPerActiveVoxel / double(estimate.memoryLimit));
  return estimate;
}

void checkVolumeBudget(const SurfaceMesh& mesh, double voxelSize, const VolumeEstimate& estimate,
                       const VolumeSettings& settings) {
  const double extent = std::max({std::abs(mesh.boundsMin.x), std::abs(mesh.boundsMin.y),
                                  std::abs(mesh.boundsMin.z), std::abs(mesh.boundsMax.x),
                                  std::abs(mesh.boundsMax.y), std::abs(mesh.boundsMax.z)});
  const double indexLimit = double(1 << 30);
  if (extent / voxelSize + settings.bandWidthVoxels + 2.0 > indexLimit) {
    throw SettingError("voxel size " + number(voxelSize) + " is too small for coordinates up to " +
                       number(extent) + ": the grid index would exceed 2^30; choose a voxel size " +
                       "of at least " + number(extent / (indexLimit / 2)));
  }
  if (estimate.peakBytes > double(estimate.memoryLimit)) {
    throw SettingError(
        "voxel size " + number(voxelSize) + " needs about " + number(estimate.activeVoxels) +
        " active voxels (surface area " + number(estimate.surfaceArea) + ", band " +
        number(settings.bandWidthVoxels) + " voxels), about " + number(estimate.peakBytes / 1e9) +
        " GB while building, more than the memory limit of " +
        number(double(estimate.memoryLimit) / 1e9) + " GB: choose a voxel size of at least " +
        number(estimate.smallestVoxelSize * 1.001) +
        " (a larger target element size), a narrower band, or a higher memory limit");
  }
}

}  // namespace volume

double chooseVoxelSize(const std::vector<Sheet>& sheets, const VolumeSettings& settings) {
  checkVolumeSettings(settings);
  if (settings.rule == VoxelSizeRule::Explicit) return settings.voxelSize;
  if (settings.rule == VoxelSizeRule::TargetElementSize && settings.targetElementSize > 0.0) {
    return settings.targetElementSize;
  }
  return volume::chooseVoxelSize(volume::buildSurfaceMesh(sheets), settings);
}

VolumeEstimate estimateVolume(const std::vector<Sheet>& sheets, double voxelSize,
                              const VolumeSettings& settings) {
  checkVolumeSettings(settings);
  return volume::estimateVolume(volume::buildSurfaceMesh(sheets), voxelSize, settings);
}

}  // namespace voxremesh
