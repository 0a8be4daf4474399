// MC33 cell topology (include/voxremesh/mc33.h): the component grouping of every one of the 256
// sign patterns, with many corner magnitudes each, against an independent oracle that samples the
// trilinear interpolant densely; face consistency between neighbouring cells; loop orientation;
// triangulation topology; complement symmetry and the tie rule for zeros.
#include "voxremesh/mc33.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace {

using namespace voxremesh::mc33;
using Vec3 = std::array<double, 3>;
/// Component per edge, numbered by first appearance in edge order; -1 for no crossing.
using Grouping = std::array<int, kEdgeCount>;

// ---------------------------------------------------------------------------------------------
// The trilinear interpolant

Vec3 cornerPosition(int c) {
  return {static_cast<double>(c & 1), static_cast<double>((c >> 1) & 1),
          static_cast<double>((c >> 2) & 1)};
}

double trilinear(const CellValues& v, const Vec3& p) {
  double sum = 0.0;
  for (int c = 0; c < kCornerCount; ++c) {
    const Vec3 q = cornerPosition(c);
    double w = 1.0;
    for (int k = 0; k < 3; ++k) w *= q[k] > 0.5 ? p[k] : 1.0 - p[k];
    sum += w * v[c];
  }
  return sum;
}

Vec3 gradient(const CellValues& v, const Vec3& p) {
  Vec3 g{0.0, 0.0, 0.0};
  for (int c = 0; c < kCornerCount; ++c) {
    const Vec3 q = cornerPosition(c);
    for (int k = 0; k < 3; ++k) {
      double w = q[k] > 0.5 ? 1.0 : -1.0;
      for (int m = 0; m < 3; ++m) {
        if (m != k) w *= q[m] > 0.5 ? p[m] : 1.0 - p[m];
      }
      g[k] += w * v[c];
    }
  }
  return g;
}

Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

bool isNegative(float value) {
  return value < 0.0F;
}

bool crosses(const CellValues& v, int edge) {
  return isNegative(v[kEdgeCorners[edge][0]]) != isNegative(v[kEdgeCorners[edge][1]]);
}

Grouping groupingOf(const CellTopology& t) {
  Grouping g;
  for (int e = 0; e < kEdgeCount; ++e) g[e] = t.edgeComponent[e];
  return g;
}

/// Renumbers components by first appearance in edge order.
Grouping canonical(const std::array<long, kEdgeCount>& label) {
  Grouping g;
  std::map<long, int> ids;
  for (int e = 0; e < kEdgeCount; ++e) {
    if (label[e] < 0) {
      g[e] = -1;
      continue;
    }
    const auto found = ids.emplace(label[e], static_cast<int>(ids.size())).first;
    g[e] = found->second;
  }
  return g;
}

std::string describe(const CellValues& v) {
  std::string text = "values {";
  char number[32];
  for (int c = 0; c < kCornerCount; ++c) {
    std::snprintf(number, sizeof number, "%s%.9g", c == 0 ? "" : ", ", static_cast<double>(v[c]));
    text += number;
  }
  return text + "}";
}

std::string describe(const Grouping& g) {
  std::string text = "[";
  for (int e = 0; e < kEdgeCount; ++e) text += (e ? " " : "") + std::to_string(g[e]);
  return text + "]";
}

// ---------------------------------------------------------------------------------------------
// The oracle
//
// The isosurface S = {F = 0} cuts the closed cell into connected regions where F < 0 and where
// F >= 0. Each component of S separates one negative region from one positive region, and since
// the cell is simply connected no two components separate the same pair (the graph of regions and
// components is a tree). A crossing on an edge lies between the edge's negative part and its
// positive part, so two crossings are on the same component iff the negative regions holding their
// edges' negative parts are the same and the positive regions holding the positive parts are too.
//
// The regions are found by sampling F densely, not by any face or interior test: the cell is
// covered by (M+1)^2 lines parallel to x through (y, z) = (i/M, j/M). Along such a line F is linear
// in x, so its negative part and its positive part are each one interval, found exactly from the
// line's end values. Two runs of one sign on neighbouring lines (distance 1/M) are joined when
// their x-intervals overlap; the regions are the classes of this union-find. The edges of the cell
// are on lines (x-edges) or cross lines at x = 0 or 1 (y- and z-edges), so every crossing is seen
// between two runs. The sampling resolves a region's neck down to about 1/M. Necks become thinner
// than any grid only when a critical value of F comes close to 0: a saddle of F on a face or a
// critical point of F inside the cell (the topology of {F < c} changes only at critical values of
// F on the cell's strata; corners are resolved exactly by the lines through them). A cell whose
// narrowest neck (narrowestNeck) is below two line spacings needs a finer oracle, see
// AdaptiveOracle.
class LineOracle {
 public:
  explicit LineOracle(int resolution)
      : m_(resolution),
        lines_((resolution + 1) * (resolution + 1)),
        parent_(2 * lines_),
        runs_(2 * lines_),
        atX0_(lines_),
        atX1_(lines_) {}

  Grouping grouping(const CellValues& v) {
    for (int j = 0; j <= m_; ++j) {
      for (int i = 0; i <= m_; ++i) {
        const double y = static_cast<double>(i) / m_;
        const double z = static_cast<double>(j) / m_;
        const auto bilinear = [&](int c00, int c10, int c01, int c11) {
          return (1.0 - y) * (1.0 - z) * v[c00] + y * (1.0 - z) * v[c10] + (1.0 - y) * z * v[c01] +
                 y * z * v[c11];
        };
        const int l = line(i, j);
        atX0_[l] = bilinear(0, 2, 4, 6);
        atX1_[l] = bilinear(1, 3, 5, 7);
        for (const bool negative : {true, false}) runs_[node(l, negative)] = run(l, negative);
      }
    }
    for (int n = 0; n < 2 * lines_; ++n) parent_[n] = n;
    for (int j = 0; j <= m_; ++j) {
      for (int i = 0; i <= m_; ++i) {
        if (i < m_) joinLines(line(i, j), line(i + 1, j));
        if (j < m_) joinLines(line(i, j), line(i, j + 1));
      }
    }
    std::array<long, kEdgeCount> label;
    label.fill(-1);
    for (int e = 0; e < kEdgeCount; ++e) {
      if (!crosses(v, e)) continue;
      const int axis = e / 4;
      const int a = e & 1;
      const int b = (e >> 1) & 1;
      int negativeNode = -1;
      int positiveNode = -1;
      if (axis == 0) {
        const int l = line(a * m_, b * m_);
        negativeNode = node(l, true);
        positiveNode = node(l, false);
      } else {
        // A y-edge at (x, z) = (a, b) or a z-edge at (x, y) = (a, b): walk its samples.
        for (int s = 0; s < m_; ++s) {
          const int l0 = axis == 1 ? line(s, b * m_) : line(b * m_, s);
          const int l1 = axis == 1 ? line(s + 1, b * m_) : line(b * m_, s + 1);
          const double f0 = a == 0 ? atX0_[l0] : atX1_[l0];
          const double f1 = a == 0 ? atX0_[l1] : atX1_[l1];
          if ((f0 < 0.0) == (f1 < 0.0)) continue;
          negativeNode = f0 < 0.0 ? node(l0, true) : node(l1, true);
          positiveNode = f0 < 0.0 ? node(l1, false) : node(l0, false);
          break;
        }
      }
      if (negativeNode < 0) continue;  // rounding hid the crossing; cannot happen for finite v
      label[e] = static_cast<long>(find(negativeNode)) * (2L * lines_) + find(positiveNode);
    }
    return canonical(label);
  }

