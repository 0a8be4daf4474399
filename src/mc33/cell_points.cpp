// Edge crossing points and component centroids of a cell (include/voxremesh/mc33.h).
#include "voxremesh/mc33.h"

namespace voxremesh::mc33 {

float edgeCrossing(const CellValues& values, int edge) noexcept {
  const float a = values[kEdgeCorners[edge][0]];
  const float b = values[kEdgeCorners[edge][1]];
  // a and b differ in sign (one < 0, the other >= 0), so a - b != 0 and the ratio is in [0,1];
  // the clamp only guards against rounding in a - b.
  const float t = a / (a - b);
  return t < 0.0F ? 0.0F : (t > 1.0F ? 1.0F : t);
}

CellPoint edgePoint(const CellValues& values, int edge) noexcept {
  const int first = kEdgeCorners[edge][0];
  CellPoint point{static_cast<float>(first & 1), static_cast<float>((first >> 1) & 1),
                  static_cast<float>((first >> 2) & 1)};
  point[edge / 4] = edgeCrossing(values, edge);
  return point;
}

CellPoints cellPoints(const CellValues& values, const CellTopology& topology) noexcept {
  CellPoints points;
  std::array<int, kMaxComponents> counts{};
  for (int l = 0; l < topology.loopCount; ++l) {
    const int c = topology.loopComponent[l];
    counts[c] += topology.loopSize(l);
    for (int i = topology.loopBegin[l]; i < topology.loopBegin[l + 1]; ++i) {
      const int e = topology.loopEdges[i];
      const CellPoint p = edgePoint(values, e);
      points.edgePoints[e] = p;
      for (int k = 0; k < 3; ++k) points.centroids[c][k] += p[k];
    }
  }
  for (int c = 0; c < topology.componentCount; ++c) {
    const float scale = 1.0F / static_cast<float>(counts[c]);
    for (int k = 0; k < 3; ++k) points.centroids[c][k] *= scale;
  }
  return points;
}

}  // namespace voxremesh::mc33
