// reconnectFailingFaces: tries other connectivities round each failing face (edge rotations,
// diagonal collapses), each followed by a pattern search of the points round it, and keeps the
// one whose neighbourhood fails fewest criteria (see optimize.h).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/chord_error.h"
#include "optimize/edge_polygon.h"
#include "optimize/point_search.h"
#include "optimize/search_engine.h"
#include "optimize/steps.h"
#include "voxremesh/errors.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

namespace {

using opt::Face;
using opt::Vec3;
using namespace geom;  // NOLINT: the vector operators

/// The pattern searches of a try are shorter than improveFailingElements': they stop at steps of
/// a sixteenth of an edge (not a sixty-fourth) and make at most 3 moves per step length (not 8):
/// a try only has to show whether a connectivity is worth keeping; the full searches of the
/// later passes refine the points of the one kept.
constexpr double kTrialSmallestStep = 0.06;
constexpr int kTrialMovesPerStep = 3;

/// After one sweep of searches in every try of a face, only the tries that score best go on to
/// the remaining sweeps: a try far behind after one sweep seldom wins, and the others cost most
/// of the step's face scores.
constexpr std::size_t kContinuedTries = 3;

/// The faces round the points round a failing face: what a change of connectivity at the face,
/// and the searches of the points of its faces' neighbours, can alter.
struct Neighbourhood {
  std::vector<std::uint32_t> faces;    ///< ascending
  std::vector<CornerIndex> searched;   ///< points of the faces round the face's corners, ascending
  std::vector<CornerIndex> allPoints;  ///< the corners of `faces`, ascending
};

/// A change of connectivity inside a neighbourhood.
struct Edit {
  std::vector<std::uint32_t> removed;  ///< faces taken out
  std::vector<Face> added;             ///< faces put in (before the merge)
  std::optional<opt::Merge> merge;     ///< two points made one
  bool split = false;                  ///< a quad cut into two triangles (the share is limited)
};

/// A neighbourhood after an edit: its own small mesh, and the state of the pattern searches of its
/// points (kept from the first sweep to the next ones).
struct Trial {
  QuadMesh mesh;                            ///< points, constraints, faces (curves left empty)
  std::vector<CornerIndex> global;          ///< global index per point of `mesh`
  opt::Topology topology;                   ///< of `mesh`
  std::vector<CornerIndex> searched;        ///< local indexes of the points searched, ascending
  opt::VainTries<CornerIndex> searches{0};  ///< per point, its searches in vain so far
  std::uint32_t stamp = 0;                  ///< raised as each search is noted
  bool converged = false;                   ///< a whole sweep moved no point
  opt::Score score;
  double chord = 0.0;     ///< chordError of its faces
  std::size_t folds = 0;  ///< faces of `mesh` folded against their neighbours (foldedFaces)
  bool split = false;     ///< Edit::split of the edit it follows
};
template <class T>
void sortUnique(std::vector<T>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

Neighbourhood neighbourhoodOf(const QuadMesh& mesh, const opt::Topology& t, std::uint32_t face) {
  Neighbourhood n;
  const Face& corners = mesh.faces[face];
  for (int k = 0; k < cornerCount(corners); ++k)
    for (const std::uint32_t* f = t.facesBegin(corners[std::size_t(k)]);
         f != t.facesEnd(corners[std::size_t(k)]); ++f)
      for (int j = 0; j < cornerCount(mesh.faces[*f]); ++j)
        n.searched.push_back(mesh.faces[*f][std::size_t(j)]);
  sortUnique(n.searched);
  for (const CornerIndex v : n.searched)
    n.faces.insert(n.faces.end(), t.facesBegin(v), t.facesEnd(v));
  sortUnique(n.faces);
  for (const std::uint32_t f : n.faces)
    for (int j = 0; j < cornerCount(mesh.faces[f]); ++j)
      n.allPoints.push_back(mesh.faces[f][std::size_t(j)]);
  sortUnique(n.allPoints);
  return n;
}

/// The number of faces of the mesh folded against their neighbours (quality.h, foldedFaces).
std::size_t foldedCount(const QuadMesh& mesh) {
  const std::vector<std::uint8_t> folded = foldedFaces(mesh);
  return std::size_t(std::count(folded.begin(), folded.end(), std::uint8_t(1)));
}

opt::Score scoreOf(const QuadMesh& mesh, const QualitySettings& settings) {
  opt::Score score;
  for (const Face& face : mesh.faces) score += opt::faceScore(mesh, face, settings);
  return score;
}

/// Renames `merge.remove` to `merge.keep` in `faces`; a face that then repeats a corner loses the
/// repeat (a quad along the merged edge becomes a triangle, a triangle along it goes).
void mergeCorners(std::vector<Face>& faces, const opt::Merge& merge) {
  std::vector<Face> merged;
  for (const Face& face : faces) {
    Face reduced{kNoCorner, kNoCorner, kNoCorner, kNoCorner};
    std::size_t count = 0;
    for (int k = 0; k < cornerCount(face); ++k) {
      const CornerIndex v =
          face[std::size_t(k)] == merge.remove ? merge.keep : face[std::size_t(k)];
      if (std::find(reduced.begin(), reduced.begin() + count, v) == reduced.begin() + count)
        reduced[count++] = v;
    }
    if (count >= 3) merged.push_back(reduced);
  }
  faces = std::move(merged);
}

/// The neighbourhood after `edit`, as its own mesh, its points not yet searched.
Trial buildTrial(const QuadMesh& mesh, const opt::Topology& t, const Neighbourhood& n,
                 const Edit& edit) {
  Trial trial;
  std::vector<Face> faces;
  for (const std::uint32_t f : n.faces)
    if (std::find(edit.removed.begin(), edit.removed.end(), f) == edit.removed.end())
      faces.push_back(mesh.faces[f]);
  faces.insert(faces.end(), edit.added.begin(), edit.added.end());
  if (edit.merge) mergeCorners(faces, *edit.merge);
  trial.global = n.allPoints;
  if (edit.merge)
    trial.global.erase(std::find(trial.global.begin(), trial.global.end(), edit.merge->remove));
  auto local = [&](CornerIndex v) {
    return CornerIndex(std::lower_bound(trial.global.begin(), trial.global.end(), v) -
                       trial.global.begin());
  };
  for (const CornerIndex v : trial.global) {
    trial.mesh.points.push_back(mesh.points[v]);
    if (!mesh.constraints.empty()) trial.mesh.constraints.push_back(mesh.constraints[v]);
  }
  if (edit.merge) trial.mesh.points[local(edit.merge->keep)] = edit.merge->position;
  for (Face face : faces) {
    for (int k = 0; k < cornerCount(face); ++k) face[std::size_t(k)] = local(face[std::size_t(k)]);
    trial.mesh.faces.push_back(face);
  }
  trial.topology = opt::buildTopology(trial.mesh);
  for (const CornerIndex v : n.searched)
    if ((!edit.merge || v != edit.merge->remove) && opt::searchable(mesh, t, v))
      trial.searched.push_back(local(v));
  trial.split = edit.split;
  trial.searches = opt::VainTries<CornerIndex>(trial.global.size());
  return trial;
}

/// Up to `sweeps` more rounds of pattern searches of a trial's searched points (in ascending
/// order, until a round moves none); then scores it.
void searchTrial(Trial& trial, const ReferenceSurface& original, const QualitySettings& settings,
                 const std::vector<std::vector<Vec3>>& fixedOnCurve,
                 const std::vector<PolylineIndex>& curves, int sweeps) {
  const opt::Topology& t = trial.topology;
  // A point searched in vain is skipped until a point of its faces moves.
  for (int sweep = 0; sweep < sweeps && !trial.converged; ++sweep) {
    bool moved = false;
    for (const CornerIndex v : trial.searched) {
      if (opt::searchUnchangedSinceVain(trial.searches, trial.mesh, t, v)) continue;
      const bool movedNow = opt::improvePoint(trial.mesh, t, original, settings, fixedOnCurve,
                                              curves, v, kTrialSmallestStep, kTrialMovesPerStep);
      if (movedNow)
        trial.searches.noteChanged(v, ++trial.stamp);
      else
        trial.searches.noteVain(v, ++trial.stamp);
      moved = moved || movedNow;
    }
    trial.converged = !moved;
  }
  trial.score = scoreOf(trial.mesh, settings);
}

/// The hexagon the three quads round inner point v make, oriented like them (v's ring: each
/// quad's corner after v, its opposite corner, and so on); empty unless v is an inner point of
/// exactly three quads.
std::vector<CornerIndex> hexagonAround(const QuadMesh& mesh, const opt::Topology& t,
                                       CornerIndex v) {
  if (t.boundary[v] || t.faceCount(v) != 3u) return {};
  struct Wedge {
    CornerIndex next, opposite, previous;
  };
  std::vector<Wedge> wedges;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f) {
    const Face& face = mesh.faces[*f];
    if (cornerCount(face) != 4) return {};
    const auto k = std::size_t(std::find(face.begin(), face.end(), v) - face.begin());
    wedges.push_back({face[(k + 1) % 4], face[(k + 2) % 4], face[(k + 3) % 4]});
  }
  std::vector<CornerIndex> hexagon{wedges[0].next, wedges[0].opposite, wedges[0].previous};
  for (int step = 0; step < 2; ++step) {
    const auto w = std::find_if(wedges.begin(), wedges.end(),
                                [&](const Wedge& x) { return x.next == hexagon.back(); });
    if (w == wedges.end()) return {};
    hexagon.push_back(w->opposite);
    if (step == 0) hexagon.push_back(w->previous);
  }
  std::vector<CornerIndex> sorted = hexagon;
  sortUnique(sorted);
  if (sorted.size() != 6) return {};
  return hexagon;
}

/// Whether v may move or lose faces as the edits see it: Free.
bool isFree(const QuadMesh& mesh, CornerIndex v) {
  return opt::roleOf(mesh, v) == PointRole::Free;
}

/// Whether v may lose a face and keep 3 (2 on the boundary): no doublet, no spike.
bool keepsFaces(const opt::Topology& t, CornerIndex v) {
  return t.faceCount(v) >= (t.boundary[v] ? 3u : 4u);
}

/// Every other cut of the polygon face f makes with its neighbour across each of its edges: an
/// edge between two constrained points (it may run along a curve) stays, a diagonal between two
/// constrained points or along an existing edge is not made, nor one whose faces turn against
/// the faces round them (cutKeepsOrientation: a cut outside a non-convex polygon).
void addRecuts(const QuadMesh& mesh, const opt::Topology& t, std::uint32_t f,
               std::vector<Edit>& edits) {
  const Face& face = mesh.faces[f];
  const int n = cornerCount(face);
  for (int k = 0; k < n; ++k) {
    const CornerIndex a = face[std::size_t(k)], b = face[std::size_t((k + 1) % n)];
    if ((!isFree(mesh, a) && !isFree(mesh, b)) || t.edgeFaces(a, b) != 2) continue;
    if (!keepsFaces(t, a) || !keepsFaces(t, b)) continue;
    std::uint32_t g = f;
    for (const std::uint32_t* h = t.facesBegin(a); h != t.facesEnd(a); ++h) {
      const Face& other = mesh.faces[*h];
      const auto end = other.begin() + cornerCount(other);
      if (*h != f && std::find(other.begin(), end, b) != end) g = *h;
    }
    if (g == f) continue;
    const std::vector<CornerIndex> polygon = opt::polygonAroundEdge(face, mesh.faces[g], a, b);
    if (polygon.empty()) continue;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      if (polygon.size() != 5 && i >= polygon.size() / 2) continue;
      const CornerIndex p = polygon[i], q = polygon[opt::diagonalEnd(polygon.size(), i)];
      if (t.edgeFaces(p, q) > 0 || (!isFree(mesh, p) && !isFree(mesh, q))) continue;
      const std::array<Face, 2> cut = opt::cutPolygon(polygon, i);
      if (!opt::cutKeepsOrientation(mesh, t, f, g, cut)) continue;
      edits.push_back(
          Edit{{std::min(f, g), std::max(f, g)}, {cut[0], cut[1]}, std::nullopt, false});
    }
  }
}