 private:
  int line(int i, int j) const { return j * (m_ + 1) + i; }
  static int node(int l, bool negative) { return 2 * l + (negative ? 0 : 1); }

  /// The run of one sign on a line as an x-interval (empty when lo >= hi and not a full run).
  struct Run {
    bool exists;
    double lo;
    double hi;
  };
  Run run(int l, bool negative) const {
    const double f0 = atX0_[l];
    const double f1 = atX1_[l];
    const bool in0 = (f0 < 0.0) == negative;
    const bool in1 = (f1 < 0.0) == negative;
    if (in0 && in1) return {true, 0.0, 1.0};
    if (!in0 && !in1) return {false, 0.0, 0.0};
    const double root = f0 / (f0 - f1);
    return in0 ? Run{true, 0.0, root} : Run{true, root, 1.0};
  }

  void joinLines(int a, int b) {
    for (const bool negative : {true, false}) {
      const Run& ra = runs_[node(a, negative)];
      const Run& rb = runs_[node(b, negative)];
      if (ra.exists && rb.exists && std::max(ra.lo, rb.lo) < std::min(ra.hi, rb.hi)) {
        unite(node(a, negative), node(b, negative));
      }
    }
  }

  int find(int n) {
    while (parent_[n] != n) {
      parent_[n] = parent_[parent_[n]];
      n = parent_[n];
    }
    return n;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

  int m_;
  int lines_;
  std::vector<int> parent_;
  std::vector<Run> runs_;
  std::vector<double> atX0_;
  std::vector<double> atX1_;
};

/// The narrowest neck of F's sign regions: the smallest sqrt(|F*| / k) over the saddles of F on
/// the open faces and the critical points of F inside the open cell, F* the critical value and k
/// the curvature there (near a face saddle F = F* + k (s - s*)(t - t*), so the hyperbola branches
/// are about that far from the saddle; inside, k is the norm of the Hessian). Computed from F's
/// polynomial form, independently of the code under test. Infinity without such points.
double narrowestNeck(const CellValues& v) {
  double scale = 0.0;
  for (const float value : v) scale = std::max(scale, std::fabs(static_cast<double>(value)));
  double narrowest = std::numeric_limits<double>::infinity();
  // Faces, corners a, b, d, c in face order: the saddle is at s = (a - c)/k, t = (a - b)/k with
  // k = a - b - c + d, and F* = (ad - bc)/k.
  for (const auto& corners : kFaceCorners) {
    const double a = v[corners[0]];
    const double b = v[corners[1]];
    const double d = v[corners[2]];
    const double c = v[corners[3]];
    const double k = a - b - c + d;
    if (k == 0.0) continue;
    const double s = (a - c) / k;
    const double t = (a - b) / k;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) {
      narrowest = std::min(narrowest, std::sqrt(std::fabs((a * d - b * c) / k / k)));
    }
  }
  // Interior: F = k0 + k1 x + k2 y + k3 z + k4 xy + k5 yz + k6 xz + k7 xyz. Solving F_x = F_y = 0
  // for x, y at fixed z and substituting into F_z = 0 gives a quadratic in z. Solved three times
  // with the axes rotated (a degenerate elimination along one axis is covered by another);
  // candidates are kept where the gradient vanishes.
  for (int rotation = 0; rotation < 3; ++rotation) {
    // Values with axes rotated: new axis k is old axis (k + rotation) % 3.
    CellValues w;
    for (int c = 0; c < kCornerCount; ++c) {
      int old = 0;
      for (int k = 0; k < 3; ++k) old |= ((c >> k) & 1) << ((k + rotation) % 3);
      w[c] = v[old];
    }
    const double k1 = w[1] - w[0];
    const double k2 = w[2] - w[0];
    const double k3 = w[4] - w[0];
    const double k4 = w[3] - w[2] - w[1] + w[0];
    const double k5 = w[6] - w[4] - w[2] + w[0];
    const double k6 = w[5] - w[4] - w[1] + w[0];
    const double k7 = w[7] - w[6] - w[5] - w[3] + w[4] + w[2] + w[1] - w[0];
    const double qa = k7 * (k3 * k7 - k5 * k6);
    const double qb = 2.0 * k4 * (k3 * k7 - k5 * k6);
    const double qc = k3 * k4 * k4 - k1 * k4 * k5 - k2 * k4 * k6 + k1 * k2 * k7;
    std::vector<double> zs;
    if (qa != 0.0) {
      const double disc = qb * qb - 4.0 * qa * qc;
      if (disc >= 0.0) {
        zs.push_back((-qb + std::sqrt(disc)) / (2.0 * qa));
        zs.push_back((-qb - std::sqrt(disc)) / (2.0 * qa));
      }
    } else if (qb != 0.0) {
      zs.push_back(-qc / qb);
    }
    for (const double z : zs) {
      const double den = k4 + k7 * z;
      if (den == 0.0) continue;
      const double x = -(k2 + k5 * z) / den;
      const double y = -(k1 + k6 * z) / den;
      if (!(x > 0.0 && x < 1.0 && y > 0.0 && y < 1.0 && z > 0.0 && z < 1.0)) continue;
      Vec3 p{0.0, 0.0, 0.0};
      const Vec3 rotated{x, y, z};
      for (int k = 0; k < 3; ++k) p[(k + rotation) % 3] = rotated[k];
      if (norm(gradient(v, p)) > 1e-6 * scale) continue;
      const double hxy = k4 + k7 * z;
      const double hyz = k5 + k7 * x;
      const double hxz = k6 + k7 * y;
      const double curvature = std::sqrt(2.0 * (hxy * hxy + hyz * hyz + hxz * hxz));
      if (curvature > 0.0) {
        narrowest = std::min(narrowest, std::sqrt(std::fabs(trilinear(v, p)) / curvature));
      }
    }
  }
  return narrowest;
}

/// The oracle at the resolution a cell needs: 192 lines per side, or 768 where the narrowest neck
/// is below two line spacings of 192; cells whose neck is below two spacings of 768 are
/// numerically ambiguous for the oracle (no grouping). A scratch run over 98,304 cells of
/// randomCell at 192 lines found the oracle wrong on 3 cells, all with a neck below one spacing,
/// and right on all three at 2048 lines.
class AdaptiveOracle {
 public:
  static constexpr int kCoarse = 192;
  static constexpr int kFine = 768;

  /// The oracle's grouping, or false when the cell is skipped.
  bool grouping(const CellValues& v, Grouping& out) {
    const double neck = narrowestNeck(v);
    if (neck < 2.0 / kFine) return false;
    if (neck < 2.0 / kCoarse) {
      ++fineCells;
      out = fine_.grouping(v);
    } else {
      out = coarse_.grouping(v);
    }
    return true;
  }

  long fineCells = 0;  ///< cells that needed the fine resolution

 private:
  LineOracle coarse_{kCoarse};
  LineOracle fine_{kFine};
};

// ---------------------------------------------------------------------------------------------
// Sign patterns and their MC case

/// Faces whose corners alternate in sign around the face (the ambiguous faces).
unsigned ambiguousFaces(unsigned negativeMask) {
  unsigned faces = 0;
  for (int f = 0; f < kFaceCount; ++f) {
    unsigned s = 0;
    for (int k = 0; k < 4; ++k) s |= ((negativeMask >> kFaceCorners[f][k]) & 1U) << k;
    if (s == 0x5U || s == 0xAU) faces |= 1U << f;
  }
  return faces;
}

