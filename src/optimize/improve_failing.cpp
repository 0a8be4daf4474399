// improveFailingElements: moves the points of failing elements, one at a time, by a pattern
// search on the surface that lowers the failures of their faces (see optimize.h).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/face_score.h"
#include "optimize/mesh_topology.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// The summed score of the faces around v.
opt::Score scoreAround(const QuadMesh& mesh, const opt::Topology& t, CornerIndex v,
                       const QualitySettings& settings) {
  opt::Score score;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f)
    score += opt::faceScore(mesh, mesh.faces[*f], settings);
  return score;
}

/// Whether the summed score of the faces around v is better than `best` (Score::betterThan),
/// summed in the order of scoreAround and given up as soon as the part summed cannot be better
/// (failures and penalties are never negative). The summed score goes to `score` when better.
bool scoresBetterAround(const QuadMesh& mesh, const opt::Topology& t, CornerIndex v,
                        const QualitySettings& settings, const opt::Score& best,
                        opt::Score& score) {
  opt::Score sum;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f) {
    sum += opt::faceScore(mesh, mesh.faces[*f], settings);
    if (sum.failures > best.failures || (sum.failures == best.failures && !sum.betterThan(best)))
      return false;
  }
  score = sum;
  return true;
}

/// A unit normal of the surface at v (the sum of its faces' normals) and the mean length of its
/// edges.
void localFrame(const QuadMesh& mesh, const opt::Topology& t, CornerIndex v, Vec3& normal,
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

/// The points of the faces that fail a criterion and can move, ascending.
std::vector<CornerIndex> pointsOfFailingFaces(const QuadMesh& mesh, const opt::Topology& t,
                                              const QualitySettings& settings) {
  std::vector<CornerIndex> points;
  const std::vector<ElementQuality> qualities = elementQualities(mesh);  // in parallel
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    if (elementFailures(qualities[f], cornerCount(face), settings) == 0) continue;
    for (int k = 0; k < cornerCount(face); ++k) {
      const CornerIndex v = face[std::size_t(k)];
      const PointRole role = opt::roleOf(mesh, v);
      const bool free = role == PointRole::Free && !t.boundary[v];
      if (free || role == PointRole::Boundary || role == PointRole::Feature) points.push_back(v);
    }
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

/// Splits `points` (ascending) into classes of points that share no face, greedily in index
/// order: each point goes to the first class none of whose points shares a face with it.
std::vector<std::vector<CornerIndex>> independentClasses(const QuadMesh& mesh,
                                                         const opt::Topology& t,
                                                         const std::vector<CornerIndex>& points) {
  std::vector<int> colour(mesh.points.size(), -1);
  std::vector<std::vector<CornerIndex>> classes;
  std::vector<std::uint8_t> taken;
  for (const CornerIndex v : points) {
    taken.assign(classes.size() + 1, 0);
    for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f)
      for (int k = 0; k < cornerCount(mesh.faces[*f]); ++k) {
        const int c = colour[mesh.faces[*f][std::size_t(k)]];
        if (c >= 0) taken[std::size_t(c)] = 1;
      }
    std::size_t c = 0;
    while (taken[c]) ++c;
    if (c == classes.size()) classes.emplace_back();
    classes[c].push_back(v);
    colour[v] = int(c);
  }
  return classes;
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
    if (opt::roleOf(mesh, v) != PointRole::Corner) continue;
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
/// `curves`: the indexes of the mesh's curves (opt::indexCurves).
bool improvePoint(QuadMesh& mesh, const opt::Topology& t, const ReferenceSurface& original,
                  const QualitySettings& settings,
                  const std::vector<std::vector<Vec3>>& fixedOnCurve,
                  const std::vector<PolylineIndex>& curves, CornerIndex v) {
  const Vec3 start = mesh.points[v];
  const bool free = opt::roleOf(mesh, v) == PointRole::Free;
  Vec3 normal;
  double edge = 0.0;
  localFrame(mesh, t, v, normal, edge);
  if (!(edge > 0.0) || norm(normal) == 0.0) return false;
  // An in-plane basis.
  const Vec3 axis = std::abs(normal[0]) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
  const Vec3 u = normalized(cross(normal, axis));
  const Vec3 w = cross(normal, u);
  const std::array<Vec3, 8> directions = {u,
                                          u * -1.0,
                                          w,
                                          w * -1.0,
                                          normalized(u + w),
                                          normalized(u - w) * -1.0,
                                          normalized(u - w),
                                          normalized(u + w) * -1.0};
  std::uint32_t hint = kNoCorner;
  auto place = [&](const Vec3& wanted) {
    if (!free) return opt::constrainedPosition(mesh, curves, v, wanted);
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
  opt::Score best = scoreAround(mesh, t, v, settings);
  if (best.failures == 0 && best.penalty == 0.0) return false;
  Vec3 position = start;
  for (double step = 0.25 * edge; step > 0.01 * edge; step *= 0.5) {
    bool improved = true;
    for (int round = 0; improved && round < 8; ++round) {
      improved = false;
      for (const Vec3& direction : directions) {
        mesh.points[v] = place(position + direction * step);
        if (onFixedPoint(mesh.points[v])) continue;
        opt::Score score;
        if (scoresBetterAround(mesh, t, v, settings, best, score)) {
          best = score;
          position = mesh.points[v];
          improved = true;
          break;
        }
      }
    }
  }
  mesh.points[v] = position;
  return position != start;
}

}  // namespace

std::size_t improveFailingElements(QuadMesh& mesh, const ReferenceSurface& original,
                                   const QualitySettings& settings, int sweeps) {
  if (original.empty())
    throw std::invalid_argument("improveFailingElements: the original surface is empty");
  if (sweeps < 0) throw std::invalid_argument("improveFailingElements: negative sweep count");
  if (!(settings.targetSize > 0.0))
    throw std::invalid_argument("improveFailingElements: targetSize must be > 0");
  checkQualitySettings(settings);
  opt::checkMesh(mesh);
  const opt::Topology topology = opt::buildTopology(mesh);
  const std::vector<std::vector<Vec3>> fixedOnCurve = fixedPointsOnCurves(mesh);
  const std::vector<PolylineIndex> curves = opt::indexCurves(mesh);
  std::size_t moved = 0;
  std::vector<std::uint8_t> movedNow(mesh.points.size(), 0);
  // A point's search depends only on the positions of the points of its faces: a point whose
  // search left it in place is not searched again until one of those has moved. Stamps count
  // the colour classes processed (0: never); a point searched in vain at stamp s is skipped while
  // every point of its faces last moved before s. The classes are formed before the skipping, so
  // the order of the searches, and with it the result, is the same as without it.
  std::vector<std::uint32_t> movedAt(mesh.points.size(), 0), stayedAt(mesh.points.size(), 0);
  std::uint32_t stamp = 0;
  auto unchangedSinceSearch = [&](CornerIndex v) {
    if (stayedAt[v] == 0) return false;
    for (const std::uint32_t* f = topology.facesBegin(v); f != topology.facesEnd(v); ++f)
      for (int k = 0; k < cornerCount(mesh.faces[*f]); ++k)
        if (movedAt[mesh.faces[*f][std::size_t(k)]] >= stayedAt[v]) return false;
    return true;
  };
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    // Points that share no face do not see each other's moves: the points of one colour class
    // are improved in parallel, the classes one after another, so the result does not depend
    // on the thread count.
    const std::vector<std::vector<CornerIndex>> classes =
        independentClasses(mesh, topology, pointsOfFailingFaces(mesh, topology, settings));
    std::size_t movedThisSweep = 0;
    for (std::vector<CornerIndex> points : classes) {
      points.erase(std::remove_if(points.begin(), points.end(), unchangedSinceSearch),
                   points.end());
      ++stamp;
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 8),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i < r.end(); ++i)
                            movedNow[points[i]] = improvePoint(mesh, topology, original, settings,
                                                               fixedOnCurve, curves, points[i]);
                        });
      for (const CornerIndex v : points) {
        movedThisSweep += movedNow[v];
        movedAt[v] = movedNow[v] ? stamp : movedAt[v];
        stayedAt[v] = movedNow[v] ? 0 : stamp;
      }
    }
    moved += movedThisSweep;
    if (movedThisSweep == 0) break;
  }
  return moved;
}

}  // namespace voxremesh
