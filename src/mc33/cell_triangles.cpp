// Triangulation of a cell's isosurface components (include/voxremesh/mc33.h).
//
// A disk is triangulated over its loop's points, except where the loop runs along one face twice
// (both arcs of an ambiguous face in the same loop: a saddle-shaped polygon such as the hexagon of
// MC33 case 3.2): a fan from one of its points could have all three points on that face or fold
// over, so the fan is centred on the interior vertex instead. A tunnel is a band
// zipping its two loops. Loops are oriented as the boundary of their component (normal towards
// the positive side), and every triangle holds each of its loop edges in the loop's direction, so
// the triangles are oriented consistently with the loops.
#include <array>
#include <cmath>
#include <cstdint>

#include "voxremesh/mc33.h"

namespace voxremesh::mc33 {

namespace {

/// Per edge, bit f set for the two faces f it lies on.
constexpr std::array<std::uint8_t, kEdgeCount> kEdgeFaces = [] {
  std::array<std::uint8_t, kEdgeCount> faces{};
  for (int f = 0; f < kFaceCount; ++f) {
    for (const std::uint8_t e : kFaceEdges[f]) {
      faces[e] = static_cast<std::uint8_t>(faces[e] | (1U << f));
    }
  }
  return faces;
}();

/// Faces a triangle vertex lies on (none for an interior vertex).
unsigned vertexFaces(int vertex) {
  return vertex < kEdgeCount ? kEdgeFaces[vertex] : 0U;
}

/// True when the three vertices lie on one face of the cell (such a triangle would lie in the
/// face).
bool inOneFace(int a, int b, int c) {
  return (vertexFaces(a) & vertexFaces(b) & vertexFaces(c)) != 0U;
}

float distance(const CellPoint& a, const CellPoint& b) {
  float sum = 0.0F;
  for (int k = 0; k < 3; ++k) sum += (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(sum);
}

/// Appends triangles to a CellTriangles, one component at a time.
class TriangleWriter {
 public:
  TriangleWriter(CellTriangles& out, const CellPoints& points) : out_(out), points_(points) {}

  void add(int a, int b, int c, int component) {
    auto& triangle = out_.triangles[out_.count];
    triangle = {static_cast<std::uint8_t>(a), static_cast<std::uint8_t>(b),
                static_cast<std::uint8_t>(c)};
    out_.component[out_.count] = static_cast<std::uint8_t>(component);
    ++out_.count;
  }

  /// Removes the last triangle and returns it.
  std::array<std::uint8_t, 3> removeLast() { return out_.triangles[--out_.count]; }

  const CellPoint& point(int vertex) const {
    return vertex < kEdgeCount ? points_.edgePoints[vertex]
                               : points_.centroids[vertex - kEdgeCount];
  }

  /// The disk bounded by one loop (vertices in loop order).
  void disk(const std::uint8_t* loop, int n, int component) {
    if (n == 3) {
      add(loop[0], loop[1], loop[2], component);
      return;
    }
    unsigned arcFaces = 0;
    bool twiceOnAFace = false;
    for (int i = 0; i < n; ++i) {
      const unsigned face = vertexFaces(loop[i]) & vertexFaces(loop[(i + 1) % n]);
      twiceOnAFace = twiceOnAFace || (arcFaces & face) != 0U;
      arcFaces |= face;
    }
    if (twiceOnAFace) {
      const int centre = interiorVertex(component);
      out_.interiorVertexMask =
          static_cast<std::uint8_t>(out_.interiorVertexMask | (1U << component));
      for (int i = 0; i < n; ++i) add(centre, loop[i], loop[(i + 1) % n], component);
      return;
    }
    // A fan from the first point (no triangle can lie in a face: a face holding two of its points
    // other than the first would carry a second arc); for a quadrilateral from the end of its
    // shorter diagonal.
    int root = 0;
    if (n == 4 &&
        distance(point(loop[1]), point(loop[3])) < distance(point(loop[0]), point(loop[2]))) {
      root = 1;
    }
    for (int i = 1; i + 1 < n; ++i) {
      add(loop[root], loop[(root + i) % n], loop[(root + i + 1) % n], component);
    }
  }

  /// The annulus between two loops a (size n) and b (size m), both in their boundary orientation.
  /// Walking a forwards and b backwards, every step adds a triangle on one loop edge and a new
  /// "rung" between the loops; over all starting rungs from a[0] and all step orders (dynamic
  /// programming on the (n+1) x (m+1) grid of rungs), the band with the fewest triangles lying in a
  /// cell face (none, on the cells cellTopology yields) and then the shortest rungs is taken. The
  /// walk starts along a and ends along b, and never reaches the end of a before leaving the
  /// start of b: otherwise a rung would be used twice and the band pinched.
  void band(const std::uint8_t* a, int n, const std::uint8_t* b, int m, int component) {
    constexpr float kInFacePenalty = 1e6F;
    constexpr float kUnreachable = 1e30F;
    constexpr int kSize = kEdgeCount + 1;
    float bestCost = kUnreachable;
    int bestStart = 0;
    std::array<std::array<std::uint8_t, kSize>, kSize> bestSteps{};
    for (int start = 0; start < m; ++start) {
      const auto bAt = [&](int j) { return b[((start - j) % m + m) % m]; };
      std::array<std::array<float, kSize>, kSize> cost{};
      std::array<std::array<std::uint8_t, kSize>, kSize> steps{};  // 1: came along a, 2: along b
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= m; ++j) {
          if (i == 0 && j == 0) continue;
          float best = kUnreachable;
          std::uint8_t step = 0;
          const bool allowed = i > 0 && !(i == n && j == 0);
          if (allowed && !(i == n && j == m) && cost[i - 1][j] < kUnreachable) {
            // Triangle (a[i-1], a[i], b[j]) with the new rung a[i] - b[j].
            const int x = a[(i - 1) % n];
            const int y = a[i % n];
            const int z = bAt(j);
            best = cost[i - 1][j] + distance(point(y), point(z)) +
                   (inOneFace(x, y, z) ? kInFacePenalty : 0.0F);
            step = 1;
          }
          if (allowed && j > 0 && cost[i][j - 1] < kUnreachable) {
            // Triangle (a[i], b[j], b[j-1]) with the new rung a[i] - b[j].
            const int x = a[i % n];
            const int y = bAt(j);
            const int z = bAt(j - 1);
            const float viaB = cost[i][j - 1] + distance(point(x), point(y)) +
                               (inOneFace(x, y, z) ? kInFacePenalty : 0.0F);
            if (viaB < best) {
              best = viaB;
              step = 2;
            }
          }
          cost[i][j] = best;
          steps[i][j] = step;
        }
      }
      const float total = cost[n][m] + distance(point(a[0]), point(bAt(0)));
      if (total < bestCost) {
        bestCost = total;
        bestStart = start;
        bestSteps = steps;
      }
    }
    // Walk the chosen path back from (n, m) and emit its triangles (order does not matter).
    const auto bAt = [&](int j) { return b[((bestStart - j) % m + m) % m]; };
    int i = n;
    int j = m;
    while (i > 0 || j > 0) {
      if (bestSteps[i][j] == 1) {
        add(a[(i - 1) % n], a[i % n], bAt(j), component);
        --i;
      } else {
        add(a[i % n], bAt(j), bAt(j - 1), component);
        --j;
      }
    }
  }

