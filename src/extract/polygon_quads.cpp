// A quad-dominant mesh of a closed polygon without inner points (see polygon_quads.h).
#include "extract/polygon_quads.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/vec3.h"

namespace voxremesh::extract {

using namespace geom;  // NOLINT: the vector operators

namespace {

constexpr double kInfinite = std::numeric_limits<double>::infinity();
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
/// A quad corner may not be flatter than this (degrees): the quad must stay clearly convex.
constexpr double kFlattestQuadCornerDeg = 170.0;

/// The edges the triangulation may use from each corner to a later one: polygon edges and
/// allowed chords, ascending.
std::vector<std::vector<std::uint32_t>> candidateEdges(const std::vector<Vec3>& corners,
                                                       double maxChord, const ChordTest& chordOk) {
  const std::size_t n = corners.size();
  std::vector<std::vector<std::uint32_t>> edges(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool polygonEdge = j == i + 1 || (i == 0 && j == n - 1);
      if (polygonEdge || (distance(corners[i], corners[j]) <= maxChord && chordOk(i, j)))
        edges[i].push_back(std::uint32_t(j));
    }
  }
  return edges;
}

/// The shape cost of triangle a-b-c against the surface normal `up`: the inverse of its shape
/// quality, infinite when it has no area or faces against `up`.
double triangleCost(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& up) {
  const Vec3 normal = cross(b - a, c - a);
  if (!(dot(normal, up) > 0.0)) return kInfinite;
  const double squares = dot(b - a, b - a) + dot(c - b, c - b) + dot(a - c, a - c);
  const double quality = 2.0 * std::sqrt(3.0) * norm(normal) / squares;
  return quality > 1e-9 ? 1.0 / quality : kInfinite;
}

/// One triangle of the triangulation: corners i < k < j (oriented i, k, j), and the triangles on
/// its chords i-k and k-j (kNone on a polygon edge).
struct Triangle {
  std::uint32_t i, k, j;
  std::uint32_t left = kNone, right = kNone;
};

}  // namespace

bool convexQuad(const std::array<Vec3, 4>& q, const Vec3& up) {
  const Vec3 normal = cross(q[2] - q[0], q[3] - q[1]);
  if (!(dot(normal, up) > 0.0)) return false;
  for (std::size_t c = 0; c < 4; ++c) {
    const Vec3& previous = q[(c + 3) % 4];
    const Vec3& next = q[(c + 1) % 4];
    if (!(dot(cross(q[c] - previous, next - q[c]), normal) > 0.0)) return false;
    if (angleDeg(previous - q[c], next - q[c]) > kFlattestQuadCornerDeg) return false;
  }
  return true;
}

std::vector<PolygonFace> polygonQuads(const std::vector<Vec3>& corners,
                                      const std::vector<Vec3>& normals, double maxChord,
                                      const ChordTest& chordOk) {
  const std::size_t n = corners.size();
  if (n < 3 || normals.size() != n) return {};
  const auto edges = candidateEdges(corners, maxChord, chordOk);
  // Best cost and split corner of the sub-polygon i..j below each edge i-j, smallest spans first.
  std::vector<std::vector<double>> cost(n);
  std::vector<std::vector<std::uint32_t>> split(n);
  for (std::size_t i = 0; i < n; ++i) {
    cost[i].assign(edges[i].size(), kInfinite);
    split[i].assign(edges[i].size(), kNone);
  }
  auto slot = [&](std::size_t i, std::size_t j) -> std::ptrdiff_t {
    const auto it = std::lower_bound(edges[i].begin(), edges[i].end(), std::uint32_t(j));
    return it != edges[i].end() && *it == j ? it - edges[i].begin() : -1;
  };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> spans;
  for (std::size_t i = 0; i < n; ++i)
    for (const std::uint32_t j : edges[i]) spans.emplace_back(std::uint32_t(i), j);
  std::stable_sort(spans.begin(), spans.end(), [](const auto& a, const auto& b) {
    return a.second - a.first < b.second - b.first;
  });
  for (const auto& [i, j] : spans) {
    const std::ptrdiff_t ij = slot(i, j);
    if (j == i + 1) {
      cost[i][std::size_t(ij)] = 0.0;
      continue;
    }
    for (std::size_t a = 0; a < edges[i].size() && edges[i][a] < j; ++a) {
      const std::uint32_t k = edges[i][a];
      const std::ptrdiff_t kj = slot(k, j);
      if (kj < 0 || cost[i][a] == kInfinite || cost[k][std::size_t(kj)] == kInfinite) continue;
      const double total =
          cost[i][a] + cost[k][std::size_t(kj)] +
          triangleCost(corners[i], corners[k], corners[j], normals[i] + normals[k] + normals[j]);
      if (total < cost[i][std::size_t(ij)]) {
        cost[i][std::size_t(ij)] = total;
        split[i][std::size_t(ij)] = k;
      }
    }
  }
  const std::ptrdiff_t root = slot(0, n - 1);
  if (root < 0 || cost[0][std::size_t(root)] == kInfinite) return {};

  // The triangles, each after the one on its outer chord (the root on edge 0 - (n-1)).
  std::vector<Triangle> triangles;
  std::vector<std::uint32_t> parent;
  std::vector<std::array<std::uint32_t, 3>> pending{{0, std::uint32_t(n - 1), kNone}};
  while (!pending.empty()) {
    const auto [i, j, from] = pending.back();
    pending.pop_back();
    const std::uint32_t k = split[i][std::size_t(slot(i, j))];
    const std::uint32_t t = std::uint32_t(triangles.size());
    triangles.push_back({i, k, j});
    parent.push_back(from);
    if (from != kNone) (triangles[from].i == i ? triangles[from].left : triangles[from].right) = t;
    if (k > i + 1) pending.push_back({i, k, t});
    if (j > k + 1) pending.push_back({k, j, t});
  }

  // Leaves first (children come after their parent): each unmatched triangle takes its parent.
  std::vector<std::uint32_t> partner(triangles.size(), kNone);
  for (std::size_t t = triangles.size(); t-- > 1;) {
    const std::uint32_t p = parent[t];
    if (partner[t] != kNone || partner[p] != kNone) continue;
    const Triangle& up = triangles[p];
    const Triangle& child = triangles[t];
    // The child lies on the parent's chord i-k (corners i, m, k) or k-j (corners k, m, j).
    const std::array<std::uint32_t, 4> quad = up.left == t ? std::array{up.i, child.k, up.k, up.j}
                                                           : std::array{up.i, up.k, child.k, up.j};
    const std::array<Vec3, 4> q{corners[quad[0]], corners[quad[1]], corners[quad[2]],
                                corners[quad[3]]};
    if (!convexQuad(q, normals[quad[0]] + normals[quad[1]] + normals[quad[2]] + normals[quad[3]]))
      continue;
    partner[t] = p;
    partner[p] = std::uint32_t(t);
  }

  std::vector<PolygonFace> faces;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Triangle& tri = triangles[t];
    if (partner[t] == kNone) {
      faces.push_back({tri.i, tri.k, tri.j, kNone});
    } else if (partner[t] < t) {  // the child of a pair writes the quad
      const Triangle& up = triangles[partner[t]];
      faces.push_back(up.left == t ? PolygonFace{up.i, tri.k, up.k, up.j}
                                   : PolygonFace{up.i, up.k, tri.k, up.j});
    }
  }
  return faces;
}

}  // namespace voxremesh::extract
