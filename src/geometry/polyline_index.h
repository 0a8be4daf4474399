// PolylineIndex: closestPointOnPolyline (reference_surface.h) for many queries on one fixed
// polyline, through a hierarchy of boxes over runs of consecutive segments instead of a scan of
// every segment. The answers are those of closestPointOnPolyline bit for bit: the same closest
// point of each segment, the first segment winning exact ties, the first point beating them all.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/safe_box.h"
#include "geometry/vec3.h"

namespace voxremesh {

/// A fixed polyline (a copy of its points) with fast exact closest-point queries.
class PolylineIndex {
 public:
  /// An empty index (closestPoint must not be called on it).
  PolylineIndex() = default;

  /// Indexes the polyline through `points`; `closed` adds the segment from the last point back to
  /// the first (when there are more than two points), as closestPointOnPolyline. A polyline with a
  /// non-finite coordinate is kept unindexed (every query scans it). Never throws but bad_alloc.
  PolylineIndex(const std::vector<std::array<double, 3>>& points, bool closed);

  /// True without points.
  bool empty() const { return points_.empty(); }

  /// closestPointOnPolyline(points, closed, p) of the indexed polyline. Precondition: !empty()
  /// (std::invalid_argument otherwise).
  std::array<double, 3> closestPoint(const std::array<double, 3>& p) const;

 private:
  struct Node {
    geom::Box box;            ///< holds the closest points of its segments (safeBox)
    std::uint32_t begin = 0;  ///< first segment
    std::uint32_t end = 0;    ///< one past the last segment
    std::uint32_t right = 0;  ///< inner node: the second child (the first follows the node)
  };
  std::uint32_t build(std::uint32_t begin, std::uint32_t end);

  std::vector<geom::Vec3> points_;
  std::size_t segments_ = 0;
  std::vector<Node> nodes_;  ///< depth first, nodes_[0] the root; empty when unindexed
};

}  // namespace voxremesh
