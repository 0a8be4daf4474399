// Corners of a surface sharper than the triangle angle limit (quality.h, "Sharp corners"): a mesh
// of such a surface must have an element with that angle there, whatever its quality, so the
// element that fills the corner is judged by its other angles. Internal to src/quality.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/vec3.h"
#include "quality/ridge_edges.h"
#include "voxremesh/quad_mesh.h"

namespace voxremesh::quality {

/// A corner of a surface: a point, the directions of its two sides (unit vectors along the edges
/// that bound it) and the angle the surface spans between them (the sum of the face angles at the
/// point between its boundary edges and the edges along feature lines and junction curves).
struct SharpCorner {
  geom::Vec3 point;
  geom::Vec3 side1, side2;
  double angleDeg = 0.0;
};

/// The corners of `surface` whose angle is below `belowDeg`: at each point, its faces are grouped
/// into sectors (faces joined across edges that two faces share and no ridge runs along), and each
/// sector spanning less than `belowDeg` between two sides is a corner.
/// @param surface   the original surface; faces name existing points
/// @param ridges    its feature lines and junction curves
/// @param belowDeg  the angle limit (degrees)
/// @return the corners, sorted by point (x, then y, then z)
std::vector<SharpCorner> sharpCorners(const QuadMesh& surface, RidgeEdges& ridges, double belowDeg);

/// Per face of `mesh`, 1 for a triangle that fills one of `corners`: it has a corner at the
/// corner's point (within 1e-6 of its longest edge), its two edges there run along the corner's
/// two sides (each within half the corner's angle of one), and its other two angles lie within
/// [minAngleDeg, maxAngleDeg].
/// @param mesh     the mesh judged; faces name existing points
/// @param corners  sharpCorners of its original
std::vector<std::uint8_t> cornerFillingTriangles(const QuadMesh& mesh,
                                                 const std::vector<SharpCorner>& corners,
                                                 double minAngleDeg, double maxAngleDeg);

}  // namespace voxremesh::quality
