// The boundary strip (see boundary_strip.h).
#include "extract/boundary_strip.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "extract/bridge_tree.h"
#include "extract/neck_ladder.h"
#include "extract/pinch_fans.h"
#include "extract/polyline_param.h"
#include "extract/strip_zip.h"
#include "geometry/disjoint_sets.h"
#include "model/shell_edges.h"

namespace voxremesh::extract {

namespace {

using openvdb::math::Vec3d;

Vec3d toVec(const std::array<double, 3>& p) {
  return Vec3d(p[0], p[1], p[2]);
}

/// The closed boundary loops of the mesh (point indices, mesh on the left), and for every face
/// its piece: faces joined across shared edges (a face touching the rest at a corner only is a
/// piece of its own).
struct DualBoundary {
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<std::uint32_t> loopFace;  ///< a face on each loop
  std::vector<std::uint32_t> piece;     ///< per face: the lowest face of its piece
};

DualBoundary dualBoundary(const QuadMesh& mesh) {
  std::vector<model::ShellCorners> corners(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    corners[f].count = static_cast<std::uint8_t>(cornerCount(mesh.faces[f]));
    for (int c = 0; c < corners[f].count; ++c)
      corners[f].node[std::size_t(c)] = mesh.faces[f][std::size_t(c)];
  }
  const model::ShellEdges adjacency(corners);
  DualBoundary result;
  for (const model::BoundaryChain& chain : model::boundaryChains(adjacency)) {
    if (!chain.closed) throw std::runtime_error("extraction: the dual mesh is not edge-manifold");
    result.loops.push_back(chain.nodes);
    result.loopFace.push_back(adjacency.incidences(chain.edges.front())[0].shell);
  }
  DisjointSets pieces(mesh.faces.size());
  for (std::size_t e = 0; e < adjacency.edgeCount(); ++e) {
    const auto incidences = adjacency.incidences(model::Index(e));
    for (std::size_t i = 1; i < incidences.size(); ++i)
      pieces.join(incidences[0].shell, incidences[i].shell);
  }
  result.piece.resize(mesh.faces.size());
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
    result.piece[f] = static_cast<std::uint32_t>(pieces.find(f));
  return result;
}

std::string describePoint(const Vec3d& p) {
  std::ostringstream text;
  text << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return text.str();
}

/// Indices of the longest strictly increasing subsequence of `values` (first of equals).
std::vector<std::size_t> longestIncreasingRun(const std::vector<double>& values) {
  std::vector<std::size_t> tails, previous(values.size(), std::numeric_limits<std::size_t>::max());
  for (std::size_t i = 0; i < values.size(); ++i) {
    auto it = std::lower_bound(tails.begin(), tails.end(), values[i],
                               [&](std::size_t t, double v) { return values[t] < v; });
    if (it != tails.begin()) previous[i] = *(it - 1);
    if (it == tails.end()) {
      tails.push_back(i);
    } else {
      *it = i;
    }
  }
  std::vector<std::size_t> run;
  for (std::size_t i = tails.empty() ? previous.size() : tails.back(); i < previous.size();
       i = previous[i]) {
    run.push_back(i);
  }
  std::reverse(run.begin(), run.end());
  return run;
}

/// The closed curve a dual loop is zipped to: one original loop, or several joined by bridges
/// (keyholes) where the dual mesh could not pass between them.
struct TargetLoop {
  std::vector<std::array<double, 3>> points;
  std::vector<std::uint32_t> segmentCurve;  ///< per segment i -> i+1: the curve, or kNoCurve
  std::vector<double> cornerParams;         ///< arc lengths of nodes the strip must have
};

/// True when point i of the closed polyline `points` lies inside a junction stretch (both of its
/// segments are junction curve edges) without being a node of the curve: a node there would be
/// one the part across the junction does not have.
bool insideJunctionStretch(const std::vector<std::array<double, 3>>& points, std::size_t i,
                           const JunctionNodes& junctions) {
  const std::size_t n = points.size();
  const std::array<double, 3>& p = points[i];
  return junctions.edge(points[(i + n - 1) % n], p) && junctions.edge(p, points[(i + 1) % n]) &&
         !junctions.isNodePoint(p);
}

/// Joins the loops into one target loop: starting from the first, each further loop is inserted
/// at a bridge (there and back) from a loop joined already, the bridge ends becoming corners. The
/// bridges are `pairs` (indices into `curves`, bridgePairs' tree) where they reach a loop not
/// joined yet, each between the closest points of its two loops (on the joined one, a point whose
/// next segment runs along it); loops no pair reaches are joined nearest first (Prim's order: the
/// loop with the closest pair of points to the target so far), so that holes in a row are joined
/// one to the next, not by a bridge across a hole between them. A bridge ends at no point inside
/// a junction stretch (insideJunctionStretch) where another pair reaches the loop. Corners of the
/// loops are the points equal to one of `corners`.
TargetLoop joinLoops(const QuadMesh& mesh, const std::vector<std::uint32_t>& curves,
                     const std::vector<std::array<double, 3>>& corners,
                     const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
                     const JunctionNodes& junctions) {
  TargetLoop target;
  std::vector<char> isCorner;
  auto cornerAt = [&](const std::array<double, 3>& p) {
    return std::find(corners.begin(), corners.end(), p) != corners.end();
  };
  std::vector<char> joined(curves.size(), 0);
  for (std::size_t step = 0; step < curves.size(); ++step) {
    std::vector<std::array<double, 3>> points;
    std::vector<std::uint32_t> segments;
    std::vector<char> flags;
    if (step == 0) {
      const std::vector<std::array<double, 3>>& loop = mesh.curves[curves[0]].points;
      joined[0] = 1;
      points = loop;
      segments.assign(loop.size(), curves[0]);
      for (const auto& p : loop) flags.push_back(cornerAt(p) ? 1 : 0);
    } else {
      // The loop k to join next, by the first pair that reaches it from a joined loop `from`
      // (or, when none does, the loop with the closest points to any point of the target so
      // far), and the closest pair (i on the target, j on loop k).
      std::size_t k = curves.size(), from = curves.size(), bestI = 0, bestJ = 0;
      for (const auto& [a, b] : pairs)
        if (joined[a] != joined[b]) {
          k = joined[a] ? b : a;
          from = joined[a] ? a : b;
          break;
        }
      double best = std::numeric_limits<double>::infinity();
      for (const bool anyEnd : {false, true}) {  // first without ends inside junction stretches
        for (std::size_t c = 0; c < curves.size(); ++c) {
          if (joined[c] || (k < curves.size() && c != k)) continue;
          const std::vector<std::array<double, 3>>& candidate = mesh.curves[curves[c]].points;
          for (std::size_t i = 0; i < target.points.size(); ++i) {
            if (from < curves.size() && target.segmentCurve[i] != curves[from]) continue;
            if (!anyEnd && insideJunctionStretch(target.points, i, junctions)) continue;
            for (std::size_t j = 0; j < candidate.size(); ++j) {
              if (!anyEnd && insideJunctionStretch(candidate, j, junctions)) continue;
              const double d = (toVec(target.points[i]) - toVec(candidate[j])).lengthSqr();
              if (d < best) best = d, k = c, bestI = i, bestJ = j;
            }
          }
        }
        if (best < std::numeric_limits<double>::infinity()) break;
      }
      if (k == curves.size()) break;  // only empty loops left
      joined[k] = 1;
      const std::vector<std::array<double, 3>>& loop = mesh.curves[curves[k]].points;
      for (std::size_t i = 0; i <= bestI; ++i) {
        points.push_back(target.points[i]);
        segments.push_back(i == bestI ? kNoCurve : target.segmentCurve[i]);
        flags.push_back(i == bestI ? 1 : isCorner[i]);
      }
      for (std::size_t n = 0; n <= loop.size(); ++n) {
        const std::size_t j = (bestJ + n) % loop.size();
        points.push_back(loop[j]);
        segments.push_back(n == loop.size() ? kNoCurve : curves[k]);
        flags.push_back(j == bestJ ? 1 : (cornerAt(loop[j]) ? 1 : 0));
      }
      for (std::size_t i = bestI; i < target.points.size(); ++i) {
        points.push_back(target.points[i]);
        segments.push_back(target.segmentCurve[i]);
        flags.push_back(i == bestI ? 1 : isCorner[i]);
      }
    }
    target.points = std::move(points);
    target.segmentCurve = std::move(segments);
    isCorner = std::move(flags);
  }
  const PolylineParam param(target.points, true);
  for (std::size_t i = 0; i < target.points.size(); ++i)
    if (isCorner[i]) target.cornerParams.push_back(param.vertexParam(i));
  return target;
}

/// A node of the strip's outer side: its arc length on the loop (relative to the strip's base),
/// what prescribes it, for a junction node its index in JunctionStretches::nodes, and for a node
/// inside a bridge its step and the bridge's number of pieces (see bridgePoint).
struct OuterNode {
  enum class Kind : std::uint8_t { Plain, Corner, Junction, Bridge };
  double param = 0.0;
  Kind kind = Kind::Plain;
  std::size_t junctionNode = std::numeric_limits<std::size_t>::max();
  long bridgeStep = 0;
  long bridgePieces = 0;
};

/// The number of pieces a bridge from p to q is cut into: about `spacing` long each. The same
/// for both visits of a bridge (it depends on the unordered pair of ends only).
long bridgePieces(const std::array<double, 3>& p, const std::array<double, 3>& q, double spacing) {
  return std::max(1L, std::lround((toVec(p) - toVec(q)).length() / spacing));
}

/// The node `step` of `pieces` along the bridge from p to q, computed from the lexicographically
/// smaller end, so that both visits of the bridge (p to q and back) get bit-identical nodes and
/// the weld makes each one node inside the surface.
std::array<double, 3> bridgePoint(const std::array<double, 3>& p, const std::array<double, 3>& q,
                                  long step, long pieces) {
  const bool forward = p < q;
  const Vec3d a = toVec(forward ? p : q), b = toVec(forward ? q : p);
  const double t = double(forward ? step : pieces - step) / double(pieces);
  const Vec3d x = a + (b - a) * t;
  return {x[0], x[1], x[2]};
}

/// A node the junction curves prescribe on the target loop.
struct JunctionNode {
  double param = 0.0;  ///< arc length on the target loop, in [0, length)
  std::array<double, 3> point{};
};

/// Which segments of the target loop lie on junction curves, and the nodes on them.
struct JunctionStretches {
  std::vector<char> segment;        ///< per target segment: on a junction curve
  std::vector<JunctionNode> nodes;  ///< ascending param, no repeats
  bool any = false;

