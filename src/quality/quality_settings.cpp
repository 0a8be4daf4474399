// checkQualitySettings and medianEdgeLength: the settings' ranges and the default target size.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geometry/vec3.h"
#include "voxremesh/errors.h"
#include "voxremesh/quality.h"

namespace voxremesh {

namespace {

void requireRange(const char* name, double value, double low, double high) {
  if (!std::isfinite(value) || value < low || value > high) {
    throw SettingError("quality setting " + std::string(name) + " = " + std::to_string(value) +
                       " is outside " + std::to_string(low) + " .. " + std::to_string(high));
  }
}

void requireOrder(const char* low, double lowValue, const char* high, double highValue) {
  if (lowValue > highValue) {
    throw SettingError("quality setting " + std::string(low) + " = " + std::to_string(lowValue) +
                       " exceeds " + high + " = " + std::to_string(highValue));
  }
}

/// Checks that a criterion's index thresholds are finite, ordered (ideal, good, warn, worst
/// growing worse) and weighted by a finite weight >= 0.
void checkIndexThresholds(Criterion c, const QualitySettings& s) {
  const IndexThresholds& t = s.index[static_cast<std::size_t>(c)];
  const std::string name = std::string("quality index of ") + criterionName(c);
  const double sign = isMaximumCriterion(c) ? 1.0 : -1.0;
  const double values[] = {t.ideal, t.good, t.warn, t.worst};
  const char* const names[] = {"ideal", "good", "warn", "worst"};
  for (std::size_t k = 0; k < 4; ++k) {
    if (!std::isfinite(values[k]))
      throw SettingError(name + ": " + names[k] + " = " + std::to_string(values[k]) +
                         " is not a finite number");
    if (k > 0 && sign * values[k] < sign * values[k - 1])
      throw SettingError(name + ": " + names[k] + " = " + std::to_string(values[k]) +
                         (sign > 0 ? " is below " : " is above ") + names[k - 1] + " = " +
                         std::to_string(values[k - 1]) + " (a " +
                         (sign > 0 ? "larger" : "smaller") + " value is worse)");
  }
  requireRange((name + " weight").c_str(), t.weight, 0.0, 1e300);
}

}  // namespace

void checkQualitySettings(const QualitySettings& s) {
  constexpr double kHuge = 1e300;
  requireRange("maxWarpingDeg", s.maxWarpingDeg, 0.0, 180.0);
  requireRange("maxAspectRatio", s.maxAspectRatio, 1.0, kHuge);
  requireRange("minQuadAngleDeg", s.minQuadAngleDeg, 0.0, 360.0);
  requireRange("maxQuadAngleDeg", s.maxQuadAngleDeg, 0.0, 360.0);
  requireRange("minTriaAngleDeg", s.minTriaAngleDeg, 0.0, 180.0);
  requireRange("maxTriaAngleDeg", s.maxTriaAngleDeg, 0.0, 180.0);
  requireOrder("minQuadAngleDeg", s.minQuadAngleDeg, "maxQuadAngleDeg", s.maxQuadAngleDeg);
  requireOrder("minTriaAngleDeg", s.minTriaAngleDeg, "maxTriaAngleDeg", s.maxTriaAngleDeg);
  requireRange("maxSkewDeg", s.maxSkewDeg, 0.0, 90.0);
  requireRange("minJacobianRatio", s.minJacobianRatio, -1.0, 1.0);
  requireRange("minScaledJacobian", s.minScaledJacobian, -1.0, 1.0);
  requireRange("maxTaper", s.maxTaper, 0.0, kHuge);
  requireRange("minLengthFactor", s.minLengthFactor, 0.0, kHuge);
  requireRange("targetSize", s.targetSize, 0.0, kHuge);
  requireRange("maxTriangleShare", s.maxTriangleShare, 0.0, 1.0);
  requireRange("maxDistanceFactor", s.maxDistanceFactor, 0.0, kHuge);
  requireRange("distanceSize", s.distanceSize, 0.0, kHuge);
  for (int c = 0; c < kCriterionCount; ++c) checkIndexThresholds(static_cast<Criterion>(c), s);
}

double medianEdgeLength(const QuadMesh& mesh) {
  std::vector<std::pair<CornerIndex, CornerIndex>> edges;
  edges.reserve(mesh.faces.size() * 4);
  for (const auto& face : mesh.faces) {
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k) {
      const CornerIndex a = face[static_cast<std::size_t>(k)];
      const CornerIndex b = face[static_cast<std::size_t>((k + 1) % n)];
      if (a >= mesh.points.size() || b >= mesh.points.size())
        throw std::invalid_argument("a face names point " + std::to_string(std::max(a, b)) +
                                    " of a mesh with " + std::to_string(mesh.points.size()));
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  if (edges.empty()) return 0.0;
  std::vector<double> lengths;
  lengths.reserve(edges.size());
  for (const auto& [a, b] : edges)
    lengths.push_back(geom::distance(mesh.points[a], mesh.points[b]));
  const std::size_t middle = lengths.size() / 2;
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(middle),
                   lengths.end());
  double median = lengths[middle];
  if (lengths.size() % 2 == 0) {
    median =
        0.5 * (median + *std::max_element(lengths.begin(),
                                          lengths.begin() + static_cast<std::ptrdiff_t>(middle)));
  }
  return median;
}

}  // namespace voxremesh
