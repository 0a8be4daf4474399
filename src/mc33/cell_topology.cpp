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
//    body saddle of F seen along z. This decides the tunnels (MC33 cases 4, 6, 7, 10, 12, 13).
//
// Speed. The topology depends on the values only through the sign pattern, the decisions on the
// pattern's ambiguous faces and the outcomes of the interior tests that could change the grouping.
// So the derivation (steps 1-3 with the decisions given as bits, class Derivation) is run once, on
// first use, for every sign pattern, every combination of its face decisions and every
// combination of the interior tests that matter there, and the results are kept in immutable
// tables (1,024 topologies in 656 decision cases, 41 kB). cellTopology then only takes the signs,
// decides the ambiguous faces (exactly) and the relevant interior tests from the values, and
// copies the tabled topology: no loops are traced and nothing is allocated per cell.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "voxremesh/mc33.h"

namespace voxremesh::mc33 {

namespace {

// ---------------------------------------------------------------------------------------------
// Decisions from the values

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

/// The z-edges' corners as (bottom, top), in the order of the slice square: (0,0), (1,0), (0,1),
/// (1,1) in (x, y).
constexpr std::array<std::array<std::uint8_t, 2>, 4> kZEdgeCorners = {
    {{kEdgeCorners[8][0], kEdgeCorners[8][1]},
     {kEdgeCorners[9][0], kEdgeCorners[9][1]},
     {kEdgeCorners[10][0], kEdgeCorners[10][1]},
     {kEdgeCorners[11][0], kEdgeCorners[11][1]}}};

/// The diagonal pairs of z-edges (indices into kZEdgeCorners) followed by the other two.
constexpr std::array<std::array<int, 4>, 2> kPairs = {{{0, 3, 1, 2}, {1, 2, 0, 3}}};

/// Interior tests are numbered 2 * pair + sign (sign 0: negative, 1: positive).
constexpr int kInteriorTests = 4;

/// Evaluates interior test `test` on the values (sliceJoinsPair for its pair and sign).
bool interiorJoins(const CellValues& values, int test) {
  const auto& pair = kPairs[test / 2];
  const bool positive = (test % 2) == 1;
  const double sign = positive ? 1.0 : -1.0;
  const auto line = [&](int zEdge, double s) {
    return Linear{s * values[kZEdgeCorners[zEdge][0]], s * values[kZEdgeCorners[zEdge][1]]};
  };
  return sliceJoinsPair(line(pair[0], sign), line(pair[1], sign), line(pair[2], -sign),
                        line(pair[3], -sign), positive);
}

// ---------------------------------------------------------------------------------------------
// Derivation of the topology from the decisions

/// Union-find over the 8 corners.
struct CornerClasses {
  std::array<std::uint8_t, kCornerCount> parent{0, 1, 2, 3, 4, 5, 6, 7};

  int find(int c) {
    while (parent[c] != c) c = parent[c];
    return c;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = static_cast<std::uint8_t>(std::min(a, b));
  }
};

/// Steps 1-3 of the derivation for one sign pattern and its face decisions.
class Derivation {
 public:
  /// `faceJoinsNegatives`: bit f set when ambiguous face f joins its negative corners.
  Derivation(unsigned negativeMask, unsigned faceJoinsNegatives) : mask_(negativeMask) {
    if (mask_ == 0 || mask_ == 0xFFU) return;
    traceLoops(faceJoinsNegatives);
    // Step 2's surface relations: corners of one sign along edges and joined face diagonals.
    for (const auto& edge : kEdgeCorners) {
      if (negative(edge[0]) == negative(edge[1])) surface_.unite(edge[0], edge[1]);
    }
    for (int f = 0; f < kFaceCount; ++f) {
      if (!ambiguous(f)) continue;
      const auto& corners = kFaceCorners[f];
      const bool joinsNegatives = ((faceJoinsNegatives >> f) & 1U) != 0U;
      const int k = negative(corners[0]) == joinsNegatives ? 0 : 1;
      surface_.unite(corners[k], corners[k + 2]);
    }
  }

