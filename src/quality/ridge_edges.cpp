// RidgeEdges (ridge_edges.h).
#include "quality/ridge_edges.h"

namespace voxremesh::quality {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// How near a segment's ends (kEndShare) and middle (kMiddleShare) must lie to a curve, as shares
/// of the segment's length: the ends are curve points, the middle may cut a curved stretch.
constexpr double kEndShare = 1e-4, kMiddleShare = 0.05;

}  // namespace

bool RidgeEdges::along(const Vec3& a, const Vec3& b) {
  if (!curves_) return false;
  if (!built_) build();
  const double length = norm(b - a);
  const Vec3 middle = (a + b) * 0.5;
  const double endReach = kEndShare * length, middleReach = kMiddleShare * length;
  for (std::size_t c = 0; c < indexes_.size(); ++c) {
    if (geom::boxDistance2(a, boxes_[c]) > endReach * endReach) continue;
    const PolylineIndex& curve = indexes_[c];
    if (norm(curve.closestPoint(a) - a) <= endReach &&
        norm(curve.closestPoint(b) - b) <= endReach &&
        norm(curve.closestPoint(middle) - middle) <= middleReach)
      return true;
  }
  return false;
}

void RidgeEdges::build() {
  built_ = true;
  for (const MeshCurve& curve : *curves_) {
    if (curve.role == PointRole::Boundary || curve.points.size() < 2) continue;
    indexes_.emplace_back(curve.points, curve.closed);
    geom::Box box;
    for (const Vec3& p : curve.points) box.add(p);
    boxes_.push_back(box);
  }
}

}  // namespace voxremesh::quality