  JunctionStretches(const TargetLoop& target, const PolylineParam& loop,
                    const JunctionNodes& junctions) {
    const std::size_t count = target.points.size();
    segment.assign(count, 0);
    if (junctions.empty()) return;
    std::vector<const JunctionEdgeNodes*> edges(count, nullptr);
    for (std::size_t s = 0; s < count; ++s) {
      if (target.segmentCurve[s] == kNoCurve) continue;
      edges[s] = junctions.edge(target.points[s], target.points[(s + 1) % count]);
      segment[s] = edges[s] != nullptr;
      any = any || segment[s];
    }
    const double length = loop.length();
    for (std::size_t s = 0; s < count; ++s) {
      if (!segment[s]) continue;
      const double s0 = loop.vertexParam(s), s1 = loop.vertexParam(s + 1);
      const bool forward = edges[s]->from == target.points[s];
      const std::size_t k = edges[s]->along.size();
      for (std::size_t j = 0; j < k; ++j) {
        const std::size_t n = forward ? j : k - 1 - j;
        const double t = forward ? edges[s]->along[n] : 1.0 - edges[s]->along[n];
        nodes.push_back({s0 + t * (s1 - s0), edges[s]->points[n]});
      }
      // The segment's ends: nodes of the curve, and the ends of a stretch.
      for (const std::size_t end : {s, s + 1}) {
        const std::size_t other = end == s ? (s + count - 1) % count : (s + 1) % count;
        const std::array<double, 3>& p = target.points[end % count];
        if (junctions.isNodePoint(p) || !segment[other])
          nodes.push_back({std::fmod(loop.vertexParam(end), length), p});
      }
    }
    std::sort(nodes.begin(), nodes.end(), [](const JunctionNode& a, const JunctionNode& b) {
      return a.param < b.param || (a.param == b.param && a.point < b.point);
    });
    nodes.erase(std::unique(nodes.begin(), nodes.end(),
                            [](const JunctionNode& a, const JunctionNode& b) {
                              return a.point == b.point;
                            }),
                nodes.end());
  }

