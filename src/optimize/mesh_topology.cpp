// The connectivity and point-merging helpers the optimisation steps share (mesh_topology.h).
#include "optimize/mesh_topology.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "voxremesh/reference_surface.h"

namespace voxremesh::opt {

using namespace geom;  // NOLINT: the vector operators

namespace {

bool isCurveRole(PointRole role) {
  return role == PointRole::Feature || role == PointRole::Boundary || role == PointRole::Junction;
}

/// Builds CSR lists from (key, value) pairs sorted by key then value.
void toCsr(std::vector<std::array<std::uint32_t, 2>>& pairs, std::size_t keys,
           std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& list) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  start.assign(keys + 1, 0);
  list.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    ++start[pairs[i][0] + 1];
    list[i] = pairs[i][1];
  }
  for (std::size_t k = 0; k < keys; ++k) start[k + 1] += start[k];
}

}  // namespace

void checkMesh(const QuadMesh& mesh) {
  const std::size_t n = mesh.points.size();
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    const int count = cornerCount(face);
    for (int k = 0; k < count; ++k) {
      const CornerIndex c = face[static_cast<std::size_t>(k)];
      if (c >= n)
        throw std::invalid_argument("face " + std::to_string(f) + " names point " +
                                    std::to_string(c) + " of a mesh with " + std::to_string(n));
      for (int j = 0; j < k; ++j)
        if (face[static_cast<std::size_t>(j)] == c)
          throw std::invalid_argument("face " + std::to_string(f) + " repeats point " +
                                      std::to_string(c));
    }
  }
  if (!mesh.constraints.empty() && mesh.constraints.size() != n)
    throw std::invalid_argument("the mesh has " + std::to_string(mesh.constraints.size()) +
                                " constraints for " + std::to_string(n) + " points");
  for (std::size_t v = 0; v < mesh.constraints.size(); ++v) {
    const PointConstraint& c = mesh.constraints[v];
    if (isCurveRole(c.role) &&
        (c.curve >= mesh.curves.size() || mesh.curves[c.curve].points.empty()))
      throw std::invalid_argument("point " + std::to_string(v) + " is bound to curve " +
                                  std::to_string(c.curve) + ", which is missing or empty");
  }
}

std::size_t Topology::edgeFaces(CornerIndex a, CornerIndex b) const {
  const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
  const auto first =
      std::lower_bound(edges.begin(), edges.end(), std::array<std::uint32_t, 3>{lo, hi, 0});
  std::size_t count = 0;
  for (auto it = first; it != edges.end() && (*it)[0] == lo && (*it)[1] == hi; ++it) ++count;
  return count;
}

Topology buildTopology(const QuadMesh& mesh, const std::vector<std::uint8_t>* deleted) {
  Topology t;
  std::vector<std::array<std::uint32_t, 2>> vf, vv;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (deleted && (*deleted)[f]) continue;
    const auto& face = mesh.faces[f];
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k) {
      const CornerIndex a = face[static_cast<std::size_t>(k)];
      const CornerIndex b = face[static_cast<std::size_t>((k + 1) % n)];
      vf.push_back({a, static_cast<std::uint32_t>(f)});
      vv.push_back({a, b});
      vv.push_back({b, a});
      t.edges.push_back({std::min(a, b), std::max(a, b), static_cast<std::uint32_t>(f)});
    }
  }
  std::sort(t.edges.begin(), t.edges.end());
  toCsr(vf, mesh.points.size(), t.faceStart, t.faceList);
  toCsr(vv, mesh.points.size(), t.nbrStart, t.nbrList);
  t.boundary.assign(mesh.points.size(), 0);
  for (std::size_t i = 0; i < t.edges.size();) {
    std::size_t j = i;
    while (j < t.edges.size() && t.edges[j][0] == t.edges[i][0] && t.edges[j][1] == t.edges[i][1])
      ++j;
    if (j - i == 1) t.boundary[t.edges[i][0]] = t.boundary[t.edges[i][1]] = 1;
    i = j;
  }
  return t;
}

Vec3 constrainedPosition(const QuadMesh& mesh, CornerIndex v, const Vec3& wanted) {
  const PointRole role = roleOf(mesh, v);
  if (role == PointRole::Corner) return mesh.points[v];
  if (isCurveRole(role)) {
    const MeshCurve& curve = mesh.curves[mesh.constraints[v].curve];
    return closestPointOnPolyline(curve.points, curve.closed, wanted);
  }
  return wanted;
}

std::optional<Merge> mergeUnderConstraints(const QuadMesh& mesh, CornerIndex u, CornerIndex v) {
  const PointRole ru = roleOf(mesh, u), rv = roleOf(mesh, v);
  const Vec3 middle = (mesh.points[u] + mesh.points[v]) * 0.5;
  if (ru == PointRole::Free && rv == PointRole::Free)
    return Merge{std::min(u, v), std::max(u, v), middle};
  if (ru == PointRole::Free) return Merge{v, u, mesh.points[v]};
  if (rv == PointRole::Free) return Merge{u, v, mesh.points[u]};
  if (ru == PointRole::Corner && rv == PointRole::Corner) return std::nullopt;
  if (ru == PointRole::Corner) return Merge{u, v, mesh.points[u]};
  if (rv == PointRole::Corner) return Merge{v, u, mesh.points[v]};
  if (mesh.constraints[u].curve != mesh.constraints[v].curve) return std::nullopt;
  return Merge{std::min(u, v), std::max(u, v), constrainedPosition(mesh, u, middle)};
}

