// cleanUpMesh: zero-area faces and doublets (Free interior points in exactly two faces).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/mesh_topology.h"
#include "optimize/steps.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

namespace {

using geom::operator-;

/// Interior angle of a face at a curve point above which the face is folded along the curve.
constexpr double kFoldedCurveAngleDeg = 150.0;

/// Drops repeated consecutive corners of every face (a-a-b-c is the triangle a-b-c); faces left
/// with fewer than three distinct corners, or repeating a diagonal, are erased. Returns how many
/// faces changed or went.
std::size_t dropRepeatedCorners(QuadMesh& mesh) {
  std::vector<std::uint8_t> deleted(mesh.faces.size(), 0);
  std::size_t changed = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    auto& face = mesh.faces[f];
    const int n = cornerCount(face);
    std::array<CornerIndex, 4> kept{kNoCorner, kNoCorner, kNoCorner, kNoCorner};
    int m = 0;
    for (int k = 0; k < n; ++k) {
      const CornerIndex c = face[static_cast<std::size_t>(k)];
      if (m > 0 && kept[static_cast<std::size_t>(m - 1)] == c) continue;
      kept[static_cast<std::size_t>(m++)] = c;
    }
    if (m > 1 && kept[static_cast<std::size_t>(m - 1)] == kept[0])
      kept[static_cast<std::size_t>(--m)] = kNoCorner;
    if (m == n) continue;
    ++changed;
    if (m < 3 || (m == 4 && (kept[0] == kept[2] || kept[1] == kept[3])))
      deleted[f] = 1;
    else
      face = kept;
  }
  opt::eraseFaces(mesh, deleted);
  return changed;
}

/// Removes faces that use the same points as another face: both of a pair that runs opposite ways
/// (a fold, two faces back to back), all but the first of faces that run the same way. Returns
/// the number of faces removed.
std::size_t removeDuplicateFaces(QuadMesh& mesh) {
  // (sorted corners, face) for every face, sorted: equal point sets become neighbours.
  std::vector<std::pair<std::array<CornerIndex, 4>, std::uint32_t>> keys;
  keys.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    std::array<CornerIndex, 4> key = mesh.faces[f];
    std::sort(key.begin(), key.end());  // kNoCorner sorts last
    keys.emplace_back(key, static_cast<std::uint32_t>(f));
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint8_t> deleted(mesh.faces.size(), 0);
  std::size_t removed = 0;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && keys[j].first == keys[i].first) ++j;
    for (std::size_t k = i + 1; k < j; ++k) {
      const auto& first = mesh.faces[keys[i].second];
      const auto& other = mesh.faces[keys[k].second];
      // Same way round: the corner after first[0] is the same in both.
      const int n = cornerCount(first);
      int at = 0;
      while (other[static_cast<std::size_t>(at)] != first[0]) ++at;
      const bool sameWay = other[static_cast<std::size_t>((at + 1) % n)] == first[1];
      if (!sameWay && !deleted[keys[i].second]) {
        deleted[keys[i].second] = 1;
        ++removed;
      }
      deleted[keys[k].second] = 1;
      ++removed;
    }
    i = j;
  }
  opt::eraseFaces(mesh, deleted);
  return removed;
}

/// One round of shortest-edge collapses of faces with area at most zeroArea or an edge shorter
/// than shortEdge; the counts of each kind are added to `result`. Returns the number done.
std::size_t collapseSmallFaces(QuadMesh& mesh, const opt::Topology& topology, double zeroArea,
                               double shortEdge, CleanupResult& result) {
  std::vector<std::uint8_t> locked(mesh.points.size(), 0), deleted(mesh.faces.size(), 0);
  std::size_t done = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (deleted[f]) continue;
    const auto face = mesh.faces[f];
    const int n = cornerCount(face);
    int shortest = 0;
    double length = geom::distance(mesh.points[face[0]], mesh.points[face[1]]);
    for (int k = 1; k < n; ++k) {
      const double l = geom::distance(mesh.points[face[static_cast<std::size_t>(k)]],
                                      mesh.points[face[static_cast<std::size_t>((k + 1) % n)]]);
      if (l < length) length = l, shortest = k;
    }
    const bool zero = opt::faceArea(mesh, face) <= zeroArea;
    if (!zero && !(length < shortEdge)) continue;
    const CornerIndex u = face[static_cast<std::size_t>(shortest)];
    const CornerIndex v = face[static_cast<std::size_t>((shortest + 1) % n)];
    if (!opt::tryMerge(mesh, topology, u, v, locked, deleted)) continue;
    ++(zero ? result.zeroAreaFaces : result.shortEdges);
    ++done;
  }
  opt::eraseFaces(mesh, deleted);
  return done;
}

/// The corners of `face` starting after v, up to the one before v.
std::vector<CornerIndex> pathAround(const std::array<CornerIndex, 4>& face, CornerIndex v) {
  const int n = cornerCount(face);
  int at = 0;
  while (face[static_cast<std::size_t>(at)] != v) ++at;
  std::vector<CornerIndex> path;
  for (int k = 1; k < n; ++k) path.push_back(face[static_cast<std::size_t>((at + k) % n)]);
  return path;
}