 private:
  CellTriangles& out_;
  const CellPoints& points_;
};

}  // namespace

CellTriangles cellTriangles(const CellTopology& topology, const CellPoints& points) noexcept {
  CellTriangles out;
  TriangleWriter writer(out, points);
  for (int c = 0; c < topology.componentCount; ++c) {
    std::array<int, kMaxLoops> loops{};
    int loopCount = 0;
    for (int l = 0; l < topology.loopCount; ++l) {
      if (topology.loopComponent[l] == c) loops[loopCount++] = l;
    }
    const auto edges = [&](int k) {
      return topology.loopEdges.data() + topology.loopBegin[loops[k]];
    };
    const auto size = [&](int k) { return topology.loopSize(loops[k]); };
    if (loopCount == 1) {
      writer.disk(edges(0), size(0), c);
      continue;
    }
    writer.band(edges(0), size(0), edges(1), size(1), c);
    // The trilinear interpolant has no component with three or more loops (the tests confirm it
    // on millions of cells), but a topology handed in by a caller might: each further loop
    // replaces the last triangle by a band from the loop to that triangle's boundary, which keeps
    // the surface connected, planar and consistently oriented.
    for (int k = 2; k < loopCount; ++k) {
      const std::array<std::uint8_t, 3> hole = writer.removeLast();
      writer.band(edges(k), size(k), hole.data(), 3, c);
    }
  }
  return out;
}

}  // namespace voxremesh::mc33
