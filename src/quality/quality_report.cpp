// elementQualities and assessQuality: the metrics of every element and the per-mesh summary.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "quality/channel_width.h"
#include "quality/sharp_corners.h"
#include "voxremesh/errors.h"
#include "voxremesh/quality.h"

namespace voxremesh {

namespace {

/// What a criterion measures, which elements it applies to, and its limit.
struct CriterionRule {
  const char* name;
  double ElementQuality::*value;
  bool quads;      ///< applies to quads
  bool triangles;  ///< applies to triangles
  bool isMaximum;
  double QualitySettings::*limit;  ///< for MinLength: the factor of targetSize
};

/// The rules, in the order of Criterion.
const CriterionRule kRules[kElementCriterionCount] = {
    {"warping", &ElementQuality::warpingDeg, true, false, true, &QualitySettings::maxWarpingDeg},
    {"aspect", &ElementQuality::aspectRatio, true, true, true, &QualitySettings::maxAspectRatio},
    {"quad_min_angle", &ElementQuality::minAngleDeg, true, false, false,
     &QualitySettings::minQuadAngleDeg},
    {"quad_max_angle", &ElementQuality::maxAngleDeg, true, false, true,
     &QualitySettings::maxQuadAngleDeg},
    {"tria_min_angle", &ElementQuality::minAngleDeg, false, true, false,
     &QualitySettings::minTriaAngleDeg},
    {"tria_max_angle", &ElementQuality::maxAngleDeg, false, true, true,
     &QualitySettings::maxTriaAngleDeg},
    {"skew", &ElementQuality::skewDeg, true, true, true, &QualitySettings::maxSkewDeg},
    {"jacobian_ratio", &ElementQuality::jacobianRatio, true, false, false,
     &QualitySettings::minJacobianRatio},
    {"scaled_jacobian", &ElementQuality::scaledJacobian, true, true, false,
     &QualitySettings::minScaledJacobian},
    {"taper", &ElementQuality::taper, true, false, true, &QualitySettings::maxTaper},
    {"min_length", &ElementQuality::minLength, true, true, false,
     &QualitySettings::minLengthFactor},
    {"degenerate_corner", &ElementQuality::maxAngleDeg, true, false, true,
     &QualitySettings::degenerateCornerDeg},
};

/// The names of the criteria decided from the whole mesh, after the element criteria.
const char* const kMeshCriterionNames[kCriterionCount - kElementCriterionCount] = {"folded",
                                                                                   "distance"};

/// The metric a criterion looks at under the settings.
double ElementQuality::*valueOf(Criterion c, const QualitySettings& s) {
  if (c == Criterion::JacobianRatio && s.jacobianAtGaussPoints)
    return &ElementQuality::jacobianRatioGauss;
  return kRules[static_cast<int>(c)].value;
}

double limitOf(Criterion c, const QualitySettings& s) {
  const double limit = s.*(kRules[static_cast<int>(c)].limit);
  return c == Criterion::MinLength ? limit * lengthScale(s, c, s.targetSize) : limit;
}

/// The value fails the limit (NaN always fails).
bool fails(double value, double limit, bool isMaximum) {
  if (std::isnan(value)) return true;
  return isMaximum ? value > limit : value < limit;
}

}  // namespace

bool isMaximumCriterion(Criterion c) {
  const int index = static_cast<int>(c);
  return index < kElementCriterionCount ? kRules[index].isMaximum : true;
}

double QualitySettings::*limitField(Criterion c) {
  if (c == Criterion::Folded) return nullptr;
  if (c == Criterion::Distance) return &QualitySettings::maxDistanceFactor;
  return kRules[static_cast<int>(c)].limit;
}

bool QualitySettings::*absoluteLengthField(Criterion c) {
  if (c == Criterion::MinLength) return &QualitySettings::minLengthAbsolute;
  if (c == Criterion::Distance) return &QualitySettings::distanceAbsolute;
  return nullptr;
}

double lengthScale(const QualitySettings& s, Criterion c, double size) {
  const auto absolute = absoluteLengthField(c);
  return absolute && !(s.*absolute) ? size : 1.0;
}

const char* criterionName(Criterion c) {
  const int index = static_cast<int>(c);
  return index < kElementCriterionCount ? kRules[index].name
                                        : kMeshCriterionNames[index - kElementCriterionCount];
}

std::vector<ElementQuality> elementQualities(const QuadMesh& mesh) {
  std::vector<ElementQuality> result(mesh.faces.size());
  for (const auto& face : mesh.faces)
    for (int k = 0; k < cornerCount(face); ++k)
      if (face[static_cast<std::size_t>(k)] >= mesh.points.size())
        throw std::invalid_argument("a face names point " +
                                    std::to_string(face[static_cast<std::size_t>(k)]) +
                                    " of a mesh with " + std::to_string(mesh.points.size()));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.faces.size()),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t f = r.begin(); f < r.end(); ++f) {
                        const auto& face = mesh.faces[f];
                        const int n = cornerCount(face);
                        std::array<std::array<double, 3>, 4> p{};
                        for (int k = 0; k < n; ++k)
                          p[static_cast<std::size_t>(k)] =
                              mesh.points[face[static_cast<std::size_t>(k)]];
                        result[f] = elementQuality(p, n);
                      }
                    });
  return result;
}

