// sharpCorners and cornerFillingTriangles (sharp_corners.h).
#include "quality/sharp_corners.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "geometry/disjoint_sets.h"

namespace voxremesh::quality {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// The angle of a face at its corner k (degrees; 0 at a zero-length edge).
double cornerAngle(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face, int k) {
  const int n = cornerCount(face);
  const Vec3& p = mesh.points[face[std::size_t(k)]];
  return angleDeg(mesh.points[face[std::size_t((k + n - 1) % n)]] - p,
                  mesh.points[face[std::size_t((k + 1) % n)]] - p);
}

/// The edges `u` and `v` leaving a corner's point run along its two sides, each within half the
/// corner's angle of one (a triangle with these edges fills the corner).
bool fills(const SharpCorner& corner, const Vec3& u, const Vec3& v) {
  const double half = 0.5 * corner.angleDeg;
  const auto near = [&](const Vec3& edge, const Vec3& side) { return angleDeg(edge, side) < half; };
  return (near(u, corner.side1) && near(v, corner.side2)) ||
         (near(u, corner.side2) && near(v, corner.side1));
}

}  // namespace

std::vector<SharpCorner> sharpCorners(const QuadMesh& surface, RidgeEdges& ridges,
                                      double belowDeg) {
  // Every face edge as (low point, high point, face corner at low, face corner at high).
  struct HalfEdge {
    CornerIndex low, high;
    std::size_t atLow, atHigh;
  };
  std::vector<HalfEdge> halfEdges;
  for (std::size_t f = 0; f < surface.faces.size(); ++f) {
    const auto& face = surface.faces[f];
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k) {
      const int next = (k + 1) % n;
      const CornerIndex a = face[std::size_t(k)], b = face[std::size_t(next)];
      const std::size_t ca = 4 * f + std::size_t(k), cb = 4 * f + std::size_t(next);
      halfEdges.push_back(a < b ? HalfEdge{a, b, ca, cb} : HalfEdge{b, a, cb, ca});
    }
  }
  std::sort(halfEdges.begin(), halfEdges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.low, x.high, x.atLow) < std::tie(y.low, y.high, y.atLow);
  });
  DisjointSets sectors(4 * surface.faces.size());  // over face corners: 4 x face + corner
  for (std::size_t i = 0; i < halfEdges.size();) {
    std::size_t j = i;
    while (j < halfEdges.size() && halfEdges[j].low == halfEdges[i].low &&
           halfEdges[j].high == halfEdges[i].high)
      ++j;
    const HalfEdge& a = halfEdges[i];
    if (j - i == 2 && !ridges.along(surface.points[a.low], surface.points[a.high])) {
      sectors.join(a.atLow, halfEdges[i + 1].atLow);
      sectors.join(a.atHigh, halfEdges[i + 1].atHigh);
    }
    i = j;
  }
  std::vector<double> sectorAngle(4 * surface.faces.size(), 0.0);
  for (std::size_t f = 0; f < surface.faces.size(); ++f)
    for (int k = 0; k < cornerCount(surface.faces[f]); ++k) {
      const std::size_t root = sectors.find(4 * f + std::size_t(k));
      sectorAngle[root] += cornerAngle(surface, surface.faces[f], k);
    }
  // Each sharp sector's sides: the edges at its point that only one of its face corners has.
  std::vector<std::pair<std::size_t, CornerIndex>> sides;  // (sector, the edge's far point)
  for (std::size_t f = 0; f < surface.faces.size(); ++f) {
    const auto& face = surface.faces[f];
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k) {
      const std::size_t root = sectors.find(4 * f + std::size_t(k));
      if (!(sectorAngle[root] > 0.0 && sectorAngle[root] < belowDeg)) continue;
      sides.emplace_back(root, face[std::size_t((k + n - 1) % n)]);
      sides.emplace_back(root, face[std::size_t((k + 1) % n)]);
    }
  }
  std::sort(sides.begin(), sides.end());
  std::vector<SharpCorner> corners;
  for (std::size_t i = 0; i < sides.size();) {
    const std::size_t root = sides[i].first;
    const Vec3& point = surface.points[surface.faces[root / 4][root % 4]];
    std::vector<Vec3> directions;
    std::size_t j = i;
    while (j < sides.size() && sides[j].first == root) {
      std::size_t k = j;
      while (k < sides.size() && sides[k] == sides[j]) ++k;
      if (k - j == 1) directions.push_back(normalized(surface.points[sides[j].second] - point));
      j = k;
    }
    if (directions.size() == 2)
      corners.push_back({point, directions[0], directions[1], sectorAngle[root]});
    i = j;
  }
  std::sort(corners.begin(), corners.end(), [](const SharpCorner& a, const SharpCorner& b) {
    return std::tie(a.point, a.angleDeg) < std::tie(b.point, b.angleDeg);
  });
  return corners;
}

std::vector<std::uint8_t> cornerFillingTriangles(const QuadMesh& mesh,
                                                 const std::vector<SharpCorner>& corners,
                                                 double minAngleDeg, double maxAngleDeg) {
  std::vector<std::uint8_t> filling(mesh.faces.size(), 0);
  if (corners.empty()) return filling;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    if (cornerCount(face) != 3) continue;
    std::array<double, 3> angle{};
    std::array<Vec3, 3> edge{};  // from corner k to corner k + 1
    double longest = 0.0;
    for (int k = 0; k < 3; ++k) {
      angle[std::size_t(k)] = cornerAngle(mesh, face, k);
      edge[std::size_t(k)] =
          mesh.points[face[std::size_t((k + 1) % 3)]] - mesh.points[face[std::size_t(k)]];
      longest = std::max(longest, norm(edge[std::size_t(k)]));
    }
    const double reach = 1e-6 * longest;
    for (int k = 0; k < 3 && !filling[f]; ++k) {
      const Vec3& p = mesh.points[face[std::size_t(k)]];
      const double a1 = angle[std::size_t((k + 1) % 3)], a2 = angle[std::size_t((k + 2) % 3)];
      if (std::min(a1, a2) < minAngleDeg || std::max(a1, a2) > maxAngleDeg) continue;
      // The corners whose x lies within reach of p, then those within reach.
      auto it = std::lower_bound(corners.begin(), corners.end(), p[0] - reach,
                                 [](const SharpCorner& c, double x) { return c.point[0] < x; });
      for (; it != corners.end() && it->point[0] <= p[0] + reach; ++it)
        if (distance(it->point, p) <= reach &&
            fills(*it, edge[std::size_t(k)], edge[std::size_t((k + 2) % 3)] * -1.0)) {
          filling[f] = 1;
          break;
        }
    }
  }
  return filling;
}

}  // namespace voxremesh::quality