  /// True when arc length v (in [0, length)) lies on a junction stretch, its ends included.
  bool contains(const TargetLoop& target, const PolylineParam& loop, double v) const {
    if (!any) return false;
    const std::size_t s = loop.segmentAt(v);
    const std::size_t count = target.points.size();
    return segment[s] || (v <= loop.vertexParam(s) && segment[(s + count - 1) % count]);
  }
};

/// Builds the strip between dual loop `dual` (point indices) and original loop `loop`.
void buildStrip(QuadMesh& mesh, const std::vector<std::uint32_t>& dualLoop,
                const std::vector<Vec3d>& normals, const TargetLoop& target,
                const JunctionNodes& junctions, double spacing, double tolerance,
                StripStats& stats) {
  const PolylineParam loop(target.points, true);
  const JunctionStretches stretches(target, loop, junctions);
  const std::size_t m = dualLoop.size();
  const double length = loop.length();
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  // Closest-point arc lengths, unwrapped from the dual vertex closest to the loop.
  std::vector<double> t(m), distance(m);
  for (std::size_t i = 0; i < m; ++i)
    t[i] = loop.closestParam(toVec(mesh.points[dualLoop[i]]), distance[i]);
  // The zip starts at the dual vertex closest to the loop, but not at one whose closest point is
  // on a bridge: a bridge is run twice, there and back, and its closest point may be on the wrong
  // run, which would zip the two rows in opposite directions.
  std::size_t start = m;
  for (int pass = 0; pass < 2 && start == m; ++pass)
    for (std::size_t i = 0; i < m; ++i)
      if ((pass == 1 || target.segmentCurve[loop.segmentAt(t[i])] != kNoCurve) &&
          (start == m || distance[i] < distance[start]))
        start = i;
  const double base = t[start];
  std::vector<std::uint32_t> a(m);
  std::vector<double> u(m), dualArc(m + 1, 0.0);
  for (std::size_t i = 0; i < m; ++i) {
    a[i] = dualLoop[(start + i) % m];
    double v = std::fmod(t[(start + i) % m] - base, length);
    if (v < 0.0) v += length;
    u[i] = v;
  }
  for (std::size_t i = 0; i < m; ++i)
    dualArc[i + 1] =
        dualArc[i] + (toVec(mesh.points[a[(i + 1) % m]]) - toVec(mesh.points[a[i]])).length();
  // Where each dual vertex lies along the loop, made monotone: the longest increasing run of the
  // closest-point arc lengths, the others spaced by the dual loop's own arc length. This only
  // centres the search of the zip.
  u[0] = 0.0;
  std::vector<std::size_t> run = longestIncreasingRun(u);
  if (run.empty() || run.front() != 0) run.insert(run.begin(), 0);
  for (std::size_t r = 0; r < run.size(); ++r) {
    const std::size_t i0 = run[r];
    const std::size_t i1 = r + 1 < run.size() ? run[r + 1] : m;
    const double u0 = u[i0];
    const double u1 = r + 1 < run.size() ? u[i1] : length;
    const double s0 = dualArc[i0], s1 = dualArc[i1];
    for (std::size_t i = i0 + 1; i < i1; ++i)
      u[i] = u0 + (s1 > s0 ? (dualArc[i] - s0) / (s1 - s0) : 0.0) * (u1 - u0);
  }
  // Arc lengths relative to `base` and back; whether one lies on a junction stretch or a bridge.
  auto relative = [&](double v) {
    const double c = std::fmod(v - base, length);
    return c < 0.0 ? c + length : c;
  };
  auto absolute = [&](double c) {
    double v = std::fmod(c + base, length);
    return v < 0.0 ? v + length : v;
  };
  auto onJunction = [&](double c) { return stretches.contains(target, loop, absolute(c)); };
  auto onBridge = [&](double c) {
    return target.segmentCurve[loop.segmentAt(absolute(c))] == kNoCurve;
  };

  // The nodes the loop prescribes: corners (bridge ends included) and junction nodes.
  std::vector<OuterNode> anchors;
  for (const double cornerParam : target.cornerParams) {
    const double c = relative(cornerParam);
    if (!onJunction(c)) anchors.push_back({c, OuterNode::Kind::Corner, kNone});
  }
  for (std::size_t k = 0; k < stretches.nodes.size(); ++k)
    anchors.push_back({relative(stretches.nodes[k].param), OuterNode::Kind::Junction, k});
  auto byParam = [](const OuterNode& x, const OuterNode& y) { return x.param < y.param; };
  std::stable_sort(anchors.begin(), anchors.end(), byParam);
  anchors.erase(std::unique(anchors.begin(), anchors.end(),
                            [&](const OuterNode& x, const OuterNode& y) {
                              return y.param - x.param <= 1e-12 * length;
                            }),
                anchors.end());
  if (anchors.empty()) anchors.push_back({0.0, OuterNode::Kind::Plain, kNone});
  // Between consecutive nodes: their arc lengths, and whether nodes may go between them (not
  // along a junction, whose nodes are prescribed, nor inside a bridge).
  auto gapEnd = [&](const std::vector<OuterNode>& nodes, std::size_t j) {
    return j + 1 < nodes.size() ? nodes[j + 1].param : nodes[0].param + length;
  };
  auto splittable = [&](const std::vector<OuterNode>& nodes, std::size_t j) {
    const double middle = 0.5 * (nodes[j].param + gapEnd(nodes, j));
    const bool junction = nodes[j].kind == OuterNode::Kind::Junction &&
                          nodes[(j + 1) % nodes.size()].kind == OuterNode::Kind::Junction &&
                          onJunction(middle);
    return !junction && !onBridge(middle);
  };
  auto wrap = [&](double c) { return c >= length ? c - length : c; };
  // Whether the gap [c0, c1] is exactly one bridge segment (from one bridge end to the other).
  auto isWholeBridge = [&](double c0, double c1) {
    const std::size_t segment = loop.segmentAt(absolute(0.5 * (c0 + c1)));
    const double bridge = loop.vertexParam(segment + 1) - loop.vertexParam(segment);
    return std::abs((c1 - c0) - bridge) <= 1e-9 * length;
  };
  // Evenly spaced nodes between the anchors, about `spacing` apart.
  std::vector<OuterNode> nodes;
  for (std::size_t j = 0; j < anchors.size(); ++j) {
    nodes.push_back(anchors[j]);
    const double middle = 0.5 * (anchors[j].param + gapEnd(anchors, j));
    if (onBridge(middle) && isWholeBridge(anchors[j].param, gapEnd(anchors, j))) {
      // A bridge across a neck the dual mesh did not pass: nodes inside the surface about
      // `spacing` apart, so that the faces across the neck are of the element size and the
      // optimisation can lay them on the surface (they are Free points once welded).
      const std::size_t segment = loop.segmentAt(absolute(middle));
      const long pieces = bridgePieces(
          target.points[segment], target.points[(segment + 1) % target.points.size()], spacing);
      const double c0 = anchors[j].param, c1 = gapEnd(anchors, j);
      for (long q = 1; q < pieces; ++q)
        nodes.push_back({wrap(c0 + (c1 - c0) * double(q) / double(pieces)), OuterNode::Kind::Bridge,
                         kNone, q, pieces});
      continue;
    }
    if (!splittable(anchors, j)) continue;
    const double c0 = anchors[j].param, c1 = gapEnd(anchors, j);
    const long pieces = std::max(1L, std::lround((c1 - c0) / spacing));
    for (long q = 1; q < pieces; ++q)
      nodes.push_back(
          {wrap(c0 + (c1 - c0) * double(q) / double(pieces)), OuterNode::Kind::Plain, kNone});
  }
  std::stable_sort(nodes.begin(), nodes.end(), byParam);
  // Where a chord between consecutive nodes misses a vertex of the loop by more than the
  // tolerance (a narrow tab the dual mesh could not enter), that vertex becomes a node too.
  {
    std::vector<double> far;
    for (std::size_t j = 0; j < nodes.size(); ++j)
      addFarVertices(loop, nodes[j].param + base, gapEnd(nodes, j) + base, tolerance, far);
    for (const double v : far) {
      const double c = relative(v);
      if (!onJunction(c)) nodes.push_back({c, OuterNode::Kind::Plain, kNone});
    }
    std::stable_sort(nodes.begin(), nodes.end(), byParam);
  }
  // At least four nodes, and as many as make the strip's two sides even in all (a strip of quads
  // only needs an even number of edges around it): split the longest gaps.
  auto splitLongest = [&] {
    std::size_t best = kNone;
    double widest = 0.0;
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      const double gap = gapEnd(nodes, j) - nodes[j].param;
      if (gap > widest && splittable(nodes, j)) widest = gap, best = j;
    }
    if (best == kNone) return false;
    nodes.push_back({wrap(nodes[best].param + 0.5 * widest), OuterNode::Kind::Plain, kNone});
    std::stable_sort(nodes.begin(), nodes.end(), byParam);
    return true;
  };
  while (nodes.size() < 4 && splitLongest()) {
  }
  if ((m + nodes.size()) % 2 == 1) splitLongest();

