// A structured grid over a four-sided patch (see mapped_patch.h).
#include "extract/mapped_patch.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "extract/polygon_quads.h"
#include "geometry/vec3.h"

namespace voxremesh::extract {

using namespace geom;  // NOLINT: the vector operators

/// A loop turns by more than this (degrees) at a corner of a mapped patch.
constexpr double kMappedCornerDeg = 45.0;

std::vector<std::size_t> loopCorners(const std::vector<std::array<double, 3>>& loop) {
  std::vector<std::size_t> corners;
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = loop[i];
    const Vec3 in = p - loop[(i + n - 1) % n], out = loop[(i + 1) % n] - p;
    if (norm(in) > 0.0 && norm(out) > 0.0 && angleDeg(in, out) > kMappedCornerDeg)
      corners.push_back(i);
  }
  return corners;
}

std::vector<std::size_t> reflexCorners(const std::vector<std::array<double, 3>>& loop) {
  const std::size_t n = loop.size();
  Vec3 centre{0.0, 0.0, 0.0};
  for (const Vec3& p : loop) centre = centre + p * (1.0 / double(n));
  Vec3 normal{0.0, 0.0, 0.0};  // Newell's: twice the loop's vector area
  for (std::size_t i = 0; i < n; ++i)
    normal = normal + cross(loop[i] - centre, loop[(i + 1) % n] - centre);
  std::vector<std::size_t> reflex;
  for (const std::size_t c : loopCorners(loop))
    if (dot(cross(loop[c] - loop[(c + n - 1) % n], loop[(c + 1) % n] - loop[c]), normal) < 0.0)
      reflex.push_back(c);
  return reflex;
}

namespace {

/// The indices of the nodes where the loop of nodes turns by more than 45 degrees (loopCorners).
std::vector<std::size_t> turningNodes(const std::vector<LoopNode>& nodes) {
  std::vector<std::array<double, 3>> points;
  points.reserve(nodes.size());
  for (const LoopNode& node : nodes) points.push_back(node.point);
  return loopCorners(points);
}

/// One side of the patch: its nodes from one corner to the next, both included.
using Side = std::vector<LoopNode>;

/// True when no inner node of the side is prescribed (all have role Boundary) and no stretch of
/// it is fixed.
bool movable(const Side& side) {
  for (std::size_t k = 0; k + 1 < side.size(); ++k)
    if ((k > 0 && side[k].role != PointRole::Boundary) || side[k].fixedAfter) return false;
  return true;
}

/// The side spaced again evenly along the loop in `pieces` pieces.
Side respaced(const PolylineParam& loop, const Side& side, std::size_t pieces) {
  const double length = loop.length();
  double first = side.front().param, last = side.back().param;
  if (last <= first) last += length;
  Side out{side.front()};
  for (std::size_t k = 1; k < pieces; ++k) {
    const double v = std::fmod(first + (last - first) * double(k) / double(pieces), length);
    out.push_back({v, toArray(loop.pointAt(v)), PointRole::Boundary});
  }
  out.push_back(side.back());
  return out;
}

/// Matches the piece counts of opposite sides a and b by spacing a movable one again.
bool matchCounts(const PolylineParam& loop, Side& a, Side& b) {
  if (a.size() == b.size()) return true;
  if (movable(b)) {
    b = respaced(loop, b, a.size() - 1);
    return true;
  }
  if (movable(a)) {
    a = respaced(loop, a, b.size() - 1);
    return true;
  }
  return false;
}

/// Arc length fractions along a row of points.
std::vector<double> fractions(const std::vector<Vec3>& row) {
  std::vector<double> f(row.size(), 0.0);
  for (std::size_t k = 1; k < row.size(); ++k) f[k] = f[k - 1] + distance(row[k - 1], row[k]);
  for (double& x : f) x = f.back() > 0.0 ? x / f.back() : 0.0;
  return f;
}

/// The four sides of a grid of n1 x n2 quads: bottom and top (n1 + 1 points each, running the
/// same way), left and right (n2 + 1 points each, from bottom to top), with their arc length
/// fractions; corners shared.
struct GridSides {
  std::vector<Vec3> bottom, top, left, right;
  std::vector<double> uBottom, uTop, vLeft, vRight;