/// An inner corner of face f that three quads share taken out, their hexagon cut into two quads
/// along each of its diagonals: the three-quad corner an uneven count of rows leaves, moved away.
void addThreeQuadCornerRemovals(const QuadMesh& mesh, const opt::Topology& t, std::uint32_t f,
                                std::vector<Edit>& edits) {
  const Face& face = mesh.faces[f];
  for (int k = 0; k < cornerCount(face); ++k) {
    const CornerIndex v = face[std::size_t(k)];
    if (!isFree(mesh, v)) continue;
    const std::vector<CornerIndex> hexagon = hexagonAround(mesh, t, v);
    if (hexagon.empty()) continue;
    std::vector<std::uint32_t> removed(t.facesBegin(v), t.facesEnd(v));
    for (std::size_t i = 0; i < 3; ++i) {
      if (t.edgeFaces(hexagon[i], hexagon[i + 3]) > 0) continue;
      const std::array<Face, 2> cut = opt::cutPolygon(hexagon, i);
      edits.push_back(Edit{removed, {cut[0], cut[1]}, std::nullopt, false});
    }
  }
}

/// The merge of u and v under the constraint and manifold rules, a Free point that stays laid on
/// the original; nothing where the rules forbid it.
std::optional<opt::Merge> collapse(const QuadMesh& mesh, const opt::Topology& t, CornerIndex u,
                                   CornerIndex v, const ReferenceSurface& original) {
  if (!opt::mergeKeepsManifold(mesh, t, u, v)) return std::nullopt;
  std::optional<opt::Merge> merge = opt::mergeUnderConstraints(mesh, u, v);
  if (merge && isFree(mesh, merge->keep))
    merge->position = original.closestPoint(merge->position).point;
  return merge;
}

