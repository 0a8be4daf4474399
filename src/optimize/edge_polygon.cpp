// The polygon round a shared edge and its cuts (edge_polygon.h).
#include "optimize/edge_polygon.h"

#include <algorithm>

#include "geometry/vec3.h"

namespace voxremesh::opt {

namespace {

using namespace geom;  // NOLINT: the vector operators

/// The normal of a face, not normalised (geom::elementNormal).
geom::Vec3 faceNormal(const QuadMesh& mesh, const Face& face) {
  const bool triangle = cornerCount(face) == 3;
  return geom::elementNormal(mesh.points[face[0]], mesh.points[face[1]], mesh.points[face[2]],
                             mesh.points[face[triangle ? 2 : 3]], triangle);
}

/// The corners of `face` from the one after `from` round to `to`, both included.
std::vector<CornerIndex> walk(const Face& face, CornerIndex from, CornerIndex to) {
  const int n = cornerCount(face);
  int k = 0;
  while (face[std::size_t(k)] != from) ++k;
  std::vector<CornerIndex> corners;
  for (int step = 1; step <= n; ++step) {
    const CornerIndex v = face[std::size_t((k + step) % n)];
    corners.push_back(v);
    if (v == to) break;
  }
  return corners;
}

}  // namespace

std::vector<CornerIndex> polygonAroundEdge(const Face& f, const Face& g, CornerIndex a,
                                           CornerIndex b) {
  std::vector<CornerIndex> polygon = walk(f, a, a);
  std::rotate(polygon.begin(), std::find(polygon.begin(), polygon.end(), b), polygon.end());
  if (walk(g, b, a).size() != 1) return {};  // g runs (a, b) the same way
  const std::vector<CornerIndex> rest = walk(g, a, b);
  polygon.insert(polygon.end(), rest.begin(), rest.end() - 1);
  std::vector<CornerIndex> sorted = polygon;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return {};
  return polygon;
}

std::size_t diagonalEnd(std::size_t n, std::size_t i) {
  return (i + (n == 4 ? 2 : 3)) % n;
}

std::array<Face, 2> cutPolygon(const std::vector<CornerIndex>& polygon, std::size_t i) {
  const std::size_t n = polygon.size();
  auto at = [&](std::size_t k) { return polygon[(i + k) % n]; };
  if (n == 4) return {Face{at(0), at(1), at(2), kNoCorner}, Face{at(2), at(3), at(0), kNoCorner}};
  const Face first{at(0), at(1), at(2), at(3)};
  if (n == 5) return {first, Face{at(3), at(4), at(0), kNoCorner}};
  return {first, Face{at(3), at(4), at(5), at(0)}};
}

bool cutKeepsOrientation(const QuadMesh& mesh, const Topology& topology, std::uint32_t f,
                         std::uint32_t g, const std::array<Face, 2>& cut) {
  constexpr double kFoldCosine = -0.5;
  const auto has = [](const Face& face, CornerIndex v) {
    return std::find(face.begin(), face.begin() + cornerCount(face), v) !=
           face.begin() + cornerCount(face);
  };
  for (int c = 0; c < 2; ++c) {
    const Face& face = cut[std::size_t(c)];
    const Vec3 n = normalized(faceNormal(mesh, face));
    const int corners = cornerCount(face);
    for (int k = 0; k < corners; ++k) {
      const CornerIndex p = face[std::size_t(k)], q = face[std::size_t((k + 1) % corners)];
      const Face& other = cut[std::size_t(1 - c)];
      if (has(other, p) && has(other, q)) {
        if (dot(n, normalized(faceNormal(mesh, other))) < kFoldCosine) return false;
        continue;
      }
      for (const std::uint32_t* h = topology.facesBegin(p); h != topology.facesEnd(p); ++h)
        if (*h != f && *h != g && has(mesh.faces[*h], p) && has(mesh.faces[*h], q) &&
            dot(n, normalized(faceNormal(mesh, mesh.faces[*h]))) < kFoldCosine)
          return false;
    }
  }
  return true;
}

}  // namespace voxremesh::opt