/// The Marching Cubes case (Lorensen's 15 up to symmetry and complement) of a sign pattern, told
/// apart by the number of corners of the rarer sign, their adjacency and the ambiguous faces; the
/// four patterns of four corners without an ambiguous face (cases 8, 9, 11, 14) share a label.
std::string mcCase(unsigned negativeMask) {
  const int negatives = __builtin_popcount(negativeMask);
  const unsigned rare = negatives <= 4 ? negativeMask : (~negativeMask & 0xFFU);
  const int k = std::min(negatives, 8 - negatives);
  const unsigned faces = ambiguousFaces(negativeMask);
  const int ambiguous = __builtin_popcount(faces);
  if (k == 0) return "0";
  if (k == 1) return "1";
  if (k == 2) {
    if (ambiguous == 1) return "3";
    const int a = __builtin_ctz(rare);
    const int b = 31 - __builtin_clz(rare);
    return __builtin_popcount(static_cast<unsigned>(a ^ b)) == 1 ? "2" : "4";
  }
  if (k == 3) return ambiguous == 0 ? "5" : (ambiguous == 1 ? "6" : "7");
  if (ambiguous == 0) return "8/9/11/14";
  if (ambiguous == 6) return "13";
  // Two ambiguous faces: opposite (case 10) or adjacent (case 12).
  const int f = __builtin_ctz(faces);
  return (faces >> (f ^ 1)) & 1U ? "10" : "12";
}

// ---------------------------------------------------------------------------------------------
// Random cells

/// Corner values with the given signs and magnitudes from one of several families: uniform,
/// log-uniform down to 1e-3, uniform with one or two corners near zero (down to 1e-7), one sign
/// strong and the other weak (the tunnel cases), and an ambiguous face driven close to its saddle
/// tie.
CellValues randomCell(unsigned negativeMask, int family, std::mt19937& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  CellValues v;
  for (int c = 0; c < kCornerCount; ++c) {
    const bool negative = ((negativeMask >> c) & 1U) != 0U;
    double magnitude = 0.0;
    switch (family) {
      case 1:
        magnitude = std::pow(10.0, -3.0 * unit(random));
        break;
      case 3:  // negative corners strong
        magnitude = negative ? 0.3 + 0.7 * unit(random) : 0.3 * unit(random) + 1e-3;
        break;
      case 4:  // positive corners strong
        magnitude = negative ? 0.3 * unit(random) + 1e-3 : 0.3 + 0.7 * unit(random);
        break;
      default:
        magnitude = 0.02 + 0.98 * unit(random);
        break;
    }
    v[c] = static_cast<float>(negative ? -magnitude : magnitude);
  }
  if (family == 2) {
    // One or two corners close to zero.
    for (int k = 0; k < 1 + static_cast<int>(random() % 2); ++k) {
      const int c = static_cast<int>(random() % kCornerCount);
      v[c] = static_cast<float>(std::copysign(std::pow(10.0, -3.0 - 4.0 * unit(random)), v[c]));
    }
  }
  if (family == 5) {
    // Rescale one corner of a random ambiguous face so that a*d = b*c (1 + delta): the face saddle
    // value is then proportional to delta, |delta| in [1e-3, 1e-1].
    const unsigned faces = ambiguousFaces(negativeMask);
    if (faces != 0) {
      std::vector<int> list;
      for (int f = 0; f < kFaceCount; ++f) {
        if ((faces >> f) & 1U) list.push_back(f);
      }
      const auto& corners = kFaceCorners[list[random() % list.size()]];
      const double delta =
          (unit(random) < 0.5 ? -1.0 : 1.0) * std::pow(10.0, -1.0 - 2.0 * unit(random));
      const double target = static_cast<double>(v[corners[1]]) * v[corners[3]] * (1.0 + delta);
      v[corners[0]] = static_cast<float>(target / v[corners[2]]);
    }
  }
  return v;
}

constexpr int kFamilies = 6;

// ---------------------------------------------------------------------------------------------
// Tables

TEST(Mc33Tables, EdgesJoinCornersDifferingInTheirAxis) {
  for (int e = 0; e < kEdgeCount; ++e) {
    const int a = kEdgeCorners[e][0];
    const int b = kEdgeCorners[e][1];
    EXPECT_EQ(a ^ b, 1 << (e / 4)) << "edge " << e;
    EXPECT_EQ(a & (1 << (e / 4)), 0) << "edge " << e << " starts at the axis' 0 end";
    // Numbered by the other two coordinates in axis order.
    const int axis = e / 4;
    const int u = (axis + 1) % 3;
    const int w = (axis + 2) % 3;
    const int first = std::min(u, w);
    const int second = std::max(u, w);
    EXPECT_EQ(e % 4, ((a >> first) & 1) + 2 * ((a >> second) & 1)) << "edge " << e;
  }
}

TEST(Mc33Tables, FacesAreCounterClockwiseFromOutsideAndUseEachEdgeOncePerDirection) {
  std::map<std::pair<int, int>, int> directedEdges;
  for (int f = 0; f < kFaceCount; ++f) {
    const int axis = f / 2;
    const int side = f % 2;
    Vec3 outward{0.0, 0.0, 0.0};
    outward[axis] = side == 1 ? 1.0 : -1.0;
    for (int k = 0; k < 4; ++k) {
      const int c0 = kFaceCorners[f][k];
      const int c1 = kFaceCorners[f][(k + 1) % 4];
      const int c2 = kFaceCorners[f][(k + 2) % 4];
      EXPECT_EQ((c0 >> axis) & 1, side) << "face " << f << " corner " << c0;
      const Vec3 turn = cross(sub(cornerPosition(c1), cornerPosition(c0)),
                              sub(cornerPosition(c2), cornerPosition(c1)));
      EXPECT_GT(dot(turn, outward), 0.0) << "face " << f << " at corner " << c1;
      const int e = kFaceEdges[f][k];
      const std::set<int> edgeCorners{kEdgeCorners[e][0], kEdgeCorners[e][1]};
      EXPECT_EQ(edgeCorners, (std::set<int>{c0, c1})) << "face " << f << " edge " << k;
      ++directedEdges[{c0, c1}];
    }
  }
  ASSERT_EQ(directedEdges.size(), 24U);
  for (const auto& [edge, count] : directedEdges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directedEdges.count({edge.second, edge.first}), 1U);
  }
}

// ---------------------------------------------------------------------------------------------
// Structure of the output

/// Checks the invariants every CellTopology must satisfy; returns a failure text or "".
std::string structureProblem(const CellValues& v, const CellTopology& t) {
  int crossing = 0;
  for (int e = 0; e < kEdgeCount; ++e) {
    if (crosses(v, e) != (t.edgeComponent[e] != kNoComponent)) return "edge " + std::to_string(e);
    crossing += crosses(v, e) ? 1 : 0;
  }
  if (t.loopBegin[t.loopCount] != crossing) return "loop sizes";
  if (t.componentCount > t.loopCount || t.loopCount > kMaxLoops) return "counts";
  std::set<int> seen;
  int previousFirst = -1;
  int nextComponent = 0;
  for (int l = 0; l < t.loopCount; ++l) {
    const int n = t.loopSize(l);
    if (n < 3) return "short loop";
    const int first = t.loopEdge(l, 0);
    if (first <= previousFirst) return "loop order";
    previousFirst = first;
    if (t.loopComponent[l] > nextComponent) return "component order";
    if (t.loopComponent[l] == nextComponent) ++nextComponent;
    for (int i = 0; i < n; ++i) {
      const int e = t.loopEdge(l, i);
      if (e < first) return "loop start";
      if (!seen.insert(e).second) return "edge twice";
      if (t.edgeComponent[e] != t.loopComponent[l]) return "loop component";
      // Consecutive edges lie on one face (an arc of the face).
      const int e2 = t.loopEdge(l, (i + 1) % n);
      bool shareFace = false;
      for (const auto& edges : kFaceEdges) {
        shareFace = shareFace || (std::count(edges.begin(), edges.end(), e) &&
                                  std::count(edges.begin(), edges.end(), e2));
      }
      if (!shareFace) return "arc off the faces";
    }
  }
  if (nextComponent != t.componentCount) return "component count";
  return "";
}

