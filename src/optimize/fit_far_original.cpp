// fitFarOriginalPoints: points of the mesh pulled towards the nodes of the original surface the
// mesh passes farthest from (tight bends it cuts across), where that brings them closer without
// failing more criteria (optimize.h).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "optimize/chord_error.h"
#include "optimize/face_score.h"
#include "optimize/mesh_topology.h"
#include "optimize/point_search.h"
#include "optimize/search_engine.h"
#include "optimize/steps.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

namespace {

using Face = std::array<CornerIndex, 4>;
using opt::Vec3;
using namespace geom;  // NOLINT: the vector operators

/// The step works first on the samples of the original farther from the mesh than this share of
/// the distance limit (a margin under the limit), then on those farther than kNearShare of it:
/// the chords across bends that make the new mesh softer than the original.
constexpr double kFarShare = 0.8;
constexpr double kNearShare = 0.2;

/// The faces round v.
std::vector<Face> facesAround(const QuadMesh& mesh, const opt::Topology& t, CornerIndex v) {
  std::vector<Face> faces;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f)
    faces.push_back(mesh.faces[*f]);
  return faces;
}

/// The distance from p to the nearest of `faces` of `mesh`, each cut into triangles as
/// ReferenceSurface cuts it (p0-p1-p2, and p0-p2-p3 for a quad), faces[first] tried first; or,
/// as soon as a triangle within `enough` of p is found, that triangle's distance.
double distanceToFaces(const QuadMesh& mesh, const std::vector<Face>& faces, std::size_t first,
                       const Vec3& p, double enough) {
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < faces.size() && nearest > enough; ++i) {
    const Face& face = faces[i == 0 ? first : i == first ? 0 : i];
    for (int k = 2; k < cornerCount(face) && nearest > enough; ++k) {
      const Vec3& a = mesh.points[face[0]];
      const Vec3 q = closestPointOnTriangle(p, a, mesh.points[face[std::size_t(k - 1)]],
                                            mesh.points[face[std::size_t(k)]]);
      nearest = std::min(nearest, distance(p, q));
    }
  }
  return nearest;
}

/// A sample of the original near a point's faces, with its distance to them before any move and
/// the one of them it was nearest to (an index into them).
struct NearSample {
  Vec3 point;
  double before = 0.0;
  std::size_t nearestFace = 0;
};

/// How far the samples `near` (sorted by `before`, farthest first) lie beyond `far` from the faces
/// `faces` of `mesh` after a corner of those faces moved by `moved`: the sum of the squares of
/// their excess. Infinite when a sample ends up farther than both `far` and its distance before.
/// A sample whose distance before plus `moved` is within `far` is not measured (no point of the
/// faces moved farther than `moved`): it stays within. The sum stops once it reaches `enough`
/// (the caller wants only sums below it).
double excessNear(const QuadMesh& mesh, const std::vector<Face>& faces,
                  const std::vector<NearSample>& near, double moved, double far, double enough) {
  double excess = 0.0;
  for (const NearSample& s : near) {
    if (s.before + moved <= far || excess >= enough) break;
    // Within `far` a sample adds nothing, whatever its distance: the search stops there.
    const double d = distanceToFaces(mesh, faces, s.nearestFace, s.point, far);
    if (d > std::max(s.before, far)) return std::numeric_limits<double>::infinity();
    if (d > far) excess += (d - far) * (d - far);
  }
  return excess;
}

/// The samples each face of the mesh is closest to, ascending, all in one array: face f's are
/// samples[start[f]] .. samples[start[f + 1]].
struct SamplesByFace {
  std::vector<std::uint32_t> start, samples;
  SamplesByFace(const std::vector<SurfaceHit>& hits, std::size_t faces) : start(faces + 1, 0) {
    for (const SurfaceHit& hit : hits) ++start[hit.face + 1];
    for (std::size_t f = 0; f < faces; ++f) start[f + 1] += start[f];
    samples.resize(hits.size());
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::uint32_t i = 0; i < hits.size(); ++i) samples[next[hits[i].face]++] = i;
  }
};

/// What the pulls of one pass read: the original's samples, the closest point of the mesh to each
/// (as the pass began), the samples each face is closest to, the criteria and the distance beyond
/// which a sample is far.
struct PassState {
  const ReferenceSurface& original;
  const QualitySettings& settings;
  const std::vector<Vec3>& samples;
  const std::vector<SurfaceHit>& hits;
  const SamplesByFace& nearestTo;
  double far = 0.0;
};

