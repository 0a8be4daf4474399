// MC33 cell topology (include/voxremesh/mc33.h): which edge crossings of a cell belong to the same
// component of the isosurface of the trilinear interpolant, and their loops.
//
// Derivation
// 1. Loops on the cell's surface. On a face F is bilinear, its zero set is one or two hyperbola
//    arcs, each joining two crossings on the face's edges (a bilinear function has no closed zero
//    curves: it is harmonic, without interior extrema). Walking a face's edges counter-clockwise
//    seen from outside, an edge going from a positive to a negative corner "enters" the negative
//    part, one going from negative to positive "leaves" it. Every arc joins an entering crossing to
//    a leaving one and, oriented from entering to leaving, has the face's positive part on its left
//    seen from outside; that is the boundary orientation of a surface whose normal points to the
//    positive side (T = N x n_face). A face with two crossings has one arc. A face with four
//    (negative corners on one diagonal, positive on the other) is ambiguous: the arcs cut off the
//    two negative corners (arc from each entering crossing to the next one counter-clockwise) or
//    the two positive corners (to the previous one). Which one is the asymptotic decider: with
//    corner values a, d on one diagonal and b, c on the other, F's saddle on the face has the value
//    (ad - bc) / (a + d - b - c), so the negative corners are joined exactly when the product of
//    the negative pair exceeds the product of the positive pair. Both products of two floats are
//    exact in double, so the comparison is exact and symmetric: the cells sharing a face agree.
//    Each crossing edge is shared by two faces and traversed in opposite directions by them, so it
//    is entering in one and leaving in the other: "next arc" is a permutation of the crossing
//    edges, and its cycles are the loops, oriented counter-clockwise seen from the positive side.
// 2. Components from regions. The isosurface S cuts the closed cell (a ball) into connected
//    regions of negative and positive values. Every component of S is two-sided and separates one
//    negative region from one positive region; and since a ball is simply connected, the graph of
//    regions joined by components is a tree, so two regions share at most one component. Hence two
//    loops belong to the same component exactly when they separate the same negative 3D region from
//    the same positive 3D region. Every region holds a corner (F is harmonic: no interior extrema,
//    and on a face or an edge every sign region reaches a corner), so regions are classes of
//    corners, found with a union-find over the 8 corners.
// 3. Which corners share a region. Cut the cell into the bilinear slices z = t. In one slice two
//    corners (points on z-edges) of the same sign are in one region of the slice when they are
//    adjacent and both of that sign, or diagonally opposite with the other two of the other sign
//    and the slice's saddle on their side. A 3D region is the union of its slice regions, every
//    slice region holds a slice corner, and the sign part of a z-edge is one interval (F is linear
//    along it); so two z-edges are in one 3D region iff a chain of slices joins them. For adjacent
//    z-edges that happens iff they share a sign at some height, which is exactly the connectivity
//    of the side face between them (edges plus the face's asymptotic decider), already joined in
//    step 2's surface relations, as are the slices t = 0 and t = 1 (the bottom and top faces). What
//    remains is the interior test: the diagonal pairs of z-edges {8, 11} and {9, 10} in slices
//    0 < t < 1. With the pair's values A(t), D(t) and the other two B(t), C(t) all linear in t, the
//    pair is joined for the sign s when some t has s*A, s*D > 0, s*B, s*C < 0 (an interval of t)
//    and AD - BC > 0 (the slice saddle on their side; >= 0 for the positive sign, the tie rule).
//    AD - BC is a quadratic in t. Its maximum over the interval is at an end or at the vertex, and
//    at an end it adds nothing (see sliceJoinsPair), so the test is: the quadratic is concave, its
//    vertex lies inside the interval, and its value there is on the pair's side. The vertex is a
//    body saddle of F seen along z. This decides the tunnels (MC33 cases 4, 6, 7, 10, 12, 13)
//    without a table.
#include <algorithm>
#include <cstdint>

#include "voxremesh/mc33.h"

