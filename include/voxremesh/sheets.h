// Sheets: the clean, manifold, consistently oriented pieces a part is split into before it is
// written into a volume, with the curves extraction must keep (boundary loops, feature lines,
// feature points, junction curves).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "voxremesh/fe_model.h"

namespace voxremesh {

/// Index of a point in Sheet::points.
using PointIndex = std::uint32_t;

/// Marks the unused fourth corner of a triangle in Sheet::faces.
constexpr PointIndex kNoPoint = std::numeric_limits<PointIndex>::max();

/// A polyline through sheet points; closed polylines do not repeat their first point.
struct Polyline {
  std::vector<PointIndex> points;
  bool closed = false;
};

/// One manifold, consistently oriented sheet (with boundary) of a part.
struct Sheet {
  Id part = 0;
  std::vector<std::array<double, 3>> points;  ///< positions
  std::vector<Id> pointNodeIds;               ///< the model node ID of each point
  /// Corners in a consistent orientation; a triangle has faces[f][3] == kNoPoint.
  std::vector<std::array<PointIndex, 4>> faces;
  std::vector<Id> faceShellIds;         ///< the model shell ID of each face
  std::vector<bool> faceFlipped;        ///< the face's corner order is reversed from the model's
  std::vector<Polyline> boundaryLoops;  ///< closed, following the boundary
  std::vector<Polyline> featureLines;   ///< chains of edges whose dihedral angle exceeds the limit
  std::vector<PointIndex> featurePoints;  ///< corners of feature lines and of boundary loops
  /// Curves along which this sheet met another sheet or part (non-manifold edges of the part, or
  /// nodes shared with another part), to be meshed conformingly on both sides.
  std::vector<Polyline> junctionCurves;
};

/// Thresholds for feature detection.
struct SheetSettings {
  double featureAngleDeg = 30.0;  ///< an edge is a feature when its dihedral angle exceeds this
  double cornerAngleDeg = 30.0;   ///< a boundary or feature-line point is a corner when the curve
                                  ///< turns by more than this there
};

}  // namespace voxremesh