  GridSides(std::vector<Vec3> bottomRow, std::vector<Vec3> topRow, std::vector<Vec3> leftColumn,
            std::vector<Vec3> rightColumn)
      : bottom(std::move(bottomRow)),
        top(std::move(topRow)),
        left(std::move(leftColumn)),
        right(std::move(rightColumn)),
        uBottom(fractions(bottom)),
        uTop(fractions(top)),
        vLeft(fractions(left)),
        vRight(fractions(right)) {}

  /// Grid point (i, j) inside, 0 < i < n1 and 0 < j < n2: the transfinite (Coons) interpolation
  /// of the sides at arc-length fractions, laid on the surface.
  Vec3 inner(std::size_t i, std::size_t j, const ReferenceSurface& reference) const {
    const std::size_t n1 = bottom.size() - 1;
    const double vMean = 0.5 * (vLeft[j] + vRight[j]), uMean = 0.5 * (uBottom[i] + uTop[i]);
    const double u = uBottom[i] * (1 - vMean) + uTop[i] * vMean;
    const double v = vLeft[j] * (1 - uMean) + vRight[j] * uMean;
    const Vec3 p = bottom[i] * (1 - v) + top[i] * v + left[j] * (1 - u) + right[j] * u -
                   (bottom[0] * ((1 - u) * (1 - v)) + bottom[n1] * (u * (1 - v)) +
                    top[0] * ((1 - u) * v) + top[n1] * (u * v));
    return reference.closestPoint(p).point;
  }
};

/// True when the quad is convex, agrees with the surface normal and stays within `tolerance` of
/// the surface at its centre and edge midpoints.
bool quadOnSurface(const std::array<Vec3, 4>& q, const ReferenceSurface& reference,
                   const NormalAt& normalAt, double tolerance) {
  const auto within = [&](const Vec3& p) {
    return reference.closestPoint(p).distance <= tolerance;
  };
  const Vec3 centre = (q[0] + q[1] + q[2] + q[3]) * 0.25;
  if (!convexQuad(q, normalAt(centre)) || !within(centre)) return false;
  for (std::size_t c = 0; c < 4; ++c)
    if (!within((q[c] + q[(c + 1) % 4]) * 0.5)) return false;
  return true;
}

/// The area of a quad (half the norm of the cross product of its diagonals).
double quadArea(const std::array<Vec3, 4>& q) {
  return 0.5 * norm(cross(q[2] - q[0], q[3] - q[1]));
}

/// True when the quads keep the area of the surface they span within what edges of `sagittaShare`
/// keep of a curved surface (8/3 sagittaShare^2, chord_limit.h), measured over all of them
/// together: each quad is compared with its four quarters, their edge midpoints and centre laid
/// on the surface, and the difference taken 4/3 times (halving a chord leaves a quarter of its
/// sagitta). A crease across the grid costs only the quads along it, where a limit per edge would
/// refuse every edge crossing it. Always true where sagittaShare is not positive.
bool keepsArea(const std::vector<std::array<Vec3, 4>>& quads, const ReferenceSurface& reference,
               double sagittaShare) {
  if (!(sagittaShare > 0.0) || quads.empty()) return true;
  const auto onSurface = [&](const Vec3& p) { return reference.closestPoint(p).point; };
  double flat = 0.0, refined = 0.0;
  for (const auto& q : quads) {
    flat += quadArea(q);
    const Vec3 centre = onSurface((q[0] + q[1] + q[2] + q[3]) * 0.25);
    std::array<Vec3, 4> middle;
    for (std::size_t c = 0; c < 4; ++c) middle[c] = onSurface((q[c] + q[(c + 1) % 4]) * 0.5);
    for (std::size_t c = 0; c < 4; ++c)
      refined += quadArea({q[c], middle[c], centre, middle[(c + 3) % 4]});
  }
  const double surface = refined + (refined - flat) / 3.0;
  return surface - flat <= 8.0 / 3.0 * sagittaShare * sagittaShare * surface;
}

/// Fills the inside of `grid` ((n1 + 1) x (n2 + 1) indices into the patch's loop nodes, then its
/// inner nodes; its boundary given: row 0 and column n1 running with the loop) with nodes
/// interpolated from its sides (GridSides) and appends its quads to `patch`. False when a quad is
/// not convex or leaves the surface (quadOnSurface), or the quads lose area (keepsArea).
bool addGrid(MappedPatch& patch, std::vector<std::vector<std::uint32_t>>& grid,
             const ReferenceSurface& reference, const NormalAt& normalAt, double tolerance,
             double sagittaShare) {
  const std::size_t loopCount = patch.loop.size();
  const auto point = [&](std::uint32_t index) -> const Vec3& {
    return index < loopCount ? patch.loop[index].point : patch.inner[index - loopCount];
  };
  const std::size_t n1 = grid.size() - 1, n2 = grid.front().size() - 1;
  std::vector<Vec3> bottom, top, left, right;
  for (std::size_t i = 0; i <= n1; ++i) {
    bottom.push_back(point(grid[i][0]));
    top.push_back(point(grid[i][n2]));
  }
  for (std::size_t j = 0; j <= n2; ++j) {
    left.push_back(point(grid[0][j]));
    right.push_back(point(grid[n1][j]));
  }
  const GridSides sides(bottom, top, left, right);
  for (std::size_t j = 1; j < n2; ++j)
    for (std::size_t i = 1; i < n1; ++i) {
      grid[i][j] = std::uint32_t(loopCount + patch.inner.size());
      patch.inner.push_back(sides.inner(i, j, reference));
    }
  std::vector<std::array<Vec3, 4>> corners;
  for (std::size_t j = 0; j < n2; ++j)
    for (std::size_t i = 0; i < n1; ++i) {
      const std::array<std::uint32_t, 4> quad{grid[i][j], grid[i + 1][j], grid[i + 1][j + 1],
                                              grid[i][j + 1]};
      const std::array<Vec3, 4> q{point(quad[0]), point(quad[1]), point(quad[2]), point(quad[3])};
      if (!quadOnSurface(q, reference, normalAt, tolerance)) return false;
      patch.quads.push_back(quad);
      corners.push_back(q);
    }
  return keepsArea(corners, reference, sagittaShare);
}

}  // namespace

