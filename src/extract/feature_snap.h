// Feature snapping of the extraction stage (paper Sect. 4.3): dual vertices of cells the feature
// mask marks move onto the feature point inside the cell, else onto the closest feature line.
#pragma once

#include <openvdb/openvdb.h>

#include <array>
#include <cstdint>
#include <vector>

#include "voxremesh/quad_mesh.h"

namespace voxremesh::extract {

/// Snaps the points of marked cells. A point whose cell (pointCells[i], lowest corner voxel) is on
/// in `featureCells` moves to the nearest feature point inside the closed cell (role Corner), or
/// else to the closest point of the feature line segments near the cell (role Feature, curve: the
/// line's index in mesh.curves). Points of cells without a feature nearby are left as they are.
/// Where three or four corners of a quad land on one feature line, only the two neighbouring
/// corners that moved least stay there; the others go back (Free), so no quad collapses onto a
/// line.
/// Runs in parallel; deterministic.
/// @param mesh           points and constraints (one per point) to update
/// @param pointCells     the cell of each point of mesh (the first pointCells.size() points)
/// @param featureCells   the volume's feature mask (cells)
/// @param transform      the volume's transform
/// @param lineCurves     indices into mesh.curves of the feature lines
/// @param featurePoints  the feature points (world)
/// @return the number of points moved
std::uint64_t snapToFeatures(QuadMesh& mesh, const std::vector<openvdb::Coord>& pointCells,
                             const openvdb::MaskTree& featureCells,
                             const openvdb::math::Transform& transform,
                             const std::vector<std::uint32_t>& lineCurves,
                             const std::vector<std::array<double, 3>>& featurePoints);

}  // namespace voxremesh::extract