namespace voxremesh::mc33 {

namespace {

/// Bit e set for the edges whose corners differ in sign, for a corner sign mask (bit c = corner c
/// negative).
std::uint16_t crossingEdges(unsigned negativeMask) {
  std::uint16_t mask = 0;
  for (int e = 0; e < kEdgeCount; ++e) {
    const unsigned a = (negativeMask >> kEdgeCorners[e][0]) & 1U;
    const unsigned b = (negativeMask >> kEdgeCorners[e][1]) & 1U;
    mask = static_cast<std::uint16_t>(mask | ((a ^ b) << e));
  }
  return mask;
}

/// The asymptotic decider on a face with corner values v0..v3 in face order, negative corners on
/// one diagonal and positive corners on the other: true when the negative corners are joined
/// (the face saddle value is < 0). Exact: products of two floats are exact in double.
bool faceJoinsNegatives(float v0, float v1, float v2, float v3) {
  const double diagonal02 = static_cast<double>(v0) * static_cast<double>(v2);
  const double diagonal13 = static_cast<double>(v1) * static_cast<double>(v3);
  return v0 < 0.0F ? diagonal02 > diagonal13 : diagonal13 > diagonal02;
}

/// A linear function of t in [0,1] from its values at 0 and 1.
struct Linear {
  double at0;
  double at1;
  double operator()(double t) const { return (1.0 - t) * at0 + t * at1; }
};

/// Narrows [lo, hi] to the closure of where f > 0 (f >= 0 with `zeroCounts`).
void keepPositive(const Linear& f, bool zeroCounts, double& lo, double& hi) {
  const bool in0 = zeroCounts ? f.at0 >= 0.0 : f.at0 > 0.0;
  const bool in1 = zeroCounts ? f.at1 >= 0.0 : f.at1 > 0.0;
  if (in0 && in1) return;
  if (!in0 && !in1) {
    lo = 1.0;
    hi = 0.0;
    return;
  }
  const double root = f.at0 / (f.at0 - f.at1);
  if (in1) {
    lo = std::max(lo, root);
  } else {
    hi = std::min(hi, root);
  }
}

/// The interior test for one diagonal pair of z-edges and one sign, in sign-normalised form: a, d
/// are the pair's values times the sign, b, c the other two z-edges' values times minus the sign.
/// True when some slice 0 < t < 1 has a, d, b, c > 0 and a*d - b*c > 0 at an interior maximum of
/// a*d - b*c. For the positive sign (`positive`) a zero of a, d counts as positive and a*d - b*c
/// >= 0 joins; for the negative sign a zero of b, c does (the tie rule: zero counts as positive).
/// A maximum at an end of the interval needs no test: at t = 0 or 1 it is the bottom or top face,
/// already decided by the face decider; at a root of a or d the value is -b*c <= 0; at a root of
/// b or c one of those z-edges turns to the pair's sign beyond it, so the side faces already join
/// the pair. (Evaluating only the vertex also keeps rounding at the roots out of the decision.)
bool sliceJoinsPair(const Linear& a, const Linear& d, const Linear& b, const Linear& c,
                    bool positive) {
  double lo = 0.0;
  double hi = 1.0;
  keepPositive(a, positive, lo, hi);
  keepPositive(d, positive, lo, hi);
  keepPositive(b, !positive, lo, hi);
  keepPositive(c, !positive, lo, hi);
  if (lo >= hi) return false;
  // a*d - b*c = q0 + q1 t + q2 t^2; an interior maximum needs q2 < 0.
  const double da = a.at1 - a.at0;
  const double dd = d.at1 - d.at0;
  const double db = b.at1 - b.at0;
  const double dc = c.at1 - c.at0;
  const double q2 = da * dd - db * dc;
  if (q2 >= 0.0) return false;
  const double q1 = a.at0 * dd + d.at0 * da - b.at0 * dc - c.at0 * db;
  const double vertex = -q1 / (2.0 * q2);
  if (!(vertex > lo && vertex < hi)) return false;
  const double saddleSide = a(vertex) * d(vertex) - b(vertex) * c(vertex);
  return positive ? saddleSide >= 0.0 : saddleSide > 0.0;
}

/// Union-find over the 8 corners.
struct CornerClasses {
  std::array<std::uint8_t, kCornerCount> parent{0, 1, 2, 3, 4, 5, 6, 7};