/// The collapses at face f: of each diagonal of a quad and, when `edgesToo` (a face with a
/// short side, a degenerate corner or, a triangle, a sharp one), of each of its edges, which
/// turns it and its neighbour across the edge into triangles.
void addCollapses(const QuadMesh& mesh, const opt::Topology& t, std::uint32_t f,
                  const ReferenceSurface& original, bool edgesToo, std::vector<Edit>& edits) {
  const Face& face = mesh.faces[f];
  const int n = cornerCount(face);
  for (int k = 0; edgesToo && k < n; ++k)
    if (const auto merge =
            collapse(mesh, t, face[std::size_t(k)], face[std::size_t((k + 1) % n)], original))
      edits.push_back(Edit{{}, {}, merge, false});
  for (std::size_t k = 0; n == 4 && k < 2; ++k) {
    if (!keepsFaces(t, face[k + 1]) || !keepsFaces(t, face[(k + 3) % 4])) continue;
    if (const auto merge = collapse(mesh, t, face[k], face[k + 2], original))
      edits.push_back(Edit{{f}, {}, merge, false});
  }
}

/// A quad cut into two triangles along a diagonal that is not already an edge of other faces
/// (a quad folded over a bend tighter than its size: warping, Jacobian ratio).
void addQuadSplits(const QuadMesh& mesh, const opt::Topology& t, std::uint32_t f,
                   std::vector<Edit>& edits) {
  const Face& face = mesh.faces[f];
  if (cornerCount(face) != 4) return;
  for (std::size_t k = 0; k < 2; ++k) {
    if (t.edgeFaces(face[k], face[k + 2]) > 0) continue;
    const auto at = [&](std::size_t i) { return face[(k + i) % 4]; };
    edits.push_back(
        Edit{{f},
             {Face{at(0), at(1), at(2), kNoCorner}, Face{at(2), at(3), at(0), kNoCorner}},
             std::nullopt,
             true});
  }
}