  /// The interior tests that can change the grouping: the pattern has the pair of the test's sign
  /// and the other pair of the other sign, the pair's corners are not yet in one region, and there
  /// are at least two loops.
  std::vector<int> relevantTests() const {
    std::vector<int> tests;
    if (topology_.loopCount < 2) return tests;
    for (int test = 0; test < kInteriorTests; ++test) {
      const int first = pairCorner(test, 0);
      const int second = pairCorner(test, 1);
      CornerClasses classes = surface_;
      if (first >= 0 && second >= 0 && pairCorner(test, 2) >= 0 && pairCorner(test, 3) >= 0 &&
          classes.find(first) != classes.find(second)) {
        tests.push_back(test);
      }
    }
    return tests;
  }

  /// The topology when the interior tests in `joined` (bit per test number) join their pairs.
  CellTopology topology(unsigned joined) const {
    CellTopology topology = topology_;
    if (topology.loopCount == 0) return topology;
    CornerClasses classes = surface_;
    for (int test = 0; test < kInteriorTests; ++test) {
      if (((joined >> test) & 1U) != 0U) classes.unite(pairCorner(test, 0), pairCorner(test, 1));
    }
    // Loops separating the same negative and positive regions are one component.
    std::array<int, kMaxLoops> keys{};
    int components = 0;
    for (int l = 0; l < topology.loopCount; ++l) {
      const auto& corners = kEdgeCorners[topology.loopEdge(l, 0)];
      const bool firstNegative = negative(corners[0]);
      const int negativeRegion = classes.find(firstNegative ? corners[0] : corners[1]);
      const int positiveRegion = classes.find(firstNegative ? corners[1] : corners[0]);
      keys[l] = negativeRegion * kCornerCount + positiveRegion;
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
    for (int l = 0; l < topology.loopCount; ++l) {
      for (int i = topology.loopBegin[l]; i < topology.loopBegin[l + 1]; ++i) {
        topology.edgeComponent[topology.loopEdges[i]] =
            static_cast<std::int8_t>(topology.loopComponent[l]);
      }
    }
    return topology;
  }

 private:
  bool negative(int c) const { return ((mask_ >> c) & 1U) != 0U; }

  /// Negative-corner bits of face f in face order.
  unsigned faceSigns(int f) const {
    unsigned signs = 0;
    for (int k = 0; k < 4; ++k) signs |= (negative(kFaceCorners[f][k]) ? 1U : 0U) << k;
    return signs;
  }
  bool ambiguous(int f) const { return faceSigns(f) == 0x5U || faceSigns(f) == 0xAU; }

  /// For interior test `test`: member k of its z-edge quadruple (pair, then the other two), the
  /// corner of that z-edge with the test's sign (k < 2) or the other sign (k >= 2); -1 if none.
  int pairCorner(int test, int k) const {
    const bool wantNegative = ((test % 2) == 0) == (k < 2);
    for (const std::uint8_t c : kZEdgeCorners[kPairs[test / 2][k]]) {
      if (negative(c) == wantNegative) return c;
    }
    return -1;
  }

  /// Step 1: the arcs of every face as "next edge", and their cycles, the loops (each started at
  /// its smallest edge, in order of that edge).
  void traceLoops(unsigned faceJoinsNegatives) {
    std::array<std::uint8_t, kEdgeCount> next{};
    unsigned crossing = 0;
    for (int f = 0; f < kFaceCount; ++f) {
      const unsigned signs = faceSigns(f);
      const auto& edges = kFaceEdges[f];
      const auto bit = [signs](int k) { return (signs >> (k & 3)) & 1U; };
      for (int k = 0; k < 4; ++k) {
        if (bit(k) == bit(k + 1)) continue;
        crossing |= 1U << edges[k];
        if (bit(k) != 0U) continue;  // leaving the negative part
        // Entering: the arc runs to the leaving crossing; on an ambiguous face to the next one
        // counter-clockwise when the negative corners are cut off, else to the previous one.
        int to = k + 1;
        if (ambiguous(f)) {
          if (((faceJoinsNegatives >> f) & 1U) != 0U) to = k + 3;
        } else {
          while (bit(to) == 0U || bit(to + 1) != 0U) ++to;
        }
        next[edges[k]] = edges[to & 3];
      }
    }
    unsigned visited = 0;
    int size = 0;
    int loops = 0;
    for (int e = 0; e < kEdgeCount; ++e) {
      if (((crossing >> e) & 1U) == 0U || ((visited >> e) & 1U) != 0U) continue;
      topology_.loopBegin[loops] = static_cast<std::uint8_t>(size);
      int edge = e;
      do {
        topology_.loopEdges[size++] = static_cast<std::uint8_t>(edge);
        visited |= 1U << edge;
        edge = next[edge];
      } while (edge != e);
      ++loops;
    }
    topology_.loopBegin[loops] = static_cast<std::uint8_t>(size);
    topology_.loopCount = static_cast<std::uint8_t>(loops);
  }

  unsigned mask_;
  CellTopology topology_;  // loops only
  CornerClasses surface_;
};

// ---------------------------------------------------------------------------------------------
// The tables

/// Per sign pattern: its ambiguous faces and where its decision cases start.
struct PatternEntry {
  std::uint16_t firstCase = 0;
  std::uint8_t ambiguousCount = 0;
  std::array<std::uint8_t, kFaceCount> ambiguousFaces{};
};

/// Per sign pattern and combination of its face decisions: the relevant interior tests and where
/// the 2^tests topologies start.
struct DecisionCase {
  std::uint16_t firstTopology = 0;
  std::uint8_t testCount = 0;
  std::array<std::uint8_t, kInteriorTests> tests{};
};

struct Tables {
  std::array<PatternEntry, 256> patterns;
  std::vector<DecisionCase> cases;
  std::vector<CellTopology> topologies;

