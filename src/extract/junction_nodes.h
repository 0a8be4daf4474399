// The nodes extraction puts on junction curves (curves where sheets or parts met): computed from
// the curve alone, so that every sheet meshed on either side gets bit-identical nodes there and
// the meshes share nodes after welding (DESIGN.md, "Junctions": discretise such curves once and
// use them on both sides).
//
// Sampling of one curve (junctionNodes):
// - Canonical direction: a closed curve starts at its lexicographically smallest point (x, then
//   y, then z) and runs towards the smaller of that point's two neighbours; an open curve starts
//   at the smaller of its two ends. Every side therefore walks the same points the same way.
// - Anchors: the ends of an open curve, and the points where the curve turns by more than
//   kJunctionCornerDeg; a closed curve without such a point is anchored at its start.
// - Between consecutive anchors (arc length L) round(L / spacing) (at least one) pieces of equal
//   arc length; where the chord between two nodes misses a curve point by more than `tolerance`
//   (or than `sagittaShare` of the chord's length, where that is less), that point becomes a node
//   too (farthest first, recursively, as Douglas-Peucker).
// - A node at a curve point takes its exact coordinates.
// - A curve that keeps its points (the seam to a part that keeps its elements), or, unless it is
//   graded (below), whose every segment is already within a factor 1.5 of the spacing (the
//   range of an even sampling's pieces), has every point as a node and no other: an original seam
//   that fits the size stays as it was, and the nodes on the two sides of a narrow strip keep
//   facing each other.
// - An open curve with a count of its own (VolumeCurve::nodeCount: opposite sides of a narrow
//   sheet's four-sided patch get the same count, seam_counts.h) is cut into that many pieces:
//   its points when it has that many segments, else pieces spread over its spans between
//   anchors by length, with no far points added.
// - Where a span ends at a graded point (VolumeCurve::grading: a sharp corner of a sheet, where
//   a row of quads narrows into a wedge), its pieces shrink toward that point: the piece at the
//   point is as long as the span's others, and every next node lies at most the point's ratio
//   times as far from it as the node before, so that the rungs across the wedge keep that ratio.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <utility>
#include <vector>

#include "voxremesh/volume.h"

namespace voxremesh::extract {

/// A curve point turning by more than this (degrees) anchors the sampling of a junction curve.
inline constexpr double kJunctionCornerDeg = 30.0;

using Point3 = std::array<double, 3>;

/// The nodes on one edge of a junction curve.
struct JunctionEdgeNodes {
  Point3 from;                 ///< the edge's first point in the canonical direction
  std::vector<double> along;   ///< fractions in (0, 1) from `from`, ascending
  std::vector<Point3> points;  ///< the node positions, one per fraction
};

/// The nodes of all junction curves of a volume, looked up by edge and by point.
class JunctionNodes {
 public:
  /// No junctions.
  JunctionNodes() = default;

  /// Samples every curve (see the top of the file).
  /// @param curves     junction curves in world space (Volume::junctionCurves)
  /// @param spacing    target distance between nodes, > 0 (the voxel size); a curve with a
  ///                   VolumeCurve::nodeSpacing of its own is sampled at that instead, with the
  ///                   tolerance scaled alike
  /// @param tolerance  largest distance of a curve point from the chord between two nodes, > 0
  /// @param sagittaShare  where positive, the largest such distance as a share of the chord's
  ///                   length (where that is less than the tolerance)
  /// Throws std::invalid_argument when spacing or tolerance is not positive and finite.
  JunctionNodes(const std::vector<VolumeCurve>& curves, double spacing, double tolerance,
                double sagittaShare = 0.0);

  /// Samples more curves, at their own spacing and tolerance (as the constructor); an edge that
  /// already has nodes keeps them. Throws as the constructor.
  void add(const std::vector<VolumeCurve>& curves, double spacing, double tolerance,
           double sagittaShare = 0.0);

  /// True when there are no junction curves.
  bool empty() const { return edges_.empty(); }

  /// The nodes strictly inside the edge a-b (either direction) when it is an edge of a junction
  /// curve, else null.
  const JunctionEdgeNodes* edge(const Point3& a, const Point3& b) const;

  /// True when p is a point of a junction curve that is itself a node.
  bool isNodePoint(const Point3& p) const;

  /// Every node of every curve (curve points that are nodes, then the nodes inside edges), each
  /// once.
  std::vector<Point3> nodes() const;

 private:
  std::map<std::pair<Point3, Point3>, JunctionEdgeNodes> edges_;  ///< key: (lower, higher) point
  std::vector<Point3> nodePoints_;                                ///< sorted
};

}  // namespace voxremesh::extract
