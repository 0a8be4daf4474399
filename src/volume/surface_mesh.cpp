// The triangle mesh of a part's sheets with edges, pseudo-normals and the closest-point descent.
#include "volume/surface_mesh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace voxremesh::volume {

namespace {

/// One directed use of an edge by a triangle, keyed by its endpoints (lower first).
struct EdgeUse {
  std::uint32_t a, b;  // endpoints, a < b
  std::uint32_t tri;   // the triangle
  std::uint8_t local;  // which of the triangle's edges (corners local, local + 1)
  bool forward;        // the triangle runs from a to b
  bool diagonal;       // the split diagonal of a quad, not an element edge
  bool operator<(const EdgeUse& o) const {
    if (a != o.a) return a < o.a;
    if (b != o.b) return b < o.b;
    return tri < o.tri;
  }
};

V3 toV3(const std::array<double, 3>& p) {
  return {p[0], p[1], p[2]};
}

/// The angle at corner a of triangle (a, b, c), 0 for a degenerate corner.
double cornerAngle(const V3& a, const V3& b, const V3& c) {
  const V3 u = b - a, v = c - a;
  const double s = length(cross(u, v)), d = dot(u, v);
  if (s == 0.0 && d == 0.0) return 0.0;
  return std::atan2(s, d);
}

/// Closest point of segment [a, b] to p.
V3 closestOnSegment(const V3& p, const V3& a, const V3& b) {
  const V3 ab = b - a;
  const double len2 = dot(ab, ab);
  if (len2 <= 0.0) return a;
  const double t = std::clamp(dot(p - a, ab) / len2, 0.0, 1.0);
  return a + ab * t;
}

/// Regions of a triangle's closest point: the face, corner k (1 + k), edge k (4 + k) joining
/// corners k and k + 1.
constexpr int kRegionFace = 0;
constexpr int kRegionVertex0 = 1;
constexpr int kRegionEdge0 = 4;

/// The closest point of triangle (a, b, c) to p and its region (Ericson, Real-Time Collision
/// Detection, 5.1.5). Degenerate triangles fall back to the closest of their edges.
int closestOnTriangle(const V3& p, const V3& a, const V3& b, const V3& c, V3& q) {
  const V3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    q = a;
    return kRegionVertex0;
  }
  const V3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) {
    q = b;
    return kRegionVertex0 + 1;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    q = a + ab * (d1 / (d1 - d3));
    return kRegionEdge0;
  }
  const V3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) {
    q = c;
    return kRegionVertex0 + 2;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    q = a + ac * (d2 / (d2 - d6));
    return kRegionEdge0 + 2;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    q = b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    return kRegionEdge0 + 1;
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0) || !std::isfinite(sum)) {
    // Degenerate (collinear) triangle: the closest of its three edges.
    const V3 e[3] = {closestOnSegment(p, a, b), closestOnSegment(p, b, c),
                     closestOnSegment(p, c, a)};
    int best = 0;
    double bestD2 = dot(p - e[0], p - e[0]);
    for (int k = 1; k < 3; ++k) {
      const double d2k = dot(p - e[k], p - e[k]);
      if (d2k < bestD2) bestD2 = d2k, best = k;
    }
    q = e[best];
    return kRegionEdge0 + best;
  }
  const double denom = 1.0 / sum;
  q = a + ab * (vb * denom) + ac * (vc * denom);
  return kRegionFace;
}

/// Evaluates triangle t for p: its closest point, region, and the squared distance.
struct TriangleHit {
  V3 q;
  double d2 = std::numeric_limits<double>::infinity();
  int region = kRegionFace;
  std::uint32_t tri = kNone;
};

TriangleHit evalTriangle(const SurfaceMesh& mesh, std::uint32_t t, const V3& p, double tol2) {
  const auto& c = mesh.tris[t];
  TriangleHit hit;
  hit.tri = t;
  hit.region = closestOnTriangle(p, mesh.points[c[0]], mesh.points[c[1]], mesh.points[c[2]], hit.q);
  const V3 v = p - hit.q;
  hit.d2 = dot(v, v);
  if (hit.region != kRegionFace) {
    // The element wins a tie with its edge or corner: v is (nearly) along the face normal.
    const double vn = dot(v, mesh.triNormals[t]);
    if (hit.d2 - vn * vn <= tol2) hit.region = kRegionFace;
  }
  return hit;
}

}  // namespace

