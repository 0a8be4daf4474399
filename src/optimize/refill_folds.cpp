// refillFoldedRegions: the faces round folds cut out and their outline filled again (optimize.h).
#include <algorithm>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <vector>

#include "geometry/plane_basis.h"
#include "optimize/chord_error.h"
#include "optimize/face_score.h"
#include "optimize/mesh_topology.h"
#include "optimize/steps.h"
#include "voxremesh/optimize.h"
#include "voxremesh/quality.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

using Face = std::array<CornerIndex, 4>;

/// Rounds of growAtReflexCorners before a fold's region is untangled.
constexpr int kGrowRounds = 3;

/// The connected sets (across shared points) of the flagged faces, each ascending.
std::vector<std::vector<std::uint32_t>> flaggedRegions(const QuadMesh& mesh, const opt::Topology& t,
                                                       const std::vector<std::uint8_t>& flagged) {
  std::vector<std::uint8_t> seen(mesh.faces.size(), 0);
  std::vector<std::vector<std::uint32_t>> regions;
  for (std::uint32_t start = 0; start < mesh.faces.size(); ++start) {
    if (!flagged[start] || seen[start]) continue;
    std::vector<std::uint32_t> region{start};
    seen[start] = 1;
    for (std::size_t i = 0; i < region.size(); ++i) {
      const Face& face = mesh.faces[region[i]];
      for (int c = 0; c < cornerCount(face); ++c)
        for (const std::uint32_t* g = t.facesBegin(face[std::size_t(c)]);
             g != t.facesEnd(face[std::size_t(c)]); ++g)
          if (flagged[*g] && !seen[*g]) {
            seen[*g] = 1;
            region.push_back(*g);
          }
    }
    std::sort(region.begin(), region.end());
    regions.push_back(std::move(region));
  }
  return regions;
}

/// The outline of a region of faces as one closed loop of points in the faces' direction, or
/// empty when the outline is not a single simple loop.
std::vector<CornerIndex> outlineOf(const QuadMesh& mesh, const std::vector<std::uint32_t>& region) {
  std::map<std::pair<CornerIndex, CornerIndex>, int> directed;
  for (const std::uint32_t f : region) {
    const Face& face = mesh.faces[f];
    const int n = cornerCount(face);
    for (int c = 0; c < n; ++c) ++directed[{face[std::size_t(c)], face[std::size_t((c + 1) % n)]}];
  }
  std::map<CornerIndex, CornerIndex> next;
  for (const auto& [edge, count] : directed) {
    if (count != 1) return {};
    if (directed.count({edge.second, edge.first})) continue;       // inside the region
    if (!next.emplace(edge.first, edge.second).second) return {};  // pinched outline
  }
  if (next.size() < 3) return {};
  std::vector<CornerIndex> loop{next.begin()->first};
  while (loop.size() <= next.size()) {
    const auto it = next.find(loop.back());
    if (it == next.end()) return {};
    if (it->second == loop.front()) break;
    loop.push_back(it->second);
  }
  return loop.size() == next.size() ? loop : std::vector<CornerIndex>{};
}

/// Ear clipping of a loop projected on the plane normal to `normal`, the loop running counter-
/// clockwise seen from it; empty when the projection is not a simple polygon it can clip.
std::vector<Face> clipEars(const QuadMesh& mesh, const std::vector<CornerIndex>& loop,
                           const Vec3& normal) {
  const Vec3 axis = std::abs(normal[0]) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
  const Vec3 u = normalized(cross(normal, axis));
  const Vec3 w = cross(normal, u);
  std::vector<std::array<double, 2>> xy;
  for (const CornerIndex v : loop) xy.push_back({dot(mesh.points[v], u), dot(mesh.points[v], w)});
  const auto turn = [&](std::size_t a, std::size_t b, std::size_t c) {
    return (xy[b][0] - xy[a][0]) * (xy[c][1] - xy[a][1]) -
           (xy[b][1] - xy[a][1]) * (xy[c][0] - xy[a][0]);
  };
  std::vector<std::size_t> left(loop.size());
  for (std::size_t i = 0; i < left.size(); ++i) left[i] = i;
  std::vector<Face> triangles;
  while (left.size() > 3) {
    bool clipped = false;
    for (std::size_t i = 0; i < left.size() && !clipped; ++i) {
      const std::size_t a = left[(i + left.size() - 1) % left.size()], b = left[i],
                        c = left[(i + 1) % left.size()];
      if (turn(a, b, c) <= 0.0) continue;  // reflex or flat corner
      bool empty = true;
      for (const std::size_t p : left) {
        if (p == a || p == b || p == c) continue;
        if (turn(a, b, p) >= 0.0 && turn(b, c, p) >= 0.0 && turn(c, a, p) >= 0.0) empty = false;
      }
      if (!empty) continue;
      triangles.push_back({loop[a], loop[b], loop[c], kNoCorner});
      left.erase(left.begin() + std::ptrdiff_t(i));
      clipped = true;
    }
    if (!clipped) return {};
  }
  if (turn(left[0], left[1], left[2]) <= 0.0) return {};
  triangles.push_back({loop[left[0]], loop[left[1]], loop[left[2]], kNoCorner});
  return triangles;
}

