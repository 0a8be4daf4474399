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

/// A node of the strip's outer side: its arc length on the loop, and the dual vertex it pairs
/// with (or none for a corner that needs a node of its own).
struct OuterNode {
  double param = 0.0;
  std::size_t fromDual = std::numeric_limits<std::size_t>::max();
  bool corner = false;
};

/// Builds the strip between dual loop `dual` (point indices) and original loop `loop`.
void buildStrip(QuadMesh& mesh, const std::vector<std::uint32_t>& dualLoop,
                const PolylineParam& loop, std::uint32_t curve,
                const std::vector<double>& cornerParams, StripStats& stats) {
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

  // Match every dual loop to the original loop most of its vertices are closest to.
  std::vector<std::size_t> match(dualLoops.size(), loops.size());
  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    std::vector<std::size_t> votes(loops.size(), 0);
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
      if (bestLoop < loops.size()) ++votes[bestLoop];
    }
    if (!loops.empty())
      match[d] = std::size_t(std::max_element(votes.begin(), votes.end()) - votes.begin());
  }
  std::vector<std::size_t> taken(loops.size(), dualLoops.size());
  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    const std::size_t l = match[d];
    if (l < loops.size() &&
        (taken[l] == dualLoops.size() || dualLoops[d].size() > dualLoops[taken[l]].size()))
      taken[l] = d;
  }
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (taken[l] == dualLoops.size()) {
      throw std::runtime_error("extraction: boundary loop " + std::to_string(l) + " at " +
                               describePoint(loops[l].point(0)) +
                               " has no dual boundary to join (the part is too small for the "
                               "voxel size there)");
    }
  }

  // Remove stray pieces: components with a boundary of which no loop was taken.
  Components components(mesh.points.size());
  for (const auto& face : mesh.faces)
    for (int c = 1; c < cornerCount(face); ++c) components.unite(face[0], face[std::size_t(c)]);
  std::vector<char> keepsLoop(mesh.points.size(), 0), hasBoundary(mesh.points.size(), 0);
  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    const std::uint32_t root = components.find(dualLoops[d].front());
    hasBoundary[root] = 1;
    if (match[d] < loops.size() && taken[match[d]] == d) keepsLoop[root] = 1;
  }
  for (std::size_t d = 0; d < dualLoops.size(); ++d) {
    const std::uint32_t root = components.find(dualLoops[d].front());
    const bool takenHere = match[d] < loops.size() && taken[match[d]] == d;
    if (keepsLoop[root] && !takenHere) {
      throw std::runtime_error("extraction: the dual mesh has a boundary loop near " +
                               describePoint(toVec(mesh.points[dualLoops[d].front()])) +
                               " that no original boundary loop takes");
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

  for (std::size_t l = 0; l < loops.size(); ++l) {
    std::vector<double> cornerParams;
    for (std::size_t i = 0; i < loops[l].pointCount(); ++i) {
      const Vec3d& p = loops[l].point(i);
      for (const auto& corner : corners) {
        if (corner[0] == p[0] && corner[1] == p[1] && corner[2] == p[2]) {
          cornerParams.push_back(loops[l].vertexParam(i));
          break;
        }
      }
    }
    buildStrip(mesh, dualLoops[taken[l]], loops[l], loopCurves[l], cornerParams, stats);
  }
  return stats;
}

}  // namespace voxremesh::extract
