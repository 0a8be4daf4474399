// Feature snapping (see feature_snap.h).
#include "extract/feature_snap.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace voxremesh::extract {

namespace {

using openvdb::Coord;
using openvdb::Vec3d;

struct CoordHash {
  std::size_t operator()(const Coord& c) const {
    return std::size_t(c.x()) * 73856093u ^ std::size_t(c.y()) * 19349663u ^
           std::size_t(c.z()) * 83492791u;
  }
};

struct Segment {
  Vec3d a, b;  ///< world
  std::uint32_t curve = 0;
};

/// Cells [floor(lo - eps), floor(hi + eps)] per axis, i.e. every closed cell the box touches.
template <typename F>
void forEachCell(const Vec3d& lo, const Vec3d& hi, F&& f) {
  constexpr double kEps = 1e-6;
  const Coord from(int(std::floor(lo[0] - kEps)), int(std::floor(lo[1] - kEps)),
                   int(std::floor(lo[2] - kEps)));
  const Coord to(int(std::floor(hi[0] + kEps)), int(std::floor(hi[1] + kEps)),
                 int(std::floor(hi[2] + kEps)));
  for (int x = from.x(); x <= to.x(); ++x)
    for (int y = from.y(); y <= to.y(); ++y)
      for (int z = from.z(); z <= to.z(); ++z) f(Coord(x, y, z));
}

Vec3d closestOnSegment(const Segment& s, const Vec3d& p) {
  const Vec3d ab = s.b - s.a;
  const double len2 = ab.lengthSqr();
  const double t = len2 > 0.0 ? std::clamp((p - s.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return s.a + ab * t;
}

/// Squared distance a point moved when it was snapped.
double snapMove(const QuadMesh& mesh, const std::vector<std::array<double, 3>>& before,
                CornerIndex v) {
  double sum = 0.0;
  for (std::size_t c = 0; c < 3; ++c)
    sum += (mesh.points[v][c] - before[v][c]) * (mesh.points[v][c] - before[v][c]);
  return sum;
}

/// Where three or four corners of a quad were snapped onto one feature line (all the cells
/// around a grid edge the line passes close to are marked), the quad would collapse onto the
/// line. Keeps the two neighbouring corners that moved least (a Corner point always counts as
/// on the line) and puts the other Feature corners of that line back where they were, as Free
/// points. Faces in order, so the result is deterministic. Returns the number of points put back.
std::uint64_t keepOnePairPerFace(QuadMesh& mesh, const std::vector<std::array<double, 3>>& before) {
  std::uint64_t restored = 0;
  for (const auto& face : mesh.faces) {
    if (cornerCount(face) != 4) continue;
    for (int k = 0; k < 4; ++k) {
      const PointConstraint& seed = mesh.constraints[face[std::size_t(k)]];
      if (seed.role != PointRole::Feature) continue;
      const std::uint32_t curve = seed.curve;
      auto onLine = [&](int c) {
        const PointConstraint& constraint = mesh.constraints[face[std::size_t(c & 3)]];
        return constraint.role == PointRole::Corner ||
               (constraint.role == PointRole::Feature && constraint.curve == curve);
      };
      int count = 0;
      for (int c = 0; c < 4; ++c) count += onLine(c) ? 1 : 0;
      if (count < 3) continue;
      int bestPair = -1;
      double bestMove = std::numeric_limits<double>::infinity();
      for (int c = 0; c < 4; ++c) {
        if (!onLine(c) || !onLine(c + 1)) continue;
        const CornerIndex a = face[std::size_t(c)], b = face[std::size_t((c + 1) & 3)];
        const double move = (a < before.size() ? snapMove(mesh, before, a) : 0.0) +
                            (b < before.size() ? snapMove(mesh, before, b) : 0.0);
        if (move < bestMove) bestMove = move, bestPair = c;
      }
      for (int c = 0; c < 4; ++c) {
        if (c == bestPair || c == ((bestPair + 1) & 3)) continue;
        const CornerIndex v = face[std::size_t(c)];
        PointConstraint& constraint = mesh.constraints[v];
        if (constraint.role != PointRole::Feature || constraint.curve != curve ||
            v >= before.size())
          continue;
        mesh.points[v] = before[v];
        constraint = PointConstraint{};
        ++restored;
      }
    }
  }
  return restored;
}

}  // namespace

std::uint64_t snapToFeatures(QuadMesh& mesh, const std::vector<Coord>& pointCells,
                             const openvdb::MaskTree& featureCells,
                             const openvdb::math::Transform& transform,
                             const std::vector<std::uint32_t>& lineCurves,
                             const std::vector<std::array<double, 3>>& featurePoints) {
  if (mesh.constraints.size() != mesh.points.size()) mesh.constraints.resize(mesh.points.size());
  // Buckets: per cell, the feature points in it and the segments whose box touches it.
  std::vector<Segment> segments;
  std::unordered_map<Coord, std::vector<std::uint32_t>, CoordHash> segmentsOfCell, pointsOfCell;
  for (std::uint32_t curve : lineCurves) {
    const MeshCurve& line = mesh.curves[curve];
    const std::size_t n = line.points.size();
    const std::size_t count = line.closed && n > 2 ? n : (n > 0 ? n - 1 : 0);
    for (std::size_t i = 0; i < count; ++i) {
      const auto& a = line.points[i];
      const auto& b = line.points[(i + 1) % n];
      segments.push_back({Vec3d(a[0], a[1], a[2]), Vec3d(b[0], b[1], b[2]), curve});
    }
  }
  for (std::uint32_t s = 0; s < segments.size(); ++s) {
    const Vec3d ia = transform.worldToIndex(segments[s].a);
    const Vec3d ib = transform.worldToIndex(segments[s].b);
    forEachCell(minComponent(ia, ib), maxComponent(ia, ib),
                [&](const Coord& c) { segmentsOfCell[c].push_back(s); });
  }
  for (std::uint32_t f = 0; f < featurePoints.size(); ++f) {
    const Vec3d ip = transform.worldToIndex(
        Vec3d(featurePoints[f][0], featurePoints[f][1], featurePoints[f][2]));
    forEachCell(ip, ip, [&](const Coord& c) { pointsOfCell[c].push_back(f); });
  }

  const std::vector<std::array<double, 3>> before(
      mesh.points.begin(), mesh.points.begin() + std::ptrdiff_t(pointCells.size()));
  std::atomic<std::uint64_t> moved{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pointCells.size()),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      openvdb::tree::ValueAccessor<const openvdb::MaskTree> feature(featureCells);
                      std::uint64_t local = 0;
                      for (std::size_t i = range.begin(); i < range.end(); ++i) {
                        const Coord& cell = pointCells[i];
                        if (!feature.isValueOn(cell)) continue;
                        const Vec3d p(mesh.points[i][0], mesh.points[i][1], mesh.points[i][2]);
                        double best = std::numeric_limits<double>::infinity();
                        Vec3d target = p;
                        if (auto it = pointsOfCell.find(cell); it != pointsOfCell.end()) {
                          for (std::uint32_t f : it->second) {
                            const Vec3d q(featurePoints[f][0], featurePoints[f][1],
                                          featurePoints[f][2]);
                            if ((q - p).lengthSqr() < best) best = (q - p).lengthSqr(), target = q;
                          }
                          if (best < std::numeric_limits<double>::infinity()) {
                            mesh.points[i] = {target[0], target[1], target[2]};
                            mesh.constraints[i] = {PointRole::Corner, kNoCurve};
                            ++local;
                            continue;
                          }
                        }
                        auto it = segmentsOfCell.find(cell);
                        if (it == segmentsOfCell.end()) continue;
                        std::uint32_t curve = kNoCurve;
                        for (std::uint32_t s : it->second) {
                          const Vec3d q = closestOnSegment(segments[s], p);
                          if ((q - p).lengthSqr() < best)
                            best = (q - p).lengthSqr(), target = q, curve = segments[s].curve;
                        }
                        if (curve == kNoCurve) continue;
                        mesh.points[i] = {target[0], target[1], target[2]};
                        mesh.constraints[i] = {PointRole::Feature, curve};
                        ++local;
                      }
                      moved += local;
                    });
  return moved - keepOnePairPerFace(mesh, before);
}

}  // namespace voxremesh::extract