std::uint32_t elementFailures(const ElementQuality& quality, int corners,
                              const QualitySettings& settings) {
  if (corners != 3 && corners != 4)
    throw std::invalid_argument("an element has 3 or 4 corners, not " + std::to_string(corners));
  std::uint32_t failures = 0;
  for (int c = 0; c < kElementCriterionCount; ++c) {
    const auto criterion = static_cast<Criterion>(c);
    const CriterionRule& r = kRules[c];
    if (corners == 4 ? !r.quads : !r.triangles) continue;
    if (fails(quality.*valueOf(criterion, settings), limitOf(criterion, settings), r.isMaximum))
      failures |= 1u << c;
  }
  return failures;
}

bool QualityReport::passes() const {
  if (failingAnyShare > settings.maxFailingShare || triangleShare > settings.maxTriangleShare)
    return false;
  if (failing(Criterion::Folded) > 0 || failing(Criterion::DegenerateCorner) > 0) return false;
  return !distance || distance->max() <= distanceLimit;
}

namespace {

/// Adds the summary of a criterion decided from the whole mesh: `value` per element, failing
/// where `fails` says so (a maximum criterion with the given limit).
void addMeshCriterion(QualityReport& report, Criterion criterion, double limit,
                      const std::vector<double>& value, const std::vector<std::uint8_t>& fails) {
  CriterionSummary summary;
  summary.criterion = criterion;
  summary.limit = limit;
  summary.isMaximum = true;
  summary.applies = report.elements;
  for (std::size_t f = 0; f < report.elements; ++f) {
    summary.worst = std::max(summary.worst, value[f]);
    if (!fails[f]) continue;
    ++summary.failing;
    report.elementFailures[f] |= 1u << static_cast<int>(criterion);
  }
  summary.share = report.elements ? double(summary.failing) / double(report.elements) : 0.0;
  report.criteria.push_back(summary);
}

}  // namespace

