// The boundary strip (see boundary_strip.h).
#include "extract/boundary_strip.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "extract/polyline_param.h"
#include "model/shell_edges.h"

namespace voxremesh::extract {

namespace {

using openvdb::math::Vec3d;

Vec3d toVec(const std::array<double, 3>& p) {
  return Vec3d(p[0], p[1], p[2]);
}

/// Union-find over point indices.
struct Components {
  std::vector<std::uint32_t> parent;
  explicit Components(std::size_t n) : parent(n) {
    std::iota(parent.begin(), parent.end(), std::uint32_t{0});
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

/// The closed boundary loops of the mesh (point indices, mesh on the left).
std::vector<std::vector<std::uint32_t>> dualBoundaryLoops(const QuadMesh& mesh) {
  std::vector<model::ShellCorners> corners(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    corners[f].count = static_cast<std::uint8_t>(cornerCount(mesh.faces[f]));
    for (int c = 0; c < corners[f].count; ++c)
      corners[f].node[std::size_t(c)] = mesh.faces[f][std::size_t(c)];
  }
  const model::ShellEdges adjacency(corners);
  std::vector<std::vector<std::uint32_t>> loops;
  for (const model::BoundaryChain& chain : model::boundaryChains(adjacency)) {
    if (!chain.closed) throw std::runtime_error("extraction: the dual mesh is not edge-manifold");
    loops.push_back(chain.nodes);
  }
  return loops;
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

  /// The segment holding arc length s (s in [0, length)).
  std::size_t segmentAt(const PolylineParam& param, double s) const {
    std::size_t lo = 0, hi = points.size();
    while (hi - lo > 1) {
      const std::size_t mid = (lo + hi) / 2;
      (param.vertexParam(mid) <= s ? lo : hi) = mid;
    }
    return lo;
  }
};

/// Joins the loops into one target loop: each further loop is inserted at the closest pair of
/// points (a bridge there and back), the bridge ends becoming corners. Corners of the loops are
/// the points equal to one of `corners`.
TargetLoop joinLoops(const QuadMesh& mesh, const std::vector<std::uint32_t>& curves,
                     const std::vector<std::array<double, 3>>& corners) {
  TargetLoop target;
  std::vector<char> isCorner;
  auto cornerAt = [&](const std::array<double, 3>& p) {
    return std::find(corners.begin(), corners.end(), p) != corners.end();
  };
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const std::vector<std::array<double, 3>>& loop = mesh.curves[curves[k]].points;
    std::vector<std::array<double, 3>> points;
    std::vector<std::uint32_t> segments;
    std::vector<char> flags;
    if (k == 0) {
      points = loop;
      segments.assign(loop.size(), curves[k]);
      for (const auto& p : loop) flags.push_back(cornerAt(p) ? 1 : 0);
    } else {
      // The closest pair (i on the target so far, j on this loop).
      std::size_t bestI = 0, bestJ = 0;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < target.points.size(); ++i)
        for (std::size_t j = 0; j < loop.size(); ++j) {
          const double d = (toVec(target.points[i]) - toVec(loop[j])).lengthSqr();
          if (d < best) best = d, bestI = i, bestJ = j;
        }
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

/// A node of the strip's outer side: its arc length on the loop, and the dual vertex it pairs
/// with (or none for a corner that needs a node of its own).
struct OuterNode {
  double param = 0.0;
  std::size_t fromDual = std::numeric_limits<std::size_t>::max();
  bool corner = false;
};

/// Builds the strip between dual loop `dual` (point indices) and original loop `loop`.
void buildStrip(QuadMesh& mesh, const std::vector<std::uint32_t>& dualLoop,
                const TargetLoop& target, StripStats& stats) {
  const PolylineParam loop(target.points, true);
  const std::vector<double>& cornerParams = target.cornerParams;
  const std::size_t m = dualLoop.size();
  const double length = loop.length();
  // Closest-point arc lengths, unwrapped from the dual vertex closest to the loop.
  std::vector<double> t(m), distance(m);
  for (std::size_t i = 0; i < m; ++i)
    t[i] = loop.closestParam(toVec(mesh.points[dualLoop[i]]), distance[i]);
  const std::size_t start =
      std::size_t(std::min_element(distance.begin(), distance.end()) - distance.begin());
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
  // Keep the longest increasing run; space the others by the dual loop's arc length.
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
  // No node inside a bridge: such nodes move to the bridge's nearer end.
  for (std::size_t i = 0; i < m; ++i) {
    const double v = std::fmod(u[i] + base, length);
    const std::size_t segment = target.segmentAt(loop, v);
    if (target.segmentCurve[segment] != kNoCurve) continue;
    const double from = loop.vertexParam(segment), to = loop.vertexParam(segment + 1);
    u[i] += (v - from < to - v ? from - v : to - v);
  }
  // Outer nodes: one per dual vertex; corners replace the nearest one where the order allows.
  std::vector<OuterNode> outer(m);
  for (std::size_t i = 0; i < m; ++i) outer[i] = {u[i], i, false};
  std::vector<OuterNode> extra;
  for (double cornerParam : cornerParams) {
    double c = std::fmod(cornerParam - base, length);
    if (c < 0.0) c += length;
    const std::size_t next = std::size_t(std::upper_bound(u.begin(), u.end(), c) - u.begin());
    const std::size_t previous = next == 0 ? m - 1 : next - 1;
    const double dPrevious = next == 0 ? c + length - u[m - 1] : c - u[previous];
    const double dNext = next == m ? u[0] + length - c : u[next] - c;
    const std::size_t nearest = dPrevious <= dNext ? previous : next % m;
    const double lower = nearest == 0 ? u[m - 1] - length : u[nearest - 1];
    const double upper = nearest + 1 == m ? length : u[nearest + 1];
    double cc = c;
    if (nearest == 0 && c > length / 2) cc = c - length;
    if (!outer[nearest].corner && cc > lower && cc < upper) {
      outer[nearest].param = cc;
      outer[nearest].corner = true;
    } else if (!(outer[nearest].corner && std::abs(outer[nearest].param - cc) < 1e-12 * length)) {
      extra.push_back({c, std::numeric_limits<std::size_t>::max(), true});
    }
  }
  std::vector<OuterNode> nodes = outer;
  for (const OuterNode& e : extra) nodes.push_back(e);
  std::stable_sort(nodes.begin(), nodes.end(),
                   [](const OuterNode& x, const OuterNode& y) { return x.param < y.param; });
  // Node 0 must pair with dual vertex 0 (param 0, or a corner moved there).
  const auto first = std::find_if(nodes.begin(), nodes.end(),
                                  [](const OuterNode& node) { return node.fromDual == 0; });
  std::rotate(nodes.begin(), first, nodes.end());

  const std::size_t n = nodes.size();
  std::vector<std::uint32_t> b(n);
  for (std::size_t j = 0; j < n; ++j) {
    const Vec3d p = loop.pointAt(nodes[j].param + base);
    double v = std::fmod(nodes[j].param + base, length);
    if (v < 0.0) v += length;
    std::size_t segment = target.segmentAt(loop, v);
    if (target.segmentCurve[segment] == kNoCurve)  // a bridge end: take the loop's curve
      segment = (segment + (v - loop.vertexParam(segment) < loop.vertexParam(segment + 1) - v
                                ? target.points.size() - 1
                                : 1)) %
                target.points.size();
    const std::uint32_t curve = target.segmentCurve[segment];
    b[j] = static_cast<std::uint32_t>(mesh.points.size());
    mesh.points.push_back({p[0], p[1], p[2]});
    mesh.constraints.push_back(nodes[j].corner ? PointConstraint{PointRole::Corner, curve}
                                               : PointConstraint{PointRole::Boundary, curve});
  }
  // Zip: both sides advance together where the next outer node pairs with the next dual vertex.
  std::size_t i = 0, j = 0;
  while (i < m || j < n) {
    const std::size_t nextI = (i + 1) % m, nextJ = (j + 1) % n;
    const bool dualLeft = i < m, outerLeft = j < n;
    const bool paired = dualLeft && outerLeft && nodes[nextJ].fromDual == nextI;
    if (paired) {
      mesh.faces.push_back({a[nextI], a[i % m], b[j % n], b[nextJ]});
      ++stats.quads;
      ++i;
      ++j;
    } else if (outerLeft &&
               (nodes[nextJ].fromDual == std::numeric_limits<std::size_t>::max() || !dualLeft)) {
      mesh.faces.push_back({a[i % m], b[j % n], b[nextJ], kNoCorner});
      ++stats.triangles;
      ++j;
    } else {
      mesh.faces.push_back({a[nextI], a[i % m], b[j % n], kNoCorner});
      ++stats.triangles;
      ++i;
    }
  }
}

}  // namespace

StripStats rebuildBoundaryStrip(QuadMesh& mesh, const std::vector<std::uint32_t>& loopCurves,
                                const std::vector<std::array<double, 3>>& corners) {
  StripStats stats;
  if (mesh.constraints.size() != mesh.points.size()) mesh.constraints.resize(mesh.points.size());
  std::vector<PolylineParam> loops;
  for (std::uint32_t c : loopCurves) loops.emplace_back(mesh.curves[c].points, true);
  const std::vector<std::vector<std::uint32_t>> dualLoops = dualBoundaryLoops(mesh);

  // Votes: for every dual loop, how many of its vertices are closest to each original loop.
  std::vector<std::vector<std::size_t>> votes(dualLoops.size(),
                                              std::vector<std::size_t>(loops.size(), 0));
  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    for (std::uint32_t v : dualLoops[d]) {
      const Vec3d p = toVec(mesh.points[v]);
      double best = std::numeric_limits<double>::infinity();
      std::size_t bestLoop = loops.size();
      for (std::size_t l = 0; l < loops.size(); ++l) {
        if (loops[l].boxDistance(p) >= best) continue;
        double distance = 0.0;
        loops[l].closestParam(p, distance);
        if (distance < best) best = distance, bestLoop = l;
      }
      if (bestLoop < loops.size()) ++votes[d][bestLoop];
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
  Components components(mesh.points.size());
  for (const auto& face : mesh.faces)
    for (int c = 1; c < cornerCount(face); ++c) components.unite(face[0], face[std::size_t(c)]);
  std::vector<char> keepsLoop(mesh.points.size(), 0), hasBoundary(mesh.points.size(), 0);
  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    const std::uint32_t root = components.find(dualLoops[d].front());
    hasBoundary[root] = 1;
    if (!loopsOfDual[d].empty()) keepsLoop[root] = 1;
  }
  // A boundary loop of a kept piece that no original loop takes is a gap inside the surface (a
  // grid edge whose quad is missing next to a boundary): closed by a fan of quads (a triangle
  // last when the loop is odd), oriented like the mesh.
  std::vector<std::array<CornerIndex, 4>> patches;
  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    const std::uint32_t root = components.find(dualLoops[d].front());
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
  mesh.faces.erase(std::remove_if(mesh.faces.begin(), mesh.faces.end(),
                                  [&](const std::array<CornerIndex, 4>& face) {
                                    const std::uint32_t root = components.find(face[0]);
                                    return hasBoundary[root] && !keepsLoop[root];
                                  }),
                   mesh.faces.end());
  stats.removedFaces = before - mesh.faces.size();
  mesh.faces.insert(mesh.faces.end(), patches.begin(), patches.end());

  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    if (loopsOfDual[d].empty()) continue;
    buildStrip(mesh, dualLoops[d], joinLoops(mesh, loopsOfDual[d], corners), stats);
  }
  return stats;
}

}  // namespace voxremesh::extract