/// The edits of the kinds `kinds` (ReconnectEdit bits) tried at face f; the edges of a face are
/// collapsed only when `collapseEdges`, quads split only when `splitQuads`.
std::vector<Edit> editsAt(const QuadMesh& mesh, const opt::Topology& t, std::uint32_t f,
                          const ReferenceSurface& original, unsigned kinds, bool collapseEdges,
                          bool splitQuads) {
  std::vector<Edit> edits;
  if (kinds & kRecutPair) addRecuts(mesh, t, f, edits);
  if (kinds & kThreeQuadCorner) addThreeQuadCornerRemovals(mesh, t, f, edits);
  if (kinds & kCollapse) addCollapses(mesh, t, f, original, collapseEdges, edits);
  if ((kinds & kSplitQuad) && splitQuads) addQuadSplits(mesh, t, f, edits);
  return edits;
}

/// Puts a trial's faces and positions into the mesh in place of its neighbourhood's: the faces
/// that go are flagged in `deleted` (their slots reused first), the merged point left unused.
void applyTrial(QuadMesh& mesh, const Neighbourhood& n, const Trial& trial,
                std::vector<std::uint8_t>& deleted) {
  for (CornerIndex v = 0; v < trial.global.size(); ++v)
    mesh.points[trial.global[v]] = trial.mesh.points[v];
  std::size_t k = 0;
  for (const std::uint32_t f : n.faces) {
    if (k < trial.mesh.faces.size()) {
      Face face = trial.mesh.faces[k++];
      for (int j = 0; j < cornerCount(face); ++j)
        face[std::size_t(j)] = trial.global[face[std::size_t(j)]];
      mesh.faces[f] = face;
    } else {
      deleted[f] = 1;
    }
  }
  for (; k < trial.mesh.faces.size(); ++k) {
    Face face = trial.mesh.faces[k];
    for (int j = 0; j < cornerCount(face); ++j)
      face[std::size_t(j)] = trial.global[face[std::size_t(j)]];
    mesh.faces.push_back(face);
    deleted.push_back(0);
  }
}