SurfaceMesh buildSurfaceMesh(const std::vector<Sheet>& sheets) {
  SurfaceMesh mesh;
  // Points and polygons in sheet order.
  std::size_t pointCount = 0, faceCount = 0;
  for (std::size_t s = 0; s < sheets.size(); ++s) {
    if (sheets[s].part != sheets.front().part) {
      throw std::invalid_argument("sheets of different parts (" +
                                  std::to_string(sheets.front().part) + " and " +
                                  std::to_string(sheets[s].part) + ") cannot share one volume");
    }
    pointCount += sheets[s].points.size();
    faceCount += sheets[s].faces.size();
  }
  if (pointCount >= kNone || faceCount * 2 >= kNone) {
    throw std::invalid_argument("too many points or faces for one volume");
  }
  mesh.points.reserve(pointCount);
  mesh.polygons.reserve(faceCount);
  mesh.polygonSheet.reserve(faceCount);
  for (std::size_t s = 0; s < sheets.size(); ++s) {
    const Sheet& sheet = sheets[s];
    const auto offset = static_cast<std::uint32_t>(mesh.points.size());
    mesh.sheetPointOffset.push_back(offset);
    for (std::size_t i = 0; i < sheet.points.size(); ++i) {
      const auto& p = sheet.points[i];
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
        throw std::invalid_argument("sheet " + std::to_string(s) + ": point " + std::to_string(i) +
                                    " has a coordinate that is not finite");
      }
      mesh.points.push_back(toV3(p));
    }
    for (std::size_t f = 0; f < sheet.faces.size(); ++f) {
      const auto& face = sheet.faces[f];
      std::array<std::uint32_t, 4> polygon{};
      const int corners = face[3] == kNoPoint ? 3 : 4;
      for (int k = 0; k < corners; ++k) {
        if (face[k] >= sheet.points.size()) {
          throw std::invalid_argument("sheet " + std::to_string(s) + ": face " + std::to_string(f) +
                                      " refers to point " + std::to_string(face[k]) + " of " +
                                      std::to_string(sheet.points.size()));
        }
        polygon[k] = offset + face[k];
      }
      polygon[3] = corners == 3 ? kNone : polygon[3];
      mesh.polygons.push_back(polygon);
      mesh.polygonSheet.push_back(static_cast<std::uint32_t>(s));
    }
  }
  if (!mesh.points.empty()) {
    mesh.boundsMin = mesh.boundsMax = mesh.points.front();
    for (const V3& p : mesh.points) {
      mesh.boundsMin = {std::min(mesh.boundsMin.x, p.x), std::min(mesh.boundsMin.y, p.y),
                        std::min(mesh.boundsMin.z, p.z)};
      mesh.boundsMax = {std::max(mesh.boundsMax.x, p.x), std::max(mesh.boundsMax.y, p.y),
                        std::max(mesh.boundsMax.z, p.z)};
    }
  }

  // Triangles: quads split 0-1-2 / 0-2-3; triangles with a repeated corner are dropped.
  const std::size_t polygonCount = mesh.polygons.size();
  std::vector<std::uint32_t> triCount(polygonCount + 1, 0);
  auto halves = [&](std::size_t i, std::array<std::array<std::uint32_t, 3>, 2>& out) {
    const auto& g = mesh.polygons[i];
    int n = 0;
    auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      if (a != b && b != c && c != a) out[n++] = {a, b, c};
    };
    add(g[0], g[1], g[2]);
    if (g[3] != kNone) add(g[0], g[2], g[3]);
    return n;
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polygonCount),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::array<std::array<std::uint32_t, 3>, 2> out{};
                      for (std::size_t i = r.begin(); i < r.end(); ++i) {
                        triCount[i] = static_cast<std::uint32_t>(halves(i, out));
                      }
                    });
  mesh.polygonFirstTri.assign(polygonCount + 1, 0);
  std::exclusive_scan(triCount.begin(), triCount.end(), mesh.polygonFirstTri.begin(),
                      std::uint32_t{0});
  const std::size_t triTotal = mesh.polygonFirstTri.back();
  mesh.tris.resize(triTotal);
  std::vector<std::uint8_t> triDiagonal(triTotal, 0);
  mesh.triPolygon.resize(triTotal);
  mesh.triNormals.resize(triTotal);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polygonCount),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::array<std::array<std::uint32_t, 3>, 2> out{};
                      for (std::size_t i = r.begin(); i < r.end(); ++i) {
                        const int n = halves(i, out);
                        for (int k = 0; k < n; ++k) {
                          const std::size_t t = mesh.polygonFirstTri[i] + k;
                          // With both halves present, 0-2 is the split diagonal: edge 2 of the
                          // first half, edge 0 of the second.
                          triDiagonal[t] = n == 2 ? std::uint8_t(k == 0 ? 4u : 1u) : 0u;
                          mesh.tris[t] = out[k];
                          mesh.triPolygon[t] = static_cast<std::uint32_t>(i);
                          const V3 &a = mesh.points[out[k][0]], &b = mesh.points[out[k][1]],
                                   &c = mesh.points[out[k][2]];
                          mesh.triNormals[t] = normalized(cross(b - a, c - a));
                        }
                      }
                    });
  mesh.area = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, triTotal, 1024), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double sum) {
        for (std::size_t t = r.begin(); t < r.end(); ++t) {
          const auto& c = mesh.tris[t];
          sum += 0.5 * length(cross(mesh.points[c[1]] - mesh.points[c[0]],
                                    mesh.points[c[2]] - mesh.points[c[0]]));
        }
        return sum;
      },
      [](double x, double y) { return x + y; });

  // Edges: sort the directed uses by endpoints; each run is one edge.
  std::vector<EdgeUse> uses(triTotal * 3);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, triTotal), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t < r.end(); ++t) {
          for (int k = 0; k < 3; ++k) {
            const std::uint32_t from = mesh.tris[t][k], to = mesh.tris[t][(k + 1) % 3];
            uses[t * 3 + k] = {
                std::min(from, to),           std::max(from, to), static_cast<std::uint32_t>(t),
                static_cast<std::uint8_t>(k), from < to,          (triDiagonal[t] >> k & 1u) != 0};
          }
        }
      });
  tbb::parallel_sort(uses.begin(), uses.end());
  std::vector<std::uint32_t> runStarts;
  for (std::size_t i = 0; i < uses.size(); ++i) {
    if (i == 0 || uses[i].a != uses[i - 1].a || uses[i].b != uses[i - 1].b) {
      runStarts.push_back(static_cast<std::uint32_t>(i));
    }
  }
  runStarts.push_back(static_cast<std::uint32_t>(uses.size()));
  const std::size_t edgeCount = runStarts.size() - 1;
  mesh.edgePoints.resize(edgeCount);
  mesh.edgeTris.resize(edgeCount);
  mesh.edgeNormals.resize(edgeCount);
  mesh.triEdges.resize(triTotal);
  std::vector<std::uint8_t> edgeIsDiagonal(edgeCount, 0);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, edgeCount), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t e = r.begin(); e < r.end(); ++e) {
          const EdgeUse* first = &uses[runStarts[e]];
          const std::size_t n = runStarts[e + 1] - runStarts[e];
          auto where = [&](const EdgeUse& u) {
            const std::uint32_t s = mesh.polygonSheet[mesh.triPolygon[u.tri]];
            const std::uint32_t o = mesh.sheetPointOffset[s];
            return "sheet " + std::to_string(s) + " between points " + std::to_string(u.a - o) +
                   " and " + std::to_string(u.b - o);
          };
          if (n > 2) {
            throw std::invalid_argument(
                "not a manifold sheet: more than two faces at the edge of " + where(*first));
          }
          if (n == 2 && first[0].forward == first[1].forward) {
            throw std::invalid_argument(
                "sheet not consistently oriented: two faces run the same way "
                "through the edge of " +
                where(*first));
          }
          edgeIsDiagonal[e] = first[0].diagonal || (n == 2 && first[1].diagonal);
          mesh.edgePoints[e] = {first->a, first->b};
          mesh.edgeTris[e] = {first[0].tri, n == 2 ? first[1].tri : kNone};
          V3 normal = mesh.triNormals[first[0].tri];
          if (n == 2) normal = normal + mesh.triNormals[first[1].tri];
          mesh.edgeNormals[e] = normalized(normal);
          for (std::size_t i = 0; i < n; ++i) {
            mesh.triEdges[first[i].tri][first[i].local] = static_cast<std::uint32_t>(e);
          }
        }
      });
  struct LengthStats {
    double sum = 0.0;
    double min = std::numeric_limits<double>::infinity();
    std::size_t count = 0;  // non-degenerate element edges
    std::size_t edges = 0;  // element edges
  };
  const V3 diagonal = mesh.boundsMax - mesh.boundsMin;
  const double degenerate = 1e-9 * length(diagonal);
  const LengthStats stats = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, edgeCount, 1024), LengthStats{},
      [&](const tbb::blocked_range<std::size_t>& r, LengthStats s) {
        for (std::size_t e = r.begin(); e < r.end(); ++e) {
          if (edgeIsDiagonal[e]) continue;  // a quad's split diagonal is no element edge
          const double l =
              length(mesh.points[mesh.edgePoints[e][1]] - mesh.points[mesh.edgePoints[e][0]]);
          s.sum += l;
          ++s.edges;
          if (l > degenerate) s.min = std::min(s.min, l), ++s.count;
        }
        return s;
      },
      [](LengthStats x, const LengthStats& y) {
        x.sum += y.sum;
        x.min = std::min(x.min, y.min);
        x.count += y.count;
        x.edges += y.edges;
        return x;
      });
  mesh.meanEdgeLength = stats.edges > 0 ? stats.sum / static_cast<double>(stats.edges) : 0.0;
  mesh.minEdgeLength = stats.count > 0 ? stats.min : 0.0;

  // Vertex one-rings (sorted by triangle) and pseudo-normals.
  std::vector<std::array<std::uint32_t, 2>> corners(triTotal * 3);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triTotal),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t t = r.begin(); t < r.end(); ++t) {
                        for (int k = 0; k < 3; ++k) {
                          corners[t * 3 + k] = {mesh.tris[t][k], static_cast<std::uint32_t>(t)};
                        }
                      }
                    });
  tbb::parallel_sort(corners.begin(), corners.end());
  const std::size_t pointTotal = mesh.points.size();
  mesh.vertexTriStart.assign(pointTotal + 1, 0);
  mesh.vertexTris.resize(corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i) {
    ++mesh.vertexTriStart[corners[i][0] + 1];
    mesh.vertexTris[i] = corners[i][1];
  }
  std::partial_sum(mesh.vertexTriStart.begin(), mesh.vertexTriStart.end(),
                   mesh.vertexTriStart.begin());
  mesh.vertexNormals.resize(pointTotal);
  mesh.vertexOnBoundary.assign(pointTotal, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, edgeCount),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t e = r.begin(); e < r.end(); ++e) {
                        if (mesh.edgeTris[e][1] == kNone) {
                          // Both endpoints are marked; byte stores of the same value.
                          mesh.vertexOnBoundary[mesh.edgePoints[e][0]] = 1;
                          mesh.vertexOnBoundary[mesh.edgePoints[e][1]] = 1;
                        }
                      }
                    });
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, pointTotal),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t v = r.begin(); v < r.end(); ++v) {
          V3 normal;
          for (std::uint32_t i = mesh.vertexTriStart[v]; i < mesh.vertexTriStart[v + 1]; ++i) {
            const auto& c = mesh.tris[mesh.vertexTris[i]];
            const int k = c[0] == v ? 0 : (c[1] == v ? 1 : 2);
            const double angle = cornerAngle(mesh.points[c[k]], mesh.points[c[(k + 1) % 3]],
                                             mesh.points[c[(k + 2) % 3]]);
            normal = normal + mesh.triNormals[mesh.vertexTris[i]] * angle;
          }
          mesh.vertexNormals[v] = normalized(normal);
        }
      });
  return mesh;
}