/// One round of doublet removal; returns the number of points removed.
std::size_t removeDoublets(QuadMesh& mesh, const opt::Topology& topology) {
  std::vector<std::uint8_t> locked(mesh.points.size(), 0), deleted(mesh.faces.size(), 0);
  std::size_t done = 0;
  for (CornerIndex v = 0; v < mesh.points.size(); ++v) {
    if (topology.faceCount(v) != 2 || topology.boundary[v] ||
        opt::roleOf(mesh, v) != PointRole::Free ||
        opt::neighbourhoodLocked(mesh, topology, v, locked))
      continue;
    const std::uint32_t f1 = topology.facesBegin(v)[0], f2 = topology.facesBegin(v)[1];
    const std::vector<CornerIndex> a = pathAround(mesh.faces[f1], v);
    const std::vector<CornerIndex> b = pathAround(mesh.faces[f2], v);
    if (a.front() != b.back() || a.back() != b.front()) continue;  // not consistently oriented
    std::vector<CornerIndex> polygon(a.begin(), a.end());
    polygon.insert(polygon.end(), b.begin() + 1, b.end() - 1);
    bool repeats = false;
    for (std::size_t i = 0; i < polygon.size(); ++i)
      for (std::size_t j = 0; j < i; ++j) repeats = repeats || polygon[i] == polygon[j];
    if (repeats) continue;
    opt::lockNeighbourhood(mesh, topology, v, locked);
    deleted[f2] = 1;
    if (polygon.size() < 3) {
      deleted[f1] = 1;
    } else {
      std::array<CornerIndex, 4> merged{kNoCorner, kNoCorner, kNoCorner, kNoCorner};
      for (std::size_t k = 0; k < polygon.size(); ++k) merged[k] = polygon[k];
      mesh.faces[f1] = merged;
    }
    ++done;
  }
  opt::eraseFaces(mesh, deleted);
  return done;
}

/// True when the points are on one curve: a shares b's curve or is a Corner.
bool onCurveOf(const QuadMesh& mesh, CornerIndex a, CornerIndex b) {
  const PointRole role = opt::roleOf(mesh, a);
  return role == PointRole::Corner ||
         (role != PointRole::Free && mesh.constraints[a].curve == mesh.constraints[b].curve);
}

/// One round of folded-curve collapses: a face with three consecutive corners a, b, c on one
/// curve (b a curve point, a and c on its curve or Corners) and an interior angle above
/// kFoldedCurveAngleDeg at b lies along the curve (a quad like a triangle with b on its side, a
/// triangle as a sliver); b merges into the nearer of a and c. Returns the number done.
std::size_t collapseFoldedCurveFaces(QuadMesh& mesh, const opt::Topology& topology) {
  if (mesh.constraints.empty()) return 0;
  std::vector<std::uint8_t> locked(mesh.points.size(), 0), deleted(mesh.faces.size(), 0);
  std::size_t done = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto face = mesh.faces[f];
    const std::size_t n = static_cast<std::size_t>(cornerCount(face));
    if (deleted[f]) continue;
    for (std::size_t k = 0; k < n; ++k) {
      const CornerIndex a = face[(k + n - 1) % n], b = face[k], c = face[(k + 1) % n];
      const PointRole role = opt::roleOf(mesh, b);
      if (role == PointRole::Free || role == PointRole::Corner || !onCurveOf(mesh, a, b) ||
          !onCurveOf(mesh, c, b))
        continue;
      const geom::Vec3& pb = mesh.points[b];
      if (geom::angleDeg(mesh.points[a] - pb, mesh.points[c] - pb) <= kFoldedCurveAngleDeg)
        continue;
      const CornerIndex into =
          geom::distance(mesh.points[a], pb) <= geom::distance(mesh.points[c], pb) ? a : c;
      if (!opt::tryMerge(mesh, topology, b, into, locked, deleted)) continue;
      ++done;
      break;
    }
  }
  opt::eraseFaces(mesh, deleted);
  return done;
}

}  // namespace

CleanupResult cleanUpMesh(QuadMesh& mesh, const CleanupSettings& settings, opt::MeshCache& cache) {
  const double zeroArea = settings.zeroArea, shortEdge = settings.shortEdge;
  if (!std::isfinite(zeroArea) || zeroArea < 0.0)
    throw std::invalid_argument("cleanUpMesh: zero-area threshold " + std::to_string(zeroArea) +
                                " is not finite and >= 0");
  if (!std::isfinite(shortEdge) || shortEdge < 0.0)
    throw std::invalid_argument("cleanUpMesh: short-edge threshold " + std::to_string(shortEdge) +
                                " is not finite and >= 0");
  CleanupResult result;
  result.zeroAreaFaces += dropRepeatedCorners(mesh);
  opt::checkMesh(mesh);
  // Each step reads the topology of the mesh as it finds it (built again only after a step
  // changed the mesh).
  for (;;) {
    const std::size_t duplicates = removeDuplicateFaces(mesh);
    result.duplicateFaces += duplicates;
    const std::size_t zero =
        collapseSmallFaces(mesh, cache.topology(mesh), zeroArea, shortEdge, result);
    const std::size_t doublets = removeDoublets(mesh, cache.topology(mesh));
    result.valence2Points += doublets;
    const std::size_t folded = settings.foldedCurves && !mesh.constraints.empty()
                                   ? collapseFoldedCurveFaces(mesh, cache.topology(mesh))
                                   : 0;
    result.foldedCurveFaces += folded;
    if (duplicates == 0 && zero == 0 && doublets == 0 && folded == 0) break;
  }
  eraseUnusedPoints(mesh);
  return result;
}

CleanupResult cleanUpMesh(QuadMesh& mesh, const CleanupSettings& settings) {
  opt::MeshCache cache;
  return cleanUpMesh(mesh, settings, cache);
}

}  // namespace voxremesh
