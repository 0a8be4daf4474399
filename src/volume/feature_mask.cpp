// The feature mask: cells crossed by feature line segments (3D DDA, Amanatides & Woo 1987) and
// cells holding feature points, in parallel over the segments.
#include <openvdb/openvdb.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "volume/volume_build.h"

namespace voxremesh::volume {

namespace {

/// Cells closer than this (in voxels) to a segment count as touched, so that a segment running
/// exactly along a cell face, edge or corner marks every cell sharing it despite rounding.
constexpr double kTouchTolerance = 1e-6;

struct Segment {
  openvdb::Vec3d a, b;  // index space
};

using MaskAccessor = openvdb::tree::ValueAccessor<openvdb::MaskTree>;

/// Marks cell c and the neighbours that the piece of segment between a and b (inside or on
/// cell c) comes within kTouchTolerance of.
void markPiece(const openvdb::Coord& c, const openvdb::Vec3d& a, const openvdb::Vec3d& b,
               MaskAccessor& accessor) {
  int lo[3], hi[3];
  for (int axis = 0; axis < 3; ++axis) {
    const double low = std::min(a[axis], b[axis]) - double(c[axis]);
    const double high = double(c[axis]) + 1.0 - std::max(a[axis], b[axis]);
    lo[axis] = low < kTouchTolerance ? -1 : 0;
    hi[axis] = high < kTouchTolerance ? 1 : 0;
  }
  for (int i = lo[0]; i <= hi[0]; ++i) {
    for (int j = lo[1]; j <= hi[1]; ++j) {
      for (int k = lo[2]; k <= hi[2]; ++k) accessor.setValueOn(c.offsetBy(i, j, k));
    }
  }
}

openvdb::Coord cellOf(const openvdb::Vec3d& q) {
  return openvdb::Coord(int(std::floor(q[0])), int(std::floor(q[1])), int(std::floor(q[2])));
}

/// Walks the cells segment s passes through, in order, marking each (Amanatides-Woo).
void markSegment(const Segment& s, MaskAccessor& accessor) {
  const openvdb::Vec3d d = s.b - s.a;
  openvdb::Coord cell = cellOf(s.a);
  const openvdb::Coord last = cellOf(s.b);
  int step[3];
  double tMax[3], tDelta[3];
  for (int axis = 0; axis < 3; ++axis) {
    if (d[axis] > 0.0) {
      step[axis] = 1;
      tMax[axis] = (double(cell[axis]) + 1.0 - s.a[axis]) / d[axis];
      tDelta[axis] = 1.0 / d[axis];
    } else if (d[axis] < 0.0) {
      step[axis] = -1;
      tMax[axis] = (double(cell[axis]) - s.a[axis]) / d[axis];
      tDelta[axis] = -1.0 / d[axis];
    } else {
      step[axis] = 0;
      tMax[axis] = tDelta[axis] = std::numeric_limits<double>::infinity();
    }
  }
  // Each step crosses one cell face; the walk ends in the last cell, so it takes at most the
  // Manhattan distance between the two cells (plus slack for rounding).
  const long maxSteps = std::abs(long(last[0]) - cell[0]) + std::abs(long(last[1]) - cell[1]) +
                        std::abs(long(last[2]) - cell[2]) + 3;
  double tEnter = 0.0;
  for (long n = 0; n <= maxSteps; ++n) {
    const int axis =
        tMax[0] <= tMax[1] ? (tMax[0] <= tMax[2] ? 0 : 2) : (tMax[1] <= tMax[2] ? 1 : 2);
    const double tExit = std::min(tMax[axis], 1.0);
    markPiece(cell, s.a + d * tEnter, s.a + d * tExit, accessor);
    if (tMax[axis] >= 1.0) break;
    cell[axis] += step[axis];
    tMax[axis] += tDelta[axis];
    tEnter = tExit;
  }
}

/// parallel_reduce body: marks its segments into its own tree; trees are joined by union.
struct MarkSegments {
  const std::vector<Segment>* segments;
  openvdb::MaskTree tree;

  explicit MarkSegments(const std::vector<Segment>& s) : segments(&s) {}
  MarkSegments(MarkSegments& other, tbb::split) : segments(other.segments) {}
  void operator()(const tbb::blocked_range<std::size_t>& r) {
    MaskAccessor accessor(tree);
    for (std::size_t i = r.begin(); i < r.end(); ++i) markSegment((*segments)[i], accessor);
  }
  void join(MarkSegments& other) { tree.topologyUnion(other.tree); }
};

}  // namespace

openvdb::MaskGrid::Ptr buildFeatureMask(const std::vector<VolumeCurve>& curves,
                                        const std::vector<std::array<double, 3>>& points,
                                        const openvdb::math::Transform::Ptr& transform) {
  std::vector<Segment> segments;
  auto toIndex = [&](const std::array<double, 3>& p) {
    return transform->worldToIndex(openvdb::Vec3d(p[0], p[1], p[2]));
  };
  for (const VolumeCurve& curve : curves) {
    const std::size_t n = curve.points.size();
    if (n == 1) segments.push_back({toIndex(curve.points[0]), toIndex(curve.points[0])});
    const std::size_t count = curve.closed && n > 2 ? n : (n > 0 ? n - 1 : 0);
    for (std::size_t i = 0; i < count; ++i) {
      segments.push_back({toIndex(curve.points[i]), toIndex(curve.points[(i + 1) % n])});
    }
  }
  for (const auto& p : points) segments.push_back({toIndex(p), toIndex(p)});

  MarkSegments body(segments);
  tbb::parallel_reduce(tbb::blocked_range<std::size_t>(0, segments.size(), 16), body);
  openvdb::MaskGrid::Ptr grid = openvdb::MaskGrid::create();
  grid->setTransform(transform);
  grid->tree().merge(body.tree);
  grid->setName(kFeatureGridName);
  return grid;
}

}  // namespace voxremesh::volume