namespace {

/// The closest triangle hit reachable from a start polygon by descending over edges and vertices
/// to adjacent triangles while that brings p strictly closer. From a free boundary edge the
/// descent also looks at the triangles around both its endpoints, so that it can turn a corner
/// of the boundary onto the next face. Returns a hit with tri == kNone when the polygon has no
/// proper triangle and none of its corners has one.
TriangleHit descend(const SurfaceMesh& mesh, std::uint32_t startPolygon, const V3& p, double tol2) {
  TriangleHit best;
  for (std::uint32_t t = mesh.polygonFirstTri[startPolygon];
       t < mesh.polygonFirstTri[startPolygon + 1]; ++t) {
    const TriangleHit hit = evalTriangle(mesh, t, p, tol2);
    if (hit.d2 < best.d2) best = hit;
  }
  auto ring = [&](std::uint32_t v, std::uint32_t skip) {
    for (std::uint32_t i = mesh.vertexTriStart[v]; i < mesh.vertexTriStart[v + 1]; ++i) {
      if (mesh.vertexTris[i] == skip) continue;
      const TriangleHit hit = evalTriangle(mesh, mesh.vertexTris[i], p, tol2);
      if (hit.d2 < best.d2) best = hit;
    }
  };
  if (best.tri == kNone) {
    // A polygon without proper triangles (corners repeated): start from its corners' triangles.
    const auto& g = mesh.polygons[startPolygon];
    for (int k = 0; k < 4 && g[k] != kNone; ++k) ring(g[k], kNone);
    if (best.tri == kNone) return best;
  }
  for (int step = 0; step < 16 && best.region != kRegionFace; ++step) {
    const TriangleHit current = best;
    if (current.region >= kRegionEdge0) {
      const std::uint32_t e = mesh.triEdges[current.tri][current.region - kRegionEdge0];
      if (mesh.edgeTris[e][1] == kNone) {
        ring(mesh.edgePoints[e][0], current.tri);
        ring(mesh.edgePoints[e][1], current.tri);
      } else {
        const std::uint32_t other =
            mesh.edgeTris[e][0] == current.tri ? mesh.edgeTris[e][1] : mesh.edgeTris[e][0];
        const TriangleHit hit = evalTriangle(mesh, other, p, tol2);
        if (hit.d2 < best.d2) best = hit;
      }
    } else {
      ring(mesh.tris[current.tri][current.region - kRegionVertex0], current.tri);
    }
    if (best.tri == current.tri) break;
  }
  return best;
}

}  // namespace