/// A fan of triangles from a new point at `centre` (added to `mesh` as a Free point) to every
/// edge of the loop, when each of them turns the loop's way seen from `normal` (the loop is star-
/// shaped round the centre); else empty and `mesh` unchanged.
std::vector<Face> fanFill(QuadMesh& mesh, const std::vector<CornerIndex>& loop, const Vec3& normal,
                          const Vec3& centre) {
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec3& a = mesh.points[loop[i]];
    const Vec3& b = mesh.points[loop[(i + 1) % loop.size()]];
    if (dot(cross(b - a, centre - a), normal) <= 0.0) return {};
  }
  const auto middle = static_cast<CornerIndex>(mesh.points.size());
  mesh.points.push_back(centre);
  if (!mesh.constraints.empty()) mesh.constraints.push_back(PointConstraint{});
  std::vector<Face> triangles;
  for (std::size_t i = 0; i < loop.size(); ++i)
    triangles.push_back({loop[i], loop[(i + 1) % loop.size()], middle, kNoCorner});
  return triangles;
}

/// Each triangle farther than `allowed` from the original (chordError) split into three at its
/// centroid's closest point on the original (a new Free point); the points are added to `mesh`.
std::vector<Face> splitFarTriangles(QuadMesh& mesh, const ReferenceSurface& original,
                                    const std::vector<Face>& triangles, double allowed) {
  std::vector<Face> result;
  for (const Face& t : triangles) {
    if (opt::chordError(mesh, {t}, original) <= allowed) {
      result.push_back(t);
      continue;
    }
    const Vec3 centroid = (mesh.points[t[0]] + mesh.points[t[1]] + mesh.points[t[2]]) * (1.0 / 3.0);
    const auto middle = static_cast<CornerIndex>(mesh.points.size());
    mesh.points.push_back(original.closestPoint(centroid).point);
    if (!mesh.constraints.empty()) mesh.constraints.push_back(PointConstraint{});
    for (int c = 0; c < 3; ++c)
      result.push_back({t[std::size_t(c)], t[std::size_t((c + 1) % 3)], middle, kNoCorner});
  }
  return result;
}

/// Twice the signed area of the triangle (a, b, c) in the plane.
double turn2d(const std::array<double, 2>& a, const std::array<double, 2>& b,
              const std::array<double, 2>& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/// The region grown at the reflex corners of its outline projected on the plane normal to
/// `normal` (unit): the faces round each such corner that is a Free point inside the surface are
/// added, for at most `rounds` rounds, so that the outline comes closer to convex (Tutte's
/// embedding is then fold-free). Stops early where the outline would no longer be one simple
/// loop. Returns the grown region (ascending) and its outline in `loop`.
std::vector<std::uint32_t> growAtReflexCorners(const QuadMesh& mesh, const opt::Topology& t,
                                               std::vector<std::uint32_t> region,
                                               std::vector<CornerIndex>& loop, const Vec3& normal,
                                               int rounds) {
  const std::pair<Vec3, Vec3> basis = planeBasis(normal);
  const Vec3 u = basis.first, w = basis.second;
  const auto at = [&](CornerIndex v) {
    return std::array<double, 2>{dot(mesh.points[v], u), dot(mesh.points[v], w)};
  };
  for (int round = 0; round < rounds; ++round) {
    std::vector<std::uint32_t> grown = region;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const CornerIndex v = loop[i];
      if (opt::roleOf(mesh, v) != PointRole::Free || t.boundary[v]) continue;
      if (turn2d(at(loop[(i + loop.size() - 1) % loop.size()]), at(v),
                 at(loop[(i + 1) % loop.size()])) > 0.0)
        continue;
      grown.insert(grown.end(), t.facesBegin(v), t.facesEnd(v));
    }
    std::sort(grown.begin(), grown.end());
    grown.erase(std::unique(grown.begin(), grown.end()), grown.end());
    if (grown.size() == region.size()) break;
    std::vector<CornerIndex> grownLoop = outlineOf(mesh, grown);
    if (grownLoop.empty()) break;
    region = std::move(grown);
    loop = std::move(grownLoop);
  }
  return region;
}

