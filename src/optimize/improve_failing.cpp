// improveFailingElements: moves the points of failing elements, one at a time, by a pattern
// search on the surface that lowers the failures of their faces (see optimize.h).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/point_search.h"
#include "optimize/search_engine.h"
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

/// The engine's items that move one point of a failing face each (improvePoint, in place).
/// Points that share no face do not see each other's moves in their faces' scores: one class is
/// searched in parallel. Their fold checks also read the faces across their faces' edges, which
/// may hold another point of the class: they read the positions from before the class (`frozen`),
/// so that the result does not depend on the thread count.
struct FailingPointSearches {
  struct Item {
    CornerIndex key;                   ///< the point searched
    opt::PointAccess access;           ///< the points of its faces; itself
    std::vector<CornerIndex> depends;  ///< the points of its faces
  };
  QuadMesh& mesh;
  const opt::Topology& topology;
  opt::MeshCache& cache;
  const ReferenceSurface& original;
  const QualitySettings& settings;
  std::vector<std::vector<Vec3>> fixedOnCurve;
  std::vector<PolylineIndex> curves;
  std::vector<Vec3> frozen;

  std::vector<Item> items(int /*round*/) {
    std::vector<Item> items;
    for (const CornerIndex v : pointsOfFailingFaces(mesh, topology, cache.failures(mesh))) {
      Item item{v, {}, {}};
      for (const std::uint32_t* f = topology.facesBegin(v); f != topology.facesEnd(v); ++f)
        for (int k = 0; k < cornerCount(mesh.faces[*f]); ++k)
          item.depends.push_back(mesh.faces[*f][std::size_t(k)]);
      item.access = {item.depends, {v}};
      items.push_back(std::move(item));
    }
    return items;
  }
  void startClass() { frozen = mesh.points; }
  bool tryItem(const Item& item) {
    return improvePoint(mesh, topology, original, settings, fixedOnCurve, curves, item.key, 0.01, 8,
                        &frozen);
  }
  std::vector<CornerIndex> apply(const Item& item, bool moved) {
    return moved ? std::vector<CornerIndex>{item.key} : std::vector<CornerIndex>{};
  }
  void endRound(std::size_t /*changed*/) {}
};

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
  FailingPointSearches kind{mesh,
                            cache.topology(mesh),
                            cache,
                            original,
                            settings,
                            fixedPointsOnCurves(mesh),
                            opt::indexCurves(mesh),
                            {}};
  // A point's search sees the moves of the classes before its own within the sweep; the classes
  // are formed before the record drops any point, so that the order of the searches, and with it
  // the result, is the same as without the record.
  return opt::runEngineRounds(sweeps, mesh.points.size(), {false, false}, kind);
}

std::size_t improveFailingElements(QuadMesh& mesh, const ReferenceSurface& original,
                                   const QualitySettings& settings, int sweeps) {
  opt::MeshCache cache(settings);
  return improveFailingElements(mesh, original, settings, sweeps, cache);
}

}  // namespace voxremesh
