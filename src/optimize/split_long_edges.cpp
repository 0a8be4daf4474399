// splitLongEdges: edges much longer than the target size get a midpoint on the surface, and the
// faces around them are cut into quads (triangles where a template needs one).
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "optimize/mesh_topology.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

using Face = std::array<CornerIndex, 4>;
using Edge = std::pair<CornerIndex, CornerIndex>;

/// An edge whose midpoint lies farther than this fraction of its length from the surface spans a
/// gap (a hole, a fold), not a bend: splitting it would pull its midpoint to the gap's edge.
constexpr double kMaxSagitta = 0.25;

Edge edgeKey(CornerIndex a, CornerIndex b) {
  return {std::min(a, b), std::max(a, b)};
}

/// The smallest interior angle of a face, in degrees (0 for a degenerate corner).
double smallestAngle(const QuadMesh& mesh, const Face& face) {
  const int n = cornerCount(face);
  double smallest = 180.0;
  for (int k = 0; k < n; ++k) {
    const Vec3& p = mesh.points[face[std::size_t(k)]];
    const Vec3& prev = mesh.points[face[std::size_t((k + n - 1) % n)]];
    const Vec3& next = mesh.points[face[std::size_t((k + 1) % n)]];
    const Vec3 a = prev - p, b = next - p;
    if (norm(a) == 0.0 || norm(b) == 0.0) return 0.0;
    // The largest angle counts too: 180 - angle, so that a flat corner scores as badly as a sharp
    // one.
    const double angle = angleDeg(a, b);
    smallest = std::min(smallest, std::min(angle, n == 4 ? 180.0 - angle : angle * 2.0));
  }
  return smallest;
}

/// Of several ways to cut a face, the one whose worst face has the largest smallestAngle (ties:
/// the first).
std::vector<Face> bestCut(const QuadMesh& mesh, const std::vector<std::vector<Face>>& options) {
  std::size_t best = 0;
  double bestScore = -1.0;
  for (std::size_t o = 0; o < options.size(); ++o) {
    double score = 180.0;
    for (const Face& face : options[o]) score = std::min(score, smallestAngle(mesh, face));
    if (score > bestScore) bestScore = score, best = o;
  }
  return options[best];
}

Face quad(CornerIndex a, CornerIndex b, CornerIndex c, CornerIndex d) {
  return {a, b, c, d};
}
Face tria(CornerIndex a, CornerIndex b, CornerIndex c) {
  return {a, b, c, kNoCorner};
}

/// Whether edge (a, b) may be split: at least one end is Free (an edge between two constrained
/// points may run along a curve, or along a junction that another mesh shares).
bool splittable(const QuadMesh& mesh, CornerIndex a, CornerIndex b) {
  return opt::roleOf(mesh, a) == PointRole::Free || opt::roleOf(mesh, b) == PointRole::Free;
}

/// The faces replacing `face`, whose edge k (corner k to k + 1) has midpoint mid[k] (kNoCorner:
/// not split); `centre` makes a centre point when called.
template <typename MakeCentre>
std::vector<Face> cutFace(const QuadMesh& mesh, const Face& face,
                          const std::array<CornerIndex, 4>& mid, MakeCentre&& centre) {
  const int n = cornerCount(face);
  int splits = 0;
  for (int k = 0; k < n; ++k) splits += mid[std::size_t(k)] != kNoCorner;
  if (splits == 0) return {face};
  // Rotate so that edge 0 is split and, for two adjacent splits, edge 1 is the other one.
  int r = 0;
  while (mid[std::size_t(r)] == kNoCorner ||
         (splits == 2 && n == 4 && mid[std::size_t((r + 2) % 4)] == kNoCorner &&
          mid[std::size_t((r + 1) % n)] == kNoCorner) ||
         (splits == 2 && n == 3 && mid[std::size_t((r + 1) % n)] == kNoCorner) ||
         (splits == 3 && n == 4 && mid[std::size_t((r + 3) % 4)] != kNoCorner))
    ++r;
  auto v = [&](int k) { return face[std::size_t((r + k) % n)]; };
  auto m = [&](int k) { return mid[std::size_t((r + k) % n)]; };
  if (n == 3) {
    if (splits == 1) return {tria(v(0), m(0), v(2)), tria(m(0), v(1), v(2))};
    if (splits == 2) return {quad(v(0), m(0), m(1), v(2)), tria(m(0), v(1), m(1))};
    const CornerIndex c = centre();
    return {quad(c, m(2), v(0), m(0)), quad(c, m(0), v(1), m(1)), quad(c, m(1), v(2), m(2))};
  }
  if (splits == 1)
    return bestCut(mesh, {{quad(m(0), v(1), v(2), v(3)), tria(v(0), m(0), v(3))},
                          {quad(v(0), m(0), v(2), v(3)), tria(m(0), v(1), v(2))}});
  if (splits == 2 && m(2) != kNoCorner)
    return {quad(v(0), m(0), m(2), v(3)), quad(m(0), v(1), v(2), m(2))};
  // Two adjacent edges or more: around a centre point (two quads alone would have a straight
  // corner at a midpoint).
  const CornerIndex c = centre();
  if (splits == 2)  // edges 0 and 1
    return {quad(c, m(0), v(1), m(1)), quad(c, m(1), v(2), v(3)), quad(c, v(3), v(0), m(0))};
  if (splits == 3)  // edges 0, 1, 2; edge 3 (v3 - v0) whole
    return {quad(c, m(0), v(1), m(1)), quad(c, m(1), v(2), m(2)), quad(c, m(2), v(3), v(0)),
            tria(c, v(0), m(0))};
  return {quad(c, m(3), v(0), m(0)), quad(c, m(0), v(1), m(1)), quad(c, m(1), v(2), m(2)),
          quad(c, m(2), v(3), m(3))};
}

