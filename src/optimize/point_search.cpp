// The pattern search of one point (point_search.h).
#include "optimize/point_search.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "quality/fold_check.h"
#include "voxremesh/quality.h"

namespace voxremesh::opt {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// Whether the summed score of the faces `faces` is better than `best` (Score::betterThan),
/// given up as soon as the part summed cannot be better (failures and penalties are never
/// negative). The summed score goes to `score` when better; otherwise the face whose score gave it
/// up moves to the front of `faces`, as the one most likely to give up the next try.
bool scoresBetter(const QuadMesh& mesh, std::vector<std::uint32_t>& faces,
                  const QualitySettings& settings, const Score& best, Score& score) {
  Score sum;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    sum += faceScore(mesh, mesh.faces[faces[i]], settings);
    if (sum.failures > best.failures || (sum.failures == best.failures && !sum.betterThan(best))) {
      std::rotate(faces.begin(), faces.begin() + std::ptrdiff_t(i),
                  faces.begin() + std::ptrdiff_t(i) + 1);
      return false;
    }
  }
  score = sum;
  return true;
}

/// The faces touching a corner of a face round v, as a mesh of their own (points renumbered, no
/// constraints), and v's index in it: enough to see whether a move of v folds a face (foldedFaces,
/// quality.h), since only faces round v change and only their neighbours see it.
struct LocalRing {
  QuadMesh mesh;
  CornerIndex v = 0;
  std::vector<CornerIndex> global;  ///< per local point, its index in the whole mesh, ascending
  std::optional<quality::FoldCheck> folds;  ///< of `mesh`'s faces
};

LocalRing ringAround(const QuadMesh& mesh, const std::vector<Vec3>& positions, const Topology& t,
                     CornerIndex v) {
  std::vector<std::uint32_t> faces;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f)
    for (int k = 0; k < cornerCount(mesh.faces[*f]); ++k) {
      const CornerIndex p = mesh.faces[*f][std::size_t(k)];
      faces.insert(faces.end(), t.facesBegin(p), t.facesEnd(p));
    }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  LocalRing ring;
  for (const std::uint32_t f : faces)
    for (int k = 0; k < cornerCount(mesh.faces[f]); ++k)
      ring.global.push_back(mesh.faces[f][std::size_t(k)]);
  std::sort(ring.global.begin(), ring.global.end());
  ring.global.erase(std::unique(ring.global.begin(), ring.global.end()), ring.global.end());
  const auto local = [&](CornerIndex p) {
    return CornerIndex(std::lower_bound(ring.global.begin(), ring.global.end(), p) -
                       ring.global.begin());
  };
  for (const CornerIndex p : ring.global) ring.mesh.points.push_back(positions[p]);
  for (const std::uint32_t f : faces) {
    auto face = mesh.faces[f];
    for (int k = 0; k < cornerCount(face); ++k) face[std::size_t(k)] = local(face[std::size_t(k)]);
    ring.mesh.faces.push_back(face);
  }
  ring.v = local(v);
  ring.folds.emplace(ring.mesh);
  return ring;
}

/// The number of faces of the ring folded (foldedFaces) with v at `position`.
std::size_t foldedWithVAt(LocalRing& ring, const Vec3& position) {
  ring.mesh.points[ring.v] = position;
  const std::vector<std::uint8_t> folded = ring.folds->folded(ring.mesh);
  return std::size_t(std::count(folded.begin(), folded.end(), std::uint8_t(1)));
}

/// A unit normal of the surface at v (the sum of its faces' normals) and the mean length of its
/// edges.
void localFrame(const QuadMesh& mesh, const Topology& t, CornerIndex v, Vec3& normal,
                double& edge) {
  const auto& p = mesh.points;
  Vec3 sum{0.0, 0.0, 0.0};
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f) {
    const auto& face = mesh.faces[*f];
    sum = sum + (cornerCount(face) == 3 ? cross(p[face[1]] - p[face[0]], p[face[2]] - p[face[0]])
                                        : cross(p[face[2]] - p[face[0]], p[face[3]] - p[face[1]]));
  }
  normal = normalized(sum);
  edge = 0.0;
  for (const std::uint32_t* w = t.nbrsBegin(v); w != t.nbrsEnd(v); ++w)
    edge += distance(p[v], p[*w]);
  edge /= double(std::max<std::size_t>(1, t.degree(v)));
}

}  // namespace

bool searchDirections(const QuadMesh& mesh, const Topology& t, CornerIndex v,
                      std::array<Vec3, 8>& directions, double& edge) {
  Vec3 normal;
  localFrame(mesh, t, v, normal, edge);
  if (!(edge > 0.0) || norm(normal) == 0.0) return false;
  // An in-plane basis.
  const Vec3 axis = std::abs(normal[0]) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
  const Vec3 u = normalized(cross(normal, axis));
  const Vec3 w = cross(normal, u);
  directions = {u,
                u * -1.0,
                w,
                w * -1.0,
                normalized(u + w),
                normalized(u - w) * -1.0,
                normalized(u - w),
                normalized(u + w) * -1.0};
  return true;
}

