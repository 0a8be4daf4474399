// The dual-quad pass of the extraction stage (see include/voxremesh/extract.h): MC33 per cell, one
// vertex per component loop, one quad per sign-changing grid edge whose four cells all have
// vertices. Internal to src/extract; includes OpenVDB.
#pragma once

#include <openvdb/openvdb.h>

#include <array>
#include <cstdint>
#include <vector>

namespace voxremesh::extract {

/// The dual mesh of a grid, in world coordinates.
struct DualMesh {
  std::vector<std::array<double, 3>> points;
  /// The cell (its lowest corner voxel) each point belongs to.
  std::vector<openvdb::Coord> pointCells;
  /// Quads, counter-clockwise seen from the positive side.
  std::vector<std::array<std::uint32_t, 4>> quads;
  std::uint64_t surfaceCells = 0;
  std::uint64_t tunnelCells = 0;
  std::uint64_t skippedCells = 0;
  std::uint64_t cutCells = 0;  ///< cells whose loop was cut at a doubly ambiguous face
};

/// Builds the dual mesh (one vertex per MC33 loop; see cellVertices in dual_mesh.cpp for the one
/// exception, a loop cut at a face that both cells' loops wind around) of the zero level of `sdf`
/// over its active leaves, in parallel with TBB. A cell (lowest corner voxel (i,j,k)) takes part
/// when its 8 corners are active in sdf, none is on in `invalidVoxels`, the cell is not on in
/// `excludedCells`, and its corners are not all of one sign. The output is the same for any number
/// of threads: points ordered by leaf (tree order), voxel offset and MC33 loop; quads by leaf and
/// voxel of their owning cell, then axis.
/// @param sdf            the signed distance grid (finite values)
/// @param invalidVoxels  voxels no cell may touch (may be empty)
/// @param excludedCells  cells that get no vertex (may be empty)
DualMesh buildDualMesh(const openvdb::FloatGrid& sdf, const openvdb::MaskTree& invalidVoxels,
                       const openvdb::MaskTree& excludedCells);

}  // namespace voxremesh::extract
