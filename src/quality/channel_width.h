// ChannelWidth: how wide the channel of a surface is at a point, between the curves that bound it
// (boundary loops, feature lines, junction curves). Internal to src/quality (quality.h,
// "Minimum element length in narrow channels").
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/vec3.h"
#include "voxremesh/quad_mesh.h"

namespace voxremesh::quality {

/// The segments of a set of curves in a uniform grid, for the distance of a point to the nearest
/// one within a fixed reach, and the width of the channel a point lies in.
class ChannelWidth {
 public:
  /// Indexes every segment of `curves` (closed curves include their closing segment) in a grid of
  /// cells half the cap wide, or as wide as the median segment where that is less.
  /// @param cap  the largest width of interest (> 0, finite): widths are measured up to it
  /// Never throws but bad_alloc.
  ChannelWidth(const std::vector<MeshCurve>& curves, double cap);

  /// The diameter of the largest ball that contains `point` and that no curve passes through,
  /// its centre sought in the plane through `point` normal to `normal` (a pattern search from
  /// `point`, deterministic); `cap` when that ball is at least `cap` wide or no curve is near.
  /// In a strip between two curves this is the strip's width; next to a single curve, or in a
  /// corner wider than a right angle, the ball grows past the point and the width is large.
  double at(const geom::Vec3& point, const geom::Vec3& normal) const;

  /// As at(point, normal), with the ball sought only up to `cap` (at most the constructor's):
  /// `cap` when the channel is at least that wide. A smaller cap searches fewer segments.
  double at(const geom::Vec3& point, const geom::Vec3& normal, double cap) const;

 private:
  /// The segments that may come within `reach` of `p` (sorted, without repeats).
  std::vector<std::uint32_t> segmentsNear(const geom::Vec3& p, double reach) const;
  /// The distance of `p` to the nearest of the segments `near`, at most half the cap.
  double clearance(const geom::Vec3& p, const std::vector<std::uint32_t>& near) const;
  /// The grid cell index of a coordinate (clamped for huge ones).
  std::int64_t cellIndex(double coordinate) const;
  std::uint64_t cellKey(const geom::Vec3& p) const;
  std::uint64_t cellKey(std::int64_t i, std::int64_t j, std::int64_t k) const;

  double cap_ = 0.0;
  double cell_ = 0.0;
  std::vector<std::pair<geom::Vec3, geom::Vec3>> segments_;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> cells_;  ///< (cell key, segment), sorted
  std::vector<std::uint32_t> longSegments_;  ///< segments too long to grid, checked every query
};

}  // namespace voxremesh::quality