  // The outer row starts at the node nearest to the first dual vertex's closest point.
  std::size_t first = 0;
  for (std::size_t j = 1; j < nodes.size(); ++j)
    if (std::min(nodes[j].param, length - nodes[j].param) <
        std::min(nodes[first].param, length - nodes[first].param))
      first = j;
  std::rotate(nodes.begin(), nodes.begin() + std::ptrdiff_t(first), nodes.end());

  const std::size_t n = nodes.size();
  std::vector<std::uint32_t> b(n);
  for (std::size_t j = 0; j < n; ++j) {
    Vec3d p = loop.pointAt(nodes[j].param + base);
    const double v = absolute(nodes[j].param);
    std::size_t segment = loop.segmentAt(v);
    if (nodes[j].kind == OuterNode::Kind::Junction) {  // exact, as on every other side
      const std::array<double, 3>& point = stretches.nodes[nodes[j].junctionNode].point;
      b[j] = static_cast<std::uint32_t>(mesh.points.size());
      mesh.points.push_back(point);
      std::uint32_t curve = target.segmentCurve[segment];
      if (curve == kNoCurve) {
        const std::size_t count = target.points.size();
        curve = target.segmentCurve[(segment + count - 1) % count];
      }
      mesh.constraints.push_back({PointRole::Junction, curve});
      ++stats.junctionNodes;
      continue;
    }
    if (nodes[j].kind == OuterNode::Kind::Bridge) {
      b[j] = static_cast<std::uint32_t>(mesh.points.size());
      mesh.points.push_back(bridgePoint(target.points[segment],
                                        target.points[(segment + 1) % target.points.size()],
                                        nodes[j].bridgeStep, nodes[j].bridgePieces));
      mesh.constraints.push_back(PointConstraint{});
      stats.bridgeNodes.push_back(b[j]);
      continue;
    }
    // A node at a vertex of the loop (a corner, a bridge end) takes its exact coordinates, so
    // that the two visits of a bridge end become one node when the mesh is welded.
    for (std::size_t end : {segment, (segment + 1) % target.points.size()}) {
      if ((p - loop.point(end)).length() <= 1e-9 * length) p = loop.point(end);
    }
    if (target.segmentCurve[segment] == kNoCurve)  // a bridge end: take the loop's curve
      segment = (segment + (v - loop.vertexParam(segment) < loop.vertexParam(segment + 1) - v
                                ? target.points.size() - 1
                                : 1)) %
                target.points.size();
    const std::uint32_t curve = target.segmentCurve[segment];
    b[j] = static_cast<std::uint32_t>(mesh.points.size());
    mesh.points.push_back({p[0], p[1], p[2]});
    mesh.constraints.push_back(nodes[j].kind == OuterNode::Kind::Corner
                                   ? PointConstraint{PointRole::Corner, curve}
                                   : PointConstraint{PointRole::Boundary, curve});
  }

