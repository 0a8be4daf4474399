// The ideal shape of a face: the square (quad) or equilateral triangle that fits its corners
// best, for the shape-driven relaxation.
#pragma once

#include <array>

#include "geometry/vec3.h"
#include "voxremesh/quad_mesh.h"

namespace voxremesh::opt {

/// The corners of the regular polygon (square or equilateral triangle) with edge length
/// `edgeLength` that best fits the face in the least-squares sense: centred on the face's
/// centroid, in the plane through it normal to the face normal (quads: the cross product of the
/// diagonals; triangles: of two edges), turned in that plane by the rotation that minimises the
/// summed squared distances to the corners projected on the plane, corners in the face's order.
/// Entry 3 is unused for a triangle. A face without a normal (zero area) gets its own corners.
std::array<geom::Vec3, 4> idealCorners(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face,
                                       double edgeLength);

}  // namespace voxremesh::opt