/// The Free inner points of a region (its points off the outline `loop` and inside the surface;
/// `t` the topology of `mesh`) moved, its faces kept: on the plane normal to `normal` (unit) the
/// outline and the inner points on curves are held where they project and every other inner
/// point put at the mean of its edge neighbours (Tutte's barycentric embedding, by Gauss-Seidel
/// sweeps in point order), which unfolds the region when the projected outline is convex or
/// nearly so; then each moved point is laid on the original. True when, so placed, every face
/// of the region has a positive area on the plane (turning the outline's way), the mesh has
/// fewer folded faces than `foldsBefore`, no face is a sliver and the faces stay within
/// `allowed` of the original (chordError); else the points are put back.
bool untangleRegion(QuadMesh& mesh, const opt::Topology& t, const ReferenceSurface& original,
                    const std::vector<std::uint32_t>& region, const std::vector<CornerIndex>& loop,
                    const Vec3& normal, const QualitySettings& settings, double allowed,
                    std::ptrdiff_t foldsBefore) {
  std::map<CornerIndex, std::size_t> index;  // every point of the region -> its slot
  std::vector<std::uint8_t> fixed;
  for (const CornerIndex v : loop) index.emplace(v, index.size()), fixed.push_back(1);
  for (const std::uint32_t f : region)
    for (int c = 0; c < cornerCount(mesh.faces[f]); ++c)
      if (index.emplace(mesh.faces[f][std::size_t(c)], index.size()).second) fixed.push_back(0);
  if (index.size() == loop.size()) return false;
  for (const auto& [v, slot] : index)  // points on curves or the boundary stay where they are
    if (opt::roleOf(mesh, v) != PointRole::Free || t.boundary[v]) fixed[slot] = 1;
  std::vector<std::vector<std::size_t>> neighbours(index.size());
  for (const std::uint32_t f : region) {
    const Face& face = mesh.faces[f];
    const int n = cornerCount(face);
    for (int c = 0; c < n; ++c) {
      const std::size_t a = index[face[std::size_t(c)]], b = index[face[std::size_t((c + 1) % n)]];
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
    }
  }
  const auto [u, w] = planeBasis(normal);
  std::vector<std::array<double, 2>> xy(index.size());
  std::vector<CornerIndex> pointOf(index.size());
  Vec3 centre{0.0, 0.0, 0.0};
  for (const auto& [v, slot] : index) {
    pointOf[slot] = v;
    xy[slot] = {dot(mesh.points[v], u), dot(mesh.points[v], w)};
  }
  for (const CornerIndex v : loop) centre = centre + mesh.points[v] * (1.0 / double(loop.size()));
  double scale = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i)
    scale = std::max(scale, std::hypot(xy[i][0] - xy[(i + 1) % loop.size()][0],
                                       xy[i][1] - xy[(i + 1) % loop.size()][1]));
  for (int sweep = 0; sweep < 500; ++sweep) {
    double moved = 0.0;
    for (std::size_t slot = 0; slot < xy.size(); ++slot) {
      if (fixed[slot]) continue;
      std::array<double, 2> mean{0.0, 0.0};
      for (const std::size_t n : neighbours[slot])
        mean = {mean[0] + xy[n][0] / double(neighbours[slot].size()),
                mean[1] + xy[n][1] / double(neighbours[slot].size())};
      moved = std::max(moved, std::hypot(mean[0] - xy[slot][0], mean[1] - xy[slot][1]));
      xy[slot] = mean;
    }
    if (moved < 1e-9 * scale) break;
  }
  for (const std::uint32_t f : region) {  // each face keeps the outline's turn on the plane
    const Face& face = mesh.faces[f];
    const int n = cornerCount(face);
    double area = 0.0;
    for (int c = 1; c + 1 < n; ++c)
      area += turn2d(xy[index[face[0]]], xy[index[face[std::size_t(c)]]],
                     xy[index[face[std::size_t(c + 1)]]]);
    if (area <= 0.0) return false;
  }
  std::vector<std::pair<CornerIndex, Vec3>> before;
  const double height = dot(centre, normal);
  for (std::size_t slot = 0; slot < xy.size(); ++slot) {
    if (fixed[slot]) continue;
    const CornerIndex v = pointOf[slot];
    before.emplace_back(v, mesh.points[v]);
    mesh.points[v] =
        original.closestPoint(u * xy[slot][0] + w * xy[slot][1] + normal * height).point;
  }
  std::vector<Face> faces;
  for (const std::uint32_t f : region) faces.push_back(mesh.faces[f]);
  const std::vector<std::uint8_t> folded = foldedFaces(mesh);
  bool good = std::count(folded.begin(), folded.end(), std::uint8_t(1)) < foldsBefore &&
              opt::chordError(mesh, faces, original) <= allowed;
  for (const Face& face : faces) {
    std::array<std::array<double, 3>, 4> p{};
    for (int c = 0; c < cornerCount(face); ++c)
      p[std::size_t(c)] = mesh.points[face[std::size_t(c)]];
    good =
        good && elementQuality(p, cornerCount(face)).minLength >= opt::degenerateLength(settings);
  }
  if (!good)
    for (const auto& [v, position] : before) mesh.points[v] = position;
  return good;
}

}  // namespace