namespace {

/// Per face, the size its minimum length is judged against: the target size, or the width of the
/// channel it lies in where the face is too short for the target size and the channel narrow
/// enough to excuse it (narrower than twice its length: a wider channel would not, and is not
/// measured beyond that).
std::vector<double> judgedSizes(const QuadMesh& mesh, const std::vector<ElementQuality>& values,
                                const QualitySettings& s, const std::vector<MeshCurve>* channels) {
  using namespace geom;  // NOLINT: the vector operators
  std::vector<double> sizes(mesh.faces.size(), s.targetSize);
  if (!channels || channels->empty() || s.minLengthAbsolute) return sizes;
  std::vector<std::size_t> shortFaces;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (fails(values[f].minLength, s.minLengthFactor * s.targetSize, false))
      shortFaces.push_back(f);
  if (shortFaces.empty()) return sizes;
  const quality::ChannelWidth width(*channels, s.targetSize);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, shortFaces.size()),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i < r.end(); ++i) {
                        const auto& face = mesh.faces[shortFaces[i]];
                        const bool triangle = cornerCount(face) == 3;
                        const int n = triangle ? 3 : 4;
                        Vec3 centroid{0.0, 0.0, 0.0};
                        for (int k = 0; k < n; ++k)
                          centroid = centroid + mesh.points[face[std::size_t(k)]];
                        centroid = centroid * (1.0 / n);
                        const auto& p = mesh.points;
                        const Vec3 normal = elementNormal(p[face[0]], p[face[1]], p[face[2]],
                                                          p[face[triangle ? 2 : 3]], triangle);
                        // Only a channel narrower than twice the face's length excuses it.
                        const double cap = 2.0 * values[shortFaces[i]].minLength;
                        const double channel = width.at(centroid, normal, cap);
                        if (channel < cap) sizes[shortFaces[i]] = channel;
                      }
                    });
  return sizes;
}

/// Adds a criterion's weighted penalty (indexPenalty) to an element's quality index.
void addPenalty(double& index, double value, const IndexThresholds& t, double limit,
                bool isMaximum) {
  index += t.weight * indexPenalty(value, t, limit, isMaximum);
}

/// The criteria a triangle filling a sharp corner fails by the corner's angle alone.
bool forcedByCorner(Criterion c) {
  return c == Criterion::AspectRatio || c == Criterion::TriaMinAngle || c == Criterion::Skew ||
         c == Criterion::ScaledJacobian;
}

/// Per face, 1 for a triangle filling a corner of `original` sharper than the triangle angle
/// limit (cornerFillingTriangles); none without an original or its curves, and none (the
/// corners not sought) where no triangle fails a criterion such a corner could excuse.
std::vector<std::uint8_t> sharpCornerTriangles(const QuadMesh& mesh,
                                               const std::vector<ElementQuality>& values,
                                               const QuadMesh* original,
                                               const std::vector<MeshCurve>* channels,
                                               const QualitySettings& s) {
  std::vector<std::uint8_t> none(mesh.faces.size(), 0);
  if (!original || !channels) return none;
  bool excusable = false;
  for (std::size_t f = 0; f < mesh.faces.size() && !excusable; ++f) {
    if (cornerCount(mesh.faces[f]) != 3) continue;
    for (int c = 0; c < kElementCriterionCount && !excusable; ++c) {
      const auto criterion = static_cast<Criterion>(c);
      excusable = forcedByCorner(criterion) && fails(values[f].*valueOf(criterion, s),
                                                     limitOf(criterion, s), kRules[c].isMaximum);
    }
  }
  if (!excusable) return none;
  quality::RidgeEdges ridges(channels);
  return quality::cornerFillingTriangles(
      mesh, quality::sharpCorners(*original, ridges, s.minTriaAngleDeg), s.minTriaAngleDeg,
      s.maxTriaAngleDeg);
}

}  // namespace

