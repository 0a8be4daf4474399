// improveFailingElements: moves the points of failing elements, one at a time, to the candidate
// position that leaves their faces failing fewest criteria (see optimize.h).
#include <algorithm>
#include <bitset>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/mesh_topology.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// How well the faces around a point do: fewer failed criteria first, then the larger smallest
/// Jacobian ratio (as the settings evaluate it), then the larger smallest scaled Jacobian.
struct Score {
  int failures = 0;
  double jacobian = 1.0;
  double scaled = 1.0;
  bool betterThan(const Score& other) const {
    if (failures != other.failures) return failures < other.failures;
    if (jacobian != other.jacobian) return jacobian > other.jacobian + 1e-9;
    return scaled > other.scaled + 1e-9;
  }
};

std::uint32_t faceFailures(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face,
                           const QualitySettings& settings, ElementQuality& quality) {
  const int n = cornerCount(face);
  std::array<std::array<double, 3>, 4> p{};
  for (int k = 0; k < n; ++k) p[std::size_t(k)] = mesh.points[face[std::size_t(k)]];
  quality = elementQuality(p, n);
  return elementFailures(quality, n, settings);
}

Score scoreAround(const QuadMesh& mesh, const opt::Topology& t, CornerIndex v,
                  const QualitySettings& settings) {
  Score score;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f) {
    ElementQuality q;
    score.failures += int(std::bitset<32>(faceFailures(mesh, mesh.faces[*f], settings, q)).count());
    if (cornerCount(mesh.faces[*f]) == 4)
      score.jacobian = std::min(
          score.jacobian, settings.jacobianAtGaussPoints ? q.jacobianRatioGauss : q.jacobianRatio);
    score.scaled = std::min(score.scaled, q.scaledJacobian);
  }
  return score;
}

/// Positions worth trying for point v: the centroid of its edge neighbours, the mean of the
/// positions that would make each of its quads a parallelogram, and half-way steps to both.
std::vector<Vec3> candidates(const QuadMesh& mesh, const opt::Topology& t, CornerIndex v) {
  const Vec3& p = mesh.points[v];
  Vec3 centroid{0.0, 0.0, 0.0};
  for (const std::uint32_t* w = t.nbrsBegin(v); w != t.nbrsEnd(v); ++w)
    centroid = centroid + mesh.points[*w];
  centroid = centroid * (1.0 / double(std::max<std::size_t>(1, t.degree(v))));
  Vec3 parallelogram{0.0, 0.0, 0.0};
  std::vector<Vec3> single;
  int quads = 0;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f) {
    const auto& face = mesh.faces[*f];
    if (cornerCount(face) != 4) continue;
    std::size_t k = 0;
    while (face[k] != v) ++k;
    const Vec3 own = mesh.points[face[(k + 1) % 4]] + mesh.points[face[(k + 3) % 4]] -
                     mesh.points[face[(k + 2) % 4]];
    parallelogram = parallelogram + own;
    single.push_back((p + own) * 0.5);
    ++quads;
  }
  std::vector<Vec3> result{centroid, (p + centroid) * 0.5};
  if (quads > 0) {
    parallelogram = parallelogram * (1.0 / quads);
    result.push_back(parallelogram);
    result.push_back((p + parallelogram) * 0.5);
  }
  result.insert(result.end(), single.begin(), single.end());
  return result;
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
  std::size_t moved = 0;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    // The movable points of the failing faces, in index order (deterministic).
    std::vector<CornerIndex> points;
    const std::vector<ElementQuality> qualities = elementQualities(mesh);  // in parallel
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const auto& face = mesh.faces[f];
      if (elementFailures(qualities[f], cornerCount(face), settings) == 0) continue;
      for (int k = 0; k < cornerCount(face); ++k) {
        const CornerIndex v = face[std::size_t(k)];
        const PointRole role = opt::roleOf(mesh, v);
        const bool free = role == PointRole::Free && !topology.boundary[v];
        if (free || role == PointRole::Boundary || role == PointRole::Feature) points.push_back(v);
      }
    }
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    std::size_t movedThisSweep = 0;
    for (const CornerIndex v : points) {
      const Vec3 start = mesh.points[v];
      const Score initial = scoreAround(mesh, topology, v, settings);
      Score best = initial;
      Vec3 bestPosition = start;
      // Free points: the candidates are weighed where they are (near the surface) and only the
      // best is projected on it, then taken if it is still better.
      const bool free = opt::roleOf(mesh, v) == PointRole::Free;
      for (const Vec3& wanted : candidates(mesh, topology, v)) {
        mesh.points[v] = free ? wanted : opt::constrainedPosition(mesh, v, wanted);
        const Score score = scoreAround(mesh, topology, v, settings);
        if (score.betterThan(best)) best = score, bestPosition = mesh.points[v];
      }
      if (free && bestPosition != start) {
        mesh.points[v] = original.closestPoint(bestPosition).point;
        bestPosition =
            scoreAround(mesh, topology, v, settings).betterThan(initial) ? mesh.points[v] : start;
      }
      mesh.points[v] = bestPosition;
      if (bestPosition != start) ++movedThisSweep;
    }
    moved += movedThisSweep;
    if (movedThisSweep == 0) break;
  }
  return moved;
}

}  // namespace voxremesh
