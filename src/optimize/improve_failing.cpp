// improveFailingElements: moves the points of failing elements, one at a time, by a pattern
// search on the surface that lowers the failures of their faces (see optimize.h).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/independent_classes.h"
#include "optimize/point_search.h"
#include "optimize/steps.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

using opt::fixedPointsOnCurves;
using opt::improvePoint;
using opt::Vec3;

namespace {

/// The points of the faces that fail a criterion and can move, ascending.
std::vector<CornerIndex> pointsOfFailingFaces(const QuadMesh& mesh, const opt::Topology& t,
                                              const std::vector<std::uint32_t>& failures) {
  std::vector<CornerIndex> points;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    if (failures[f] == 0) continue;
    for (int k = 0; k < cornerCount(face); ++k) {
      const CornerIndex v = face[std::size_t(k)];
      if (opt::searchable(mesh, t, v)) points.push_back(v);
    }
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

}  // namespace

std::size_t improveFailingElements(QuadMesh& mesh, const ReferenceSurface& original,
                                   const QualitySettings& settings, int sweeps,
                                   opt::MeshCache& cache) {
  if (original.empty())
    throw std::invalid_argument("improveFailingElements: the original surface is empty");
  if (sweeps < 0) throw std::invalid_argument("improveFailingElements: negative sweep count");
  if (!(settings.targetSize > 0.0))
    throw std::invalid_argument("improveFailingElements: targetSize must be > 0");
  checkQualitySettings(settings);
  opt::checkMesh(mesh);
  const opt::Topology& topology = cache.topology(mesh);
  const std::vector<std::vector<Vec3>> fixedOnCurve = fixedPointsOnCurves(mesh);
  const std::vector<PolylineIndex> curves = opt::indexCurves(mesh);
  std::size_t moved = 0;
  // A point searched in vain is not searched again until a point of its faces has moved
  // (SearchRecord); stamps count the classes processed. The classes are formed before the
  // skipping, so the order of the searches, and with it the result, is the same as without it.
  opt::SearchRecord record(mesh.points.size());
  std::uint32_t stamp = 0;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    // Points that share no face do not see each other's moves in their faces' scores: the points
    // of one class are improved in parallel, the classes one after another. Their fold checks
    // also read the faces across their faces' edges, which may hold another point of the class:
    // they read the positions from before the class (`frozen`), so the result does not depend on
    // the thread count.
    const std::vector<CornerIndex> failingPoints =
        pointsOfFailingFaces(mesh, topology, cache.failures(mesh));
    std::vector<opt::PointAccess> access(failingPoints.size());
    for (std::size_t i = 0; i < failingPoints.size(); ++i) {
      const CornerIndex v = failingPoints[i];
      for (const std::uint32_t* f = topology.facesBegin(v); f != topology.facesEnd(v); ++f)
        for (int k = 0; k < cornerCount(mesh.faces[*f]); ++k)
          access[i].reads.push_back(mesh.faces[*f][std::size_t(k)]);
      access[i].writes = {v};
    }
    std::size_t movedThisSweep = 0;
    std::vector<Vec3> frozen;
    opt::runInClasses(
        access, mesh.points.size(),
        [&](std::uint32_t i) {
          return !record.unchangedSinceSearch(mesh, topology, failingPoints[i]);
        },
        [&] {
          ++stamp;
          frozen = mesh.points;
        },
        [&](std::uint32_t i) {
          return improvePoint(mesh, topology, original, settings, fixedOnCurve, curves,
                              failingPoints[i], 0.01, 8, &frozen);
        },
        [&](std::uint32_t i, bool movedNow) {
          movedThisSweep += movedNow;
          record.note(failingPoints[i], movedNow, stamp);
        });
    moved += movedThisSweep;
    if (movedThisSweep == 0) break;
  }
  return moved;
}

std::size_t improveFailingElements(QuadMesh& mesh, const ReferenceSurface& original,
                                   const QualitySettings& settings, int sweeps) {
  opt::MeshCache cache(settings);
  return improveFailingElements(mesh, original, settings, sweeps, cache);
}

}  // namespace voxremesh
