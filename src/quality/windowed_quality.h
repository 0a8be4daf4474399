// The element metrics as the optimisation's face score needs them (src/optimize/face_score.cpp):
// an angle metric known to lie inside a window, where the score does not depend on its value, is
// not turned into degrees (the atan2 that is most of a metric's cost) but reported as the window's
// bound.
#pragma once

#include <array>

#include "voxremesh/quality.h"

namespace voxremesh {

/// Bounds, in degrees, of the angle metrics inside which their exact values do not matter to
/// the caller, with the ordering keys elementQuality compares angles by (see makeAngleWindow).
struct AngleWindow {
  double minAngleDeg = 0.0;    ///< an interior angle at or above it is reported as it
  double maxAngleDeg = 180.0;  ///< an interior angle at or below it is reported as it
  double maxWarpingDeg = 180.0;
  double maxSkewDeg = 90.0;
  double minAngleKey = 0.0, maxAngleKey = 0.0, maxWarpingKey = 0.0, minLineKey = 0.0;
};

/// A window with the given bounds (degrees; min and max angle within 0..180, warping within
/// 0..180, skew within 0..90) and their keys.
AngleWindow makeAngleWindow(double minAngleDeg, double maxAngleDeg, double maxWarpingDeg,
                            double maxSkewDeg);

/// elementQuality(p, corners), except that minAngleDeg, maxAngleDeg, warpingDeg and skewDeg are
/// the window's bound where the metric lies inside it by a margin far above rounding (checked on
/// the atan2-free keys): the element fails a criterion whose limit lies outside the window exactly
/// when it fails it with elementQuality's values. jacobianRatioGauss is left at 1 unless
/// `gaussJacobian`. Precondition: corners is 3 or 4 (std::invalid_argument otherwise).
ElementQuality elementQualityWithin(const std::array<std::array<double, 3>, 4>& p, int corners,
                                    const AngleWindow& window, bool gaussJacobian);

}  // namespace voxremesh