  // The faces: the cheapest zip of the two rows, searched around where each dual vertex lies.
  std::vector<Vec3d> inner(m), innerNormals(m), outer(n);
  for (std::size_t i = 0; i < m; ++i)
    inner[i] = toVec(mesh.points[a[i]]), innerNormals[i] = normals[a[i]];
  for (std::size_t j = 0; j < n; ++j) outer[j] = toVec(mesh.points[b[j]]);
  const double offset = nodes[0].param > length / 2 ? nodes[0].param - length : nodes[0].param;
  std::vector<double> along(n);
  for (std::size_t j = 0; j < n; ++j) {
    along[j] = nodes[j].param - offset;  // in [0, length): node 0 at 0, the rest ascending
    if (along[j] < 0.0) along[j] += length;
    if (along[j] >= length || j == 0) along[j] = j == 0 ? 0.0 : along[j] - length;
  }
  std::vector<std::size_t> centre(m);
  for (std::size_t i = 0; i < m; ++i)
    centre[i] =
        std::size_t(std::lower_bound(along.begin(), along.end(), u[i] - offset) - along.begin());
  // Ladders of quads across the necks the bridges span; the zip takes the rest of the row.
  std::vector<std::size_t> bridgeEnd(n, 0);
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t next = (j + 1) % n;
    const double end = next == 0 ? nodes[0].param + length : nodes[next].param;
    if (nodes[j].kind != OuterNode::Kind::Corner ||
        !onBridge(std::fmod(0.5 * (nodes[j].param + end), length)))
      continue;
    std::size_t pieces = 1;
    while (pieces < n && nodes[(j + pieces) % n].kind == OuterNode::Kind::Bridge) ++pieces;
    if (nodes[(j + pieces) % n].kind == OuterNode::Kind::Corner) bridgeEnd[j] = pieces;
  }
  const NeckLadders ladders = neckLadders(outer, bridgeEnd, inner, innerNormals, spacing);
  for (const Vec3d& p : ladders.points) {  // Free nodes on the chord, laid on the surface later
    b.push_back(static_cast<std::uint32_t>(mesh.points.size()));
    stats.ladderNodes.push_back(b.back());
    mesh.points.push_back({p[0], p[1], p[2]});
    mesh.constraints.push_back(PointConstraint{});
  }
  std::vector<std::size_t> kept;  // the zip's row: indices into b
  for (std::size_t j = 0; j < n; ++j) {
    if (ladders.carved[j]) continue;
    kept.push_back(j);
    const auto insert = ladders.rowInserts.find(j);
    if (insert != ladders.rowInserts.end())
      kept.insert(kept.end(), insert->second.begin(), insert->second.end());
  }
  std::vector<Vec3d> row;
  for (const std::size_t j : kept) row.push_back(toVec(mesh.points[b[j]]));
  // Each dual vertex's centre moves to the first row node at or after it (centre ascends).
  std::size_t r = 0;
  for (std::size_t& c : centre) {
    while (r < kept.size() && (kept[r] >= n || kept[r] < c)) ++r;
    c = std::min(r, kept.size() - 1);
  }
  // The search keeps within a band of outer nodes around where each dual vertex lies.
  const std::size_t band = 12 + n / 64;
  for (const StripFace& face : zipStrip(inner, innerNormals, row, centre, band)) {
    std::array<CornerIndex, 4> corners{kNoCorner, kNoCorner, kNoCorner, kNoCorner};
    for (int k = 0; k < face.corners; ++k) {
      const std::uint32_t index = face.index[std::size_t(k)];
      corners[std::size_t(k)] = face.outer[std::size_t(k)] ? b[kept[index]] : a[index];
    }
    mesh.faces.push_back(corners);
    ++(face.corners == 4 ? stats.quads : stats.triangles);
  }
  for (const auto& quad : ladders.quads) {
    mesh.faces.push_back({b[quad[0]], b[quad[1]], b[quad[2]], b[quad[3]]});
    ++stats.quads;
    ++stats.ladderQuads;
  }
}

}  // namespace