std::size_t refillFoldedRegions(QuadMesh& mesh, const ReferenceSurface& original,
                                const QualitySettings& settings, opt::MeshCache& cache) {
  opt::checkMesh(mesh);
  if (original.empty()) throw std::invalid_argument("refillFoldedRegions: the surface is empty");
  const std::vector<std::uint8_t> folded = foldedFaces(mesh);
  if (std::count(folded.begin(), folded.end(), std::uint8_t(1)) == 0) return 0;
  const opt::Topology& t = cache.topology(mesh);
  const std::size_t pointsBefore = mesh.points.size();
  // The folded faces and every face sharing a point with them: their outline then runs through
  // faces that are not folded.
  std::vector<std::uint8_t> cut(mesh.faces.size(), 0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!folded[f]) continue;
    for (int c = 0; c < cornerCount(mesh.faces[f]); ++c)
      for (const std::uint32_t* g = t.facesBegin(mesh.faces[f][std::size_t(c)]);
           g != t.facesEnd(mesh.faces[f][std::size_t(c)]); ++g)
        cut[*g] = 1;
  }
  std::vector<std::uint8_t> removed(mesh.faces.size(), 0);
  std::vector<Face> added;
  std::size_t refilled = 0;
  for (const std::vector<std::uint32_t>& region : flaggedRegions(mesh, t, cut)) {
    const std::vector<CornerIndex> loop = outlineOf(mesh, region);
    if (loop.empty()) continue;
    // Points inside the region (not on its outline) disappear: never a fixed one.
    std::vector<std::uint8_t> onLoop(mesh.points.size(), 0);
    for (const CornerIndex v : loop) onLoop[v] = 1;
    bool keepsFixed = true;
    Vec3 normal{0.0, 0.0, 0.0};
    for (const std::uint32_t f : region) {
      const Face& face = mesh.faces[f];
      const bool triangle = cornerCount(face) == 3;
      if (!folded[f])
        normal =
            normal + elementNormal(mesh.points[face[0]], mesh.points[face[1]], mesh.points[face[2]],
                                   mesh.points[face[triangle ? 2 : 3]], triangle);
      for (int c = 0; c < cornerCount(face); ++c) {
        const CornerIndex v = face[std::size_t(c)];
        const PointRole role = opt::roleOf(mesh, v);
        if (!onLoop[v] && role != PointRole::Free) keepsFixed = false;
      }
    }
    if (norm(normal) == 0.0) continue;
    // The region stays within the distance limit of the original, or as close as its faces
    // were: its own faces unfolded where they can be; else it is filled anew.
    std::vector<Face> faces;
    for (const std::uint32_t f : region) faces.push_back(mesh.faces[f]);
    const double allowed =
        std::max(settings.maxDistanceFactor *
                     lengthScale(settings, Criterion::Distance, settings.targetSize),
                 opt::chordError(mesh, faces, original));
    const std::vector<std::uint8_t> foldedNow = foldedFaces(mesh);
    std::vector<CornerIndex> grownLoop = loop;
    const std::vector<std::uint32_t> grown =
        growAtReflexCorners(mesh, t, region, grownLoop, normalized(normal), kGrowRounds);
    if (std::none_of(grown.begin(), grown.end(),
                     [&](std::uint32_t f) { return removed[f] != 0; }) &&
        untangleRegion(mesh, t, original, grown, grownLoop, normalized(normal), settings, allowed,
                       std::count(foldedNow.begin(), foldedNow.end(), std::uint8_t(1)))) {
      ++refilled;
      continue;
    }
    if (!keepsFixed) continue;  // a fill would drop the fixed points inside
    // A fan round the outline's centroid laid on the original follows a curved region; ear
    // clipping of the outline where the outline is not star-shaped round it.
    const std::size_t pointsOfRegion = mesh.points.size();
    Vec3 centroid{0.0, 0.0, 0.0};
    for (const CornerIndex v : loop)
      centroid = centroid + mesh.points[v] * (1.0 / double(loop.size()));
    std::vector<Face> triangles =
        fanFill(mesh, loop, normalized(normal), original.closestPoint(centroid).point);
    if (triangles.empty()) triangles = clipEars(mesh, loop, normalized(normal));
    if (triangles.empty()) continue;
    // Far triangles are split at their centroid, laid on the original.
    triangles = splitFarTriangles(mesh, original, triangles, allowed);
    // No sliver (face_score.h): the fill must not trade a fold for a time step cut a hundredfold.
    bool sliver = false;
    for (const Face& triangle : triangles) {
      std::array<std::array<double, 3>, 4> p{};
      for (int c = 0; c < 3; ++c) p[std::size_t(c)] = mesh.points[triangle[std::size_t(c)]];
      sliver = sliver || !(elementQuality(p, 3).minLength >= opt::degenerateLength(settings));
    }
    if (sliver || opt::chordError(mesh, triangles, original) > allowed) {
      mesh.points.resize(pointsOfRegion);
      if (!mesh.constraints.empty()) mesh.constraints.resize(pointsOfRegion);
      continue;
    }
    for (const std::uint32_t f : region) removed[f] = 1;
    added.insert(added.end(), triangles.begin(), triangles.end());
    ++refilled;
  }
  if (refilled == 0) return 0;
  QuadMesh result = mesh;
  result.faces.clear();
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (!removed[f]) result.faces.push_back(mesh.faces[f]);
  result.faces.insert(result.faces.end(), added.begin(), added.end());
  const std::vector<std::uint8_t> after = foldedFaces(result);
  if (std::count(after.begin(), after.end(), std::uint8_t(1)) >=
      std::count(folded.begin(), folded.end(), std::uint8_t(1))) {
    mesh.points.resize(pointsBefore);
    if (!mesh.constraints.empty()) mesh.constraints.resize(pointsBefore);
    return 0;
  }
  if (settings.targetSize > 0.0) mergeTrianglePairs(result, settings);
  eraseUnusedPoints(result);
  mesh = std::move(result);
  return refilled;
}

std::size_t refillFoldedRegions(QuadMesh& mesh, const ReferenceSurface& original,
                                const QualitySettings& settings) {
  opt::MeshCache cache(settings);
  return refillFoldedRegions(mesh, original, settings, cache);
}

}  // namespace voxremesh
