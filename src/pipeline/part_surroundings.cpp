// What a part's remesh must respect of the deck around it: seams along kept parts and hard points
// (remesh_part.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "geometry/vec3.h"
#include "pipeline/remesh_part.h"

namespace voxremesh::pipeline {

namespace {

/// Cuts the polylines of `curves` at the points flagged in `cut` (an open polyline into pieces, a
/// closed one opened at its first flagged point and cut at the others).
void cutAt(std::vector<Polyline>& curves, const std::vector<std::uint8_t>& cut) {
  std::vector<Polyline> result;
  for (Polyline& curve : curves) {
    std::vector<PointIndex> points = curve.points;
    if (curve.closed) {
      const auto first =
          std::find_if(points.begin(), points.end(), [&](PointIndex p) { return cut[p] != 0; });
      if (first == points.end()) {
        result.push_back(std::move(curve));
        continue;
      }
      std::rotate(points.begin(), first, points.end());
      points.push_back(points.front());
    }
    Polyline piece;
    piece.keepPoints = curve.keepPoints;
    for (std::size_t i = 0; i < points.size(); ++i) {
      piece.points.push_back(points[i]);
      if (i > 0 && i + 1 < points.size() && cut[points[i]] != 0) {
        result.push_back(piece);
        piece.points = {points[i]};
      }
    }
    result.push_back(std::move(piece));
  }
  curves = std::move(result);
}

}  // namespace

void markKeptSeams(std::vector<Sheet>& sheets, const FeModel& model,
                   const std::vector<Id>& keptParts) {
  if (keptParts.empty()) return;
  std::unordered_map<Id, std::vector<Id>> keptPartsOfNode;
  for (const Shell& shell : model.shells) {
    if (!std::binary_search(keptParts.begin(), keptParts.end(), shell.part)) continue;
    for (int c = 0; c < shell.nodeCount; ++c) {
      std::vector<Id>& list = keptPartsOfNode[shell.nodes[static_cast<std::size_t>(c)]];
      if (std::find(list.begin(), list.end(), shell.part) == list.end()) list.push_back(shell.part);
    }
  }
  const auto alongKeptPart = [&](Id a, Id b) {
    const auto x = keptPartsOfNode.find(a), y = keptPartsOfNode.find(b);
    if (x == keptPartsOfNode.end() || y == keptPartsOfNode.end()) return false;
    for (const Id part : x->second)
      if (std::find(y->second.begin(), y->second.end(), part) != y->second.end()) return true;
    return false;
  };
  for (Sheet& sheet : sheets)
    for (Polyline& curve : sheet.junctionCurves) {
      const std::size_t n = curve.points.size();
      for (std::size_t i = 0; i + 1 < n + (curve.closed ? 1 : 0) && !curve.keepPoints; ++i)
        curve.keepPoints = alongKeptPart(sheet.pointNodeIds[curve.points[i]],
                                         sheet.pointNodeIds[curve.points[(i + 1) % n]]);
    }
}

std::vector<std::vector<Point3>> placeHardPoints(std::vector<Sheet>& sheets,
                                                 const std::unordered_set<Id>& hardPoints) {
  std::vector<std::vector<Point3>> inside(sheets.size());
  if (hardPoints.empty()) return inside;
  for (std::size_t k = 0; k < sheets.size(); ++k) {
    Sheet& sheet = sheets[k];
    std::vector<std::uint8_t> onCurve(sheet.points.size(), 0), hard(sheet.points.size(), 0);
    for (const std::vector<Polyline>* curves :
         {&sheet.boundaryLoops, &sheet.featureLines, &sheet.junctionCurves})
      for (const Polyline& curve : *curves)
        for (const PointIndex p : curve.points) onCurve[p] = 1;
    bool any = false;
    for (PointIndex p = 0; p < sheet.points.size(); ++p) {
      if (!hardPoints.count(sheet.pointNodeIds[p])) continue;
      if (!onCurve[p]) {
        inside[k].push_back(sheet.points[p]);
        continue;
      }
      hard[p] = 1;
      any = true;
      if (std::find(sheet.featurePoints.begin(), sheet.featurePoints.end(), p) ==
          sheet.featurePoints.end())
        sheet.featurePoints.push_back(p);
    }
    if (any) cutAt(sheet.junctionCurves, hard);
  }
  return inside;
}

std::size_t snapHardPoints(QuadMesh& mesh, const std::vector<Point3>& points, double reach) {
  if (points.empty()) return 0;
  mesh.constraints.resize(mesh.points.size());
  std::size_t placed = 0;
  for (const Point3& target : points) {
    std::size_t best = mesh.points.size();
    double bestDistance = reach * reach;
    for (std::size_t p = 0; p < mesh.points.size(); ++p) {
      if (mesh.constraints[p].role != PointRole::Free) continue;
      double d = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double delta = mesh.points[p][std::size_t(c)] - target[std::size_t(c)];
        d += delta * delta;
      }
      if (d <= bestDistance) {
        if (d == bestDistance && best < p) continue;
        bestDistance = d, best = p;
      }
    }
    if (best == mesh.points.size()) continue;
    mesh.points[best] = target;
    mesh.constraints[best] = {PointRole::Corner, kNoCurve};
    ++placed;
  }
  return placed;
}

