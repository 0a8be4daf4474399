// Brute-force distances for tests (see surface_distance.h).
#include "support/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace voxremesh::test {

namespace {

Point3 sub(const Point3& a, const Point3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const Point3& a, const Point3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace

double pointSegmentDistance(const Point3& p, const Point3& a, const Point3& b) {
  const Point3 ab = sub(b, a);
  const double len2 = dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(dot(sub(p, a), ab) / len2, 0.0, 1.0) : 0.0;
  const Point3 q{a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]};
  const Point3 d = sub(p, q);
  return std::sqrt(dot(d, d));
}

double pointTriangleDistance(const Point3& p, const Point3& a, const Point3& b, const Point3& c) {
  // Inside the prism over the triangle: the distance to its plane; else to the nearest side.
  const Point3 n = cross(sub(b, a), sub(c, a));
  const double n2 = dot(n, n);
  if (n2 > 0.0) {
    const bool inside = dot(cross(sub(b, a), sub(p, a)), n) >= 0.0 &&
                        dot(cross(sub(c, b), sub(p, b)), n) >= 0.0 &&
                        dot(cross(sub(a, c), sub(p, c)), n) >= 0.0;
    if (inside) return std::abs(dot(sub(p, a), n)) / std::sqrt(n2);
  }
  return std::min({pointSegmentDistance(p, a, b), pointSegmentDistance(p, b, c),
                   pointSegmentDistance(p, c, a)});
}

double distanceToMesh(const Point3& p, const QuadMesh& mesh) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& f : mesh.faces) {
    const auto& P = mesh.points;
    best = std::min(best, pointTriangleDistance(p, P[f[0]], P[f[1]], P[f[2]]));
    if (cornerCount(f) == 4)
      best = std::min(best, pointTriangleDistance(p, P[f[0]], P[f[2]], P[f[3]]));
  }
  return best;
}

std::vector<std::array<Point3, 2>> edgeSegments(const QuadMesh& mesh, int minFaces, int maxFaces) {
  std::map<std::pair<CornerIndex, CornerIndex>, int> uses;
  for (const auto& f : mesh.faces) {
    const int n = cornerCount(f);
    for (int c = 0; c < n; ++c) {
      const CornerIndex a = f[std::size_t(c)], b = f[std::size_t((c + 1) % n)];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<std::array<Point3, 2>> segments;
  for (const auto& [edge, count] : uses)
    if (count >= minFaces && count <= maxFaces)
      segments.push_back({mesh.points[edge.first], mesh.points[edge.second]});
  return segments;
}

std::vector<std::array<Point3, 2>> boundarySegments(const QuadMesh& mesh) {
  return edgeSegments(mesh, 1, 1);
}

std::vector<std::array<Point3, 2>> faceEdgeSegments(const QuadMesh& mesh) {
  std::vector<std::array<Point3, 2>> segments;
  for (const auto& f : mesh.faces) {
    const int n = cornerCount(f);
    for (int c = 0; c < n; ++c)
      segments.push_back(
          {mesh.points[f[std::size_t(c)]], mesh.points[f[std::size_t((c + 1) % n)]]});
  }
  return segments;
}

double distanceToSegments(const Point3& p, const std::vector<std::array<Point3, 2>>& segments) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& s : segments) best = std::min(best, pointSegmentDistance(p, s[0], s[1]));
  return best;
}

}  // namespace voxremesh::test