namespace {

/// rebuildBoundaryStrip on the dual mesh as it is (pinched vertices included).
StripStats rebuildStripAsIs(QuadMesh& mesh, const std::vector<std::uint32_t>& loopCurves,
                            const std::vector<std::array<double, 3>>& corners,
                            const JunctionNodes& junctions, double spacing, double tolerance,
                            double reach) {
  StripStats stats;
  if (mesh.constraints.size() != mesh.points.size()) mesh.constraints.resize(mesh.points.size());
  std::vector<PolylineParam> loops;
  for (std::uint32_t c : loopCurves) loops.emplace_back(mesh.curves[c].points, true);
  const DualBoundary boundary = dualBoundary(mesh);
  const std::vector<std::vector<std::uint32_t>>& dualLoops = boundary.loops;

  // Votes: for every dual loop, how many of its vertices are closest to each original loop
  // (within `reach`: a dual loop farther from every original loop is a gap inside the surface).
  std::vector<std::vector<std::size_t>> votes(dualLoops.size(),
                                              std::vector<std::size_t>(loops.size(), 0));
  std::vector<std::vector<int>> nearest(dualLoops.size());  // per dual vertex: its closest loop
  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    for (std::uint32_t v : dualLoops[d]) {
      const Vec3d p = toVec(mesh.points[v]);
      double best = reach;
      std::size_t bestLoop = loops.size();
      for (std::size_t l = 0; l < loops.size(); ++l) {
        if (loops[l].boxDistance(p) >= best) continue;
        double distance = 0.0;
        loops[l].closestParam(p, distance);
        if (distance < best) best = distance, bestLoop = l;
      }
      if (bestLoop < loops.size()) ++votes[d][bestLoop];
      nearest[d].push_back(bestLoop < loops.size() ? int(bestLoop) : -1);
    }
  }
  // Each original loop goes to the dual loop with the most votes for it (ties: the first); a dual
  // loop that gets several original loops joins them by bridges (the dual mesh could not pass
  // between them).
  std::vector<std::size_t> taken(loops.size(), dualLoops.size());
  for (std::size_t l = 0; l < loops.size(); ++l) {
    for (std::size_t d = 0; d < dualLoops.size(); ++d)
      if (votes[d][l] > 0 && (taken[l] == dualLoops.size() || votes[d][l] > votes[taken[l]][l]))
        taken[l] = d;
    if (taken[l] == dualLoops.size()) {
      throw std::runtime_error("extraction: boundary loop " + std::to_string(l) + " at " +
                               describePoint(loops[l].point(0)) +
                               " has no dual boundary to join (the part is too small for the "
                               "voxel size there)");
    }
  }
  std::vector<std::vector<std::uint32_t>> loopsOfDual(dualLoops.size());
  for (std::size_t l = 0; l < loops.size(); ++l) loopsOfDual[taken[l]].push_back(loopCurves[l]);

