// foldedFaces: elements whose normal points against those of their edge neighbours (quality.h).
#include <algorithm>
#include <cstdint>
#include <tuple>
#include <vector>

#include "geometry/vec3.h"
#include "quality/ridge_edges.h"
#include "voxremesh/quality.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// The unit normal of a face (elementNormal), zero when it has no area.
Vec3 unitNormal(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face) {
  const bool triangle = cornerCount(face) == 3;
  const auto& p = mesh.points;
  return normalized(
      elementNormal(p[face[0]], p[face[1]], p[face[2]], p[face[triangle ? 2 : 3]], triangle));
}

}  // namespace

std::vector<std::uint8_t> foldedFaces(const QuadMesh& mesh, const std::vector<MeshCurve>* ridges) {
  // Every directed face edge as (low point, high point, face, runs from low to high).
  struct HalfEdge {
    CornerIndex low, high;
    std::uint32_t face;
    bool forward;
  };
  std::vector<HalfEdge> halfEdges;
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k) {
      const CornerIndex a = face[std::size_t(k)], b = face[std::size_t((k + 1) % n)];
      halfEdges.push_back({std::min(a, b), std::max(a, b), f, a < b});
    }
  }
  std::sort(halfEdges.begin(), halfEdges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.low, x.high, x.face) < std::tie(y.low, y.high, y.face);
  });
  std::vector<Vec3> normals(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) normals[f] = unitNormal(mesh, mesh.faces[f]);
  // Per face: neighbours seen, and those whose normal (in this face's orientation) is opposite.
  std::vector<std::uint32_t> neighbours(mesh.faces.size(), 0), opposite(mesh.faces.size(), 0);
  const double kOpposite = -0.5;  // more than 120 degrees apart
  quality::RidgeEdges ridgeEdges(ridges);
  for (std::size_t i = 0; i < halfEdges.size();) {
    std::size_t j = i;
    while (j < halfEdges.size() && halfEdges[j].low == halfEdges[i].low &&
           halfEdges[j].high == halfEdges[i].high)
      ++j;
    if (j - i == 2) {  // a manifold edge
      const HalfEdge& a = halfEdges[i];
      const HalfEdge& b = halfEdges[i + 1];
      const double sign = a.forward != b.forward ? 1.0 : -1.0;
      const double cosine = sign * dot(normals[a.face], normals[b.face]);
      const bool bothHaveArea = dot(normals[a.face], normals[a.face]) > 0.0 &&
                                dot(normals[b.face], normals[b.face]) > 0.0;
      if (bothHaveArea && a.face != b.face) {
        ++neighbours[a.face];
        ++neighbours[b.face];
        if (cosine < kOpposite && !ridgeEdges.along(mesh.points[a.low], mesh.points[a.high])) {
          ++opposite[a.face];
          ++opposite[b.face];
        }
      }
    }
    i = j;
  }
  std::vector<std::uint8_t> folded(mesh.faces.size(), 0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    folded[f] = neighbours[f] > 0 && 2 * opposite[f] >= neighbours[f] ? 1 : 0;
  return folded;
}

}  // namespace voxremesh