/// The compass search of corner v (as improvePoint's, in the plane of its faces, on the
/// original): a move is taken when the samples near its faces lie less beyond `far`
/// (excessNear), none farther than before where beyond it, the faces fail no more criteria and
/// stray no farther from the original than allowed. Returns whether v moved.
bool pullCorner(QuadMesh& mesh, const opt::Topology& t, CornerIndex v, const PassState& pass) {
  std::array<Vec3, 8> directions;
  double edge = 0.0;
  if (!opt::searchDirections(mesh, t, v, directions, edge)) return false;
  const double far = pass.far;
  const std::vector<Face> around = facesAround(mesh, t, v);
  std::vector<NearSample> near;
  for (const std::uint32_t* g = t.facesBegin(v); g != t.facesEnd(v); ++g)
    for (std::uint32_t k = pass.nearestTo.start[*g]; k < pass.nearestTo.start[*g + 1]; ++k) {
      const std::uint32_t s = pass.nearestTo.samples[k];
      near.push_back({pass.samples[s], pass.hits[s].distance, std::size_t(g - t.facesBegin(v))});
    }
  std::stable_sort(near.begin(), near.end(),
                   [](const NearSample& a, const NearSample& b) { return a.before > b.before; });
  const Vec3 start = mesh.points[v];
  // What a try that lies less beyond `far` is checked against (most tries are not): found at the
  // first such try, with v put back at its start for the measures before the move.
  struct Guards {
    int failuresBefore = 0;
    opt::ChordAroundPoint chordError;
    double chordAllowed = 0.0;
  };
  std::optional<Guards> guards;
  const auto guardsFor = [&]() -> const Guards& {
    if (!guards) {
      const Vec3 at = mesh.points[v];
      mesh.points[v] = start;
      guards.emplace(Guards{opt::scoreAround(mesh, t, v, pass.settings).failures,
                            opt::ChordAroundPoint(mesh, around, v, pass.original), 0.0});
      guards->chordAllowed = std::max(guards->chordError(mesh), far);
      mesh.points[v] = at;
    }
    return *guards;
  };
  double best = 0.0;
  for (const NearSample& sample : near)
    if (sample.before > far) best += (sample.before - far) * (sample.before - far);
  std::uint32_t hint = kNoCorner;
  const auto place = [&](const Vec3& wanted) {
    const SurfaceHit hit = pass.original.closestPoint(wanted, hint);
    hint = hit.face;
    return hit.point;
  };
  const auto accept = [&](const Vec3& at) {
    const double enough = best * (1.0 - 1e-9);
    const double excess = excessNear(mesh, around, near, distance(at, start), far, enough);
    if (!(excess < enough)) return false;
    const Guards& g = guardsFor();
    if (opt::scoreAround(mesh, t, v, pass.settings).failures > g.failuresBefore) return false;
    if (g.chordError(mesh) > g.chordAllowed) return false;
    best = excess;
    return true;
  };
  return opt::compassSearch(mesh, v, directions, edge, 0.06, 3, place, accept);
}

/// What the passes of both shares read: the original's samples, the mesh's topology (the pulls
/// move points only), the mesh as a surface to query, and the closest point of the mesh to each
/// sample, current while no point has moved since it was found.
struct FitState {
  std::vector<Vec3> samples;
  const opt::Topology& topology;
  ReferenceSurface surface;
  std::vector<SurfaceHit> hits;
  bool hitsCurrent = false;
};

/// The engine's items that pull the corners of a face nearest to samples of the original farther
/// than `far` from the mesh (see fitFarOriginalPoints): one item per such face and pass, in the
/// order of the farthest sample of each (it stands for the rest). Points round a moved one wait
/// for the next pass (the hits there are stale).
struct FarSamplePulls {
  struct Item {
    std::uint32_t key;                 ///< the face
    opt::PointAccess access;           ///< the points of its movable corners' faces; those corners
    std::vector<CornerIndex> depends;  ///< its corners
    /// Its corners that may move, the nearest to the sample first.
    std::vector<CornerIndex> corners;
  };
  QuadMesh& mesh;
  const ReferenceSurface& original;
  const QualitySettings& settings;
  double far = 0.0;
  FitState& fit;
  std::optional<SamplesByFace> nearestTo;  ///< the pass's