std::optional<MappedPatch> mappedPatch(const PolylineParam& loop,
                                       const std::vector<LoopNode>& nodes,
                                       const ReferenceSurface& reference, const NormalAt& normalAt,
                                       double tolerance, double sagittaShare) {
  if (nodes.size() < 4) return std::nullopt;
  const std::vector<std::size_t> corners = turningNodes(nodes);
  if (corners.size() != 4) return std::nullopt;
  std::array<Side, 4> sides;
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t i = corners[k];; i = (i + 1) % nodes.size()) {
      sides[k].push_back(nodes[i]);
      if (i == corners[(k + 1) % 4]) break;
    }
  if (!matchCounts(loop, sides[0], sides[2]) || !matchCounts(loop, sides[1], sides[3]))
    return std::nullopt;
  const std::size_t n1 = sides[0].size() - 1, n2 = sides[1].size() - 1;

  MappedPatch patch;
  for (const Side& side : sides) patch.loop.insert(patch.loop.end(), side.begin(), side.end() - 1);
  const std::size_t loopCount = patch.loop.size();
  // Grid point (i, j): bottom row sides[0], right column sides[1], top row sides[2] reversed,
  // left column sides[3] reversed.
  std::vector<std::vector<std::uint32_t>> cells(n1 + 1, std::vector<std::uint32_t>(n2 + 1));
  for (std::size_t i = 0; i <= n1; ++i) {
    cells[i][0] = std::uint32_t(i);
    cells[i][n2] = std::uint32_t(n1 + n2 + (n1 - i));
  }
  for (std::size_t j = 0; j <= n2; ++j) {
    cells[n1][j] = std::uint32_t(n1 + j);
    cells[0][j] = std::uint32_t((2 * n1 + n2 + (n2 - j)) % loopCount);
  }
  if (!addGrid(patch, cells, reference, normalAt, tolerance, sagittaShare)) return std::nullopt;
  return patch;
}

