// surfaceDistance: the two-sided distance between a mesh and an original surface, sampled at
// points, edge midpoints and points inside the faces (quality.h).
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "geometry/vec3.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

using Point = std::array<double, 3>;

/// Samples of a mesh and the face each one lies inside (kNoFace for points and edge midpoints).
struct Samples {
  static constexpr std::uint32_t kNoFace = ~std::uint32_t(0);
  std::vector<Point> points;
  std::vector<std::uint32_t> face;
};

/// The number of parts k each side of triangle abc is cut into: the smallest count that makes
/// them at most `spacing` long (2 .. 64; 2 when spacing is 0).
int subdivisions(const Point& a, const Point& b, const Point& c, double spacing) {
  const double longest =
      std::sqrt(std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)}));
  if (spacing > 0.0 && std::isfinite(longest / spacing))
    return std::clamp(static_cast<int>(std::ceil(longest / spacing)), 2, 64);
  return 2;
}

/// The centroids of the k x k similar triangles triangle abc is cut into (k = subdivisions).
void addInnerSamples(const Point& a, const Point& b, const Point& c, int k, std::uint32_t face,
                     Samples& out) {
  const Point u = (b - a) * (1.0 / k), v = (c - a) * (1.0 / k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      // The upright sub-triangle at (i, j) and, where it fits, the inverted one beside it.
      out.points.push_back(a + u * (i + 1.0 / 3.0) + v * (j + 1.0 / 3.0));
      out.face.push_back(face);
      if (i + j + 1 < k) {
        out.points.push_back(a + u * (i + 2.0 / 3.0) + v * (j + 2.0 / 3.0));
        out.face.push_back(face);
      }
    }
}

/// The samples of a mesh: its points first, then its distinct edges' midpoints, then the points
/// inside its faces' triangles (p0-p1-p2 and, for quads, p0-p2-p3).
Samples samplesOf(const QuadMesh& mesh, double spacing) {
  std::vector<std::pair<CornerIndex, CornerIndex>> edges;
  edges.reserve(4 * mesh.faces.size());
  for (const auto& face : mesh.faces) {
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k) {
      const CornerIndex a = face[static_cast<std::size_t>(k)];
      const CornerIndex b = face[static_cast<std::size_t>((k + 1) % n)];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  // Per face, the subdivisions of its triangles, so that the samples are allocated once.
  std::vector<std::array<int, 2>> cuts(mesh.faces.size(), {0, 0});
  std::size_t count = mesh.points.size() + edges.size();
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    for (int t = 0; t + 2 < cornerCount(face); ++t) {
      const int k = subdivisions(mesh.points[face[0]], mesh.points[face[std::size_t(t) + 1]],
                                 mesh.points[face[std::size_t(t) + 2]], spacing);
      cuts[f][std::size_t(t)] = k;
      count += std::size_t(k) * std::size_t(k);
    }
  }
  Samples samples;
  samples.points.reserve(count);
  samples.face.reserve(count);
  samples.points.insert(samples.points.end(), mesh.points.begin(), mesh.points.end());
  samples.face.insert(samples.face.end(), mesh.points.size(), Samples::kNoFace);
  for (const auto& [a, b] : edges) {
    samples.points.push_back((mesh.points[a] + mesh.points[b]) * 0.5);
    samples.face.push_back(Samples::kNoFace);
  }
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    for (int t = 0; t + 2 < cornerCount(face); ++t)
      addInnerSamples(mesh.points[face[0]], mesh.points[face[std::size_t(t) + 1]],
                      mesh.points[face[std::size_t(t) + 2]], cuts[f][std::size_t(t)], f, samples);
  }
  return samples;
}

/// Max and mean of the distances of `samples` to `surface`; the hits are returned too.
std::pair<double, double> maxAndMean(const ReferenceSurface& surface,
                                     const std::vector<Point>& samples,
                                     std::vector<SurfaceHit>& hits) {
  hits = surface.closestPoints(samples);
  double max = 0.0, sum = 0.0;
  for (const SurfaceHit& hit : hits) {
    max = std::max(max, hit.distance);
    sum += hit.distance;
  }
  return {max, hits.empty() ? 0.0 : sum / double(hits.size())};
}

}  // namespace

SurfaceDistance surfaceDistance(const QuadMesh& mesh, const QuadMesh& original,
                                double sampleSpacing) {
  const ReferenceSurface originalSurface(original);
  const ReferenceSurface meshSurface(mesh);
  SurfaceDistance result;
  result.faceDistance.assign(mesh.faces.size(), 0.0);
  if (originalSurface.empty() || meshSurface.empty()) return result;
  std::vector<SurfaceHit> hits;
  const Samples ofMesh = samplesOf(mesh, sampleSpacing);
  std::tie(result.maxToOriginal, result.meanToOriginal) =
      maxAndMean(originalSurface, ofMesh.points, hits);
  result.pointDistance.resize(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i) result.pointDistance[i] = hits[i].distance;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < cornerCount(mesh.faces[f]); ++k)
      result.faceDistance[f] =
          std::max(result.faceDistance[f], result.pointDistance[mesh.faces[f][std::size_t(k)]]);
  for (std::size_t i = 0; i < hits.size(); ++i)
    if (ofMesh.face[i] != Samples::kNoFace)
      result.faceDistance[ofMesh.face[i]] =
          std::max(result.faceDistance[ofMesh.face[i]], hits[i].distance);
  std::tie(result.maxFromOriginal, result.meanFromOriginal) =
      maxAndMean(meshSurface, samplesOf(original, sampleSpacing).points, hits);
  for (const SurfaceHit& hit : hits)
    result.faceDistance[hit.face] = std::max(result.faceDistance[hit.face], hit.distance);
  return result;
}

}  // namespace voxremesh