/// The number of triangles among `faces`.
std::size_t triangleCount(const std::vector<Face>& faces) {
  return std::size_t(std::count_if(faces.begin(), faces.end(),
                                   [](const Face& face) { return cornerCount(face) == 3; }));
}

/// What the tries at a face need besides the mesh: the original, the criteria, the curves, the
/// kinds of edits (ReconnectEdit bits) and the number of sweeps of pattern searches per try.
struct TryContext {
  const ReferenceSurface& original;
  const QualitySettings& settings;
  const std::vector<std::vector<Vec3>>& fixedOnCurve;
  const std::vector<PolylineIndex>& curves;
  unsigned kinds = 0;
  int sweeps = 0;
};

/// A face to try, its neighbourhood and the criteria it fails.
struct Candidate {
  std::uint32_t face = 0;
  std::uint32_t failures = 0;
  Neighbourhood neighbourhood;
};

/// The tries at face c.face (reconnectFailingFaces): the neighbourhood as it is and after each
/// edit, each searched; the best of those within the distance allowed and with no more folds,
/// when it fails fewer criteria than the neighbourhood did. Reads the mesh only.
std::optional<Trial> bestTrialAt(const QuadMesh& mesh, const opt::Topology& t, const Candidate& c,
                                 const TryContext& context, bool splitQuads) {
  const QualitySettings& settings = context.settings;
  const Neighbourhood& n = c.neighbourhood;
  const std::uint32_t degenerate = 1u << unsigned(Criterion::DegenerateCorner);
  const std::uint32_t shortOrSliver = (1u << unsigned(Criterion::MinLength)) |
                                      (1u << unsigned(Criterion::TriaMinAngle)) | degenerate;
  opt::Score before;
  for (const std::uint32_t g : n.faces) before += opt::faceScore(mesh, mesh.faces[g], settings);
  // The neighbourhood as it is, searched (nothing to try when there are no searches).
  std::vector<Edit> edits;
  if (context.sweeps > 0) edits.push_back(Edit{});
  const std::vector<Edit> others = editsAt(mesh, t, c.face, context.original, context.kinds,
                                           (c.failures & shortOrSliver) != 0, splitQuads);
  edits.insert(edits.end(), others.begin(), others.end());
  // The tries are independent: in parallel, the best chosen in edit order. First one sweep of
  // searches in each; then the rest of the sweeps in the best few only (the first of equal
  // ones), kContinuedTries.
  std::vector<Trial> trials(edits.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, edits.size(), 1),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i < r.end(); ++i) {
                        trials[i] = buildTrial(mesh, t, n, edits[i]);
                        searchTrial(trials[i], context.original, settings, context.fixedOnCurve,
                                    context.curves, std::min(context.sweeps, 1));
                      }
                    });
  std::vector<std::size_t> order(trials.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const opt::Score &x = trials[a].score, &y = trials[b].score;
    return x.failures != y.failures ? x.failures < y.failures : x.penalty < y.penalty;
  });
  if (order.size() > kContinuedTries) order.resize(kContinuedTries);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 1),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i < r.end(); ++i) {
                        Trial& trial = trials[order[i]];
                        searchTrial(trial, context.original, settings, context.fixedOnCurve,
                                    context.curves, context.sweeps - 1);
                        if (trial.score.failures >= before.failures) continue;
                        trial.chord =
                            opt::chordError(trial.mesh, trial.mesh.faces, context.original);
                        trial.folds = foldedCount(trial.mesh);
                      }
                    });
  // A try failing as many criteria as the neighbourhood is never taken, and never stands in the
  // way of one failing fewer (that one scores better): only those failing fewer are measured
  // (above) and compared.
  order.erase(
      std::remove_if(order.begin(), order.end(),
                     [&](std::size_t i) { return trials[i].score.failures >= before.failures; }),
      order.end());
  if (order.empty()) return std::nullopt;
  // Only tries whose faces stay as close to the original as half the distance limit, or as the
  // neighbourhood's faces were, take part; a face with a degenerate corner, which no acceptance
  // allows, may use the whole limit.
  std::vector<Face> present;
  for (const std::uint32_t g : n.faces) present.push_back(mesh.faces[g]);
  const double limitShare = (c.failures & degenerate) != 0 ? 1.0 : 0.5;
  const double allowed =
      std::max(opt::chordError(mesh, present, context.original),
               limitShare * settings.maxDistanceFactor *
                   lengthScale(settings, Criterion::Distance, settings.targetSize));
  // Nor may a try fold more faces than the neighbourhood had folded (a flipped face can pass
  // every criterion of its own); those are counted only when a try has a fold.
  std::optional<std::size_t> foldsBefore;
  const auto foldsAllowed = [&](const Trial& trial) {
    if (trial.folds == 0) return true;
    if (!foldsBefore) foldsBefore = foldedCount(buildTrial(mesh, t, n, Edit{}).mesh);
    return trial.folds <= *foldsBefore;
  };
  std::sort(order.begin(), order.end());
  std::optional<std::size_t> best;
  for (const std::size_t i : order)
    if (trials[i].chord <= allowed && foldsAllowed(trials[i]) &&
        (!best || trials[i].score.betterThan(trials[*best].score)))
      best = i;
  if (!best) return std::nullopt;
  return std::move(trials[*best]);
}

