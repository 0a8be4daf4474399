// The OpenVDB grids behind a voxremesh::Volume, for the stages that work on them (extraction,
// inspection, I/O). Include only from .cpp files that need OpenVDB: its headers are heavy.
#pragma once

#include <openvdb/openvdb.h>

#include <array>
#include <vector>

#include "voxremesh/volume.h"

namespace voxremesh {

/// The content of a Volume. All three grids share one transform (a uniform scale by
/// info.voxelSize); see volume.h for what each grid holds.
struct Volume::Impl {
  VolumeInfo info;
  openvdb::math::Transform::Ptr transform;
  openvdb::FloatGrid::Ptr sdf;     ///< "sdf": narrow-band signed distance, class level set
  openvdb::MaskGrid::Ptr invalid;  ///< "invalid": voxels no surface may be extracted from
  openvdb::MaskGrid::Ptr feature;  ///< "feature": cells touched by feature lines and points
  std::vector<VolumeCurve> featureLines;
  std::vector<VolumeCurve> boundaryLoops;
  std::vector<std::array<double, 3>> featurePoints;
  std::vector<VolumeCurve> junctionCurves;
};

namespace volume {

/// Registers OpenVDB's grid types once per process (thread-safe, idempotent).
void initializeOpenVdb();

/// The grid names in a .vdb file.
inline constexpr const char* kSdfGridName = "sdf";
inline constexpr const char* kInvalidGridName = "invalid";
inline constexpr const char* kFeatureGridName = "feature";

}  // namespace volume
}  // namespace voxremesh
