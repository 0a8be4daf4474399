// RidgeEdges: which segments of a mesh lie along the feature lines and junction curves of its
// original (the knife edges and seams a new mesh must follow). Internal to src/quality.
#pragma once

#include <vector>

#include "geometry/polyline_index.h"
#include "geometry/safe_box.h"
#include "geometry/vec3.h"
#include "voxremesh/quad_mesh.h"

namespace voxremesh::quality {

/// The curves of a set other than boundary loops, indexed for "does this segment lie along one".
class RidgeEdges {
 public:
  /// Indexes `curves` lazily, on the first query; null (or empty) means none.
  explicit RidgeEdges(const std::vector<MeshCurve>* curves)
      : curves_(curves && !curves->empty() ? curves : nullptr) {}

  /// True when the segment a-b lies along one of the curves: both ends within 1e-4 of its length
  /// of the curve and its middle within 5 % of its length.
  bool along(const geom::Vec3& a, const geom::Vec3& b);

 private:
  void build();

  const std::vector<MeshCurve>* curves_;
  bool built_ = false;
  std::vector<PolylineIndex> indexes_;
  std::vector<geom::Box> boxes_;
};

}  // namespace voxremesh::quality