// ---------------------------------------------------------------------------------------------
// Exhaustive comparison with the oracle

struct CaseTally {
  long cells = 0;
  long skipped = 0;
  long tunnels = 0;        // cells with a component of two loops
  long oracleTunnels = 0;  // the same seen by the oracle (fewer components than loops)
  long mismatches = 0;
};

/// The oracle's number of loops that share a component: loops minus components, from its grouping.
int oracleMergedLoops(const CellTopology& t, const Grouping& oracle) {
  std::set<int> components;
  for (int e = 0; e < kEdgeCount; ++e) {
    if (oracle[e] >= 0) components.insert(oracle[e]);
  }
  return t.loopCount - static_cast<int>(components.size());
}

TEST(Mc33Oracle, EverySignPatternAgreesWithDenseSampling) {
  constexpr int kSamplesPerFamily = 12;
  AdaptiveOracle oracle;
  std::mt19937 random(20240601);
  std::map<std::string, CaseTally> tally;
  long cells = 0;
  long skipped = 0;
  long mismatches = 0;
  long maxLoopsPerComponent = 0;
  for (unsigned mask = 0; mask < 256; ++mask) {
    for (int family = 0; family < kFamilies; ++family) {
      for (int s = 0; s < kSamplesPerFamily; ++s) {
        const CellValues v = randomCell(mask, family, random);
        const CellTopology t = cellTopology(v);
        ASSERT_EQ(structureProblem(v, t), "") << describe(v);
        for (int c = 0; c < t.componentCount; ++c) {
          maxLoopsPerComponent = std::max<long>(maxLoopsPerComponent, t.componentLoopCount(c));
        }
        CaseTally& row = tally[mcCase(mask)];
        ++row.cells;
        ++cells;
        Grouping expected;
        if (!oracle.grouping(v, expected)) {
          ++row.skipped;
          ++skipped;
          continue;
        }
        const Grouping actual = groupingOf(t);
        const bool tunnel = t.componentCount < t.loopCount;
        row.tunnels += tunnel ? 1 : 0;
        row.oracleTunnels += oracleMergedLoops(t, expected) > 0 ? 1 : 0;
        if (expected != actual) {
          ++row.mismatches;
          if (++mismatches <= 10) {
            ADD_FAILURE() << "mask " << mask << " family " << family << ": " << describe(v)
                          << "\n  cellTopology " << describe(actual) << "\n  oracle       "
                          << describe(expected) << "\n  narrowest neck " << narrowestNeck(v);
          }
        }
      }
    }
  }
  std::printf("%-10s %8s %8s %8s %8s %8s\n", "MC case", "cells", "skipped", "tunnels", "oracle",
              "differ");
  for (const auto& [name, row] : tally) {
    std::printf("%-10s %8ld %8ld %8ld %8ld %8ld\n", name.c_str(), row.cells, row.skipped,
                row.tunnels, row.oracleTunnels, row.mismatches);
  }
  std::printf(
      "%ld cells, %ld skipped (%.2f %%, a neck narrower than 2/%d), %ld sampled with %d lines per "
      "side, %ld differ\n",
      cells, skipped, 100.0 * skipped / cells, AdaptiveOracle::kFine, oracle.fineCells,
      AdaptiveOracle::kFine, mismatches);
  EXPECT_EQ(mismatches, 0);
  EXPECT_LT(skipped, cells / 50) << "the oracle skipped more than 2 % of the cells";
  EXPECT_EQ(maxLoopsPerComponent, 2) << "components are disks or tunnels";
  // Tunnels only where MC33 has them (the interior cases are hunted down in the next test).
  for (const char* name : {"1", "2", "3", "5", "8/9/11/14"}) {
    EXPECT_EQ(tally[name].tunnels, 0) << "case " << name;
  }
}

TEST(Mc33Oracle, InteriorCasesAgreeWithDenseSampling) {
  // For every sign pattern of the MC cases with an interior ambiguity, draw cells until a few with
  // a tunnel and a few whose interior test kept the loops apart are found, and check them all with
  // the oracle (selecting by the code under test only chooses which cells the oracle checks).
  constexpr int kWanted = 12;
  AdaptiveOracle oracle;
  std::mt19937 random(77);
  std::map<std::string, std::array<long, 3>> checked;  // tunnels, apart, skipped
  long mismatches = 0;
  for (unsigned mask = 0; mask < 256; ++mask) {
    const std::string name = mcCase(mask);
    if (name != "4" && name != "6" && name != "7" && name != "10" && name != "12" && name != "13") {
      continue;
    }
    int tunnels = 0;
    int apart = 0;
    for (int draw = 0; draw < 20000 && (tunnels < kWanted || apart < kWanted); ++draw) {
      const CellValues v = randomCell(mask, draw % 2, random);
      const CellTopology t = cellTopology(v);
      const bool tunnel = t.componentCount < t.loopCount;
      if (tunnel ? tunnels >= kWanted : apart >= kWanted) continue;
      (tunnel ? tunnels : apart) += 1;
      Grouping expected;
      if (!oracle.grouping(v, expected)) {
        ++checked[name][2];
        continue;
      }
      ++checked[name][tunnel ? 0 : 1];
      if (expected != groupingOf(t) && ++mismatches <= 10) {
        ADD_FAILURE() << "mask " << mask << ": " << describe(v) << "\n  cellTopology "
                      << describe(groupingOf(t)) << "\n  oracle       " << describe(expected);
      }
    }
  }
  std::printf("%-8s %8s %8s %8s\n", "MC case", "tunnel", "apart", "skipped");
  for (const auto& [name, row] : checked) {
    std::printf("%-8s %8ld %8ld %8ld\n", name.c_str(), row[0], row[1], row[2]);
    EXPECT_GT(row[0], 0) << "case " << name << ": no tunnel checked";
    EXPECT_GT(row[1], 0) << "case " << name << ": no separated loops checked";
  }
  EXPECT_EQ(checked.size(), 6U);
  EXPECT_EQ(mismatches, 0);
}

}  // namespace

