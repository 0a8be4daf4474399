// The grid steps of buildVolume, one source file each: signed distance (signed_distance.cpp),
// invalid mask (invalid_mask.cpp), feature mask (feature_mask.cpp). Includes OpenVDB.
#pragma once

#include <openvdb/openvdb.h>

#include <array>
#include <vector>

#include "volume/surface_mesh.h"
#include "volume/volume_grids.h"
#include "voxremesh/volume.h"

namespace voxremesh::volume {

/// Builds the "sdf" grid and the "invalid" mask of the mesh on the transform (a uniform scale by
/// the voxel size, no offset): meshToVolume's unsigned distance and closest-polygon index give
/// the narrow band and a start polygon per voxel; the exact closest point, sign and invalid flag
/// are then computed per active voxel in parallel over the leaves.
void computeSignedDistance(const SurfaceMesh& mesh, const openvdb::math::Transform::Ptr& transform,
                           const VolumeSettings& settings, openvdb::FloatGrid::Ptr& sdf,
                           openvdb::MaskGrid::Ptr& invalid);

/// True when a voxel at p with closest point c is invalid: c lies on a free boundary edge or a
/// boundary vertex and the angle between p - c and the face normal there (the edge's face; the
/// vertex's angle-weighted pseudo-normal) exceeds the threshold whose cosine is given.
/// cosThreshold <= 0 (threshold 90 deg) marks nothing.
bool isInvalidVoxel(const SurfaceMesh& mesh, const ClosestPoint& c, const V3& p,
                    double cosThreshold);

/// A mask grid whose leaf at origins[i] has exactly the voxels of bits[i] on (leaves with no bit
/// set are skipped), on the given transform.
openvdb::MaskGrid::Ptr maskFromLeafBits(
    const std::vector<openvdb::Coord>& origins,
    const std::vector<openvdb::MaskTree::LeafNodeType::NodeMaskType>& bits,
    const openvdb::math::Transform::Ptr& transform);

/// The "feature" mask: every cell [i,i+1]x[j,j+1]x[k,k+1] (index space) that a segment of the
/// curves or one of the points touches, found by an exact 3D DDA (Amanatides-Woo) through the
/// cells along each segment; cells within 1e-6 voxel of a segment count as touched.
openvdb::MaskGrid::Ptr buildFeatureMask(const std::vector<VolumeCurve>& curves,
                                        const std::vector<std::array<double, 3>>& points,
                                        const openvdb::math::Transform::Ptr& transform);

}  // namespace voxremesh::volume
