// Seams running through the inside of a part, and their extensions from ends inside it along its
// edges to where a curve or the boundary is (see "Seams inside a sheet" in sheets.h).
#include <algorithm>
#include <cmath>

#include "sheets/sheet_internal.h"

namespace voxremesh::sheets {

namespace {

/// An extension continues along edges turning less than this (degrees) from the curve's direction.
constexpr double kExtensionTurnDeg = 45.0;

/// Per part edge, whether it is a curve the extensions end on: a boundary or non-manifold edge, a
/// seam with another part, or a cut already made.
std::vector<std::uint8_t> curveEdges(const ModelContext& context, const PartMesh& part,
                                     const std::vector<std::array<Index, 2>>& cuts) {
  const ShellEdges& edges = part.edges;
  std::vector<std::uint8_t> curve(edges.edgeCount(), 0);
  for (Index e = 0; e < edges.edgeCount(); ++e) {
    const Index a = part.nodes[edges.edge(e).a], b = part.nodes[edges.edge(e).b];
    const std::array<Index, 2> key{std::min(a, b), std::max(a, b)};
    curve[e] = !edges.isManifold(e) || context.sharedWithOtherPart(a, b, part.partEntry) ||
               std::binary_search(cuts.begin(), cuts.end(), key);
  }
  return curve;
}

/// True when every node of face f is used by shells of other parts too (the face lies on another
/// part's area rather than along a seam line).
bool sharedFace(const ModelContext& context, const PartMesh& part, Index f) {
  const ShellCorners& c = part.corners[f];
  for (unsigned k = 0; k < c.count; ++k) {
    const Index v = part.nodes[c.node[k]];
    if (context.sharedBegin.empty() || context.sharedBegin[v + 1] - context.sharedBegin[v] < 2)
      return false;
  }
  return true;
}

/// True when edge e is a seam inside the part: two faces of the part on it, not both lying on
/// another part's area, its nodes shared with another part.
bool innerSeam(const ModelContext& context, const PartMesh& part, Index e) {
  const Index a = part.nodes[part.edges.edge(e).a], b = part.nodes[part.edges.edge(e).b];
  if (!part.edges.isManifold(e) || !context.sharedWithOtherPart(a, b, part.partEntry)) return false;
  const ShellEdges::IncidenceRange on = part.edges.incidences(e);
  return !(sharedFace(context, part, on[0].shell) && sharedFace(context, part, on[1].shell));
}

Vec3 position(const ModelContext& context, const PartMesh& part, Index node) {
  return context.model.nodes[part.nodes[node]].xyz;
}

Vec3 minus(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

}  // namespace

std::vector<std::array<Index, 2>> partInnerSeamCuts(const ModelContext& context,
                                                    const PartMesh& part,
                                                    const std::vector<std::array<Index, 2>>& cuts) {
  const ShellEdges& edges = part.edges;
  // The lines extended: inner seams, and the part's own T-junctions (a fin standing on a line of
  // the panel that ends inside it).
  auto extendedLine = [&](Index e) {
    return edges.isNonManifold(e) || innerSeam(context, part, e);
  };
  bool anySeam = false;
  for (Index e = 0; e < edges.edgeCount() && !anySeam; ++e) anySeam = extendedLine(e);
  if (!anySeam) return {};
  const std::size_t nodeCount = part.nodes.size();
  std::vector<std::vector<Index>> edgesAt(nodeCount);
  for (Index e = 0; e < edges.edgeCount(); ++e) {
    edgesAt[edges.edge(e).a].push_back(e);
    edgesAt[edges.edge(e).b].push_back(e);
  }
  const std::vector<std::uint8_t> curve = curveEdges(context, part, cuts);
  // Nodes on a curve (where an extension ends) and the inner seam edges at each node.
  std::vector<std::uint8_t> onCurve(nodeCount, 0);
  std::vector<Index> seamCount(nodeCount, 0);
  std::vector<std::array<Index, 2>> result;
  for (Index e = 0; e < edges.edgeCount(); ++e) {
    if (!curve[e]) continue;
    onCurve[edges.edge(e).a] = onCurve[edges.edge(e).b] = 1;
    if (!extendedLine(e)) continue;
    ++seamCount[edges.edge(e).a];
    ++seamCount[edges.edge(e).b];
    if (!innerSeam(context, part, e)) continue;  // a T-junction parts the sheets already
    const Index a = part.nodes[edges.edge(e).a], b = part.nodes[edges.edge(e).b];
    result.push_back({std::min(a, b), std::max(a, b)});
  }
  auto other = [&](Index e, Index v) {
    return edges.edge(e).a == v ? edges.edge(e).b : edges.edge(e).a;
  };
  std::vector<Index> path;
  std::vector<std::uint8_t> visited(nodeCount, 0);
  for (Index v = 0; v < nodeCount; ++v) {
    // A line's end inside the part: one such edge, no other curve through the node but, for a
    // T-junction, the fin's own free edge.
    if (seamCount[v] != 1) continue;
    bool dangling = true, finEdge = false;
    Index from = kNoIndex;
    for (const Index e : edgesAt[v]) {
      if (!curve[e]) continue;
      if (extendedLine(e)) {
        from = other(e, v);
        finEdge = edges.isNonManifold(e);
      }
    }
    int freeEdges = 0;
    for (const Index e : edgesAt[v]) {
      if (!curve[e] || extendedLine(e)) continue;
      if (finEdge && edges.isBoundary(e) && freeEdges++ == 0) continue;
      dangling = false;
    }
    if (!dangling) continue;
    const Vec3 direction = minus(position(context, part, v), position(context, part, from));
    path.clear();
    Index at = v;
    bool reached = false;
    while (!reached) {
      visited[at] = 1;
      Index best = kNoIndex;
      double bestTurn = kExtensionTurnDeg;
      for (const Index e : edgesAt[at]) {
        const Index next = other(e, at);
        if (curve[e] || visited[next]) continue;
        const double turn =
            angleDeg(direction, minus(position(context, part, next), position(context, part, at)));
        if (turn < bestTurn) {
          bestTurn = turn;
          best = e;
        }
      }
      if (best == kNoIndex) break;
      path.push_back(best);
      at = other(best, at);
      reached = onCurve[at] != 0;
    }
    for (const Index x : path) visited[edges.edge(x).a] = visited[edges.edge(x).b] = 0;
    visited[v] = 0;
    if (!reached) continue;
    for (const Index e : path) {
      const Index a = part.nodes[edges.edge(e).a], b = part.nodes[edges.edge(e).b];
      result.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

}  // namespace voxremesh::sheets
