// faceScore and facePenalty: the comparison the optimisation steps choose by (face_score.h).
#include "optimize/face_score.h"

#include <cmath>

namespace voxremesh::opt {

namespace {

/// The square of how far `value` is beyond `soft` (in units of `scale`; 0 when within it).
double beyondMax(double value, double soft, double scale) {
  const double d = (value - soft) / scale;
  return d > 0.0 ? d * d : 0.0;
}
double beyondMin(double value, double soft, double scale) {
  return beyondMax(soft, value, scale);
}

}  // namespace

double facePenalty(const ElementQuality& q, int corners, const QualitySettings& s) {
  const double jacobian = s.jacobianAtGaussPoints ? q.jacobianRatioGauss : q.jacobianRatio;
  double p = beyondMax(q.aspectRatio, 0.8 * s.maxAspectRatio, 1.0) +
             beyondMax(q.skewDeg, 0.8 * s.maxSkewDeg, 10.0) +
             beyondMin(q.scaledJacobian, s.minScaledJacobian + 0.15, 0.1) +
             beyondMin(q.minLength, (s.minLengthFactor + 0.15) * s.targetSize, 0.1 * s.targetSize);
  if (corners == 4) {
    p += beyondMax(q.warpingDeg, 0.7 * s.maxWarpingDeg, 5.0) +
         beyondMin(q.minAngleDeg, s.minQuadAngleDeg + 10.0, 10.0) +
         beyondMax(q.maxAngleDeg, s.maxQuadAngleDeg - 10.0, 10.0) +
         beyondMin(jacobian, s.minJacobianRatio + 0.1, 0.1) +
         beyondMax(q.taper, s.maxTaper - 0.15, 0.1);
  } else {
    p += beyondMin(q.minAngleDeg, s.minTriaAngleDeg + 5.0, 10.0) +
         beyondMax(q.maxAngleDeg, s.maxTriaAngleDeg - 10.0, 10.0);
  }
  return std::isnan(p) ? 1e30 : p;
}

Score faceScore(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face,
                const QualitySettings& settings) {
  const int n = cornerCount(face);
  std::array<std::array<double, 3>, 4> p{};
  for (int k = 0; k < n; ++k) p[std::size_t(k)] = mesh.points[face[std::size_t(k)]];
  const ElementQuality q = elementQuality(p, n);
  Score score;
  score.failures = __builtin_popcount(elementFailures(q, n, settings));
  score.penalty = facePenalty(q, n, settings);
  return score;
}

}  // namespace voxremesh::opt