ClosestPoint closestPointFrom(const SurfaceMesh& mesh, const std::uint32_t* startPolygons,
                              std::size_t count, const V3& p, double tangentialTolerance) {
  const double tol2 = tangentialTolerance * tangentialTolerance;
  TriangleHit best;
  std::uint32_t fallbackPoint = kNone;
  for (std::size_t i = 0; i < count; ++i) {
    const TriangleHit hit = descend(mesh, startPolygons[i], p, tol2);
    if (hit.tri == kNone) {
      if (fallbackPoint == kNone) fallbackPoint = mesh.polygons[startPolygons[i]][0];
      continue;
    }
    if (hit.d2 < best.d2) best = hit;
  }

  ClosestPoint result;
  if (best.tri == kNone) {
    // Only polygons without any triangle nearby: their first corner.
    result.kind = ClosestKind::Vertex;
    result.element = fallbackPoint;
    result.point = mesh.points[fallbackPoint];
  } else if (best.region == kRegionFace) {
    result.triangle = best.tri;
    result.kind = ClosestKind::Face;
    result.element = best.tri;
    result.point = best.q;
  } else if (best.region >= kRegionEdge0) {
    const std::uint32_t e = mesh.triEdges[best.tri][best.region - kRegionEdge0];
    result.triangle = best.tri;
    result.kind = ClosestKind::Edge;
    result.element = e;
    result.point =
        closestOnSegment(p, mesh.points[mesh.edgePoints[e][0]], mesh.points[mesh.edgePoints[e][1]]);
  } else {
    const std::uint32_t v = mesh.tris[best.tri][best.region - kRegionVertex0];
    result.triangle = best.tri;
    result.kind = ClosestKind::Vertex;
    result.element = v;
    result.point = mesh.points[v];
  }
  const V3 d = p - result.point;
  result.distance2 = dot(d, d);
  return result;
}

}  // namespace voxremesh::volume