  int find(int c) {
    while (parent[c] != c) {
      parent[c] = parent[parent[c]];
      c = parent[c];
    }
    return c;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = static_cast<std::uint8_t>(std::min(a, b));
  }
};

/// The z-edges' corners as (bottom, top), in the order of the slice square: (0,0), (1,0), (0,1),
/// (1,1) in (x, y); diagonal pairs are {0, 3} and {1, 2} of this list.
constexpr std::array<std::array<std::uint8_t, 2>, 4> kZEdgeCorners = {
    {{kEdgeCorners[8][0], kEdgeCorners[8][1]},
     {kEdgeCorners[9][0], kEdgeCorners[9][1]},
     {kEdgeCorners[10][0], kEdgeCorners[10][1]},
     {kEdgeCorners[11][0], kEdgeCorners[11][1]}}};

/// Joins, for both signs, diagonally opposite z-edges that some interior slice joins (step 3 of
/// the derivation). Only pairs not yet in one class are tested.
void joinThroughInterior(const CellValues& values, unsigned negativeMask, CornerClasses& classes) {
  const auto corner = [&](int zEdge, bool negative) {
    // A corner of the z-edge with the given sign, or -1.
    for (const std::uint8_t c : kZEdgeCorners[zEdge]) {
      if ((((negativeMask >> c) & 1U) != 0U) == negative) return static_cast<int>(c);
    }
    return -1;
  };
  const auto line = [&](int zEdge, double sign) {
    return Linear{sign * values[kZEdgeCorners[zEdge][0]], sign * values[kZEdgeCorners[zEdge][1]]};
  };
  constexpr std::array<std::array<int, 4>, 2> kPairs = {{{0, 3, 1, 2}, {1, 2, 0, 3}}};
  for (const auto& pair : kPairs) {
    for (const bool negative : {true, false}) {
      const int first = corner(pair[0], negative);
      const int second = corner(pair[1], negative);
      if (first < 0 || second < 0 || classes.find(first) == classes.find(second)) continue;
      const int third = corner(pair[2], !negative);
      const int fourth = corner(pair[3], !negative);
      if (third < 0 || fourth < 0) continue;
      const double sign = negative ? -1.0 : 1.0;
      if (sliceJoinsPair(line(pair[0], sign), line(pair[1], sign), line(pair[2], -sign),
                         line(pair[3], -sign), !negative)) {
        classes.unite(first, second);
      }
    }
  }
}

}  // namespace

std::uint16_t CellTopology::componentEdgeMask(int c) const {
  std::uint16_t mask = 0;
  for (int e = 0; e < kEdgeCount; ++e) {
    if (edgeComponent[e] == c) mask = static_cast<std::uint16_t>(mask | (1U << e));
  }
  return mask;
}

int CellTopology::componentLoopCount(int c) const {
  int count = 0;
  for (int l = 0; l < loopCount; ++l) count += loopComponent[l] == c ? 1 : 0;
  return count;
}

CellTopology cellTopology(const CellValues& values) noexcept {
  CellTopology topology;
  unsigned negativeMask = 0;
  for (int c = 0; c < kCornerCount; ++c) negativeMask |= (values[c] < 0.0F ? 1U : 0U) << c;
  if (negativeMask == 0 || negativeMask == 0xFFU) return topology;
  const auto negative = [negativeMask](int c) { return ((negativeMask >> c) & 1U) != 0U; };

  // Step 1: the arcs on the faces, as "next edge" along the loops.
  std::array<std::uint8_t, kEdgeCount> next{};
  unsigned ambiguousFaces = 0;
  unsigned facesJoiningNegatives = 0;
  for (int f = 0; f < kFaceCount; ++f) {
    const auto& corners = kFaceCorners[f];
    const auto& edges = kFaceEdges[f];
    unsigned signs = 0;
    for (int k = 0; k < 4; ++k) signs |= (negative(corners[k]) ? 1U : 0U) << k;
    if (signs == 0 || signs == 0xFU) continue;
    const auto enters = [signs](int k) {
      return ((signs >> k) & 1U) == 0U && ((signs >> ((k + 1) & 3)) & 1U) != 0U;
    };
    if (signs == 0x5U || signs == 0xAU) {
      ambiguousFaces |= 1U << f;
      const bool joinsNegatives = faceJoinsNegatives(values[corners[0]], values[corners[1]],
                                                     values[corners[2]], values[corners[3]]);
      facesJoiningNegatives |= (joinsNegatives ? 1U : 0U) << f;
      for (int k = 0; k < 4; ++k) {
        if (enters(k)) next[edges[k]] = edges[(k + (joinsNegatives ? 3 : 1)) & 3];
      }
    } else {
      int entering = 0;
      int leaving = 0;
      for (int k = 0; k < 4; ++k) {
        if (enters(k)) entering = k;
        if (((signs >> k) & 1U) != 0U && ((signs >> ((k + 1) & 3)) & 1U) == 0U) leaving = k;
      }
      next[edges[entering]] = edges[leaving];
    }
  }

  // The loops: cycles of `next`, each started at its smallest edge, in order of that edge.
  const unsigned crossing = crossingEdges(negativeMask);
  unsigned visited = 0;
  int size = 0;
  int loops = 0;
  for (int e = 0; e < kEdgeCount; ++e) {
    if (((crossing >> e) & 1U) == 0U || ((visited >> e) & 1U) != 0U) continue;
    topology.loopBegin[loops] = static_cast<std::uint8_t>(size);
    int edge = e;
    do {
      topology.loopEdges[size++] = static_cast<std::uint8_t>(edge);
      visited |= 1U << edge;
      edge = next[edge];
    } while (edge != e && size < kEdgeCount);
    ++loops;
  }
  topology.loopBegin[loops] = static_cast<std::uint8_t>(size);
  topology.loopCount = static_cast<std::uint8_t>(loops);

  // Steps 2 and 3: loops separating the same pair of 3D regions are one component. One loop is
  // one component; with more, classify the corners into regions.
  if (loops == 1) {
    topology.componentCount = 1;
    topology.loopComponent[0] = 0;
  } else {
    CornerClasses classes;
    for (const auto& edge : kEdgeCorners) {
      if (negative(edge[0]) == negative(edge[1])) classes.unite(edge[0], edge[1]);
    }
    for (int f = 0; f < kFaceCount; ++f) {
      if (((ambiguousFaces >> f) & 1U) == 0U) continue;
      const auto& corners = kFaceCorners[f];
      // The joined diagonal: the negative one or the positive one.
      const bool joinsNegatives = ((facesJoiningNegatives >> f) & 1U) != 0U;
      const int k = negative(corners[0]) == joinsNegatives ? 0 : 1;
      classes.unite(corners[k], corners[k + 2]);
    }
    joinThroughInterior(values, negativeMask, classes);

    std::array<int, kMaxLoops> keys{};
    int components = 0;
    for (int l = 0; l < loops; ++l) {
      const auto& corners = kEdgeCorners[topology.loopEdge(l, 0)];
      const bool firstNegative = negative(corners[0]);
      const int negativeClass = classes.find(firstNegative ? corners[0] : corners[1]);
      const int positiveClass = classes.find(firstNegative ? corners[1] : corners[0]);
      keys[l] = negativeClass * kCornerCount + positiveClass;
      int component = components;
      for (int m = 0; m < l; ++m) {
        if (keys[m] == keys[l]) {
          component = topology.loopComponent[m];
          break;
        }
      }
      if (component == components) ++components;
      topology.loopComponent[l] = static_cast<std::uint8_t>(component);
    }
    topology.componentCount = static_cast<std::uint8_t>(components);
  }
  for (int l = 0; l < loops; ++l) {
    for (int i = topology.loopBegin[l]; i < topology.loopBegin[l + 1]; ++i) {
      topology.edgeComponent[topology.loopEdges[i]] =
          static_cast<std::int8_t>(topology.loopComponent[l]);
    }
  }
  return topology;
}

}  // namespace voxremesh::mc33
