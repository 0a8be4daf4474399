// faceScore and facePenalty: the comparison the optimisation steps choose by (face_score.h).
#include "optimize/face_score.h"

#include <cmath>

#include "quality/windowed_quality.h"

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

/// The soft limits of the angle metrics, set inside the criteria's limits: within them an angle
/// adds nothing to the penalty and fails nothing.
double softMinAngle(const QualitySettings& s, int corners) {
  return corners == 4 ? s.minQuadAngleDeg + 10.0 : s.minTriaAngleDeg + 5.0;
}
double softMaxAngle(const QualitySettings& s, int corners) {
  return corners == 4 ? s.maxQuadAngleDeg - 10.0 : s.maxTriaAngleDeg - 10.0;
}
double softWarping(const QualitySettings& s) {
  return 0.7 * s.maxWarpingDeg;
}
double softSkew(const QualitySettings& s) {
  return 0.8 * s.maxSkewDeg;
}
double softMinLength(const QualitySettings& s) {
  return s.minLengthAbsolute ? s.minLengthFactor + 0.15 * s.targetSize
                             : (s.minLengthFactor + 0.15) * s.targetSize;
}

/// The windows of faceScore's metrics for triangles and quads under `s`, kept per thread for the
/// settings they were last made for (making them costs more than scoring a face).
const AngleWindow& windowFor(const QualitySettings& s, int corners) {
  struct Cached {
    double limits[6] = {NAN, NAN, NAN, NAN, NAN, NAN};
    AngleWindow windows[2];
  };
  thread_local Cached cached;
  const double limits[6] = {s.minQuadAngleDeg, s.maxQuadAngleDeg, s.minTriaAngleDeg,
                            s.maxTriaAngleDeg, s.maxWarpingDeg,   s.maxSkewDeg};
  bool same = true;
  for (int i = 0; i < 6; ++i) same = same && limits[i] == cached.limits[i];
  if (!same) {
    for (int i = 0; i < 6; ++i) cached.limits[i] = limits[i];
    for (const int n : {3, 4})
      cached.windows[n - 3] =
          makeAngleWindow(softMinAngle(s, n), softMaxAngle(s, n), softWarping(s), softSkew(s));
  }
  return cached.windows[corners - 3];
}

}  // namespace

double facePenalty(const ElementQuality& q, int corners, const QualitySettings& s) {
  const double jacobian = s.jacobianAtGaussPoints ? q.jacobianRatioGauss : q.jacobianRatio;
  double p = beyondMax(q.aspectRatio, 0.8 * s.maxAspectRatio, 1.0) +
             beyondMax(q.skewDeg, softSkew(s), 10.0) +
             beyondMin(q.scaledJacobian, s.minScaledJacobian + 0.15, 0.1) +
             beyondMin(q.minLength, softMinLength(s), 0.1 * s.targetSize);
  if (corners == 4) {
    p += beyondMax(q.warpingDeg, softWarping(s), 5.0) +
         beyondMin(q.minAngleDeg, softMinAngle(s, 4), 10.0) +
         beyondMax(q.maxAngleDeg, softMaxAngle(s, 4), 10.0) +
         beyondMin(jacobian, s.minJacobianRatio + 0.1, 0.1) +
         beyondMax(q.taper, s.maxTaper - 0.15, 0.1);
  } else {
    p += beyondMin(q.minAngleDeg, softMinAngle(s, 3), 10.0) +
         beyondMax(q.maxAngleDeg, softMaxAngle(s, 3), 10.0);
  }
  return std::isnan(p) ? 1e30 : p;
}

Score scoreOfQuality(const ElementQuality& q, int corners, const QualitySettings& s) {
  Score score;
  score.failures = q.minLength >= degenerateLength(s)
                       ? __builtin_popcount(elementFailures(q, corners, s))
                       : kCriterionCount;
  score.penalty = facePenalty(q, corners, s);
  return score;
}

namespace {

/// The metrics of a face as faceScore needs them: angles inside their soft limits add nothing
/// and fail nothing, so their degrees are not computed.
ElementQuality windowedQuality(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face,
                               const QualitySettings& settings) {
  const int n = cornerCount(face);
  std::array<std::array<double, 3>, 4> p{};
  for (int k = 0; k < n; ++k) p[std::size_t(k)] = mesh.points[face[std::size_t(k)]];
  return elementQualityWithin(p, n, windowFor(settings, n), settings.jacobianAtGaussPoints);
}

}  // namespace

Score faceScore(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face,
                const QualitySettings& settings) {
  return scoreOfQuality(windowedQuality(mesh, face, settings), cornerCount(face), settings);
}

std::uint32_t faceFailures(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face,
                           const QualitySettings& settings) {
  return elementFailures(windowedQuality(mesh, face, settings), cornerCount(face), settings);
}

}  // namespace voxremesh::opt