namespace {

// ---------------------------------------------------------------------------------------------
// Hand-checked cells

/// The loops of a topology as edge lists.
std::vector<std::vector<int>> loopsOf(const CellTopology& t) {
  std::vector<std::vector<int>> loops(t.loopCount);
  for (int l = 0; l < t.loopCount; ++l) {
    for (int i = 0; i < t.loopSize(l); ++i) loops[l].push_back(t.loopEdge(l, i));
  }
  return loops;
}

TEST(Mc33Cells, EmptyCells) {
  for (const float value : {1.0F, 0.0F, -0.0F}) {
    const CellTopology t =
        cellTopology(CellValues{value, value, value, value, value, value, value, value});
    EXPECT_EQ(t.componentCount, 0);
    EXPECT_EQ(t.loopCount, 0);
    for (int e = 0; e < kEdgeCount; ++e) EXPECT_EQ(t.edgeComponent[e], kNoComponent);
  }
  EXPECT_EQ(cellTopology(CellValues{-1, -2, -3, -4, -5, -6, -7, -8}).componentCount, 0);
}

TEST(Mc33Cells, SingleCornerIsATriangleCounterClockwiseFromOutside) {
  // Corner 0 inside: the triangle through the crossings on x, y and z (edges 0, 4, 8), which runs
  // counter-clockwise seen from the positive side (from (1,1,1)).
  const CellTopology t = cellTopology(CellValues{-1, 1, 1, 1, 1, 1, 1, 1});
  EXPECT_EQ(t.componentCount, 1);
  EXPECT_EQ(loopsOf(t), (std::vector<std::vector<int>>{{0, 4, 8}}));
  // Corner 7 inside: edges 3 (6-7), 7 (5-7), 11 (3-7); from outside (0,0,0) counter-clockwise.
  const CellTopology u = cellTopology(CellValues{1, 1, 1, 1, 1, 1, 1, -1});
  EXPECT_EQ(loopsOf(u), (std::vector<std::vector<int>>{{3, 11, 7}}));
  // The complement reverses the loop.
  const CellTopology w = cellTopology(CellValues{1, -1, -1, -1, -1, -1, -1, -1});
  EXPECT_EQ(loopsOf(w), (std::vector<std::vector<int>>{{0, 8, 4}}));
}

TEST(Mc33Cells, FaceDiagonalFollowsTheAsymptoticDecider) {
  // MC case 3: corners 0 and 3 inside, on the face z = 0. The face saddle value is
  // (v0 v3 - v1 v2) / (v0 + v3 - v1 - v2): negative when v0 v3 > v1 v2.
  const CellTopology joined = cellTopology(CellValues{-1, 0.5F, 0.5F, -1, 1, 1, 1, 1});
  EXPECT_EQ(joined.componentCount, 1);
  EXPECT_EQ(joined.loopCount, 1);
  EXPECT_EQ(joined.loopSize(0), 6);
  const CellTopology apart = cellTopology(CellValues{-1, 2, 2, -1, 1, 1, 1, 1});
  EXPECT_EQ(apart.componentCount, 2);
  EXPECT_EQ(loopsOf(apart), (std::vector<std::vector<int>>{{0, 4, 8}, {1, 5, 11}}));
  // The tie (saddle exactly 0) joins the positive corners.
  const CellTopology tie = cellTopology(CellValues{-1, 1, 1, -1, 1, 1, 1, 1});
  EXPECT_EQ(tie.componentCount, 2);
}

TEST(Mc33Cells, BodyDiagonalTunnel) {
  // MC case 4: corners 0 and 7 inside. Weak positive corners let the inside pass through the cell
  // (4.1.2, one tunnel with two loops), strong ones keep the two corners apart (4.1.1).
  const CellTopology tunnel = cellTopology(CellValues{-1, 0.1F, 0.1F, 0.1F, 0.1F, 0.1F, 0.1F, -1});
  EXPECT_EQ(tunnel.componentCount, 1);
  EXPECT_EQ(tunnel.loopCount, 2);
  EXPECT_EQ(tunnel.componentLoopCount(0), 2);
  const CellTopology apart = cellTopology(CellValues{-1, 1, 1, 1, 1, 1, 1, -1});
  EXPECT_EQ(apart.componentCount, 2);
  EXPECT_EQ(apart.loopCount, 2);
  LineOracle oracle(128);
  EXPECT_EQ(oracle.grouping(CellValues{-1, 0.1F, 0.1F, 0.1F, 0.1F, 0.1F, 0.1F, -1}),
            groupingOf(tunnel));
  EXPECT_EQ(oracle.grouping(CellValues{-1, 1, 1, 1, 1, 1, 1, -1}), groupingOf(apart));
}

TEST(Mc33Cells, CrossingPointsAndCentroids) {
  const CellValues v{-1, 3, 1, 1, 0.5F, 1, 1, 1};
  EXPECT_FLOAT_EQ(edgeCrossing(v, 0), 0.25F);
  EXPECT_FLOAT_EQ(edgeCrossing(v, 4), 0.5F);
  EXPECT_FLOAT_EQ(edgeCrossing(v, 8), 2.0F / 3.0F);
  EXPECT_EQ(edgePoint(v, 8), (CellPoint{0.0F, 0.0F, 2.0F / 3.0F}));
  const CellTopology t = cellTopology(v);
  const CellPoints p = cellPoints(v, t);
  EXPECT_EQ(p.edgePoints[0], (CellPoint{0.25F, 0.0F, 0.0F}));
  EXPECT_EQ(p.edgePoints[4], (CellPoint{0.0F, 0.5F, 0.0F}));
  EXPECT_FLOAT_EQ(p.centroids[0][0], 0.25F / 3.0F);
  EXPECT_FLOAT_EQ(p.centroids[0][1], 0.5F / 3.0F);
  EXPECT_FLOAT_EQ(p.centroids[0][2], 2.0F / 9.0F);
  // A zero value puts the crossing on its corner: zero counts as positive.
  const CellValues z{-1, 0, 1, 1, 1, 1, 1, 1};
  EXPECT_EQ(edgeCrossing(z, 0), 1.0F);
  const CellValues w{0, -1, 1, 1, 1, 1, 1, 1};
  EXPECT_EQ(edgeCrossing(w, 0), 0.0F);
}

}  // namespace

