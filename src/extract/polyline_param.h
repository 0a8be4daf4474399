// Arc-length parametrisation of a polyline (open or closed) in world space: closest points,
// points at a parameter. Used to rebuild the boundary strip and to snap vertices to feature lines.
#pragma once

#include <openvdb/math/Vec3.h>

#include <array>
#include <cstddef>
#include <vector>

namespace voxremesh::extract {

/// A polyline with the arc length at each of its points.
class PolylineParam {
 public:
  /// Parameter of `points` (closed: the segment from the last point back to the first counts).
  /// Precondition: at least one point.
  PolylineParam(const std::vector<std::array<double, 3>>& points, bool closed);

  /// Total length (closed: including the closing segment).
  double length() const { return arc_.back(); }
  bool closed() const { return closed_; }
  std::size_t pointCount() const { return points_.size(); }
  /// Arc length at point i.
  double vertexParam(std::size_t i) const { return arc_[i]; }
  const openvdb::math::Vec3d& point(std::size_t i) const { return points_[i]; }

  /// The segment (from point i to point i + 1) holding arc length s, s in [0, length()).
  std::size_t segmentAt(double s) const;
  /// The arc length of the closest point of the polyline to p; `distance` receives the distance.
  double closestParam(const openvdb::math::Vec3d& p, double& distance) const;
  /// The point at arc length s; closed polylines wrap s into [0, length()), open ones clamp.
  openvdb::math::Vec3d pointAt(double s) const;
  /// Distance of p to the polyline's axis-aligned bounding box (0 inside).
  double boxDistance(const openvdb::math::Vec3d& p) const;

 private:
  std::vector<openvdb::math::Vec3d> points_;
  std::vector<double> arc_;  ///< arc_[i] at points_[i]; one more entry (the length) at the end
  bool closed_ = false;
  openvdb::math::Vec3d boxMin_, boxMax_;
};

/// The point as the std::array that meshes and curves hold.
inline std::array<double, 3> toArray(const openvdb::math::Vec3d& p) {
  return {p[0], p[1], p[2]};
}

/// Appends to `out` the arc lengths of the polyline's points strictly between s0 and s1 (s0 < s1;
/// on a closed polyline both may exceed the length) that lie farther than `tolerance` from the
/// chord between the points at s0 and s1 (and, where `sagittaShare` is positive, farther than
/// that share of the chord's length), chosen farthest first and recursively (Douglas-Peucker),
/// so that the chords pass every point within the limit; ascending.
void addFarVertices(const PolylineParam& line, double s0, double s1, double tolerance,
                    std::vector<double>& out, double sagittaShare = 0.0);

}  // namespace voxremesh::extract
