// relaxMesh: tangential smoothing projected on the original surface, curve points on their
// curves, corners fixed.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/ideal_shape.h"
#include "optimize/mesh_topology.h"
#include "optimize/steps.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// A Free boundary point where the boundary turns by more than this many degrees stays put (as
/// SheetSettings::cornerAngleDeg makes such points Corners where the sheets are built).
constexpr double kBoundaryCornerDeg = 30.0;

/// An edge runs along a curve when its midpoint is within this fraction of its length of the curve.
constexpr double kAlongCurveTolerance = 0.1;

/// The largest stable damping (see relaxMesh).
constexpr double kMaxDamping = 0.7;

/// The neighbours of v along boundary edges.
std::vector<CornerIndex> boundaryNeighbours(const opt::Topology& t, CornerIndex v) {
  std::vector<CornerIndex> result;
  for (const std::uint32_t* w = t.nbrsBegin(v); w != t.nbrsEnd(v); ++w)
    if (t.edgeFaces(v, *w) == 1) result.push_back(*w);
  return result;
}

/// The neighbours of v along its curve: along boundary edges for a Boundary point or a Free point
/// on the boundary, else along edges to points of the same curve or to Corners whose midpoint
/// lies on the curve (kAlongCurveTolerance).
std::vector<CornerIndex> curveNeighbours(const QuadMesh& mesh, const opt::Topology& t,
                                         CornerIndex v) {
  const PointRole role = opt::roleOf(mesh, v);
  if (role == PointRole::Boundary || (role == PointRole::Free && t.boundary[v]))
    return boundaryNeighbours(t, v);
  std::vector<CornerIndex> result;
  if (role == PointRole::Free || role == PointRole::Corner) return result;
  const MeshCurve& curve = mesh.curves[mesh.constraints[v].curve];
  for (const std::uint32_t* w = t.nbrsBegin(v); w != t.nbrsEnd(v); ++w) {
    const PointRole other = opt::roleOf(mesh, *w);
    if (other != PointRole::Corner &&
        (other == PointRole::Free || mesh.constraints[*w].curve != mesh.constraints[v].curve))
      continue;
    // The edge must run along the curve: a Corner (or a point of the curve) reached across the
    // surface, e.g. the end of another feature line, is no neighbour along this one.
    const Vec3 middle = (mesh.points[v] + mesh.points[*w]) * 0.5;
    const Vec3 onCurve = closestPointOnPolyline(curve.points, curve.closed, middle);
    if (distance(middle, onCurve) <=
        kAlongCurveTolerance * distance(mesh.points[v], mesh.points[*w]))
      result.push_back(*w);
  }
  return result;
}

/// The edge length of a face's ideal shape: targetSize when > 0, else the edge of the square or
/// equilateral triangle of the face's area.
double idealEdge(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face, double targetSize) {
  if (targetSize > 0.0) return targetSize;
  const double area = opt::faceArea(mesh, face);
  return cornerCount(face) == 4 ? std::sqrt(area) : std::sqrt(area * 4.0 / std::sqrt(3.0));
}

/// The shape target of a Free point: the mean of the positions its faces' ideal shapes
/// (idealCorners) give it, minus the part of the move along its normal.
Vec3 idealTarget(const QuadMesh& mesh, const opt::Topology& t,
                 const std::vector<std::array<Vec3, 4>>& ideal, CornerIndex v) {
  Vec3 sum{0.0, 0.0, 0.0}, normal{0.0, 0.0, 0.0};
  int count = 0;
  const auto& p = mesh.points;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f) {
    const auto& face = mesh.faces[*f];
    const int n = cornerCount(face);
    std::size_t k = 0;
    while (face[k] != v) ++k;
    sum = sum + ideal[*f][k];
    ++count;
    normal = normal + (n == 3 ? cross(p[face[1]] - p[face[0]], p[face[2]] - p[face[0]])
                              : cross(p[face[2]] - p[face[0]], p[face[3]] - p[face[1]]));
  }
  if (count == 0) return p[v];
  const Vec3 move = sum * (1.0 / count) - p[v];
  const Vec3 unit = normalized(normal);
  return p[v] + move - unit * dot(move, unit);
}

