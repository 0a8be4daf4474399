// An orthonormal basis of the plane normal to a vector, for work projected on a plane (the
// quality and optimisation kernels).
#pragma once

#include <cmath>
#include <utility>

#include "geometry/vec3.h"

namespace voxremesh::geom {

/// A right-handed orthonormal basis (u, w) of the plane normal to the unit vector `normal`
/// (u x w = normal).
inline std::pair<Vec3, Vec3> planeBasis(const Vec3& normal) {
  const Vec3 axis = std::abs(normal[0]) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
  const Vec3 u = normalized(cross(normal, axis));
  return {u, cross(normal, u)};
}

}  // namespace voxremesh::geom