/// The engine's items that try local edits round a failing face each (bestTrialAt). The first
/// `rounds` rounds take every failing face, as many more the faces with a degenerate corner only:
/// no acceptance allows one, while it allows a share of other failures. Point indexes stay as they
/// are until the end (merged points are left unused meanwhile), so that the engine's record holds
/// across rounds; a round's removed faces are erased after it.
struct FailingFaceTries {
  struct Item {
    Face key;                          ///< the face's corners
    opt::PointAccess access;           ///< its neighbourhood's points, read and changed
    std::vector<CornerIndex> depends;  ///< its neighbourhood's points
    Candidate candidate;
  };
  QuadMesh& mesh;
  opt::MeshCache& cache;
  const TryContext& context;
  int rounds = 0;
  double maxTriangleShare = 0.0;
  const opt::Topology* topology = nullptr;  ///< the round's
  std::vector<std::uint8_t> deleted;        ///< the round's removed faces
  std::size_t faces = 0, triangles = 0;     ///< the mesh's, as the round's changes are applied
  bool splitQuads = false;                  ///< quads may be split this round

  /// Whether a change adding `moreFaces` faces and `moreTriangles` triangles keeps the triangle
  /// share at or under maxTriangleShare.
  bool splitFits(std::size_t moreFaces, std::size_t moreTriangles) const {
    return double(triangles + moreTriangles) <= maxTriangleShare * double(faces + moreFaces) + 1e-9;
  }