QualityReport assessQuality(const QuadMesh& mesh, const QualitySettings& settings,
                            const QuadMesh* original, const std::vector<MeshCurve>* channels) {
  checkQualitySettings(settings);
  QualityReport report;
  report.settings = settings;
  if (report.settings.targetSize == 0.0) {
    report.settings.targetSize = medianEdgeLength(mesh);
    if (!(report.settings.targetSize > 0.0))
      throw SettingError("quality: no target size given and the mesh has no edge to take one from");
  }
  const QualitySettings& s = report.settings;
  report.elementValues = elementQualities(mesh);
  report.elements = mesh.faces.size();
  report.elementFailures.assign(report.elements, 0);
  report.qualityIndex.assign(report.elements, 0.0);
  report.judgedSize = judgedSizes(mesh, report.elementValues, s, channels);
  for (double size : report.judgedSize)
    if (size < s.targetSize) ++report.narrowChannelElements;
  const std::vector<std::uint8_t> fillsCorner =
      sharpCornerTriangles(mesh, report.elementValues, original, channels, s);
  report.sharpCornerElements =
      std::size_t(std::count(fillsCorner.begin(), fillsCorner.end(), std::uint8_t(1)));
  for (int c = 0; c < kElementCriterionCount; ++c) {
    const auto criterion = static_cast<Criterion>(c);
    const CriterionRule& r = kRules[c];
    CriterionSummary summary;
    summary.criterion = criterion;
    summary.limit = limitOf(criterion, s);
    summary.isMaximum = r.isMaximum;
    bool first = true;
    for (std::size_t f = 0; f < report.elements; ++f) {
      const bool quad = cornerCount(mesh.faces[f]) == 4;
      if (quad ? !r.quads : !r.triangles) continue;
      const double value = report.elementValues[f].*valueOf(criterion, s);
      ++summary.applies;
      if (first || (r.isMaximum ? value > summary.worst : value < summary.worst) ||
          std::isnan(value)) {
        summary.worst = value;
        first = false;
      }
      const double limit = criterion == Criterion::MinLength
                               ? s.minLengthFactor * lengthScale(s, criterion, report.judgedSize[f])
                               : summary.limit;
      if (fillsCorner[f] && forcedByCorner(criterion)) continue;  // excused
      const double scale = criterion == Criterion::MinLength && report.judgedSize[f] > 0.0
                               ? lengthScale(s, criterion, report.judgedSize[f])
                               : 1.0;
      addPenalty(report.qualityIndex[f], value / scale, s.index[std::size_t(c)], limit / scale,
                 r.isMaximum);
      if (fails(value, limit, r.isMaximum)) {
        ++summary.failing;
        report.elementFailures[f] |= 1u << c;
      }
    }
    summary.share = report.elements ? double(summary.failing) / double(report.elements) : 0.0;
    report.criteria.push_back(summary);
  }
  // Folded: the value is 1 for a folded element, the limit 0 (none allowed).
  // With an original, its feature lines and junction curves are the knife edges it has.
  const std::vector<std::uint8_t> folded = foldedFaces(mesh, original ? channels : nullptr);
  addMeshCriterion(report, Criterion::Folded, 0.0,
                   std::vector<double>(folded.begin(), folded.end()), folded);
  // The distance is judged (and sampled, at half the size) against the size it scales with.
  const double distanceSize = s.distanceSize > 0.0 ? s.distanceSize : s.targetSize;
  const double distanceScale = lengthScale(s, Criterion::Distance, distanceSize);
  report.distanceLimit = s.maxDistanceFactor * distanceScale;
  std::vector<double> faceDistance(report.elements, 0.0);
  std::vector<std::uint8_t> far(report.elements, 0);
  if (original) {
    report.distance = surfaceDistance(mesh, *original, 0.5 * distanceSize);
    faceDistance = report.distance->faceDistance;
    for (std::size_t f = 0; f < report.elements; ++f)
      far[f] = faceDistance[f] > report.distanceLimit ? 1 : 0;
  }
  addMeshCriterion(report, Criterion::Distance, report.distanceLimit, faceDistance, far);
  for (std::size_t f = 0; f < report.elements; ++f) {
    addPenalty(report.qualityIndex[f], folded[f], s.index[std::size_t(Criterion::Folded)], 0.0,
               true);
    if (original)
      addPenalty(report.qualityIndex[f], faceDistance[f] / distanceScale,
                 s.index[std::size_t(Criterion::Distance)], s.maxDistanceFactor, true);
  }
  for (std::size_t f = 0; f < report.elements; ++f) {
    if (cornerCount(mesh.faces[f]) == 4)
      ++report.quads;
    else
      ++report.triangles;
    if (report.elementFailures[f] != 0) ++report.failingAny;
  }
  if (report.elements) {
    double indexSum = 0.0;
    for (const double index : report.qualityIndex) indexSum += index;
    report.meanQualityIndex = indexSum / double(report.elements);
    report.failingAnyShare = double(report.failingAny) / double(report.elements);
    report.triangleShare = double(report.triangles) / double(report.elements);
  }
  return report;
}

}  // namespace voxremesh
