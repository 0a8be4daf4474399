// The flat grid of unit quads that the optimisation tests plant their defects in.
#pragma once

#include <cstddef>

#include "voxremesh/quad_mesh.h"

namespace voxremesh::test {

/// An n x n grid of unit quads in the plane z = 0: point (i, j) at index j (n + 1) + i, faces row
/// by row, each counter-clockwise seen from +z; every point Free (constraints sized, no curves).
/// Precondition: n >= 1.
QuadMesh unitGrid(int n);

/// The index of point (i, j) of unitGrid(n).
inline CornerIndex gridPoint(int n, int i, int j) {
  return static_cast<CornerIndex>(j * (n + 1) + i);
}

/// Pushes the points of unitGrid(n) that are not on its boundary by up to `amount` in x and y, in a
/// fixed pseudo-random pattern per seed (far enough, some faces fold). Precondition: `mesh` has
/// the points of unitGrid(n).
void jitterInnerPoints(QuadMesh& mesh, int n, unsigned seed, double amount);

/// The number of faces foldedFaces (quality.h) flags.
std::size_t foldedCount(const QuadMesh& mesh);

}  // namespace voxremesh::test