  /// The closest point of the mesh to each sample, unless no point has moved since they were
  /// found, with a hint (the same answers, found faster): the first time the answer for the sample
  /// before (a deck's nodes come in runs of near ones), then the previous answer.
  void updateHits() {
    if (fit.hitsCurrent) return;
    const bool first = fit.hits.empty();
    if (!first) fit.surface.movePoints(mesh.points);
    const ReferenceSurface& current = fit.surface;
    std::vector<SurfaceHit>& hits = fit.hits;
    hits.resize(fit.samples.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, fit.samples.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::uint32_t hint = kNoCorner;
                        for (std::size_t i = r.begin(); i < r.end(); ++i) {
                          hits[i] =
                              current.closestPoint(fit.samples[i], first ? hint : hits[i].face);
                          hint = hits[i].face;
                        }
                      });
    fit.hitsCurrent = true;
  }

  std::vector<Item> items(int /*pass*/) {
    updateHits();
    const std::vector<SurfaceHit>& hits = fit.hits;
    const opt::Topology& t = fit.topology;
    nearestTo.emplace(hits, mesh.faces.size());
    std::vector<std::uint32_t> farSamples;
    for (std::uint32_t i = 0; i < hits.size(); ++i)
      if (hits[i].distance > far) farSamples.push_back(i);
    std::stable_sort(farSamples.begin(), farSamples.end(), [&](std::uint32_t a, std::uint32_t b) {
      return hits[a].distance > hits[b].distance;
    });
    std::vector<Item> items;
    std::vector<std::uint8_t> taken(mesh.faces.size(), 0);
    for (const std::uint32_t i : farSamples) {
      const std::uint32_t f = hits[i].face;
      if (taken[f]) continue;
      taken[f] = 1;
      const Face& face = mesh.faces[f];
      Item item{f, {}, {face.begin(), face.begin() + cornerCount(face)}, {}};
      for (const CornerIndex v : item.depends) {
        if (opt::roleOf(mesh, v) != PointRole::Free || t.boundary[v]) continue;
        item.corners.push_back(v);
        item.access.writes.push_back(v);
        for (const Face& g : facesAround(mesh, t, v))
          item.access.reads.insert(item.access.reads.end(), g.begin(), g.begin() + cornerCount(g));
      }
      std::stable_sort(item.corners.begin(), item.corners.end(), [&](CornerIndex x, CornerIndex y) {
        return distance(mesh.points[x], fit.samples[i]) < distance(mesh.points[y], fit.samples[i]);
      });
      items.push_back(std::move(item));
    }
    return items;
  }
  void startClass() {}
  /// The first of the item's corners a search moves, or kNoCorner.
  CornerIndex tryItem(const Item& item) {
    const PassState state{original, settings, fit.samples, fit.hits, *nearestTo, far};
    for (const CornerIndex v : item.corners)
      if (pullCorner(mesh, fit.topology, v, state)) return v;
    return kNoCorner;
  }
  /// The corners of the moved point's faces.
  std::vector<CornerIndex> apply(const Item& /*item*/, CornerIndex moved) const {
    std::vector<CornerIndex> changed;
    if (moved == kNoCorner) return changed;
    for (const Face& g : facesAround(mesh, fit.topology, moved))
      changed.insert(changed.end(), g.begin(), g.begin() + cornerCount(g));
    return changed;
  }
  void endRound(std::size_t pulled) {
    if (pulled > 0) fit.hitsCurrent = false;
  }
};

}  // namespace

std::size_t fitFarOriginalPoints(QuadMesh& mesh, const ReferenceSurface& original,
                                 const QualitySettings& settings, int maxPasses,
                                 opt::MeshCache& cache) {
  if (original.empty())
    throw std::invalid_argument("fitFarOriginalPoints: the original surface is empty");
  if (maxPasses < 0) throw std::invalid_argument("fitFarOriginalPoints: negative pass count");
  if (!(settings.targetSize > 0.0))
    throw std::invalid_argument("fitFarOriginalPoints: targetSize must be > 0");
  checkQualitySettings(settings);
  opt::checkMesh(mesh);
  if (mesh.faces.empty()) return 0;
  const double limit =
      settings.maxDistanceFactor * lengthScale(settings, Criterion::Distance, settings.targetSize);
  FitState fit{original.usedPoints(), cache.topology(mesh), ReferenceSurface(mesh), {}, false};
  std::size_t pulled = 0;
  for (const double share : {kFarShare, kNearShare}) {
    FarSamplePulls kind{mesh, original, settings, share * limit, fit, std::nullopt};
    pulled += opt::runEngineRounds(maxPasses, mesh.points.size(), {true, true}, kind);
  }
  return pulled;
}

std::size_t fitFarOriginalPoints(QuadMesh& mesh, const ReferenceSurface& original,
                                 const QualitySettings& settings, int maxPasses) {
  opt::MeshCache cache(settings);
  return fitFarOriginalPoints(mesh, original, settings, maxPasses, cache);
}

}  // namespace voxremesh