namespace {

// ---------------------------------------------------------------------------------------------
// Neighbouring cells

/// The arcs of a topology on face f: consecutive loop edges that both lie on f, as (from, to).
std::set<std::pair<int, int>> arcsOnFace(const CellTopology& t, int f) {
  const auto& edges = kFaceEdges[f];
  const auto onFace = [&](int e) { return std::count(edges.begin(), edges.end(), e) > 0; };
  std::set<std::pair<int, int>> arcs;
  for (int l = 0; l < t.loopCount; ++l) {
    const int n = t.loopSize(l);
    for (int i = 0; i < n; ++i) {
      const int a = t.loopEdge(l, i);
      const int b = t.loopEdge(l, (i + 1) % n);
      if (onFace(a) && onFace(b)) arcs.insert({a, b});
    }
  }
  return arcs;
}

/// The edge joining two corners.
int edgeOf(int a, int b) {
  for (int e = 0; e < kEdgeCount; ++e) {
    if ((kEdgeCorners[e][0] == a && kEdgeCorners[e][1] == b) ||
        (kEdgeCorners[e][0] == b && kEdgeCorners[e][1] == a)) {
      return e;
    }
  }
  return -1;
}

/// A value for a face corner: random sign and magnitude from wide ranges, or exact zeros.
float faceValue(std::mt19937& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double sign = unit(random) < 0.5 ? -1.0 : 1.0;
  switch (random() % 6) {
    case 0:
      return 0.0F;
    case 1:
      return static_cast<float>(sign * std::pow(10.0, -40.0 * unit(random)));  // to subnormals
    case 2:
      return static_cast<float>(sign * std::pow(10.0, 30.0 * unit(random)));
    case 3:
      return static_cast<float>(sign * static_cast<double>(1 + random() % 8));  // exact ties
    default:
      return static_cast<float>(sign * unit(random));
  }
}

TEST(Mc33Faces, NeighboursSharingAFaceAgreeOnItsArcs) {
  // Cell A and cell B = A shifted by one along an axis share A's face 2a+1 (B's face 2a). Their
  // crossings on it are the same points, and their arcs pair them the same way, traversed in
  // opposite directions (each cell sees the face from outside). This is what makes the surfaces
  // of neighbouring cells meet without cracks. (Whether the two arcs of an ambiguous face belong
  // to one component may differ between A and B, rightly: a tunnel inside A can join them while
  // they stay apart in B.)
  std::mt19937 random(5);
  long ambiguous = 0;
  long joinedNegatives = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const int axis = trial % 3;
    CellValues a;
    CellValues b;
    for (int c = 0; c < kCornerCount; ++c) a[c] = faceValue(random);
    for (int c = 0; c < kCornerCount; ++c) {
      b[c] = ((c >> axis) & 1) != 0 ? faceValue(random) : a[c | (1 << axis)];
    }
    if (trial % 2 == 0) {
      // Force an ambiguous shared face: the face's diagonals of opposite signs.
      const auto& corners = kFaceCorners[2 * axis + 1];
      for (int k = 0; k < 4; ++k) {
        const float magnitude = std::fabs(a[corners[k]]) == 0.0F ? 1.0F : std::fabs(a[corners[k]]);
        a[corners[k]] = k % 2 == 0 ? -magnitude : magnitude;
        b[corners[k] ^ (1 << axis)] = a[corners[k]];
      }
    }
    const CellTopology ta = cellTopology(a);
    const CellTopology tb = cellTopology(b);
    const int fa = 2 * axis + 1;
    const int fb = 2 * axis;
    std::set<std::pair<int, int>> mapped;
    for (const auto& [from, to] : arcsOnFace(ta, fa)) {
      const auto shift = [&](int e) {
        return edgeOf(kEdgeCorners[e][0] ^ (1 << axis), kEdgeCorners[e][1] ^ (1 << axis));
      };
      mapped.insert({shift(to), shift(from)});
    }
    ASSERT_EQ(mapped, arcsOnFace(tb, fb))
        << describe(a) << " / " << describe(b) << " axis " << axis;
    for (const int e : kFaceEdges[fa]) {
      const int eb = edgeOf(kEdgeCorners[e][0] ^ (1 << axis), kEdgeCorners[e][1] ^ (1 << axis));
      ASSERT_EQ(ta.edgeComponent[e] == kNoComponent, tb.edgeComponent[eb] == kNoComponent);
      if (ta.edgeComponent[e] != kNoComponent) {
        ASSERT_EQ(edgeCrossing(a, e), edgeCrossing(b, eb));
      }
    }
    if (arcsOnFace(ta, fa).size() == 2) {
      ++ambiguous;
      // The negative corners are joined when the arcs cut off the positive ones: an arc's two
      // edges then meet at a positive corner.
      const auto [from, to] = *arcsOnFace(ta, fa).begin();
      const std::set<int> first{kEdgeCorners[from][0], kEdgeCorners[from][1]};
      for (const int c : kEdgeCorners[to]) {
        if (first.count(c) && !isNegative(a[c])) ++joinedNegatives;
      }
    }
  }
  std::printf("%ld ambiguous shared faces, %ld with the negative corners joined\n", ambiguous,
              joinedNegatives);
  EXPECT_GT(ambiguous, 50000);
  EXPECT_GT(joinedNegatives, ambiguous / 5);
  EXPECT_LT(joinedNegatives, ambiguous * 4 / 5);
}

// ---------------------------------------------------------------------------------------------
// Symmetry and ties

CellValues negated(const CellValues& v) {
  CellValues n;
  for (int c = 0; c < kCornerCount; ++c) n[c] = -v[c];
  return n;
}

/// The loops reversed in place: each still starts at its smallest edge.
std::vector<std::vector<int>> reversedLoops(const CellTopology& t) {
  std::vector<std::vector<int>> loops = loopsOf(t);
  for (auto& loop : loops) std::reverse(loop.begin() + 1, loop.end());
  return loops;
}

TEST(Mc33Symmetry, NegatingAllValuesKeepsTheGroupingAndReversesTheLoops) {
  std::mt19937 random(11);
  long cells = 0;
  for (unsigned mask = 0; mask < 256; ++mask) {
    for (int family = 0; family < kFamilies; ++family) {
      for (int s = 0; s < 40; ++s) {
        const CellValues v = randomCell(mask, family, random);
        const CellTopology t = cellTopology(v);
        const CellTopology n = cellTopology(negated(v));
        ASSERT_EQ(groupingOf(t), groupingOf(n)) << describe(v);
        ASSERT_EQ(reversedLoops(t), loopsOf(n)) << describe(v);
        ++cells;
      }
    }
  }
  EXPECT_EQ(cells, 256 * kFamilies * 40);
}

/// v with its exact zeros replaced by `replacement`.
CellValues replaceZeros(CellValues v, float replacement) {
  for (float& value : v) {
    if (value == 0.0F) value = replacement;
  }
  return v;
}

TEST(Mc33Symmetry, ZerosCountAsPositive) {
  // A zero (also -0) behaves like a tiny positive value; negating a cell with zeros therefore
  // gives the grouping of the cell whose zeros are tiny negative values.
  std::mt19937 random(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  long withZeros = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    CellValues v;
    for (float& value : v) {
      const int kind = static_cast<int>(random() % 4);
      value = kind == 0 ? 0.0F
              : kind == 1
                  ? -0.0F
                  : static_cast<float>((unit(random) < 0.5 ? -1.0 : 1.0) * (0.05 + unit(random)));
    }
    withZeros += std::count(v.begin(), v.end(), 0.0F) > 0 ? 1 : 0;
    const CellTopology t = cellTopology(v);
    const CellTopology up = cellTopology(replaceZeros(v, 1e-30F));
    ASSERT_EQ(groupingOf(t), groupingOf(up)) << describe(v);
    ASSERT_EQ(loopsOf(t), loopsOf(up)) << describe(v);
    const CellTopology n = cellTopology(negated(v));
    const CellTopology down = cellTopology(replaceZeros(v, -1e-30F));
    ASSERT_EQ(groupingOf(n), groupingOf(down)) << describe(v);
    ASSERT_EQ(loopsOf(n), reversedLoops(down)) << describe(v);
  }
  EXPECT_GT(withZeros, 90000);
}

TEST(Mc33Symmetry, FaceSaddleTieJoinsThePositiveCorners) {
  // An ambiguous face with v0 v2 = v1 v3 exactly (saddle value 0) decides like the cell with every
  // value raised by a tiny amount: the level set F = -e.
  std::mt19937 random(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  long ties = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    CellValues v;
    for (float& value : v) {
      value = static_cast<float>((unit(random) < 0.5 ? -1.0 : 1.0) * (1 + random() % 16));
    }
    const int f = static_cast<int>(random() % kFaceCount);
    const auto& corners = kFaceCorners[f];
    const float a = static_cast<float>(1 << (random() % 4));  // a power of two: b c / a is exact
    const float b = static_cast<float>(1 + random() % 8);
    const float c = static_cast<float>(1 + random() % 8);
    const float sign = random() % 2 == 0 ? -1.0F : 1.0F;
    v[corners[0]] = sign * a;
    v[corners[2]] = sign * b * c / a;
    v[corners[1]] = -sign * b;
    v[corners[3]] = -sign * c;
    CellValues raised = v;
    for (float& value : raised) value += 1.0F / 1024.0F;
    const CellTopology t = cellTopology(v);
    const CellTopology r = cellTopology(raised);
    ASSERT_EQ(arcsOnFace(t, f), arcsOnFace(r, f)) << describe(v);
    // The arcs cut off the negative corners: each arc's two edges meet at a negative corner.
    for (const auto& [from, to] : arcsOnFace(t, f)) {
      int shared = -1;
      for (const int x : kEdgeCorners[from]) {
        if (x == kEdgeCorners[to][0] || x == kEdgeCorners[to][1]) shared = x;
      }
      ASSERT_TRUE(isNegative(v[shared])) << describe(v);
    }
    ++ties;
  }
  EXPECT_EQ(ties, 20000);
}

}  // namespace