namespace {

/// The midpoint subdivision's split of each side (see midpointPatch): per side k, the pieces
/// m_k from its start to its split point, such that m_{k+2} = n_k - m_k round the patch (n:
/// `pieces`) and 1 <= m_k < n_k; empty when there is none. The relation links every second side:
/// one cycle through all sides when their count is odd, two when it is even; a cycle whose
/// relation leaves m free takes the value that keeps the splits farthest from the corners.
std::vector<std::size_t> midpointSplits(const std::vector<std::size_t>& pieces) {
  const std::size_t count = pieces.size();
  std::vector<long> split(count, 0);
  for (std::size_t start = 0; start < (count % 2 == 0 ? 2 : 1); ++start) {
    // Along the cycle m = offset + sign * x, x = the split of side `start`.
    std::vector<std::size_t> cycle;
    std::vector<long> offset, sign;
    long a = 0, b = 1;
    std::size_t k = start;
    do {
      cycle.push_back(k);
      offset.push_back(a);
      sign.push_back(b);
      a = long(pieces[k]) - a;
      b = -b;
      k = (k + 2) % count;
    } while (k != start);
    std::vector<long> candidates;
    if (b == -1) {
      if (a % 2 != 0) return {};
      candidates.push_back(a / 2);  // x = a - x
    } else {
      if (a != 0) return {};
      for (long x = 1; x < long(pieces[start]); ++x) candidates.push_back(x);
    }
    long best = -1, bestX = 0;
    for (const long x : candidates) {
      long slack = std::numeric_limits<long>::max();
      for (std::size_t i = 0; i < cycle.size(); ++i) {
        const long m = offset[i] + sign[i] * x;
        slack = std::min({slack, m - 1, long(pieces[cycle[i]]) - 1 - m});
      }
      if (slack > best) best = slack, bestX = x;
    }
    if (best < 0) return {};
    for (std::size_t i = 0; i < cycle.size(); ++i) split[cycle[i]] = offset[i] + sign[i] * bestX;
  }
  return std::vector<std::size_t>(split.begin(), split.end());
}

}  // namespace

std::optional<MappedPatch> midpointPatch(const std::vector<LoopNode>& nodes,
                                         const ReferenceSurface& reference,
                                         const NormalAt& normalAt, double tolerance,
                                         double sagittaShare) {
  const std::vector<std::size_t> corners = turningNodes(nodes);
  const std::size_t sides = corners.size(), n = nodes.size();
  if (sides < 3) return std::nullopt;
  std::vector<std::size_t> pieces(sides);
  for (std::size_t k = 0; k < sides; ++k)
    pieces[k] = (corners[(k + 1) % sides] + n - corners[k]) % n;
  // Side k is split `split[k]` pieces from its start; the row of nodes from the centre to that
  // point has split[k + 1] pieces.
  const std::vector<std::size_t> split = midpointSplits(pieces);
  if (split.empty()) return std::nullopt;
  MappedPatch patch;
  patch.loop = nodes;
  // Node j of side k (from corner k towards corner k + 1, j up to pieces[k]).
  const auto onSide = [&](std::size_t k, std::size_t j) {
    return std::uint32_t((corners[k] + j) % n);
  };
  Vec3 centre{0.0, 0.0, 0.0};
  for (std::size_t k = 0; k < sides; ++k)
    centre = centre + nodes[onSide(k, split[k])].point * (1.0 / double(sides));
  patch.inner.push_back(reference.closestPoint(centre).point);
  // spokes[k][t]: from the centre (t = 0) to the split point of side k.
  std::vector<std::vector<std::uint32_t>> spokes(sides);
  for (std::size_t k = 0; k < sides; ++k) {
    const std::size_t count = split[(k + 1) % sides];
    const Vec3& end = nodes[onSide(k, split[k])].point;
    spokes[k].push_back(std::uint32_t(n));
    for (std::size_t t = 1; t < count; ++t) {
      spokes[k].push_back(std::uint32_t(n + patch.inner.size()));
      const Vec3 p = patch.inner.front() + (end - patch.inner.front()) * (double(t) / count);
      patch.inner.push_back(reference.closestPoint(p).point);
    }
    spokes[k].push_back(onSide(k, split[k]));
  }
  // The grid round corner k + 1: row 0 from side k's split point to the corner, column n1 from
  // the corner along side k + 1 to its split point, the last row the spoke of side k + 1, column
  // 0 the spoke of side k from its split point back to the centre.
  for (std::size_t k = 0; k < sides; ++k) {
    const std::size_t next = (k + 1) % sides, n1 = pieces[k] - split[k], n2 = split[next];
    std::vector<std::vector<std::uint32_t>> cells(n1 + 1, std::vector<std::uint32_t>(n2 + 1));
    for (std::size_t i = 0; i <= n1; ++i) {
      cells[i][0] = onSide(k, split[k] + i);
      cells[i][n2] = spokes[next][i];
    }
    for (std::size_t j = 0; j <= n2; ++j) {
      cells[0][j] = spokes[k][n2 - j];
      cells[n1][j] = onSide(next, j);
    }
    if (!addGrid(patch, cells, reference, normalAt, tolerance, sagittaShare)) return std::nullopt;
  }
  return patch;
}

