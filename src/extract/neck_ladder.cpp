// neckLadders: quads across the necks a keyhole strip's bridges span (neck_ladder.h).
#include "extract/neck_ladder.h"

#include <algorithm>
#include <cmath>

namespace voxremesh::extract {

using openvdb::math::Vec3d;

namespace {

/// How far a rung's length may be from its number of pieces x the node spacing, and how close a
/// dual vertex may come to a rung, in node spacings; the most rungs a ladder grows.
constexpr double kRungSlack = 0.6;
constexpr double kDualClearance = 0.3;
constexpr std::size_t kMostRungs = 64;

/// The distance from p to the segment a-b.
double segmentDistance(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a;
  const double length2 = ab.lengthSqr();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + ab * t - p).length();
}

/// +1 when the quad's corners all turn left about `normal`, -1 when all turn right, else 0.
int turning(const std::array<Vec3d, 4>& quad, const Vec3d& normal) {
  int left = 0, right = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    const Vec3d e0 = quad[(k + 1) % 4] - quad[k], e1 = quad[(k + 2) % 4] - quad[(k + 1) % 4];
    (e0.cross(e1).dot(normal) > 0.0 ? left : right) += 1;
  }
  return left == 4 ? 1 : (right == 4 ? -1 : 0);
}

/// Whether p lies inside the convex quad whose corners turn `sign` about `normal`.
bool inside(const Vec3d& p, const std::array<Vec3d, 4>& quad, const Vec3d& normal, int sign) {
  for (std::size_t k = 0; k < 4; ++k)
    if (sign * (quad[(k + 1) % 4] - quad[k]).cross(p - quad[k]).dot(normal) <= 0.0) return false;
  return true;
}

}  // namespace

NeckLadders neckLadders(const std::vector<Vec3d>& outer, const std::vector<std::size_t>& bridgeEnd,
                        const std::vector<Vec3d>& inner, const std::vector<Vec3d>& innerNormals,
                        double spacing) {
  const std::size_t n = outer.size();
  NeckLadders ladders;
  ladders.carved.assign(n, 0);
  if (n < 8 || inner.empty()) return ladders;
  std::vector<char> onBridge(n, 0);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t k = 0; bridgeEnd[p] && k <= bridgeEnd[p]; ++k) onBridge[(p + k) % n] = 1;
  auto nearestNormal = [&](const Vec3d& p) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < inner.size(); ++i)
      if ((inner[i] - p).lengthSqr() < (inner[best] - p).lengthSqr()) best = i;
    Vec3d normal = innerNormals[best];
    normal.normalize();
    return normal;
  };
  auto position = [&](std::size_t node) {
    return node < n ? outer[node] : ladders.points[node - n];
  };
  for (std::size_t p = 0; p < n; ++p) {
    const std::size_t pieces = bridgeEnd[p];
    if (pieces == 0) continue;
    const std::size_t q = (p + pieces) % n;
    bool touchesStart = false;
    for (std::size_t k = 0; k <= pieces; ++k) touchesStart |= (p + k) % n == 0;
    if (touchesStart) continue;
    // Rung 0 is the bridge; each further rung is grown while it fits.
    std::vector<std::size_t> previous;
    for (std::size_t k = 0; k <= pieces; ++k) previous.push_back((p + k) % n);
    std::vector<std::array<std::size_t, 4>> quads;
    std::vector<Vec3d> points;
    std::vector<std::size_t> last;
    for (std::size_t k = 1; k <= kMostRungs && 2 * k + pieces + 2 < n; ++k) {
      const std::size_t a = (p + n - k) % n, c = (q + k) % n;
      if (a == 0 || c == 0 || a == c || ladders.carved[a] || ladders.carved[c] || onBridge[a] ||
          onBridge[c])
        break;
      const double rung = (outer[c] - outer[a]).length();
      if (std::abs(rung - double(pieces) * spacing) > kRungSlack * spacing) break;
      // The rung's nodes, a-side first; new ones numbered after those of earlier rungs.
      std::vector<std::size_t> nodes{a};
      std::vector<Vec3d> added;
      for (std::size_t t = 1; t < pieces; ++t) {
        added.push_back(outer[a] + (outer[c] - outer[a]) * (double(t) / double(pieces)));
        nodes.push_back(n + ladders.points.size() + points.size() + added.size() - 1);
      }
      nodes.push_back(c);
      auto at = [&](std::size_t node) {
        const std::size_t first = n + ladders.points.size();
        return node < first ? position(node)
                            : (node < first + points.size() ? points[node - first]
                                                            : added[node - first - points.size()]);
      };
      bool fits = true;
      std::vector<std::array<std::size_t, 4>> step;
      for (std::size_t t = 0; t < pieces && fits; ++t) {
        const std::array<std::size_t, 4> corners{previous[t], nodes[t], nodes[t + 1],
                                                 previous[t + 1]};
        const std::array<Vec3d, 4> quad{at(corners[0]), at(corners[1]), at(corners[2]),
                                        at(corners[3])};
        const Vec3d centre = (quad[0] + quad[1] + quad[2] + quad[3]) * 0.25;
        const Vec3d normal = nearestNormal(centre);
        const int sign = turning(quad, normal);
        fits = sign != 0;
        for (const Vec3d& v : inner) {
          if (!fits) break;
          fits = segmentDistance(v, outer[a], outer[c]) >= kDualClearance * spacing &&
                 !((v - centre).length() < 2.0 * spacing && inside(v, quad, normal, sign));
        }
        step.push_back(
            sign > 0 ? corners
                     : std::array<std::size_t, 4>{corners[3], corners[2], corners[1], corners[0]});
      }
      if (!fits) break;
      quads.insert(quads.end(), step.begin(), step.end());
      points.insert(points.end(), added.begin(), added.end());
      previous = nodes;
      last = nodes;
    }
    if (quads.empty()) continue;
    // Carve the nodes of all rungs but the last; the last rung's inner nodes join the row.
    const std::size_t rungs = quads.size() / pieces;
    for (std::size_t k = 0; k < rungs; ++k)
      ladders.carved[(p + n - k) % n] = ladders.carved[(q + k) % n] = 1;
    for (std::size_t k = 1; k < pieces; ++k) ladders.carved[(p + k) % n] = 1;
    ladders.rowInserts[last.front()] = std::vector<std::size_t>(last.begin() + 1, last.end() - 1);
    ladders.quads.insert(ladders.quads.end(), quads.begin(), quads.end());
    ladders.points.insert(ladders.points.end(), points.begin(), points.end());
  }
  return ladders;
}

}  // namespace voxremesh::extract
