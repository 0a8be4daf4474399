// The flat grid of unit quads that the optimisation tests plant their defects in.
#pragma once

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

}  // namespace voxremesh::test