/// The summed score of the faces around v.
Score scoreAround(const QuadMesh& mesh, const Topology& t, CornerIndex v,
                  const QualitySettings& settings) {
  Score score;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f)
    score += faceScore(mesh, mesh.faces[*f], settings);
  return score;
}

/// Per curve, the positions of the fixed points (Corners, Junction points) that lie on it.
std::vector<std::vector<Vec3>> fixedPointsOnCurves(const QuadMesh& mesh) {
  std::vector<std::vector<Vec3>> result(mesh.curves.size());
  std::vector<std::array<Vec3, 2>> boxes(mesh.curves.size());  // lower and upper corner
  for (std::size_t c = 0; c < mesh.curves.size(); ++c) {
    if (mesh.curves[c].points.empty()) continue;
    boxes[c] = {mesh.curves[c].points.front(), mesh.curves[c].points.front()};
    for (const Vec3& q : mesh.curves[c].points)
      for (std::size_t k = 0; k < 3; ++k) {
        boxes[c][0][k] = std::min(boxes[c][0][k], q[k]);
        boxes[c][1][k] = std::max(boxes[c][1][k], q[k]);
      }
  }
  for (CornerIndex v = 0; v < mesh.points.size(); ++v) {
    if (roleOf(mesh, v) != PointRole::Corner) continue;
    const Vec3& p = mesh.points[v];
    const double tolerance = 1e-9 * (1.0 + norm(p));
    for (std::size_t c = 0; c < mesh.curves.size(); ++c) {
      bool inBox = !mesh.curves[c].points.empty();
      for (std::size_t k = 0; k < 3; ++k)
        inBox = inBox && p[k] >= boxes[c][0][k] - tolerance && p[k] <= boxes[c][1][k] + tolerance;
      if (inBox && distance(p, closestPointOnPolyline(mesh.curves[c].points, mesh.curves[c].closed,
                                                      p)) <= tolerance)
        result[c].push_back(p);
    }
  }
  return result;
}

/// The pattern search of one point (see improveFailingElements). Returns whether it moved.
/// `fixedOnCurve` (fixedPointsOnCurves): a curve point never goes within a small distance of a
/// fixed point of its curve (moving along a curve past a sharp turn or the end of a line, the
/// closest curve point is the vertex there, where a Corner may sit: the two would coincide).
/// `curves`: the indexes of the mesh's curves (indexCurves).
bool improvePoint(QuadMesh& mesh, const Topology& t, const ReferenceSurface& original,
                  const QualitySettings& settings,
                  const std::vector<std::vector<Vec3>>& fixedOnCurve,
                  const std::vector<PolylineIndex>& curves, CornerIndex v, double smallestStep,
                  int movesPerStep, const std::vector<Vec3>* frozen) {
  const Vec3 start = mesh.points[v];
  const bool free = roleOf(mesh, v) == PointRole::Free;
  std::array<Vec3, 8> directions;
  double edge = 0.0;
  if (!searchDirections(mesh, t, v, directions, edge)) return false;
  std::uint32_t hint = kNoCorner;
  auto place = [&](const Vec3& wanted) {
    if (!free) return constrainedPosition(mesh, curves, v, wanted);
    const SurfaceHit hit = original.closestPoint(wanted, hint);
    hint = hit.face;
    return hit.point;
  };
  const std::vector<Vec3> none;
  const std::vector<Vec3>& fixed = free ? none : fixedOnCurve[mesh.constraints[v].curve];
  auto onFixedPoint = [&](const Vec3& q) {
    for (const Vec3& c : fixed)
      if (distance(q, c) < 0.05 * edge) return true;
    return false;
  };
  // The faces round v, the worst first: the likeliest to make a try give up early (the order
  // changes which faces are scored, not whether a try is taken).
  std::vector<std::pair<Score, std::uint32_t>> scored;
  Score best;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f) {
    scored.emplace_back(faceScore(mesh, mesh.faces[*f], settings), *f);
    best += scored.back().first;
  }
  std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) {
    return a.first.failures != b.first.failures ? a.first.failures > b.first.failures
                                                : a.first.penalty > b.first.penalty;
  });
  std::vector<std::uint32_t> faces;
  for (const auto& entry : scored) faces.push_back(entry.second);
  if (best.failures == 0 && best.penalty == 0.0) return false;
  // No try may fold a face (foldedFaces), which can pass every criterion of its own. The ring is
  // built when a try first scores better (most searches end without one).
  std::optional<LocalRing> ring;
  std::size_t foldedBefore = 0;
  const auto foldsNoMore = [&](const Vec3& at) {
    if (!ring) {
      ring = ringAround(mesh, frozen ? *frozen : mesh.points, t, v);
      foldedBefore = foldedWithVAt(*ring, start);
    }
    return foldedWithVAt(*ring, at) <= foldedBefore;
  };
  const auto accept = [&](const Vec3& at) {
    Score score;
    if (onFixedPoint(at) || !scoresBetter(mesh, faces, settings, best, score) || !foldsNoMore(at))
      return false;
    best = score;
    return true;
  };
  return compassSearch(mesh, v, directions, edge, smallestStep, movesPerStep, place, accept);
}

}  // namespace voxremesh::opt