bool mergeKeepsManifold(const QuadMesh& mesh, const Topology& t, CornerIndex u, CornerIndex v) {
  std::vector<CornerIndex> predicted;
  bool adjacent = false;
  for (const std::uint32_t* f = t.facesBegin(u); f != t.facesEnd(u); ++f) {
    const auto& face = mesh.faces[*f];
    const int n = cornerCount(face);
    int iu = -1, iv = -1;
    for (int k = 0; k < n; ++k) {
      if (face[static_cast<std::size_t>(k)] == u) iu = k;
      if (face[static_cast<std::size_t>(k)] == v) iv = k;
    }
    if (iv < 0) continue;
    const bool edge = (iu + 1) % n == iv || (iv + 1) % n == iu;
    adjacent = adjacent || edge;
    for (int k = 0; k < n; ++k) {
      if (k == iu || k == iv) continue;
      if (!edge || n == 3) predicted.push_back(face[static_cast<std::size_t>(k)]);
    }
  }
  std::sort(predicted.begin(), predicted.end());
  predicted.erase(std::unique(predicted.begin(), predicted.end()), predicted.end());
  std::vector<CornerIndex> common;
  std::set_intersection(t.nbrsBegin(u), t.nbrsEnd(u), t.nbrsBegin(v), t.nbrsEnd(v),
                        std::back_inserter(common));
  if (common != predicted) return false;
  if (t.boundary[u] && t.boundary[v]) return adjacent && t.edgeFaces(u, v) == 1;
  return true;
}

void applyMerge(QuadMesh& mesh, const Topology& t, const Merge& merge,
                std::vector<std::uint8_t>& deleted) {
  mesh.points[merge.keep] = merge.position;
  for (const std::uint32_t* f = t.facesBegin(merge.remove); f != t.facesEnd(merge.remove); ++f) {
    auto& face = mesh.faces[*f];
    const int n = cornerCount(face);
    std::array<CornerIndex, 4> kept{kNoCorner, kNoCorner, kNoCorner, kNoCorner};
    int m = 0;
    for (int k = 0; k < n; ++k) {
      CornerIndex c = face[static_cast<std::size_t>(k)];
      if (c == merge.remove) c = merge.keep;
      if (m > 0 && kept[static_cast<std::size_t>(m - 1)] == c) continue;
      kept[static_cast<std::size_t>(m++)] = c;
    }
    if (m > 1 && kept[static_cast<std::size_t>(m - 1)] == kept[0])
      kept[static_cast<std::size_t>(--m)] = kNoCorner;
    // A repeat left after removing neighbours (a-b-a-d) is a collapsed diagonal.
    const bool repeated = m == 4 && (kept[0] == kept[2] || kept[1] == kept[3]);
    if (m < 3 || repeated)
      deleted[*f] = 1;
    else
      face = kept;
  }
}

void lockNeighbourhood(const QuadMesh& mesh, const Topology& t, CornerIndex v,
                       std::vector<std::uint8_t>& locked) {
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f) {
    const auto& face = mesh.faces[*f];
    for (int k = 0; k < cornerCount(face); ++k) locked[face[static_cast<std::size_t>(k)]] = 1;
  }
  locked[v] = 1;
}

bool neighbourhoodLocked(const QuadMesh& mesh, const Topology& t, CornerIndex v,
                         const std::vector<std::uint8_t>& locked) {
  if (locked[v]) return true;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f) {
    const auto& face = mesh.faces[*f];
    for (int k = 0; k < cornerCount(face); ++k)
      if (locked[face[static_cast<std::size_t>(k)]]) return true;
  }
  return false;
}

void eraseFaces(QuadMesh& mesh, const std::vector<std::uint8_t>& deleted) {
  std::size_t out = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (!deleted[f]) mesh.faces[out++] = mesh.faces[f];
  mesh.faces.resize(out);
}

void removeUnusedPoints(QuadMesh& mesh) {
  std::vector<CornerIndex> newIndex(mesh.points.size(), kNoCorner);
  for (const auto& face : mesh.faces)
    for (int k = 0; k < cornerCount(face); ++k) newIndex[face[static_cast<std::size_t>(k)]] = 0;
  CornerIndex next = 0;
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    if (newIndex[v] == kNoCorner) continue;
    newIndex[v] = next;
    mesh.points[next] = mesh.points[v];
    if (!mesh.constraints.empty()) mesh.constraints[next] = mesh.constraints[v];
    ++next;
  }
  mesh.points.resize(next);
  if (!mesh.constraints.empty()) mesh.constraints.resize(next);
  for (auto& face : mesh.faces)
    for (int k = 0; k < cornerCount(face); ++k)
      face[static_cast<std::size_t>(k)] = newIndex[face[static_cast<std::size_t>(k)]];
}

double faceArea(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face) {
  const auto& p = mesh.points;
  if (cornerCount(face) == 3)
    return 0.5 * geom::norm(geom::cross(p[face[1]] - p[face[0]], p[face[2]] - p[face[0]]));
  return 0.5 * geom::norm(geom::cross(p[face[2]] - p[face[0]], p[face[3]] - p[face[1]]));
}

}  // namespace voxremesh::opt
