// splitInvertedQuads: a quad with one reflex or flat corner becomes two triangles (optimize.h).
#include <array>
#include <vector>

#include "optimize/mesh_topology.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

std::size_t splitInvertedQuads(QuadMesh& mesh, double degenerateCornerDeg) {
  opt::checkMesh(mesh);
  std::vector<std::array<CornerIndex, 4>> faces;
  faces.reserve(mesh.faces.size());
  std::size_t split = 0;
  for (const auto& face : mesh.faces) {
    if (cornerCount(face) != 4) {
      faces.push_back(face);
      continue;
    }
    // Corner normals c_k = e_{k-1} x e_k and their sum n, as quality.h's Jacobian ratio has
    // them: det J at corner k is c_k . n.
    std::array<Vec3, 4> c{};
    Vec3 n{0.0, 0.0, 0.0};
    for (std::size_t k = 0; k < 4; ++k) {
      const Vec3& p = mesh.points[face[k]];
      c[k] = cross(p - mesh.points[face[(k + 3) % 4]], mesh.points[face[(k + 1) % 4]] - p);
      n = n + c[k];
    }
    // A reflex corner, or one whose interior angle is degenerateCornerDeg or more (its corner
    // normal too small for a solver to estimate the shell normal from).
    int reflex = -1, count = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      const Vec3& p = mesh.points[face[k]];
      const double angle =
          angleDeg(mesh.points[face[(k + 3) % 4]] - p, mesh.points[face[(k + 1) % 4]] - p);
      if (dot(c[k], n) <= 0.0 || angle >= degenerateCornerDeg) reflex = int(k), ++count;
    }
    if (count != 1) {  // convex, or folded beyond what one cut mends
      faces.push_back(face);
      continue;
    }
    // The diagonal from the reflex corner lies inside the quad: both triangles keep its turn.
    const std::size_t k = std::size_t(reflex);
    faces.push_back({face[k], face[(k + 1) % 4], face[(k + 2) % 4], kNoCorner});
    faces.push_back({face[(k + 2) % 4], face[(k + 3) % 4], face[k], kNoCorner});
    ++split;
  }
  mesh.faces = std::move(faces);
  return split;
}

}  // namespace voxremesh
