// surfaceDistance: the two-sided distance between a mesh and an original surface, sampled at
// points, edge midpoints and face centroids.
#include <algorithm>
#include <utility>
#include <vector>

#include "geometry/vec3.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// The samples of a mesh: its points first, then its distinct edges' midpoints, then its faces'
/// centroids.
std::vector<std::array<double, 3>> samplesOf(const QuadMesh& mesh) {
  std::vector<std::array<double, 3>> samples = mesh.points;
  std::vector<std::pair<CornerIndex, CornerIndex>> edges;
  for (const auto& face : mesh.faces) {
    const int n = cornerCount(face);
    std::array<double, 3> centroid{0.0, 0.0, 0.0};
    for (int k = 0; k < n; ++k) {
      const CornerIndex a = face[static_cast<std::size_t>(k)];
      const CornerIndex b = face[static_cast<std::size_t>((k + 1) % n)];
      edges.emplace_back(std::min(a, b), std::max(a, b));
      centroid = centroid + mesh.points[a];
    }
    samples.push_back(centroid * (1.0 / n));
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const auto& [a, b] : edges) samples.push_back((mesh.points[a] + mesh.points[b]) * 0.5);
  return samples;
}

/// Max and mean of the distances of `samples` to `surface`; the hits are returned too.
std::pair<double, double> maxAndMean(const ReferenceSurface& surface,
                                     const std::vector<std::array<double, 3>>& samples,
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

SurfaceDistance surfaceDistance(const QuadMesh& mesh, const QuadMesh& original) {
  const ReferenceSurface originalSurface(original);
  const ReferenceSurface meshSurface(mesh);
  SurfaceDistance result;
  if (originalSurface.empty() || meshSurface.empty()) return result;
  std::vector<SurfaceHit> hits;
  std::tie(result.maxToOriginal, result.meanToOriginal) =
      maxAndMean(originalSurface, samplesOf(mesh), hits);
  result.pointDistance.resize(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i) result.pointDistance[i] = hits[i].distance;
  std::tie(result.maxFromOriginal, result.meanFromOriginal) =
      maxAndMean(meshSurface, samplesOf(original), hits);
  return result;
}

}  // namespace voxremesh