  // Remove stray pieces: components with a boundary of which no loop was taken.
  std::vector<char> keepsLoop(mesh.faces.size(), 0), hasBoundary(mesh.faces.size(), 0);
  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    const std::uint32_t root = boundary.piece[boundary.loopFace[d]];
    hasBoundary[root] = 1;
    if (!loopsOfDual[d].empty()) keepsLoop[root] = 1;
  }
  // A boundary loop of a kept piece that no original loop takes is a gap inside the surface (a
  // grid edge whose quad is missing next to a boundary): closed by a fan of quads (a triangle
  // last when the loop is odd), oriented like the mesh.
  std::vector<std::array<CornerIndex, 4>> patches;
  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    const std::uint32_t root = boundary.piece[boundary.loopFace[d]];
    if (!keepsLoop[root] || !loopsOfDual[d].empty()) continue;
    std::vector<std::uint32_t> hole(dualLoops[d].rbegin(), dualLoops[d].rend());
    for (std::size_t i = 1; i + 1 < hole.size(); i += 2) {
      if (i + 2 < hole.size()) {
        patches.push_back({hole[0], hole[i], hole[i + 1], hole[i + 2]});
        ++stats.filledQuads;
      } else {
        patches.push_back({hole[0], hole[i], hole[i + 1], kNoCorner});
        ++stats.filledTriangles;
      }
    }
  }
  const std::size_t before = mesh.faces.size();
  std::size_t kept = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const std::uint32_t root = boundary.piece[f];
    if (!hasBoundary[root] || keepsLoop[root]) mesh.faces[kept++] = mesh.faces[f];
  }
  mesh.faces.resize(kept);
  stats.removedFaces = before - mesh.faces.size();
  mesh.faces.insert(mesh.faces.end(), patches.begin(), patches.end());

  // Surface normals of the dual vertices (summed face normals), which orient the strip's faces.
  std::vector<Vec3d> normals(mesh.points.size(), Vec3d(0.0));
  for (const auto& face : mesh.faces) {
    const int n = cornerCount(face);
    const Vec3d p0 = toVec(mesh.points[face[0]]), p1 = toVec(mesh.points[face[1]]),
                p2 = toVec(mesh.points[face[2]]);
    const Vec3d normal =
        n == 3 ? (p1 - p0).cross(p2 - p0) : (p2 - p0).cross(toVec(mesh.points[face[3]]) - p1);
    for (int c = 0; c < n; ++c) normals[face[std::size_t(c)]] += normal;
  }
  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    if (loopsOfDual[d].empty()) continue;
    // The dual vertices' closest loops, as indices into loopsOfDual[d] (ascending loop indices).
    std::vector<int> labels;
    for (const int l : nearest[d]) {
      const bool mine = l >= 0 && taken[std::size_t(l)] == d;
      labels.push_back(mine ? int(std::count_if(taken.begin(), taken.begin() + l,
                                                [d](std::size_t t) { return t == d; }))
                            : -1);
    }
    const auto pairs = bridgePairs(labels, loopsOfDual[d].size());
    buildStrip(mesh, dualLoops[d], normals,
               joinLoops(mesh, loopsOfDual[d], corners, pairs, junctions), junctions, spacing,
               tolerance, stats);
  }
  return stats;
}

}  // namespace