namespace {

// ---------------------------------------------------------------------------------------------
// Orientation and triangles

Vec3 toVec(const CellPoint& p) {
  return {p[0], p[1], p[2]};
}

TEST(Mc33Orientation, EveryArcHasThePositiveSideOnItsLeft) {
  // Seen from outside the cell, each arc of a loop (the chord between two consecutive crossings,
  // on the face they share) has the positive corner of both its edges on its left and the negative
  // corner on its right: the loop runs counter-clockwise seen from the positive side.
  std::mt19937 random(19);
  long arcs = 0;
  for (unsigned mask = 1; mask < 255; ++mask) {
    for (int family = 0; family < kFamilies; ++family) {
      for (int s = 0; s < 20; ++s) {
        const CellValues v = randomCell(mask, family, random);
        const CellTopology t = cellTopology(v);
        const CellPoints p = cellPoints(v, t);
        for (int f = 0; f < kFaceCount; ++f) {
          Vec3 outward{0.0, 0.0, 0.0};
          outward[f / 2] = f % 2 == 1 ? 1.0 : -1.0;
          for (const auto& [from, to] : arcsOnFace(t, f)) {
            const Vec3 a = toVec(p.edgePoints[from]);
            const Vec3 left = cross(outward, sub(toVec(p.edgePoints[to]), a));
            for (const int e : {from, to}) {
              for (const int c : kEdgeCorners[e]) {
                const double side = dot(sub(cornerPosition(c), a), left);
                if (std::fabs(side) < 1e-9) continue;  // crossing on the corner
                ASSERT_EQ(side > 0.0, !isNegative(v[c]))
                    << describe(v) << " face " << f << " arc " << from << "-" << to;
              }
            }
            ++arcs;
          }
        }
      }
    }
  }
  EXPECT_GT(arcs, 100000);
}

TEST(Mc33Orientation, LoopAreaVectorFollowsTheGradient) {
  // The area vector of a loop (half the sum of p_i x p_i+1 over its crossing points) points the
  // way F grows. Checked where the surface along the loop is not strongly curved: the surface
  // normals (unit gradients) at all its crossing points within 60 degrees of their mean. The
  // area vector must then be within 90 degrees of that mean. Against the gradient at the loop's
  // centroid the check is statistical: on a disk the centroid can lie off a bent surface, near a
  // saddle of F (and a tunnel's centroid lies inside its tube, so those are left out), but the
  // gradient there must agree on all but a tiny share (a reversed orientation would agree on
  // almost none). Strongly curved loops (saddles wrapping around the cell, thin bent sheets) have
  // no meaningful single normal; the arcs' orientation is checked locally for every loop by the
  // previous test.
  std::mt19937 random(23);
  long loops = 0;
  long checked = 0;
  long disks = 0;
  long centroidAgrees = 0;
  for (unsigned mask = 1; mask < 255; ++mask) {
    for (int family = 0; family < kFamilies; ++family) {
      for (int s = 0; s < 40; ++s) {
        const CellValues v = randomCell(mask, family, random);
        const CellTopology t = cellTopology(v);
        const CellPoints p = cellPoints(v, t);
        for (int l = 0; l < t.loopCount; ++l) {
          ++loops;
          const int n = t.loopSize(l);
          Vec3 centroid{0.0, 0.0, 0.0};
          Vec3 mean{0.0, 0.0, 0.0};
          std::vector<Vec3> normals;
          for (int i = 0; i < n; ++i) {
            const Vec3 q = toVec(p.edgePoints[t.loopEdge(l, i)]);
            Vec3 g = gradient(v, q);
            const double length = norm(g);
            for (int k = 0; k < 3; ++k) {
              g[k] /= length;
              centroid[k] += q[k] / n;
              mean[k] += g[k] / n;
            }
            normals.push_back(g);
          }
          const double meanLength = norm(mean);
          bool flat = meanLength > 0.0;
          for (const Vec3& g : normals) flat = flat && dot(g, mean) >= 0.5 * meanLength;
          if (!flat) continue;
          Vec3 area{0.0, 0.0, 0.0};
          for (int i = 0; i < n; ++i) {
            const Vec3 c = cross(toVec(p.edgePoints[t.loopEdge(l, i)]),
                                 toVec(p.edgePoints[t.loopEdge(l, (i + 1) % n)]));
            for (int k = 0; k < 3; ++k) area[k] += 0.5 * c[k];
          }
          ASSERT_GT(dot(area, mean), 0.0) << describe(v) << " loop " << l;
          ++checked;
          if (t.componentLoopCount(t.loopComponent[l]) == 1) {
            ++disks;
            centroidAgrees += dot(area, gradient(v, centroid)) > 0.0 ? 1 : 0;
          }
        }
      }
    }
  }
  std::printf(
      "%ld loops, %ld on a surface flat enough to check; on %ld of the %ld disks among them the "
      "gradient at the centroid agrees\n",
      loops, checked, centroidAgrees, disks);
  EXPECT_GT(checked, loops * 2 / 3);
  EXPECT_GE(centroidAgrees, disks - disks / 1000);
}

}  // namespace