  std::vector<Item> items(int round) {
    const std::uint32_t degenerate = 1u << unsigned(Criterion::DegenerateCorner);
    const std::uint32_t criteriaTried = round < rounds ? ~0u : degenerate;
    topology = &cache.topology(mesh);
    const std::vector<std::uint32_t>& failures = cache.failures(mesh);
    std::vector<Item> failing;
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
      if ((failures[f] & criteriaTried) != 0)
        failing.push_back(Item{mesh.faces[f], {}, {}, Candidate{f, failures[f], {}}});
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, failing.size(), 16),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i < r.end(); ++i) {
                          Item& item = failing[i];
                          item.candidate.neighbourhood =
                              neighbourhoodOf(mesh, *topology, item.candidate.face);
                          item.depends = item.candidate.neighbourhood.allPoints;
                          item.access = {item.depends, item.depends};
                        }
                      });
    deleted.assign(mesh.faces.size(), 0);
    faces = mesh.faces.size();
    triangles = triangleCount(mesh.faces);
    splitQuads = maxTriangleShare > 0.0 && splitFits(1, 2);
    return failing;
  }
  void startClass() {}
  std::optional<Trial> tryItem(const Item& item) const {
    return bestTrialAt(mesh, *topology, item.candidate, context, splitQuads);
  }
  /// Applies the best try, unless it is a split the triangle share no longer allows.
  std::vector<CornerIndex> apply(const Item& item, std::optional<Trial> result) {
    const Neighbourhood& n = item.candidate.neighbourhood;
    if (!result) return {};
    const std::size_t trialTriangles = triangleCount(result->mesh.faces);
    std::size_t nTriangles = 0;
    for (const std::uint32_t g : n.faces) nTriangles += cornerCount(mesh.faces[g]) == 3;
    if (result->split &&
        !splitFits(result->mesh.faces.size() - n.faces.size(), trialTriangles - nTriangles))
      return {};
    faces += result->mesh.faces.size();
    faces -= n.faces.size();
    triangles += trialTriangles;
    triangles -= nTriangles;
    applyTrial(mesh, n, *result, deleted);
    return n.allPoints;
  }
  void endRound(std::size_t changed) {
    if (changed > 0) opt::eraseFaces(mesh, deleted);
  }
};

}  // namespace

std::size_t reconnectFailingFaces(QuadMesh& mesh, const ReferenceSurface& original,
                                  const QualitySettings& settings,
                                  const ReconnectSettings& reconnect, opt::MeshCache& cache) {
  if (original.empty())
    throw std::invalid_argument("reconnectFailingFaces: the original surface is empty");
  if (reconnect.rounds < 0 || reconnect.sweeps < 0)
    throw std::invalid_argument("reconnectFailingFaces: negative round or sweep count");
  if (!(settings.targetSize > 0.0))
    throw std::invalid_argument("reconnectFailingFaces: targetSize must be > 0");
  checkQualitySettings(settings);
  opt::checkMesh(mesh);
  if (!(reconnect.maxTriangleShare >= 0.0 && reconnect.maxTriangleShare <= 1.0))
    throw SettingError("reconnectFailingFaces: triangle share " +
                       std::to_string(reconnect.maxTriangleShare) + " is outside 0 .. 1");
  const std::vector<std::vector<Vec3>> fixedOnCurve = opt::fixedPointsOnCurves(mesh);
  const std::vector<PolylineIndex> curves = opt::indexCurves(mesh);
  const TryContext context{original, settings,        fixedOnCurve,
                           curves,   reconnect.edits, reconnect.sweeps};
  FailingFaceTries kind{
      mesh, cache, context, reconnect.rounds, reconnect.maxTriangleShare, nullptr, {}, 0, 0, false};
  // A face whose neighbourhood an earlier class changed waits for the next round (its topology
  // is stale).
  const std::size_t changed =
      opt::runEngineRounds(2 * reconnect.rounds, mesh.points.size(), {true, true}, kind);
  if (changed > 0) eraseUnusedPoints(mesh);
  return changed;
}

std::size_t reconnectFailingFaces(QuadMesh& mesh, const ReferenceSurface& original,
                                  const QualitySettings& settings,
                                  const ReconnectSettings& reconnect) {
  opt::MeshCache cache(settings);
  return reconnectFailingFaces(mesh, original, settings, reconnect, cache);
}

}  // namespace voxremesh