/// One round of splitLongEdges; returns the number of edges split.
std::size_t splitRound(QuadMesh& mesh, const ReferenceSurface* surface, double maxLength,
                       double chordTolerance) {
  // The edges to split, in ascending order of their ends: deterministic point numbering.
  std::map<Edge, CornerIndex> midpoints;
  for (const Face& face : mesh.faces) {
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k) {
      const CornerIndex a = face[std::size_t(k)], b = face[std::size_t((k + 1) % n)];
      const double length = distance(mesh.points[a], mesh.points[b]);
      if (length <= maxLength || !splittable(mesh, a, b)) continue;
      const Vec3 middle = (mesh.points[a] + mesh.points[b]) * 0.5;
      if (surface) {
        // How much farther the midpoint is from the surface than its ends are on average.
        auto off = [&](const Vec3& p) { return surface->closestPoint(p).distance; };
        const double sagitta = off(middle) - 0.5 * (off(mesh.points[a]) + off(mesh.points[b]));
        if (sagitta <= chordTolerance || sagitta > kMaxSagitta * length) continue;
      }
      midpoints.emplace(edgeKey(a, b), kNoCorner);
    }
  }
  if (midpoints.empty()) return 0;
  auto addPoint = [&](const Vec3& wanted) {
    Vec3 p = wanted;
    if (surface) p = surface->closestPoint(wanted).point;
    mesh.points.push_back(p);
    if (!mesh.constraints.empty()) mesh.constraints.push_back(PointConstraint{});
    return static_cast<CornerIndex>(mesh.points.size() - 1);
  };
  for (auto& [edge, index] : midpoints)
    index = addPoint((mesh.points[edge.first] + mesh.points[edge.second]) * 0.5);
  std::vector<Face> faces;
  faces.reserve(mesh.faces.size() + 2 * midpoints.size());
  for (const Face& face : mesh.faces) {
    const int n = cornerCount(face);
    std::array<CornerIndex, 4> mid{kNoCorner, kNoCorner, kNoCorner, kNoCorner};
    for (int k = 0; k < n; ++k) {
      const auto found =
          midpoints.find(edgeKey(face[std::size_t(k)], face[std::size_t((k + 1) % n)]));
      if (found != midpoints.end()) mid[std::size_t(k)] = found->second;
    }
    auto centre = [&] {
      Vec3 sum{0.0, 0.0, 0.0};
      for (int k = 0; k < n; ++k) sum = sum + mesh.points[face[std::size_t(k)]];
      return addPoint(sum * (1.0 / n));
    };
    for (const Face& piece : cutFace(mesh, face, mid, centre)) faces.push_back(piece);
  }
  mesh.faces = std::move(faces);
  return midpoints.size();
}

}  // namespace

std::size_t splitLongEdges(QuadMesh& mesh, double maxLength, const ReferenceSurface* surface,
                           double chordTolerance, int maxRounds) {
  if (!(maxLength > 0.0) || !std::isfinite(maxLength))
    throw std::invalid_argument("splitLongEdges: maximum length " + std::to_string(maxLength) +
                                " is not finite and > 0");
  if (!std::isfinite(chordTolerance) || chordTolerance < 0.0)
    throw std::invalid_argument("splitLongEdges: chord tolerance " +
                                std::to_string(chordTolerance) + " is not finite and >= 0");
  if (maxRounds < 0) throw std::invalid_argument("splitLongEdges: negative round count");
  if (surface && surface->empty())
    throw std::invalid_argument("splitLongEdges: the surface is empty");
  opt::checkMesh(mesh);
  std::size_t split = 0;
  for (int round = 0; round < maxRounds; ++round) {
    const std::size_t count = splitRound(mesh, surface, maxLength, chordTolerance);
    if (count == 0) break;
    split += count;
  }
  return split;
}

}  // namespace voxremesh
