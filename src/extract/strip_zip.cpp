// zipStrip: the cheapest sequence of strip faces (see strip_zip.h).
#include "extract/strip_zip.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace voxremesh::extract {

namespace {

using openvdb::math::Vec3d;

/// A triangle costs this much more than a quad of the same shape quality: two triangles never
/// replace a fair quad, one is taken only where every quad would fold or degenerate.
constexpr double kTriangleCost = 2.0;

/// The cost of a face with an edge of zero length (a dual vertex snapped onto a corner node): high
/// but finite, so that sums of costs still compare.
constexpr double kDegenerateCost = 1000.0;

/// Weight of the edge length ratio (longest / shortest - 1) in a face's cost.
constexpr double kLengthRatioWeight = 0.5;

/// The steps of the search from pair (i, j): how far each row advances.
struct Step {
  int di, dj;
};
constexpr Step kSteps[5] = {{1, 1}, {2, 0}, {0, 2}, {1, 0}, {0, 1}};

/// The shape cost of a face with corners q (3 or 4, ordered around `normal`): the sum over its
/// corners of 1 - the corner's scaled Jacobian (1 - sin of the corner angle for a convex corner,
/// more for a reflex or folded one; triangles scaled so that an equilateral one costs 0), plus the
/// edge length ratio term, plus kTriangleCost for a triangle.
double faceCost(const std::array<Vec3d, 4>& q, int corners, const Vec3d& normal) {
  double cost = corners == 3 ? kTriangleCost : 0.0;
  const double scale = corners == 3 ? 2.0 / std::sqrt(3.0) : 1.0;
  // Edge k runs from corner k to corner k + 1.
  std::array<Vec3d, 4> edge;
  std::array<double, 4> length{};
  double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
  for (int k = 0; k < corners; ++k) {
    edge[std::size_t(k)] = q[std::size_t((k + 1) % corners)] - q[std::size_t(k)];
    length[std::size_t(k)] = edge[std::size_t(k)].length();
    if (length[std::size_t(k)] <= 0.0) return kDegenerateCost;
    shortest = std::min(shortest, length[std::size_t(k)]);
    longest = std::max(longest, length[std::size_t(k)]);
  }
  for (int k = 0; k < corners; ++k) {
    const std::size_t previous = std::size_t((k + corners - 1) % corners);
    // next x previous with previous = -edge[previous]
    const double s = -edge[std::size_t(k)].cross(edge[previous]).dot(normal) /
                     (length[std::size_t(k)] * length[previous]);
    cost += 1.0 - std::min(1.0, s * scale);
  }
  return cost + kLengthRatioWeight * (longest / shortest - 1.0);
}

}  // namespace

std::vector<StripFace> zipStrip(const std::vector<Vec3d>& inner,
                                const std::vector<Vec3d>& innerNormals,
                                const std::vector<Vec3d>& outer,
                                const std::vector<std::size_t>& bandCentre, std::size_t band) {
  const std::size_t m = inner.size(), n = outer.size();
  if (m < 2 || n < 2 || innerNormals.size() != m || bandCentre.size() != m)
    throw std::invalid_argument("zipStrip: rows of fewer than two points or mismatched sizes");
  // The band of outer indices searched in each row i (0..m), contiguous and non-decreasing, so
  // that every pair in it can be reached from (0, 0) and reach (m, n).
  std::vector<std::size_t> lo(m + 1), hi(m + 1);
  for (std::size_t i = 0; i <= m; ++i) {
    const std::size_t centre = i < m ? std::min(bandCentre[i], n) : n;
    lo[i] = centre > band ? centre - band : 0;
    hi[i] = std::min(n, centre + band);
    if (i > 0) lo[i] = std::max(lo[i], lo[i - 1]), hi[i] = std::max(hi[i], hi[i - 1]);
  }
  lo[0] = 0;
  hi[m] = n;
  for (std::size_t i = m; i-- > 0;) hi[i] = std::max(hi[i], lo[i + 1] > 0 ? lo[i + 1] - 1 : 0);
  std::vector<std::size_t> rowStart(m + 2, 0);
  for (std::size_t i = 0; i <= m; ++i) rowStart[i + 1] = rowStart[i] + (hi[i] - lo[i] + 1);
  const double unreached = std::numeric_limits<double>::infinity();
  std::vector<double> cost(rowStart[m + 1], unreached);
  std::vector<std::uint8_t> via(rowStart[m + 1], 255);
  auto slot = [&](std::size_t i, std::size_t j) -> std::ptrdiff_t {
    if (i > m || j < lo[i] || j > hi[i]) return -1;
    return std::ptrdiff_t(rowStart[i] + (j - lo[i]));
  };
  auto at = [&](std::size_t i, bool isOuter) -> const Vec3d& {
    return isOuter ? outer[i % n] : inner[i % m];
  };
  // The face of step s from pair (i, j), in the dual mesh's orientation.
  auto faceOf = [&](std::size_t i, std::size_t j, int s) {
    StripFace face;
    auto set = [&](int k, std::size_t index, bool isOuter) {
      face.index[std::size_t(k)] = static_cast<std::uint32_t>(index % (isOuter ? n : m));
      face.outer[std::size_t(k)] = isOuter;
    };
    switch (s) {
      case 0:
        set(0, i + 1, false), set(1, i, false), set(2, j, true), set(3, j + 1, true);
        break;
      case 1:
        set(0, i + 2, false), set(1, i + 1, false), set(2, i, false), set(3, j, true);
        break;
      case 2:
        set(0, i, false), set(1, j, true), set(2, j + 1, true), set(3, j + 2, true);
        break;
      case 3:
        set(0, i + 1, false), set(1, i, false), set(2, j, true), face.corners = 3;
        break;
      default:
        set(0, i, false), set(1, j, true), set(2, j + 1, true), face.corners = 3;
        break;
    }
    return face;
  };
  auto costOf = [&](const StripFace& face) {
    std::array<Vec3d, 4> q;
    Vec3d normal(0.0);
    for (int k = 0; k < face.corners; ++k) {
      q[std::size_t(k)] = at(face.index[std::size_t(k)], face.outer[std::size_t(k)]);
      if (!face.outer[std::size_t(k)]) normal += innerNormals[face.index[std::size_t(k)]];
    }
    const double length = normal.length();
    return faceCost(q, face.corners, length > 0.0 ? normal / length : normal);
  };
  cost[0] = 0.0;
  for (std::size_t i = 0; i <= m; ++i) {
    for (std::size_t j = lo[i]; j <= hi[i]; ++j) {
      const double here = cost[std::size_t(slot(i, j))];
      if (here == unreached) continue;
      for (int s = 0; s < 5; ++s) {
        const std::ptrdiff_t to =
            slot(i + std::size_t(kSteps[s].di), j + std::size_t(kSteps[s].dj));
        if (to < 0) continue;
        const double c = here + costOf(faceOf(i, j, s));
        if (c < cost[std::size_t(to)])
          cost[std::size_t(to)] = c, via[std::size_t(to)] = std::uint8_t(s);
      }
    }
  }
  if (cost[std::size_t(slot(m, n))] == unreached)
    throw std::runtime_error("zipStrip: no way around the strip");
  std::vector<StripFace> faces;
  std::size_t i = m, j = n;
  while (i > 0 || j > 0) {
    const int s = via[std::size_t(slot(i, j))];
    i -= std::size_t(kSteps[s].di);
    j -= std::size_t(kSteps[s].dj);
    faces.push_back(faceOf(i, j, s));
  }
  std::reverse(faces.begin(), faces.end());
  return faces;
}

}  // namespace voxremesh::extract