namespace {

/// True when `target` lies within `reach` of the plane of `face` (its elementNormal) and strictly
/// on the inner side of each of its edges seen along that normal.
bool insideFace(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face, const Point3& target,
                double reach) {
  using namespace geom;  // NOLINT: the vector operators
  const int n = cornerCount(face);
  const auto& p = mesh.points;
  const Vec3 normal = normalized(
      elementNormal(p[face[0]], p[face[1]], p[face[2]], p[face[n == 3 ? 2 : 3]], n == 3));
  if (!(norm(normal) > 0.0) || std::abs(dot(target - p[face[0]], normal)) > reach) return false;
  for (int k = 0; k < n; ++k) {
    const Vec3& a = p[face[std::size_t(k)]];
    const Vec3& b = p[face[std::size_t((k + 1) % n)]];
    if (!(dot(cross(b - a, target - a), normal) > 0.0)) return false;
  }
  return true;
}

/// Puts `target` on the edge of `mesh` it lies on (within `reach` of the segment, away from its
/// ends), as point `point`: every face with that edge becomes the fan of triangles from its other
/// edges to the point, in its orientation. False when no edge is that close.
bool splitEdgeAt(QuadMesh& mesh, const Point3& target, CornerIndex point, double reach) {
  using namespace geom;  // NOLINT: the vector operators
  const auto& p = mesh.points;
  CornerIndex a = kNoCorner, b = kNoCorner;
  for (const auto& face : mesh.faces) {
    const int n = cornerCount(face);
    for (int k = 0; k < n && a == kNoCorner; ++k) {
      const CornerIndex u = face[std::size_t(k)], v = face[std::size_t((k + 1) % n)];
      const Vec3 along = p[v] - p[u];
      const double length2 = dot(along, along);
      if (!(length2 > 0.0)) continue;
      const double t = dot(target - p[u], along) / length2;
      if (t > 1e-6 && t < 1.0 - 1e-6 && norm(p[u] + along * t - target) <= reach) a = u, b = v;
    }
    if (a != kNoCorner) break;
  }
  if (a == kNoCorner) return false;
  std::vector<std::array<CornerIndex, 4>> faces;
  for (const auto& face : mesh.faces) {
    const int n = cornerCount(face);
    int split = -1;
    for (int k = 0; k < n; ++k) {
      const CornerIndex u = face[std::size_t(k)], v = face[std::size_t((k + 1) % n)];
      if ((u == a && v == b) || (u == b && v == a)) split = k;
    }
    if (split < 0) {
      faces.push_back(face);
      continue;
    }
    for (int k = 0; k < n; ++k)
      if (k != split)
        faces.push_back({face[std::size_t(k)], face[std::size_t((k + 1) % n)], point, kNoCorner});
  }
  mesh.faces = std::move(faces);
  return true;
}

}  // namespace

std::size_t insertHardPoints(QuadMesh& mesh, const std::vector<Point3>& points, double reach) {
  mesh.constraints.resize(mesh.points.size());
  std::size_t inserted = 0;
  for (const Point3& target : points) {
    if (missingPoints(mesh, {target}) == 0) continue;
    const auto face = std::find_if(mesh.faces.begin(), mesh.faces.end(), [&](const auto& f) {
      return insideFace(mesh, f, target, reach);
    });
    const auto point = CornerIndex(mesh.points.size());
    if (face == mesh.faces.end()) {
      if (!splitEdgeAt(mesh, target, point, reach)) continue;
      mesh.points.push_back(target);
      mesh.constraints.push_back({PointRole::Corner, kNoCurve});
      ++inserted;
      continue;
    }
    const std::array<CornerIndex, 4> corners = *face;
    const int n = cornerCount(corners);
    mesh.points.push_back(target);
    mesh.constraints.push_back({PointRole::Corner, kNoCurve});
    *face = {corners[0], corners[1], point, kNoCorner};
    for (int k = 1; k < n; ++k)
      mesh.faces.push_back(
          {corners[std::size_t(k)], corners[std::size_t((k + 1) % n)], point, kNoCorner});
    ++inserted;
  }
  return inserted;
}

std::size_t missingPoints(const QuadMesh& mesh, const std::vector<Point3>& points,
                          double tolerance) {
  if (points.empty()) return 0;
  std::vector<Point3> sorted = mesh.points;
  std::sort(sorted.begin(), sorted.end());
  return static_cast<std::size_t>(std::count_if(points.begin(), points.end(), [&](const Point3& p) {
    const Point3 low{p[0] - tolerance, -std::numeric_limits<double>::infinity(), 0.0};
    for (auto it = std::lower_bound(sorted.begin(), sorted.end(), low);
         it != sorted.end() && (*it)[0] <= p[0] + tolerance; ++it)
      if (std::abs((*it)[1] - p[1]) <= tolerance && std::abs((*it)[2] - p[2]) <= tolerance)
        return false;
    return true;
  }));
}

}  // namespace voxremesh::pipeline
