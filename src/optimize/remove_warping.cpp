// removeWarping: project the corners of warped quads on their mean planes (paper Sect. 5.1).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "optimize/mesh_topology.h"
#include "optimize/steps.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// Whether a quad is warped beyond the threshold, and the plane its corners are projected on.
struct QuadPlane {
  bool warped = false;
  Vec3 centroid{};
  Vec3 normal{};  ///< unit sum of the four diagonal-split triangle normals
};

/// The angle between a and b exceeds the angle whose cosine is cosLimit (false for a zero vector,
/// as quality.h counts a split with a zero-area triangle as flat).
bool wider(const Vec3& a, const Vec3& b, double cosLimit) {
  const double lengths = norm(a) * norm(b);
  return lengths > 0.0 && dot(a, b) < cosLimit * lengths;
}

QuadPlane quadPlane(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face, double cosLimit) {
  std::array<Vec3, 4> p;
  for (std::size_t k = 0; k < 4; ++k) p[k] = mesh.points[face[k]];
  QuadPlane plane;
  const Vec3 n012 = cross(p[1] - p[0], p[2] - p[0]), n023 = cross(p[2] - p[0], p[3] - p[0]);
  const Vec3 n123 = cross(p[2] - p[1], p[3] - p[1]), n130 = cross(p[3] - p[1], p[0] - p[1]);
  plane.warped = wider(n012, n023, cosLimit) || wider(n123, n130, cosLimit);
  plane.centroid = (p[0] + p[1] + p[2] + p[3]) * 0.25;
  plane.normal = normalized(n012 + n023 + n123 + n130);
  return plane;
}

/// q pulled back towards `from` to at most `radius` from it.
Vec3 clamped(const Vec3& from, const Vec3& q, double radius) {
  const double d = distance(from, q);
  return d > radius ? from + (q - from) * (radius / d) : q;
}

}  // namespace

WarpingResult removeWarping(QuadMesh& mesh, double maxWarpingDeg, int maxIterations, double maxMove,
                            opt::MeshCache& cache) {
  if (!std::isfinite(maxWarpingDeg) || maxWarpingDeg < 0.0)
    throw std::invalid_argument("removeWarping: threshold " + std::to_string(maxWarpingDeg) +
                                " is not a finite angle >= 0");
  if (maxIterations < 0) throw std::invalid_argument("removeWarping: negative iteration count");
  if (!(maxMove > 0.0)) throw std::invalid_argument("removeWarping: maxMove must be > 0");
  opt::checkMesh(mesh);
  const opt::Topology& topology = cache.topology(mesh);
  const std::size_t faceCount = mesh.faces.size();
  const double cosLimit = std::cos(maxWarpingDeg * 0.017453292519943295);
  std::vector<QuadPlane> planes(faceCount);
  std::vector<std::uint8_t> warped(faceCount, 0);
  auto measure = [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, faceCount),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t f = r.begin(); f < r.end(); ++f) {
                          warped[f] = 0;
                          if (cornerCount(mesh.faces[f]) != 4) continue;
                          planes[f] = quadPlane(mesh, mesh.faces[f], cosLimit);
                          warped[f] = planes[f].warped ? 1 : 0;
                        }
                      });
    std::size_t count = 0;
    for (const std::uint8_t w : warped) count += w;
    return count;
  };

  WarpingResult result;
  result.warpedBefore = result.warpedAfter = measure();
  std::size_t best = result.warpedAfter;
  int stalled = 0;
  std::vector<Vec3> next(mesh.points.size());
  const std::vector<Vec3> start = mesh.points;
  while (result.warpedAfter > 0 && result.iterations < maxIterations && stalled < 10) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.points.size()),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t v = r.begin(); v < r.end(); ++v) {
                          const auto vi = static_cast<CornerIndex>(v);
                          Vec3 sum{0.0, 0.0, 0.0};
                          int proposals = 0;
                          for (const std::uint32_t* f = topology.facesBegin(vi);
                               f != topology.facesEnd(vi); ++f) {
                            if (!warped[*f]) continue;
                            const QuadPlane& plane = planes[*f];
                            const Vec3& p = mesh.points[v];
                            sum = sum + (p - plane.normal * dot(p - plane.centroid, plane.normal));
                            ++proposals;
                          }
                          if (proposals == 0) {
                            next[v] = mesh.points[v];
                            continue;
                          }
                          const Vec3 mean = sum * (1.0 / proposals);
                          next[v] =
                              opt::constrainedPosition(mesh, vi, clamped(start[v], mean, maxMove));
                        }
                      });
    mesh.points.swap(next);
    ++result.iterations;
    result.warpedAfter = measure();
    if (result.warpedAfter < best) {
      best = result.warpedAfter;
      stalled = 0;
    } else {
      ++stalled;
    }
  }
  return result;
}

WarpingResult removeWarping(QuadMesh& mesh, double maxWarpingDeg, int maxIterations,
                            double maxMove) {
  opt::MeshCache cache;
  return removeWarping(mesh, maxWarpingDeg, maxIterations, maxMove, cache);
}

}  // namespace voxremesh
