// Where a part's faces are split at folds (see "Folds" in sheets.h): the fold edges, the side of
// each fold its faces lie on, and the faces coloured by the nearer side; and the cuts of every
// part of a model (folds and seams inside a sheet).
#include <algorithm>
#include <cmath>
#include <queue>
#include <tuple>
#include <utility>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "sheets/sheet_internal.h"
#include "voxremesh/errors.h"

namespace voxremesh::sheets {

namespace {

/// An inner edge whose faces' normals differ by more than this (degrees) is a fold: its two sides
/// open at less than 60 degrees, so that anywhere near it they are closer to each other than to
/// the fold (a right-angled corner, which a volume holds, is not a fold).
constexpr double kFoldDihedralDeg = 120.0;

constexpr std::uint8_t kNoColour = 2;

/// The faces of a part with their oriented normals and centroids.
struct FaceGeometry {
  std::vector<Vec3> normal;
  std::vector<Vec3> centroid;
};

FaceGeometry faceGeometry(const ModelContext& context, const PartMesh& part,
                          const Orientation& orientation) {
  FaceGeometry g;
  g.normal.resize(part.corners.size());
  g.centroid.resize(part.corners.size());
  for (std::size_t f = 0; f < part.corners.size(); ++f) {
    const ShellCorners& c = part.corners[f];
    std::array<Vec3, 4> p{};
    Vec3 sum{0.0, 0.0, 0.0};
    for (unsigned k = 0; k < c.count; ++k) {
      p[k] = context.model.nodes[part.nodes[c.node[k]]].xyz;
      for (int d = 0; d < 3; ++d) sum[std::size_t(d)] += p[k][std::size_t(d)];
    }
    g.normal[f] = faceNormal(p, c.count);
    if (orientation.flipped[f])
      for (double& x : g.normal[f]) x = -x;
    for (int d = 0; d < 3; ++d) g.centroid[f][std::size_t(d)] = sum[std::size_t(d)] / c.count;
  }
  return g;
}

/// True when edge e has two distinct faces.
bool twoFaces(const ShellEdges& edges, Index e) {
  return edges.isManifold(e) && edges.incidences(e)[0].shell != edges.incidences(e)[1].shell;
}

/// The fold edges of a part, ascending.
std::vector<Index> foldEdges(const PartMesh& part, const FaceGeometry& g) {
  std::vector<Index> folds;
  for (Index e = 0; e < part.edges.edgeCount(); ++e) {
    if (!twoFaces(part.edges, e)) continue;
    const ShellEdges::IncidenceRange on = part.edges.incidences(e);
    if (angleDeg(g.normal[on[0].shell], g.normal[on[1].shell]) > kFoldDihedralDeg)
      folds.push_back(e);
  }
  return folds;
}

/// Per fold edge (parallel to `folds`): true when the fold runs from the edge's node b to a. Fold
/// edges meeting at a node with exactly two of them run on one after the other, so that one side
/// of a chain of folds is the same side all along it.
std::vector<std::uint8_t> foldDirections(const PartMesh& part, const std::vector<Index>& folds) {
  std::vector<std::vector<std::size_t>> atNode(part.nodes.size());
  for (std::size_t i = 0; i < folds.size(); ++i) {
    atNode[part.edges.edge(folds[i]).a].push_back(i);
    atNode[part.edges.edge(folds[i]).b].push_back(i);
  }
  std::vector<std::uint8_t> reversed(folds.size(), 0), seen(folds.size(), 0);
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < folds.size(); ++seed) {
    if (seen[seed]) continue;
    seen[seed] = 1;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      const ShellEdges::Edge& edge = part.edges.edge(folds[i]);
      const Index from = reversed[i] ? edge.b : edge.a, to = reversed[i] ? edge.a : edge.b;
      for (const Index node : {from, to}) {
        if (atNode[node].size() != 2) continue;
        const std::size_t j = atNode[node][0] == i ? atNode[node][1] : atNode[node][0];
        if (seen[j]) continue;
        seen[j] = 1;
        // The next fold leaves `to`; the previous one arrives at `from`.
        const bool startsAtNode = part.edges.edge(folds[j]).a == node;
        reversed[j] = (node == to) != startsAtNode;
        stack.push_back(j);
      }
    }
  }
  return reversed;
}