namespace {

/// Checks that each component's triangles form a connected, consistently oriented surface whose
/// boundary is exactly its loops (each loop edge once, in the loop's direction; every other edge
/// once in each direction) with Euler characteristic 2 - loops, and that no triangle lies in a
/// face of the cell. Returns a failure text or "".
std::string triangulationProblem(const CellTopology& t, const CellPoints& p,
                                 const CellTriangles& tri) {
  if (tri.count > kMaxTriangles) return "too many triangles";
  for (int c = 0; c < t.componentCount; ++c) {
    std::map<std::pair<int, int>, int> directed;
    std::set<int> vertices;
    std::vector<int> triangles;
    for (int i = 0; i < tri.count; ++i) {
      if (tri.component[i] != c) continue;
      triangles.push_back(i);
      const auto& v = tri.triangles[i];
      if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) return "repeated vertex";
      for (int k = 0; k < 3; ++k) {
        const int x = v[k];
        const bool ownEdge = x < kEdgeCount && t.edgeComponent[x] == c;
        const bool ownCentre = x == interiorVertex(c) && ((tri.interiorVertexMask >> c) & 1U);
        if (!ownEdge && !ownCentre) return "foreign vertex " + std::to_string(x);
        vertices.insert(x);
        ++directed[{v[k], v[(k + 1) % 3]}];
      }
      bool inFace = false;
      for (int f = 0; f < kFaceCount; ++f) {
        const auto onFace = [&](int x) {
          if (x >= kEdgeCount) return false;
          const auto& edges = kFaceEdges[f];
          return std::count(edges.begin(), edges.end(), x) > 0;
        };
        inFace = inFace || (onFace(v[0]) && onFace(v[1]) && onFace(v[2]));
      }
      if (inFace) return "triangle in a face";
    }
    int loops = 0;
    std::set<std::pair<int, int>> boundary;
    for (int l = 0; l < t.loopCount; ++l) {
      if (t.loopComponent[l] != c) continue;
      ++loops;
      for (int i = 0; i < t.loopSize(l); ++i) {
        boundary.insert({t.loopEdge(l, i), t.loopEdge(l, (i + 1) % t.loopSize(l))});
      }
    }
    std::set<std::pair<int, int>> undirected;
    for (const auto& [edge, count] : directed) {
      if (count != 1) return "directed edge used twice";
      const int reverse = directed.count({edge.second, edge.first});
      if (boundary.count(edge) ? reverse != 0 : reverse != 1) return "boundary or orientation";
      undirected.insert({std::min(edge.first, edge.second), std::max(edge.first, edge.second)});
    }
    for (const auto& edge : boundary) {
      if (!directed.count(edge)) return "loop edge missing";
    }
    const long euler = static_cast<long>(vertices.size()) - static_cast<long>(undirected.size()) +
                       static_cast<long>(triangles.size());
    if (euler != 2 - loops) return "Euler characteristic " + std::to_string(euler);
    // Connected through shared edges.
    std::vector<int> group(triangles.size());
    for (std::size_t i = 0; i < group.size(); ++i) group[i] = static_cast<int>(i);
    bool changed = true;
    while (changed) {
      changed = false;
      for (std::size_t i = 0; i < triangles.size(); ++i) {
        for (std::size_t j = 0; j < triangles.size(); ++j) {
          int shared = 0;
          for (const auto x : tri.triangles[triangles[i]]) {
            for (const auto y : tri.triangles[triangles[j]]) shared += x == y ? 1 : 0;
          }
          if (shared >= 2 && group[i] != group[j]) {
            group[i] = group[j] = std::min(group[i], group[j]);
            changed = true;
          }
        }
      }
    }
    for (const int g : group) {
      if (g != 0) return "not connected";
    }
  }
  (void)p;
  return "";
}

TEST(Mc33Triangles, ComponentsAreDisksAndTunnelsBoundedByTheirLoops) {
  std::mt19937 random(29);
  long cells = 0;
  long withCentre = 0;
  long tunnels = 0;
  int most = 0;
  for (unsigned mask = 0; mask < 256; ++mask) {
    for (int family = 0; family < kFamilies; ++family) {
      for (int s = 0; s < 80; ++s) {
        const CellValues v = randomCell(mask, family, random);
        const CellTopology t = cellTopology(v);
        const CellPoints p = cellPoints(v, t);
        const CellTriangles tri = cellTriangles(t, p);
        ASSERT_EQ(triangulationProblem(t, p, tri), "") << describe(v);
        ++cells;
        withCentre += tri.interiorVertexMask != 0 ? 1 : 0;
        tunnels += t.componentCount < t.loopCount ? 1 : 0;
        most = std::max(most, static_cast<int>(tri.count));
      }
    }
  }
  std::printf("%ld cells, %ld with an interior vertex, %ld with a tunnel, at most %d triangles\n",
              cells, withCentre, tunnels, most);
  EXPECT_GT(withCentre, 0);
  EXPECT_GT(tunnels, 0);
  EXPECT_LE(most, 12);
}

TEST(Mc33Triangles, MoreLoopsPerComponentStayPlanarSurfaces) {
  // cellTopology never puts three or four loops into one component, but cellTriangles accepts
  // such a topology: the four corner triangles of MC case 13.1, declared one component, become
  // one connected surface with four boundary loops (Euler characteristic -2).
  const CellValues v{-1, 1, 1, -1, 1, -1, -1, 1};
  CellTopology t = cellTopology(v);
  ASSERT_EQ(t.componentCount, 4);
  for (const int loops : {3, 4}) {
    CellTopology merged = t;
    for (int l = 0; l < merged.loopCount; ++l) {
      merged.loopComponent[l] = static_cast<std::uint8_t>(l < loops ? 0 : l - loops + 1);
    }
    merged.componentCount = static_cast<std::uint8_t>(4 - loops + 1);
    for (int l = 0; l < merged.loopCount; ++l) {
      for (int i = 0; i < merged.loopSize(l); ++i) {
        merged.edgeComponent[merged.loopEdge(l, i)] =
            static_cast<std::int8_t>(merged.loopComponent[l]);
      }
    }
    const CellPoints p = cellPoints(v, merged);
    const CellTriangles tri = cellTriangles(merged, p);
    EXPECT_EQ(triangulationProblem(merged, p, tri), "") << loops << " loops";
  }
}

}  // namespace

namespace {

// ---------------------------------------------------------------------------------------------
// Timing (run with --gtest_also_run_disabled_tests)

/// Times f over 10 million cells (the given set cycled) and prints ns per cell; returns a checksum
/// so that the work cannot be optimised away.
template <typename F>
long timeCells(const char* what, const std::vector<CellValues>& cells, F f) {
  constexpr long kCells = 10000000;
  long checksum = 0;
  const auto start = std::chrono::steady_clock::now();
  for (long i = 0; i < kCells; ++i)
    checksum += f(cells[static_cast<std::size_t>(i) % cells.size()]);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%-52s %6.3f s for 10M cells, %5.1f ns per cell\n", what, seconds,
              seconds * 1e9 / kCells);
  return checksum;
}

TEST(Mc33Timing, DISABLED_TenMillionCells) {
  std::mt19937 random(31);
  std::uniform_real_distribution<float> uniform(-1.0F, 1.0F);
  // Random values: every sign pattern, most cells with several loops and ambiguous faces.
  std::vector<CellValues> randomCells(1 << 20);
  for (auto& cell : randomCells) {
    for (float& value : cell) value = uniform(random);
  }
  // Surface cells of a level set: a sphere's signed distance sampled on a grid (the common case).
  std::vector<CellValues> sphereCells;
  constexpr int kGrid = 160;
  const auto distance = [](int i, int j, int k) {
    const double x = i - 80.3;
    const double y = j - 79.6;
    const double z = k - 80.1;
    return static_cast<float>(std::sqrt(x * x + y * y + z * z) - 70.0);
  };
  for (int k = 0; k < kGrid; ++k) {
    for (int j = 0; j < kGrid; ++j) {
      for (int i = 0; i < kGrid; ++i) {
        CellValues cell;
        for (int c = 0; c < kCornerCount; ++c) {
          cell[c] = distance(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
        }
        const bool inside = std::all_of(cell.begin(), cell.end(), isNegative);
        const bool outside = std::none_of(cell.begin(), cell.end(), isNegative);
        if (!inside && !outside) sphereCells.push_back(cell);
      }
    }
  }
  long checksum = 0;
  checksum += timeCells("cellTopology, uniform random values", randomCells,
                        [](const CellValues& v) { return cellTopology(v).componentCount; });
  checksum += timeCells("cellTopology, sphere surface cells", sphereCells,
                        [](const CellValues& v) { return cellTopology(v).componentCount; });
  checksum += timeCells("cellTopology + cellPoints, sphere surface cells", sphereCells,
                        [](const CellValues& v) {
                          const CellTopology t = cellTopology(v);
                          return static_cast<long>(cellPoints(v, t).centroids[0][0] * 1000.0F);
                        });
  checksum += timeCells("cellTopology + cellPoints + cellTriangles, random values", randomCells,
                        [](const CellValues& v) {
                          const CellTopology t = cellTopology(v);
                          return static_cast<long>(cellTriangles(t, cellPoints(v, t)).count);
                        });
  EXPECT_GT(checksum, 0);
}

}  // namespace
