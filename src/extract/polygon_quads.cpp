// A quad-dominant mesh of a closed polygon without inner points (see polygon_quads.h).
#include "extract/polygon_quads.h"

#include <algorithm>
#include <limits>

#include "geometry/vec3.h"

namespace voxremesh::extract {

using namespace geom;  // NOLINT: the vector operators

namespace {

constexpr double kInfinite = std::numeric_limits<double>::infinity();
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
/// A quad corner may not be flatter than this (degrees): the quad must stay clearly convex.
constexpr double kFlattestQuadCornerDeg = 170.0;
/// The cost of a face failing a criterion: more than any shape and triangle costs of the faces
/// that could replace it, so that the mesh first has as few failing faces as it can.
constexpr double kFailingFaceCost = 100.0;
/// The extra cost of a triangle: two triangles cost more than one quad of the same shape.
constexpr double kTriangleCost = 0.5;
/// Quads are searched only while (sum over corners of their chords squared) x (most chords at a
/// corner) stays below this: the quad search's work.
constexpr double kQuadSearchBudget = 2.0e7;

/// The edges the mesh may use from each corner to a later one: polygon edges and allowed chords,
/// ascending.
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

/// True when the quad search fits kQuadSearchBudget.
bool quadsAffordable(const std::vector<std::vector<std::uint32_t>>& edges) {
  double squares = 0.0, most = 0.0;
  for (const auto& from : edges) {
    squares += double(from.size()) * double(from.size());
    most = std::max(most, double(from.size()));
  }
  return squares * most <= kQuadSearchBudget;
}

/// The cost of a face with the given corners (3 or 4) against the surface normal `up`: infinite
/// when it faces against `up` (a quad also when it is not convex) or has no shape (a scaled
/// Jacobian of 1e-9 or less), else kFailingFaceCost when it fails an element criterion other than
/// the minimum length, plus 1 / its scaled Jacobian - 1 (0 for a square or an equilateral
/// triangle, growing without bound towards a sliver), plus kTriangleCost for a triangle.
double faceCost(const std::array<Vec3, 4>& p, int count, const Vec3& up,
                const QualitySettings& criteria) {
  if (count == 3) {
    if (!(dot(cross(p[1] - p[0], p[2] - p[0]), up) > 0.0)) return kInfinite;
  } else if (!convexQuad(p, up)) {
    return kInfinite;
  }
  const ElementQuality quality = elementQuality(p, count);
  if (!(quality.scaledJacobian > 1e-9)) return kInfinite;
  const std::uint32_t lengthBit = 1u << static_cast<int>(Criterion::MinLength);
  const bool fails = (elementFailures(quality, count, criteria) & ~lengthBit) != 0;
  const double shape = 1.0 / std::min(quality.scaledJacobian, 1.0) - 1.0;
  return (fails ? kFailingFaceCost : 0.0) + shape + (count == 3 ? kTriangleCost : 0.0);
}

/// The face closing the sub-polygon below a chord i-j: corners i, k, j (a triangle, l == kNone)
/// or i, k, l, j (a quad).
struct Closing {
  double cost = kInfinite;  ///< of the whole sub-polygon
  std::uint32_t k = kNone, l = kNone;
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
                                      const ChordTest& chordOk, const QualitySettings& criteria) {
  const std::size_t n = corners.size();
  if (n < 3 || normals.size() != n) return {};
  const auto edges = candidateEdges(corners, maxChord, chordOk);
  const bool searchQuads = quadsAffordable(edges);
  // The best closing of the sub-polygon i..j below each edge i-j, smallest spans first.
  std::vector<std::vector<Closing>> best(n);
  for (std::size_t i = 0; i < n; ++i) best[i].assign(edges[i].size(), Closing{});
  const auto slot = [&](std::size_t i, std::size_t j) -> std::ptrdiff_t {
    const auto it = std::lower_bound(edges[i].begin(), edges[i].end(), std::uint32_t(j));
    return it != edges[i].end() && *it == j ? it - edges[i].begin() : -1;
  };
  const auto costBelow = [&](std::size_t i, std::size_t j) {
    const std::ptrdiff_t s = slot(i, j);
    return s < 0 ? kInfinite : best[i][std::size_t(s)].cost;
  };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> spans;
  for (std::size_t i = 0; i < n; ++i)
    for (const std::uint32_t j : edges[i]) spans.emplace_back(std::uint32_t(i), j);
  std::stable_sort(spans.begin(), spans.end(), [](const auto& a, const auto& b) {
    return a.second - a.first < b.second - b.first;
  });
  for (const auto& [i, j] : spans) {
    Closing& closing = best[i][std::size_t(slot(i, j))];
    if (j == i + 1) {
      closing.cost = 0.0;
      continue;
    }
    for (std::size_t a = 0; a < edges[i].size() && edges[i][a] < j; ++a) {
      const std::uint32_t k = edges[i][a];
      const double left = best[i][a].cost;
      if (left == kInfinite) continue;
      const double right = costBelow(k, j);
      if (left + right < closing.cost) {  // a face costs 0 or more
        const double total = left + right +
                             faceCost({corners[i], corners[k], corners[j], corners[j]}, 3,
                                      normals[i] + normals[k] + normals[j], criteria);
        if (total < closing.cost) closing = {total, k, kNone};
      }
      if (!searchQuads) continue;
      for (std::size_t b = 0; b < edges[k].size() && edges[k][b] < j; ++b) {
        const std::uint32_t l = edges[k][b];
        const double middle = best[k][b].cost, last = costBelow(l, j);
        // A quad is two triangles on an allowed diagonal: its middle stays on the surface.
        if (!(left + middle + last < closing.cost) || (slot(i, l) < 0 && slot(k, j) < 0)) continue;
        const double total = left + middle + last +
                             faceCost({corners[i], corners[k], corners[l], corners[j]}, 4,
                                      normals[i] + normals[k] + normals[l] + normals[j], criteria);
        if (total < closing.cost) closing = {total, k, l};
      }
    }
  }
  if (costBelow(0, n - 1) == kInfinite) return {};

  // The faces, from the closing of the whole polygon (below its edge 0 - (n-1)) down.
  std::vector<PolygonFace> faces;
  std::vector<std::array<std::uint32_t, 2>> pending{{0, std::uint32_t(n - 1)}};
  while (!pending.empty()) {
    const auto [i, j] = pending.back();
    pending.pop_back();
    if (j == i + 1) continue;
    const Closing& closing = best[i][std::size_t(slot(i, j))];
    const std::uint32_t k = closing.k, l = closing.l;
    faces.push_back(l == kNone ? PolygonFace{i, k, j, kNone} : PolygonFace{i, k, l, j});
    pending.push_back({i, k});
    if (l == kNone) {
      pending.push_back({k, j});
    } else {
      pending.push_back({k, l});
      pending.push_back({l, j});
    }
  }
  return faces;
}

}  // namespace voxremesh::extract
