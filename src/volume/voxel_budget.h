// Voxel size choice and memory budget of buildVolume on a prepared mesh (voxel_size.cpp).
#pragma once

#include "volume/surface_mesh.h"
#include "voxremesh/volume.h"

namespace voxremesh::volume {

/// chooseVoxelSize on a prepared mesh (see volume.h).
double chooseVoxelSize(const SurfaceMesh& mesh, const VolumeSettings& settings);

/// estimateVolume on a prepared mesh (see volume.h).
VolumeEstimate estimateVolume(const SurfaceMesh& mesh, double voxelSize,
                              const VolumeSettings& settings);

/// Throws SettingError when the estimate exceeds its memory limit (saying how many voxels, how
/// much memory and the smallest voxel size that fits) or when the sheets' coordinates divided by
/// the voxel size leave the 32-bit index range of the grid.
void checkVolumeBudget(const SurfaceMesh& mesh, double voxelSize, const VolumeEstimate& estimate,
                       const VolumeSettings& settings);

}  // namespace voxremesh::volume