namespace {

/// The two grids of an L-shaped loop of nodes (six corners, `corners[r]` its reflex one) cut from
/// the reflex corner, continuing the side arriving there, to the node of the side it meets that
/// leaves both pieces four-sided with as many pieces on opposite sides (see lShapedPatch); the
/// cut's length through `cutLength`. Nothing when the counts do not allow it, or a quad is not
/// convex, leaves the surface or the quads lose area (addGrid).
std::optional<MappedPatch> cutAtReflexCorner(const std::vector<LoopNode>& nodes,
                                             const std::vector<std::size_t>& corners, std::size_t r,
                                             const ReferenceSurface& reference,
                                             const NormalAt& normalAt, double tolerance,
                                             double sagittaShare, double& cutLength) {
  const std::size_t n = nodes.size();
  const auto side = [&](std::size_t k) { return (r + k) % 6; };
  std::array<std::size_t, 6> pieces{};  // pieces[k]: of the side from the corner k after r
  for (std::size_t k = 0; k < 6; ++k) pieces[k] = (corners[side(k + 1)] + n - corners[side(k)]) % n;
  // The pieces: one has sides 0 and 1, the cut and the start of side 2; the other the rest of
  // side 2, sides 3, 4 and 5 and the cut.
  if (pieces[2] <= pieces[0] || pieces[4] + pieces[0] != pieces[2] ||
      pieces[3] != pieces[1] + pieces[5])
    return std::nullopt;
  const auto onSide = [&](std::size_t k, std::size_t j) {
    return std::uint32_t((corners[side(k)] + j) % n);
  };
  MappedPatch patch;
  patch.loop = nodes;
  // The cut from the reflex corner (t = 0) to its foot on side 2, pieces[1] pieces.
  const std::size_t cutPieces = pieces[1];
  const Vec3& from = nodes[onSide(0, 0)].point;
  const Vec3& foot = nodes[onSide(2, pieces[0])].point;
  cutLength = distance(from, foot);
  std::vector<std::uint32_t> cut{onSide(0, 0)};
  for (std::size_t t = 1; t < cutPieces; ++t) {
    cut.push_back(std::uint32_t(n + patch.inner.size()));
    patch.inner.push_back(
        reference.closestPoint(from + (foot - from) * (double(t) / double(cutPieces))).point);
  }
  cut.push_back(onSide(2, pieces[0]));
  // First piece: row 0 side 0, column n1 side 1, the last row side 2 back to the foot, column 0
  // the cut.
  const std::size_t n1 = pieces[0], n2 = pieces[1];
  std::vector<std::vector<std::uint32_t>> first(n1 + 1, std::vector<std::uint32_t>(n2 + 1));
  for (std::size_t i = 0; i <= n1; ++i) {
    first[i][0] = onSide(0, i);
    first[i][n2] = onSide(2, n1 - i);
  }
  for (std::size_t j = 0; j <= n2; ++j) {
    first[n1][j] = onSide(1, j);
    first[0][j] = cut[j];
  }
  if (!addGrid(patch, first, reference, normalAt, tolerance, sagittaShare)) return std::nullopt;
  // Second piece: row 0 the rest of side 2 from the foot, column m1 side 3, the last row side 4
  // back, column 0 the cut from the foot to the reflex corner then side 5 back.
  const std::size_t m1 = pieces[2] - pieces[0], m2 = pieces[3];
  std::vector<std::vector<std::uint32_t>> second(m1 + 1, std::vector<std::uint32_t>(m2 + 1));
  for (std::size_t i = 0; i <= m1; ++i) {
    second[i][0] = onSide(2, pieces[0] + i);
    second[i][m2] = onSide(4, m1 - i);
  }
  for (std::size_t j = 0; j <= m2; ++j) {
    second[m1][j] = onSide(3, j);
    second[0][j] = j <= cutPieces ? cut[cutPieces - j] : onSide(5, pieces[5] - (j - cutPieces));
  }
  if (!addGrid(patch, second, reference, normalAt, tolerance, sagittaShare)) return std::nullopt;
  return patch;
}

}  // namespace

