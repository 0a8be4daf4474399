// The acceptance of a part's new mesh, and the fold check against the sheet it came from
// (remesh_part.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>

#include "geometry/vec3.h"
#include "pipeline/remesh_part.h"
#include "voxremesh/deck_compare.h"

namespace voxremesh::pipeline {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// The unit normal of a face (elementNormal), zero without area.
template <typename Corners>
Vec3 unitNormal(const std::vector<std::array<double, 3>>& points, const Corners& face,
                bool triangle) {
  return normalized(elementNormal(points[face[0]], points[face[1]], points[face[2]],
                                  points[face[triangle ? 2 : 3]], triangle));
}

}  // namespace

std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

namespace {

/// The area of a mesh's faces (half the norm of elementNormal per face).
double meshArea(const QuadMesh& mesh) {
  double area = 0.0;
  for (const auto& face : mesh.faces) {
    const bool triangle = cornerCount(face) == 3;
    area +=
        0.5 * norm(elementNormal(mesh.points[face[0]], mesh.points[face[1]], mesh.points[face[2]],
                                 mesh.points[face[triangle ? 2 : 3]], triangle));
  }
  return area;
}

/// The distance from point p to the segment from a to b.
double distanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double length2 = dot(d, d);
  const double t = length2 > 0.0 ? std::clamp(dot(p - a, d) / length2, 0.0, 1.0) : 0.0;
  return norm(a + d * t - p);
}

/// The length of the T-junction edges of `original` (edgesSharedBy) whose midpoints are farther
/// than `tolerance` from every T-junction edge of `mesh`: where sheets that met no longer share
/// an edge (a fin whose nodes lie on its sheet's faces instead of being its nodes).
double lostJunctionLength(const QuadMesh& original, const QuadMesh& mesh, double tolerance,
                          double& total) {
  constexpr std::size_t kAny = std::numeric_limits<std::size_t>::max();
  const auto before = edgesSharedBy(original, 3, kAny), after = edgesSharedBy(mesh, 3, kAny);
  double lost = 0.0;
  total = 0.0;
  for (const auto& [a, b] : before) {
    const Vec3 &p = original.points[a], &q = original.points[b];
    const Vec3 middle = (p + q) * 0.5;
    total += distance(p, q);
    const bool kept = std::any_of(after.begin(), after.end(), [&](const auto& edge) {
      return distanceToSegment(middle, mesh.points[edge.first], mesh.points[edge.second]) <=
             tolerance;
    });
    if (!kept) lost += distance(p, q);
  }
  return lost;
}

/// The first failed check of an acceptance, in words (empty when all pass).
std::string failedCheck(const PartAcceptance& a, const QualitySettings& settings) {
  if (a.componentsAfter != a.componentsBefore)
    return std::to_string(a.componentsAfter) + " connected pieces instead of " +
           std::to_string(a.componentsBefore);
  if (a.loopsAfter != a.loopsBefore)
    return std::to_string(a.loopsAfter) + " boundary loops instead of " +
           std::to_string(a.loopsBefore);
  if (a.junctionLengthLost > 0.0)
    return "its sheets come apart along " + formatNumber(a.junctionLengthLost) + " of the " +
           formatNumber(a.junctionLength) +
           " where three or more of its shells met (a fin or flange on a sheet)";
  if (a.distance > a.distanceLimit)
    return "distance to the original " + formatNumber(a.distance) + " over its limit " +
           formatNumber(a.distanceLimit);
  if (a.folded > 0) return std::to_string(a.folded) + " folded elements";
  if (a.degenerateCorners > 0)
    return std::to_string(a.degenerateCorners) + " quads with a corner of 180 degrees";
  if (std::abs(a.areaAfter - a.areaBefore) > kAreaTolerance * a.areaBefore)
    return "area changed by " + formatNumber(100.0 * (a.areaAfter - a.areaBefore) / a.areaBefore) +
           " % (limit " + formatNumber(100.0 * kAreaTolerance) + " %)";
  if (a.failingShare > settings.maxFailingShare)
    return formatNumber(100.0 * a.failingShare) + " % of the elements fail a criterion (limit " +
           formatNumber(100.0 * settings.maxFailingShare) + " %)";
  return {};
}

}  // namespace

QuadMesh sheetSurface(const Sheet& sheet) {
  QuadMesh mesh;
  mesh.part = sheet.part;
  mesh.points = sheet.points;
  mesh.faces.reserve(sheet.faces.size());
  for (const auto& face : sheet.faces)
    mesh.faces.push_back({face[0], face[1], face[2], face[3] == kNoPoint ? kNoCorner : face[3]});
  return mesh;
}