/// Colours the faces of the part by the side of the nearest fold (0: left of its direction, 1:
/// right), the distance walked between face centroids across inner edges that are not folds;
/// faces of components without folds keep kNoColour.
std::vector<std::uint8_t> colourBySide(const PartMesh& part, const Orientation& orientation,
                                       const FaceGeometry& g, const std::vector<Index>& folds) {
  const ShellEdges& edges = part.edges;
  const std::vector<std::uint8_t> reversed = foldDirections(part, folds);
  std::vector<std::uint8_t> colour(part.corners.size(), kNoColour), isFold(edges.edgeCount(), 0);
  std::vector<double> distance(part.corners.size(), HUGE_VAL);
  using Entry = std::tuple<double, Index, std::uint8_t>;  // distance, face, colour
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (std::size_t i = 0; i < folds.size(); ++i) {
    isFold[folds[i]] = 1;
    for (const ShellEdges::Incidence& x : edges.incidences(folds[i])) {
      // The face runs along the fold's direction (seen from its normal) when its oriented
      // traversal goes the fold's way: then it lies on the fold's left.
      const bool alongEdge = x.forward != (orientation.flipped[x.shell] != 0);
      const std::uint8_t side = alongEdge == (reversed[i] == 0) ? 0 : 1;
      if (distance[x.shell] == 0.0) continue;
      distance[x.shell] = 0.0;
      queue.emplace(0.0, x.shell, side);
    }
  }
  while (!queue.empty()) {
    const auto [d, f, side] = queue.top();
    queue.pop();
    if (colour[f] != kNoColour) continue;
    colour[f] = side;
    for (unsigned k = 0; k < part.corners[f].count; ++k) {
      const Index e = edges.shellEdge(f, k);
      if (e == kNoIndex || isFold[e] || !twoFaces(edges, e)) continue;
      const ShellEdges::IncidenceRange on = edges.incidences(e);
      const Index other = on[0].shell == f ? on[1].shell : on[0].shell;
      if (colour[other] != kNoColour) continue;
      const Vec3& a = g.centroid[f];
      const Vec3& b = g.centroid[other];
      const double step = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
      if (d + step < distance[other]) {
        distance[other] = d + step;
        queue.emplace(d + step, other, side);
      }
    }
  }
  return colour;
}

/// True when some edge with two faces is a fold, the faces' normals taken as they run along the
/// edge (one flipped where both run the same way): a quick test before orienting the part.
bool anyFold(const ModelContext& context, const PartMesh& part) {
  std::vector<Vec3> normal(part.corners.size());
  for (std::size_t f = 0; f < part.corners.size(); ++f) {
    const ShellCorners& c = part.corners[f];
    std::array<Vec3, 4> p{};
    for (unsigned k = 0; k < c.count; ++k) p[k] = context.model.nodes[part.nodes[c.node[k]]].xyz;
    normal[f] = faceNormal(p, c.count);
  }
  for (Index e = 0; e < part.edges.edgeCount(); ++e) {
    if (!twoFaces(part.edges, e)) continue;
    const ShellEdges::IncidenceRange on = part.edges.incidences(e);
    const Vec3& a = normal[on[0].shell];
    const Vec3& b = normal[on[1].shell];
    // Normals more than kFoldDihedralDeg apart (120: a cosine under -1/2), b flipped where both
    // faces run the same way along the edge.
    const double cosine =
        (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) * (on[0].forward == on[1].forward ? -1.0 : 1.0);
    const double lengths = std::hypot(a[0], a[1], a[2]) * std::hypot(b[0], b[1], b[2]);
    if (cosine < std::cos(kFoldDihedralDeg * 3.14159265358979323846 / 180.0) * lengths) return true;
  }
  return false;
}

}  // namespace

std::vector<std::array<Index, 2>> partFoldCuts(const ModelContext& context, const PartMesh& part) {
  if (!anyFold(context, part)) return {};
  const Orientation orientation = orientComponents(context, part);
  const FaceGeometry g = faceGeometry(context, part, orientation);
  const std::vector<Index> folds = foldEdges(part, g);
  if (folds.empty()) return {};
  const std::vector<std::uint8_t> colour = colourBySide(part, orientation, g, folds);
  std::vector<std::array<Index, 2>> cuts;
  for (Index e = 0; e < part.edges.edgeCount(); ++e) {
    if (!twoFaces(part.edges, e)) continue;
    const ShellEdges::IncidenceRange on = part.edges.incidences(e);
    if (colour[on[0].shell] == colour[on[1].shell]) continue;
    const Index a = part.nodes[part.edges.edge(e).a], b = part.nodes[part.edges.edge(e).b];
    cuts.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

std::vector<std::array<Index, 2>> partCuts(const ModelContext& context, const PartMesh& part) {
  try {
    std::vector<std::array<Index, 2>> cuts = partFoldCuts(context, part);
    const std::vector<std::array<Index, 2>> seams = partInnerSeamCuts(context, part, cuts);
    cuts.insert(cuts.end(), seams.begin(), seams.end());
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    return cuts;
  } catch (const InputError&) {
    return {};  // not orientable: that part's own buildSheets reports it
  }
}

std::vector<std::array<Index, 2>> findSheetCuts(const ModelContext& context) {
  const std::size_t parts = context.partIds.size();
  std::vector<std::vector<std::array<Index, 2>>> perPart(parts);
  tbb::enumerable_thread_specific<std::vector<Index>> scratch(
      [&] { return std::vector<Index>(context.model.nodes.size(), kNoIndex); });
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t entry) {
    perPart[entry] = partCuts(context, makePartMesh(context, Index(entry), scratch.local()));
  });
  std::vector<std::array<Index, 2>> cuts;
  for (const auto& list : perPart) cuts.insert(cuts.end(), list.begin(), list.end());
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  return cuts;
}

}  // namespace voxremesh::sheets
