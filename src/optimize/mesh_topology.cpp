// The connectivity and point-merging helpers the optimisation steps share (mesh_topology.h).
#include "optimize/mesh_topology.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "voxremesh/reference_surface.h"

namespace voxremesh::opt {

using namespace geom;  // NOLINT: the vector operators

namespace {

bool isCurveRole(PointRole role) {
  return role == PointRole::Feature || role == PointRole::Boundary || role == PointRole::Junction;
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
  for (std::size_t v = 0; v < n; ++v)
    for (const double x : mesh.points[v])
      if (!std::isfinite(x))
        throw std::invalid_argument("point " + std::to_string(v) + " has a non-finite coordinate");
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
  const std::uint32_t* found = std::lower_bound(nbrsBegin(a), nbrsEnd(a), b);
  return found != nbrsEnd(a) && *found == b
             ? nbrFaces[static_cast<std::size_t>(found - nbrList.data())]
             : 0;
}

Topology buildTopology(const QuadMesh& mesh, const std::vector<std::uint8_t>* deleted) {
  Topology t;
  const std::size_t points = mesh.points.size();
  // Faces per point: count, prefix sum, fill (faces come in ascending order).
  t.faceStart.assign(points + 1, 0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (deleted && (*deleted)[f]) continue;
    for (int k = 0; k < cornerCount(mesh.faces[f]); ++k)
      ++t.faceStart[mesh.faces[f][static_cast<std::size_t>(k)] + 1];
  }
  for (std::size_t v = 0; v < points; ++v) t.faceStart[v + 1] += t.faceStart[v];
  t.faceList.resize(t.faceStart[points]);
  std::vector<std::uint32_t> fill(t.faceStart.begin(), t.faceStart.end() - 1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (deleted && (*deleted)[f]) continue;
    for (int k = 0; k < cornerCount(mesh.faces[f]); ++k)
      t.faceList[fill[mesh.faces[f][static_cast<std::size_t>(k)]]++] =
          static_cast<std::uint32_t>(f);
  }
  // Neighbours per point: the two corners beside it in each of its faces, sorted; a neighbour
  // appears once per face of the edge to it, so the length of its run is that edge's face count.
  std::vector<std::uint32_t> candidates(2 * t.faceList.size()), runs(candidates.size());
  std::vector<std::uint32_t> unique(points + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t v = r.begin(); v < r.end(); ++v) {
                        std::uint32_t* const begin = candidates.data() + 2 * t.faceStart[v];
                        std::uint32_t* out = begin;
                        for (std::uint32_t i = t.faceStart[v]; i < t.faceStart[v + 1]; ++i) {
                          const auto& face = mesh.faces[t.faceList[i]];
                          const int n = cornerCount(face);
                          int k = 0;
                          while (face[static_cast<std::size_t>(k)] != v) ++k;
                          *out++ = face[static_cast<std::size_t>((k + n - 1) % n)];
                          *out++ = face[static_cast<std::size_t>((k + 1) % n)];
                        }
                        std::sort(begin, out);
                        // The distinct neighbours to the front, each with the length of its run.
                        std::uint32_t* const count = runs.data() + 2 * t.faceStart[v];
                        std::size_t distinct = 0;
                        for (const std::uint32_t* w = begin; w != out; ++w) {
                          if (distinct > 0 && begin[distinct - 1] == *w) {
                            ++count[distinct - 1];
                            continue;
                          }
                          begin[distinct] = *w;
                          count[distinct++] = 1;
                        }
                        unique[v + 1] = static_cast<std::uint32_t>(distinct);
                      }
                    });
  for (std::size_t v = 0; v < points; ++v) unique[v + 1] += unique[v];
  t.nbrStart = std::move(unique);
  t.nbrList.resize(t.nbrStart[points]);
  t.nbrFaces.resize(t.nbrList.size());
  t.boundary.assign(points, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t v = r.begin(); v < r.end(); ++v) {
                        const std::size_t from = 2 * t.faceStart[v], to = t.nbrStart[v];
                        const std::size_t degree = t.degree(static_cast<CornerIndex>(v));
                        std::copy_n(candidates.begin() + std::ptrdiff_t(from), degree,
                                    t.nbrList.begin() + std::ptrdiff_t(to));
                        std::copy_n(runs.begin() + std::ptrdiff_t(from), degree,
                                    t.nbrFaces.begin() + std::ptrdiff_t(to));
                        for (std::size_t i = to; i < to + degree; ++i)
                          if (t.nbrFaces[i] == 1) t.boundary[v] = 1;
                      }
                    });
  return t;
}

namespace {

/// The position of point v nearest to `wanted` under its constraint (see constrainedPosition),
/// with `onCurve(c, q)` the closest point of curve c to q.
template <class OnCurve>
Vec3 constrained(const QuadMesh& mesh, CornerIndex v, const Vec3& wanted, const OnCurve& onCurve) {
  const PointRole role = roleOf(mesh, v);
  if (role == PointRole::Corner) return mesh.points[v];
  if (isCurveRole(role)) return onCurve(mesh.constraints[v].curve, wanted);
  return wanted;
}

}  // namespace

Vec3 constrainedPosition(const QuadMesh& mesh, CornerIndex v, const Vec3& wanted) {
  return constrained(mesh, v, wanted, [&](std::uint32_t c, const Vec3& q) {
    return closestPointOnPolyline(mesh.curves[c].points, mesh.curves[c].closed, q);
  });
}

std::vector<PolylineIndex> indexCurves(const QuadMesh& mesh) {
  std::vector<PolylineIndex> curves;
  curves.reserve(mesh.curves.size());
  for (const MeshCurve& curve : mesh.curves) curves.emplace_back(curve.points, curve.closed);
  return curves;
}

Vec3 constrainedPosition(const QuadMesh& mesh, const std::vector<PolylineIndex>& curves,
                         CornerIndex v, const Vec3& wanted) {
  return constrained(mesh, v, wanted, [&](std::uint32_t c, const Vec3& q) {
    if (c >= curves.size())
      throw std::invalid_argument("constrainedPosition: curve " + std::to_string(c) + " of point " +
                                  std::to_string(v) + " has no index (" +
                                  std::to_string(curves.size()) + " curve indexes)");
    return curves[c].closestPoint(q);
  });
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

bool tryMerge(QuadMesh& mesh, const Topology& topology, CornerIndex u, CornerIndex v,
              std::vector<std::uint8_t>& locked, std::vector<std::uint8_t>& deleted,
              const ReferenceSurface* surface) {
  if (neighbourhoodLocked(mesh, topology, u, locked) ||
      neighbourhoodLocked(mesh, topology, v, locked) || !mergeKeepsManifold(mesh, topology, u, v))
    return false;
  std::optional<Merge> merge = mergeUnderConstraints(mesh, u, v);
  if (!merge) return false;
  if (surface && !surface->empty() && roleOf(mesh, merge->keep) == PointRole::Free)
    merge->position = surface->closestPoint(merge->position).point;
  lockNeighbourhood(mesh, topology, u, locked);
  lockNeighbourhood(mesh, topology, v, locked);
  applyMerge(mesh, topology, *merge, deleted);
  return true;
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

double faceArea(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face) {
  const auto& p = mesh.points;
  if (cornerCount(face) == 3)
    return 0.5 * geom::norm(geom::cross(p[face[1]] - p[face[0]], p[face[2]] - p[face[0]]));
  return 0.5 * geom::norm(geom::cross(p[face[2]] - p[face[0]], p[face[3]] - p[face[1]]));
}

}  // namespace voxremesh::opt