std::vector<std::uint8_t> foldedAgainstSheet(const QuadMesh& mesh, const QuadMesh& surface,
                                             const ReferenceSurface& reference) {
  std::vector<std::uint8_t> folded(mesh.faces.size(), 0);
  if (reference.empty() || mesh.faces.empty()) return folded;
  std::vector<std::array<double, 3>> centroids(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const int n = cornerCount(mesh.faces[f]);
    Vec3 sum{0.0, 0.0, 0.0};
    for (int k = 0; k < n; ++k) sum = sum + mesh.points[mesh.faces[f][std::size_t(k)]];
    centroids[f] = sum * (1.0 / n);
  }
  const std::vector<SurfaceHit> hits = reference.closestPoints(centroids);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& own = mesh.faces[f];
    const auto& closest = surface.faces[hits[f].face];
    const double cosine = dot(unitNormal(mesh.points, own, cornerCount(own) == 3),
                              unitNormal(surface.points, closest, cornerCount(closest) == 3));
    folded[f] = cosine < -0.5 ? 1 : 0;
  }
  return folded;
}

namespace {

/// A sheet's area and the length of its boundary loops.
std::pair<double, double> areaAndBoundary(const Sheet& sheet) {
  double area = 0.0, boundary = 0.0;
  for (const auto& face : sheet.faces) {
    const bool triangle = face[3] == kNoPoint;
    const auto& p = sheet.points;
    area += 0.5 * norm(elementNormal(p[face[0]], p[face[1]], p[face[2]], p[face[triangle ? 2 : 3]],
                                     triangle));
  }
  for (const Polyline& loop : sheet.boundaryLoops)
    for (std::size_t i = 0; i < loop.points.size(); ++i) {
      if (!loop.closed && i + 1 == loop.points.size()) break;
      boundary += norm(sheet.points[loop.points[(i + 1) % loop.points.size()]] -
                       sheet.points[loop.points[i]]);
    }
  return {area, boundary};
}

}  // namespace

double sheetWidth(const Sheet& sheet) {
  const auto [area, boundary] = areaAndBoundary(sheet);
  return boundary > 0.0 ? 2.0 * area / boundary : std::numeric_limits<double>::infinity();
}

double stripWidth(const Sheet& sheet) {
  const auto [area, boundary] = areaAndBoundary(sheet);
  if (!(boundary > 0.0)) return std::numeric_limits<double>::infinity();
  const double quarter = 0.25 * boundary;
  return quarter - std::sqrt(std::max(0.0, quarter * quarter - area));
}

PartAcceptance acceptPartMesh(const QuadMesh& mesh, const QuadMesh& original,
                              const std::vector<std::uint8_t>& foldedAgainstOriginal, double size,
                              double askedSize, const QualitySettings& settings,
                              const std::vector<MeshCurve>& channels) {
  QualitySettings judged = settings;
  judged.targetSize = size;
  judged.distanceSize = askedSize;
  const QualityReport report = assessQuality(mesh, judged, &original, &channels);
  PartAcceptance a;
  a.size = size;
  a.elements = report.elements;
  a.quads = report.quads;
  a.trias = report.triangles;
  a.distance = report.distance ? report.distance->max() : 0.0;
  a.distanceLimit = report.distanceLimit;
  a.degenerateCorners = report.failing(Criterion::DegenerateCorner);
  const std::uint32_t foldBit = 1u << static_cast<int>(Criterion::Folded);
  for (std::size_t f = 0; f < report.elements; ++f) {
    const bool againstOriginal = f < foldedAgainstOriginal.size() && foldedAgainstOriginal[f];
    const std::uint32_t failures = report.elementFailures[f] | (againstOriginal ? foldBit : 0u);
    if (failures & foldBit) ++a.folded;
    if (failures) ++a.failing;
  }
  a.failingShare = a.elements ? double(a.failing) / double(a.elements) : 0.0;
  a.qualityIndex = report.meanQualityIndex;
  const TopologyCounts before = topologyCounts(original), after = topologyCounts(mesh);
  a.componentsBefore = before.components;
  a.componentsAfter = after.components;
  a.loopsBefore = before.boundaryLoops;
  a.loopsAfter = after.boundaryLoops;
  a.junctionLengthLost = lostJunctionLength(original, mesh, a.distanceLimit, a.junctionLength);
  a.areaBefore = meshArea(original);
  a.areaAfter = meshArea(mesh);
  a.reason = failedCheck(a, judged);
  a.accepted = a.reason.empty();
  return a;
}

PartAcceptance keptPartQuality(const FeModel& model, const PartPlan& plan,
                               const RemeshSettings& settings) {
  const QuadMesh original = quadMeshFromModel(model, plan.part);
  std::vector<MeshCurve> channels;
  try {
    channels = channelCurves(buildSheets(model, plan.part, settings.sheets));
  } catch (const std::exception&) {
    // judged without channels: every element's minimum length against the target size
  }
  return acceptPartMesh(original, original, {}, plan.targetSize, plan.targetSize,
                        settings.optimizeSettings.quality, channels);
}

}  // namespace voxremesh::pipeline