std::optional<MappedPatch> lShapedPatch(const std::vector<LoopNode>& nodes,
                                        const ReferenceSurface& reference, const NormalAt& normalAt,
                                        double tolerance, double sagittaShare) {
  std::vector<std::array<double, 3>> points;
  for (const LoopNode& node : nodes) points.push_back(node.point);
  const std::vector<std::size_t> corners = loopCorners(points);
  const std::vector<std::size_t> reflex = reflexCorners(points);
  if (corners.size() != 6 || reflex.size() != 1) return std::nullopt;
  const std::size_t n = nodes.size();
  const std::size_t r =
      std::size_t(std::find(corners.begin(), corners.end(), reflex[0]) - corners.begin());
  // Continuing the side arriving at the reflex corner; then, on the loop reversed, the side
  // leaving it.
  double forwardCut = HUGE_VAL, backwardCut = HUGE_VAL;
  auto best = cutAtReflexCorner(nodes, corners, r, reference, normalAt, tolerance, sagittaShare,
                                forwardCut);
  const std::vector<LoopNode> reversed(nodes.rbegin(), nodes.rend());
  std::vector<std::size_t> reversedCorners;
  for (auto c = corners.rbegin(); c != corners.rend(); ++c) reversedCorners.push_back(n - 1 - *c);
  // The reversed loop's grids face the other way.
  const NormalAt flipped = [&](const std::array<double, 3>& p) { return normalAt(p) * -1.0; };
  auto other = cutAtReflexCorner(reversed, reversedCorners, 5 - r, reference, flipped, tolerance,
                                 sagittaShare, backwardCut);
  if (other && (!best || backwardCut < forwardCut)) {
    // Back to the loop's order and orientation.
    other->loop = nodes;
    for (auto& quad : other->quads) {
      for (std::uint32_t& index : quad)
        if (index < n) index = std::uint32_t(n - 1 - index);
      std::swap(quad[1], quad[3]);
    }
    best = std::move(other);
  }
  return best;
}

namespace {

/// The whole closed loop spaced evenly with `count` nodes from its first node.
Side respacedLoop(const PolylineParam& loop, const Side& nodes, std::size_t count) {
  Side out{nodes.front()};
  for (std::size_t k = 1; k < count; ++k) {
    const double v =
        std::fmod(nodes.front().param + loop.length() * double(k) / double(count), loop.length());
    out.push_back({v, toArray(loop.pointAt(v)), PointRole::Boundary});
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const LoopNode& a, const LoopNode& b) { return a.param < b.param; });
  return out;
}