  Tables() {
    for (unsigned mask = 0; mask < 256; ++mask) {
      PatternEntry& pattern = patterns[mask];
      pattern.firstCase = static_cast<std::uint16_t>(cases.size());
      const Derivation signsOnly(mask, 0);
      for (int f = 0; f < kFaceCount; ++f) {
        unsigned signs = 0;
        for (int k = 0; k < 4; ++k) signs |= ((mask >> kFaceCorners[f][k]) & 1U) << k;
        if (signs == 0x5U || signs == 0xAU) {
          pattern.ambiguousFaces[pattern.ambiguousCount++] = static_cast<std::uint8_t>(f);
        }
      }
      for (unsigned bits = 0; bits < (1U << pattern.ambiguousCount); ++bits) {
        unsigned faceJoins = 0;
        for (int k = 0; k < pattern.ambiguousCount; ++k) {
          faceJoins |= ((bits >> k) & 1U) << pattern.ambiguousFaces[k];
        }
        const Derivation derivation(mask, faceJoins);
        const std::vector<int> tests = derivation.relevantTests();
        DecisionCase decision;
        decision.firstTopology = static_cast<std::uint16_t>(topologies.size());
        decision.testCount = static_cast<std::uint8_t>(tests.size());
        for (std::size_t k = 0; k < tests.size(); ++k) {
          decision.tests[k] = static_cast<std::uint8_t>(tests[k]);
        }
        cases.push_back(decision);
        for (unsigned outcomes = 0; outcomes < (1U << tests.size()); ++outcomes) {
          unsigned joined = 0;
          for (std::size_t k = 0; k < tests.size(); ++k) {
            joined |= ((outcomes >> k) & 1U) << tests[k];
          }
          topologies.push_back(derivation.topology(joined));
        }
      }
    }
  }
};

const Tables& tables() {
  static const Tables kTables;
  return kTables;
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
  unsigned mask = 0;
  for (int c = 0; c < kCornerCount; ++c) mask |= (values[c] < 0.0F ? 1U : 0U) << c;
  const Tables& t = tables();
  const PatternEntry& pattern = t.patterns[mask];
  unsigned faceBits = 0;
  for (int k = 0; k < pattern.ambiguousCount; ++k) {
    const auto& corners = kFaceCorners[pattern.ambiguousFaces[k]];
    const bool joins = faceJoinsNegatives(values[corners[0]], values[corners[1]],
                                          values[corners[2]], values[corners[3]]);
    faceBits |= (joins ? 1U : 0U) << k;
  }
  const DecisionCase& decision = t.cases[pattern.firstCase + faceBits];
  unsigned outcomes = 0;
  for (int k = 0; k < decision.testCount; ++k) {
    outcomes |= (interiorJoins(values, decision.tests[k]) ? 1U : 0U) << k;
  }
  return t.topologies[decision.firstTopology + outcomes];
}

}  // namespace voxremesh::mc33
