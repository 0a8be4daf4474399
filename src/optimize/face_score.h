// How well a face does against the quality criteria, as the optimisation steps that choose
// between alternatives (point moves, edge rotations) compare them: the number of failed criteria
// first, then a smooth penalty that keeps a margin inside the limits.
#pragma once

#include <array>
#include <cstdint>

#include "voxremesh/quad_mesh.h"
#include "voxremesh/quality.h"

namespace voxremesh::opt {

/// Fewer failed criteria first, then the smaller penalty (facePenalty).
struct Score {
  int failures = 0;
  double penalty = 0.0;
  /// True when this score is strictly better than `other`.
  bool betterThan(const Score& other) const {
    if (failures != other.failures) return failures < other.failures;
    return penalty < other.penalty - 1e-12;
  }
  Score& operator+=(const Score& other) {
    failures += other.failures;
    penalty += other.penalty;
    return *this;
  }
};

/// A smooth measure of how close a face with the given quality comes to failing: each metric is
/// penalised (squared) beyond a soft limit set inside the criterion's limit, so that the steps
/// keep a margin; NaN scores worst (1e30).
/// @param q        the face's metrics (elementQuality)
/// @param corners  3 or 4
/// @param s        the criteria; s.targetSize > 0 for the length term
double facePenalty(const ElementQuality& q, int corners, const QualitySettings& s);

/// A face whose minimum element length (quality.h) is under this fraction of the criterion's limit
/// (QualitySettings::minLengthFactor x targetSize) is degenerate: a sliver whose explicit time
/// step would be a tenth of the allowed one, worse than any mild failure elsewhere.
inline constexpr double kDegenerateLengthFraction = 0.1;

/// The minimum element length under which a face is degenerate (kDegenerateLengthFraction of the
/// minimum length limit at targetSize).
inline double degenerateLength(const QualitySettings& s) {
  return kDegenerateLengthFraction * s.minLengthFactor *
         lengthScale(s, Criterion::MinLength, s.targetSize);
}

/// The score of a face with the given metrics: the number of criteria it fails (a degenerate face
/// counts as failing every criterion, kCriterionCount, so that no step trades mild failures
/// round it for a sliver) and facePenalty.
/// @param q        the face's metrics (elementQuality)
/// @param corners  3 or 4
/// @param s        the criteria; s.targetSize > 0
Score scoreOfQuality(const ElementQuality& q, int corners, const QualitySettings& s);

/// The score of one face of `mesh` (its corners must name existing points): scoreOfQuality of
/// its metrics, computed without the degrees of angles that lie inside their soft limits (the
/// same score, bit for bit).
Score faceScore(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face,
                const QualitySettings& settings);

/// The criteria one face of `mesh` fails: elementFailures (quality.h) of its metrics, computed as
/// faceScore computes them (the same mask as from elementQuality, found without the degrees of
/// angles inside their soft limits).
/// Preconditions: every corner names an existing point; settings pass checkQualitySettings.
std::uint32_t faceFailures(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face,
                           const QualitySettings& settings);

}  // namespace voxremesh::opt