/// A closed loop of nodes is movable when none is prescribed and no stretch is fixed.
bool movableLoop(const Side& nodes) {
  for (const LoopNode& node : nodes)
    if (node.role != PointRole::Boundary || node.fixedAfter) return false;
  return true;
}

}  // namespace

std::optional<MappedRing> mappedRing(const std::array<PolylineParam, 2>& loops,
                                     std::array<std::vector<LoopNode>, 2> nodes, double spacing,
                                     const ReferenceSurface& reference, const NormalAt& normalAt,
                                     double tolerance, double sagittaShare) {
  if (nodes[0].size() < 3 || nodes[1].size() < 3) return std::nullopt;
  if (nodes[0].size() != nodes[1].size()) {
    const std::size_t more = nodes[0].size() > nodes[1].size() ? 0 : 1;
    if (movableLoop(nodes[1 - more])) {
      nodes[1 - more] = respacedLoop(loops[1 - more], nodes[1 - more], nodes[more].size());
    } else if (movableLoop(nodes[more])) {
      nodes[more] = respacedLoop(loops[more], nodes[more], nodes[1 - more].size());
    } else {
      return std::nullopt;
    }
  }
  const std::size_t n = nodes[0].size();
  const auto& a = nodes[0];
  const auto& b = nodes[1];
  // The pairing i -> (offset + i) or (offset - i) mod n with the shortest total length.
  const auto paired = [n](std::size_t offset, bool forward, std::size_t i) {
    return forward ? (offset + i) % n : (offset + n - i % n) % n;
  };
  std::size_t bestOffset = 0;
  bool bestForward = true;
  double shortest = std::numeric_limits<double>::infinity();
  for (const bool forward : {true, false})
    for (std::size_t offset = 0; offset < n; ++offset) {
      double total = 0.0;
      for (std::size_t i = 0; i < n && total < shortest; ++i)
        total += distance(a[i].point, b[paired(offset, forward, i)].point);
      if (total < shortest) shortest = total, bestOffset = offset, bestForward = forward;
    }
  const auto pair = [&](std::size_t i) { return paired(bestOffset, bestForward, i); };
  const std::size_t rows =
      std::max<std::size_t>(1, std::size_t(std::lround(shortest / double(n) / spacing)));
  MappedRing ring;
  for (std::size_t k = 1; k < rows; ++k)
    for (std::size_t i = 0; i < n; ++i) {
      const double t = double(k) / double(rows);
      ring.inner.push_back(
          reference.closestPoint(a[i].point * (1 - t) + b[pair(i)].point * t).point);
    }
  const auto index = [&](std::size_t i, std::size_t k) -> std::uint32_t {
    i %= n;
    if (k == 0) return std::uint32_t(i);
    if (k == rows) return std::uint32_t(n + pair(i));
    return std::uint32_t(2 * n + (k - 1) * n + i);
  };
  const auto point = [&](std::uint32_t q) -> const Vec3& {
    return q < n ? a[q].point : q < 2 * n ? b[q - n].point : ring.inner[q - 2 * n];
  };
  bool reversed = false;
  std::vector<std::array<Vec3, 4>> corners;
  for (std::size_t k = 0; k < rows; ++k)
    for (std::size_t i = 0; i < n; ++i) {
      std::array<std::uint32_t, 4> quad{index(i, k), index(i + 1, k), index(i + 1, k + 1),
                                        index(i, k + 1)};
      if (reversed) std::swap(quad[1], quad[3]);
      std::array<Vec3, 4> q{point(quad[0]), point(quad[1]), point(quad[2]), point(quad[3])};
      if (!quadOnSurface(q, reference, normalAt, tolerance)) {
        if (!ring.quads.empty()) return std::nullopt;
        reversed = true;  // the first quad decides the orientation
        std::swap(quad[1], quad[3]);
        std::swap(q[1], q[3]);
        if (!quadOnSurface(q, reference, normalAt, tolerance)) return std::nullopt;
      }
      ring.quads.push_back(quad);
      corners.push_back(q);
    }
  if (!keepsArea(corners, reference, sagittaShare)) return std::nullopt;
  ring.loops = std::move(nodes);
  return ring;
}

}  // namespace voxremesh::extract