/// The closest point of `original` to q; `hint` is the face of the point's previous projection
/// (updated), which only speeds the search up.
Vec3 project(const ReferenceSurface& original, const Vec3& q, std::uint32_t& hint) {
  const SurfaceHit hit = original.closestPoint(q, hint);
  hint = hit.face;
  return hit.point;
}

/// The new position of point v in one relaxation step (see relaxMesh); `along` holds its curve
/// or boundary neighbours, `curves` the indexes of the mesh's curves (opt::indexCurves), `hint`
/// the face of its previous projection on `original`.
Vec3 relaxed(const QuadMesh& mesh, const opt::Topology& t, const ReferenceSurface& original,
             const std::vector<std::array<Vec3, 4>>& ideal, const std::vector<CornerIndex>& along,
             const std::vector<PolylineIndex>& curves, CornerIndex v, double damping,
             std::uint32_t& hint) {
  const Vec3& p = mesh.points[v];
  const PointRole role = opt::roleOf(mesh, v);
  if (t.faceCount(v) == 0 || role == PointRole::Corner) return p;
  if (role == PointRole::Free && !t.boundary[v])
    return project(original, p + (idealTarget(mesh, t, ideal, v) - p) * damping, hint);
  if (along.size() != 2)
    return role == PointRole::Free ? p : opt::constrainedPosition(mesh, curves, v, p);
  const Vec3& a = mesh.points[along[0]];
  const Vec3& b = mesh.points[along[1]];
  Vec3 move = (a + b) * 0.5 - p;
  if (role == PointRole::Free) {
    // A Free boundary point slides along the boundary only, so that the mesh does not shrink;
    // where the boundary turns by more than kBoundaryCornerDeg it is a corner and stays.
    if (angleDeg(p - a, b - p) > kBoundaryCornerDeg) return p;
    const Vec3 tangent = normalized(b - a);
    return project(original, p + tangent * (dot(move, tangent) * damping), hint);
  }
  return opt::constrainedPosition(mesh, curves, v, p + move * damping);
}

}  // namespace

void relaxMesh(QuadMesh& mesh, const ReferenceSurface& original, int iterations, double damping,
               double targetSize, opt::MeshCache& cache) {
  if (original.empty()) throw std::invalid_argument("relaxMesh: the original surface is empty");
  if (iterations < 0) throw std::invalid_argument("relaxMesh: negative iteration count");
  if (!std::isfinite(targetSize) || targetSize < 0.0)
    throw std::invalid_argument("relaxMesh: target size " + std::to_string(targetSize) +
                                " is not finite and >= 0");
  if (!(damping > 0.0 && damping <= kMaxDamping))
    throw std::invalid_argument("relaxMesh: damping " + std::to_string(damping) +
                                " is not in (0, 0.7]");
  opt::checkMesh(mesh);
  const opt::Topology& topology = cache.topology(mesh);
  const std::size_t count = mesh.points.size();
  std::vector<std::vector<CornerIndex>> along(count);
  for (CornerIndex v = 0; v < count; ++v) along[v] = curveNeighbours(mesh, topology, v);
  std::vector<Vec3> next(count);
  std::vector<std::uint32_t> hints(count, kNoCorner);
  const std::vector<PolylineIndex> curves = opt::indexCurves(mesh);
  std::vector<std::array<Vec3, 4>> ideal(mesh.faces.size());
  for (int iteration = 0; iteration < iterations; ++iteration) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ideal.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t f = r.begin(); f < r.end(); ++f)
                          ideal[f] = opt::idealCorners(mesh, mesh.faces[f],
                                                       idealEdge(mesh, mesh.faces[f], targetSize));
                      });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t v = r.begin(); v < r.end(); ++v)
                          next[v] = relaxed(mesh, topology, original, ideal, along[v], curves,
                                            static_cast<CornerIndex>(v), damping, hints[v]);
                      });
    mesh.points.swap(next);
  }
}

void relaxMesh(QuadMesh& mesh, const ReferenceSurface& original, int iterations, double damping,
               double targetSize) {
  opt::MeshCache cache;
  relaxMesh(mesh, original, iterations, damping, targetSize, cache);
}

}  // namespace voxremesh
