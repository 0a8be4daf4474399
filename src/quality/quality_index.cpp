// indexPenalty: the quality index's penalty of one value (quality.h, "Quality index").
#include <algorithm>
#include <array>
#include <cmath>

#include "voxremesh/quality.h"

namespace voxremesh {

namespace {

/// The penalties at the thresholds good, warn, limit and worst.
constexpr std::array<double, 4> kPenalties{0.0, 0.8, 1.0, 10.0};

}  // namespace

double indexPenalty(double value, const IndexThresholds& t, double limit, bool isMaximum) {
  if (std::isnan(value)) return kPenalties.back();
  // Measured so that larger is worse.
  const double sign = isMaximum ? 1.0 : -1.0;
  // A limit outside warn .. worst moves them to it.
  const double fail = sign * limit;
  const double warn = std::min(sign * t.warn, fail), worst = std::max(sign * t.worst, fail);
  const std::array<double, 4> at{std::min(sign * t.good, warn), warn, fail, worst};
  const double v = sign * value;
  if (v <= at[0]) return kPenalties[0];
  for (std::size_t k = 1; k < at.size(); ++k)
    if (v <= at[k])
      return kPenalties[k - 1] +
             (kPenalties[k] - kPenalties[k - 1]) * (v - at[k - 1]) / (at[k] - at[k - 1]);
  const double span = at[3] - at[2];
  return span > 0.0 ? kPenalties[3] + (kPenalties[3] - kPenalties[2]) * (v - at[3]) / span
                    : kPenalties[3];
}

}  // namespace voxremesh
