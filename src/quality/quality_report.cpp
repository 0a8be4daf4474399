// elementQualities and assessQuality: the metrics of every element and the per-mesh summary.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "voxremesh/errors.h"
#include "voxremesh/quality.h"

namespace voxremesh {

namespace {

/// What a criterion measures, which elements it applies to, and its limit.
struct CriterionRule {
  double (*value)(const ElementQuality&);
  bool quads;      ///< applies to quads
  bool triangles;  ///< applies to triangles
  bool isMaximum;
};

CriterionRule rule(Criterion c) {
  switch (c) {
    case Criterion::Warping:
      return {[](const ElementQuality& q) { return q.warpingDeg; }, true, false, true};
    case Criterion::AspectRatio:
      return {[](const ElementQuality& q) { return q.aspectRatio; }, true, true, true};
    case Criterion::QuadMinAngle:
      return {[](const ElementQuality& q) { return q.minAngleDeg; }, true, false, false};
    case Criterion::QuadMaxAngle:
      return {[](const ElementQuality& q) { return q.maxAngleDeg; }, true, false, true};
    case Criterion::TriaMinAngle:
      return {[](const ElementQuality& q) { return q.minAngleDeg; }, false, true, false};
    case Criterion::TriaMaxAngle:
      return {[](const ElementQuality& q) { return q.maxAngleDeg; }, false, true, true};
    case Criterion::Skew:
      return {[](const ElementQuality& q) { return q.skewDeg; }, true, true, true};
    case Criterion::JacobianRatio:
      return {[](const ElementQuality& q) { return q.jacobianRatio; }, true, false, false};
    case Criterion::ScaledJacobian:
      return {[](const ElementQuality& q) { return q.scaledJacobian; }, true, true, false};
    case Criterion::Taper:
      return {[](const ElementQuality& q) { return q.taper; }, true, false, true};
    case Criterion::MinLength:
      break;
  }
  return {[](const ElementQuality& q) { return q.minLength; }, true, true, false};
}

double limitOf(Criterion c, const QualitySettings& s) {
  switch (c) {
    case Criterion::Warping:
      return s.maxWarpingDeg;
    case Criterion::AspectRatio:
      return s.maxAspectRatio;
    case Criterion::QuadMinAngle:
      return s.minQuadAngleDeg;
    case Criterion::QuadMaxAngle:
      return s.maxQuadAngleDeg;
    case Criterion::TriaMinAngle:
      return s.minTriaAngleDeg;
    case Criterion::TriaMaxAngle:
      return s.maxTriaAngleDeg;
    case Criterion::Skew:
      return s.maxSkewDeg;
    case Criterion::JacobianRatio:
      return s.minJacobianRatio;
    case Criterion::ScaledJacobian:
      return s.minScaledJacobian;
    case Criterion::Taper:
      return s.maxTaper;
    case Criterion::MinLength:
      break;
  }
  return s.minLengthFactor * s.targetSize;
}

/// The value fails the limit (NaN always fails).
bool fails(double value, double limit, bool isMaximum) {
  if (std::isnan(value)) return true;
  return isMaximum ? value > limit : value < limit;
}

}  // namespace

const char* criterionName(Criterion c) {
  switch (c) {
    case Criterion::Warping:
      return "warping";
    case Criterion::AspectRatio:
      return "aspect";
    case Criterion::QuadMinAngle:
      return "quad_min_angle";
    case Criterion::QuadMaxAngle:
      return "quad_max_angle";
    case Criterion::TriaMinAngle:
      return "tria_min_angle";
    case Criterion::TriaMaxAngle:
      return "tria_max_angle";
    case Criterion::Skew:
      return "skew";
    case Criterion::JacobianRatio:
      return "jacobian_ratio";
    case Criterion::ScaledJacobian:
      return "scaled_jacobian";
    case Criterion::Taper:
      return "taper";
    case Criterion::MinLength:
      break;
  }
  return "min_length";
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

bool QualityReport::passes() const {
  if (failingAny > 0 || triangleShare > settings.maxTriangleShare) return false;
  return !distance || distance->max() <= distanceLimit;
}

QualityReport assessQuality(const QuadMesh& mesh, const QualitySettings& settings,
                            const QuadMesh* original) {
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
  for (int c = 0; c < kCriterionCount; ++c) {
    const auto criterion = static_cast<Criterion>(c);
    const CriterionRule r = rule(criterion);
    CriterionSummary summary;
    summary.criterion = criterion;
    summary.limit = limitOf(criterion, s);
    summary.isMaximum = r.isMaximum;
    bool first = true;
    for (std::size_t f = 0; f < report.elements; ++f) {
      const bool quad = cornerCount(mesh.faces[f]) == 4;
      if (quad ? !r.quads : !r.triangles) continue;
      const double value = r.value(report.elementValues[f]);
      ++summary.applies;
      if (first || (r.isMaximum ? value > summary.worst : value < summary.worst) ||
          std::isnan(value)) {
        summary.worst = value;
        first = false;
      }
      if (fails(value, summary.limit, r.isMaximum)) {
        ++summary.failing;
        report.elementFailures[f] |= 1u << c;
      }
    }
    summary.share = report.elements ? double(summary.failing) / double(report.elements) : 0.0;
    report.criteria.push_back(summary);
  }
  for (std::size_t f = 0; f < report.elements; ++f) {
    if (cornerCount(mesh.faces[f]) == 4)
      ++report.quads;
    else
      ++report.triangles;
    if (report.elementFailures[f] != 0) ++report.failingAny;
  }
  if (report.elements) {
    report.failingAnyShare = double(report.failingAny) / double(report.elements);
    report.triangleShare = double(report.triangles) / double(report.elements);
  }
  report.distanceLimit = s.maxDistanceFactor * s.targetSize;
  if (original) report.distance = surfaceDistance(mesh, *original);
  return report;
}

}  // namespace voxremesh
