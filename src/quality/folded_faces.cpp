// foldedFaces: elements whose normal points against those of their edge neighbours (quality.h).
#include <algorithm>
#include <cstdint>
#include <tuple>
#include <vector>

#include "geometry/vec3.h"
#include "quality/fold_check.h"
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

namespace quality {

FoldCheck::FoldCheck(const QuadMesh& mesh) {
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
  for (std::size_t i = 0; i < halfEdges.size();) {
    std::size_t j = i;
    while (j < halfEdges.size() && halfEdges[j].low == halfEdges[i].low &&
           halfEdges[j].high == halfEdges[i].high)
      ++j;
    const HalfEdge& a = halfEdges[i];
    // A manifold edge between two faces.
    if (j - i == 2 && a.face != halfEdges[i + 1].face)
      pairs_.push_back(
          {a.face, halfEdges[i + 1].face, a.forward != halfEdges[i + 1].forward, a.low, a.high});
    i = j;
  }
}

std::vector<std::uint8_t> FoldCheck::folded(const QuadMesh& mesh,
                                            const std::vector<MeshCurve>* ridges) const {
  std::vector<Vec3> normals(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) normals[f] = unitNormal(mesh, mesh.faces[f]);
  // Per face: neighbours seen, and those whose normal (in this face's orientation) is opposite.
  std::vector<std::uint32_t> neighbours(mesh.faces.size(), 0), opposite(mesh.faces.size(), 0);
  const double kOpposite = -0.5;  // more than 120 degrees apart
  RidgeEdges ridgeEdges(ridges);
  for (const EdgePair& pair : pairs_) {
    const Vec3 &a = normals[pair.first], &b = normals[pair.second];
    if (!(dot(a, a) > 0.0 && dot(b, b) > 0.0)) continue;
    ++neighbours[pair.first];
    ++neighbours[pair.second];
    const double cosine = (pair.opposite ? 1.0 : -1.0) * dot(a, b);
    if (cosine < kOpposite && !ridgeEdges.along(mesh.points[pair.low], mesh.points[pair.high])) {
      ++opposite[pair.first];
      ++opposite[pair.second];
    }
  }
  std::vector<std::uint8_t> folded(mesh.faces.size(), 0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    folded[f] = neighbours[f] > 0 && 2 * opposite[f] >= neighbours[f] ? 1 : 0;
  return folded;
}

}  // namespace quality

std::vector<std::uint8_t> foldedFaces(const QuadMesh& mesh, const std::vector<MeshCurve>* ridges) {
  return quality::FoldCheck(mesh).folded(mesh, ridges);
}

}  // namespace voxremesh