StripStats rebuildBoundaryStrip(QuadMesh& mesh, const std::vector<std::uint32_t>& loopCurves,
                                const std::vector<std::array<double, 3>>& corners,
                                const JunctionNodes& junctions, double spacing, double tolerance,
                                double reach) {
  if (!(spacing > 0.0)) throw std::invalid_argument("rebuildBoundaryStrip: spacing must be > 0");
  // A dual vertex where two parts of the dual mesh touch at a corner lies twice on its boundary;
  // usually the two passes are zipped to different stretches of the original loops, but where
  // both reach the same outer node the edge between them gets four faces. Then the strip is
  // built again on the dual mesh without the smaller fans at the ends of such edges.
  QuadMesh dual = mesh;
  StripStats stats =
      rebuildStripAsIs(mesh, loopCurves, corners, junctions, spacing, tolerance, reach);
  const std::vector<CornerIndex> ends = endsOfOverfullEdges(mesh);
  if (ends.empty()) return stats;
  const std::size_t removed = removePinchedFans(dual, ends);
  if (removed == 0) return stats;
  mesh = std::move(dual);
  stats = rebuildStripAsIs(mesh, loopCurves, corners, junctions, spacing, tolerance, reach);
  stats.pinchedFaces = removed;
  return stats;
}

}  // namespace voxremesh::extract
