// Feature lines (edges with a large dihedral angle) and feature points (their ends and branch
// points, corners of boundary loops and feature lines, and apexes).
#include <algorithm>
#include <cmath>

#include "sheets/sheet_internal.h"

namespace voxremesh::sheets {

namespace {

/// The inner points off feature lines where the sheet comes to a point (a cone's tip, a nose),
/// appended to `result`: the sum of their faces' corner angles falls short of 360 degrees by more
/// than a cone whose face normals turn by the feature angle across its tip: 360 x (1 - cos(feature
/// angle / 2)). A flat or a cylindrical point has no shortfall, a saddle a negative one.
void appendApexes(const Sheet& sheet, const std::vector<ShellCorners>& corners,
                  const std::vector<std::uint8_t>& onCurve, double featureAngleDeg,
                  std::vector<PointIndex>& result) {
  constexpr double kDegrees = 180.0 / 3.14159265358979323846;
  const double shortfall = 360.0 * (1.0 - std::cos(0.5 * featureAngleDeg / kDegrees));
  std::vector<double> angleSum(sheet.points.size(), 0.0);
  for (const ShellCorners& c : corners)
    for (unsigned k = 0; k < c.count; ++k) {
      const Vec3& at = sheet.points[c.node[k]];
      const Vec3& before = sheet.points[c.node[(k + c.count - 1) % c.count]];
      const Vec3& after = sheet.points[c.node[(k + 1) % c.count]];
      angleSum[c.node[k]] += angleDeg({before[0] - at[0], before[1] - at[1], before[2] - at[2]},
                                      {after[0] - at[0], after[1] - at[1], after[2] - at[2]});
    }
  for (PointIndex p = 0; p < sheet.points.size(); ++p)
    if (!onCurve[p] && angleSum[p] > 0.0 && angleSum[p] < 360.0 - shortfall) result.push_back(p);
}

}  // namespace

void findFeatures(SheetDraft& draft, const SheetSettings& settings) {
  Sheet& sheet = draft.sheet;
  const ShellEdges& edges = draft.edges;
  std::vector<Vec3> normals(sheet.faces.size());
  for (std::size_t f = 0; f < sheet.faces.size(); ++f) {
    const ShellCorners& c = draft.corners[f];
    std::array<Vec3, 4> p{};
    for (unsigned k = 0; k < c.count; ++k) p[k] = sheet.points[c.node[k]];
    normals[f] = faceNormal(p, c.count);
  }
  std::vector<Index> chosen;
  std::vector<std::uint8_t> onBoundary(sheet.points.size(), 0);
  for (Index e = 0; e < edges.edgeCount(); ++e) {
    if (edges.isBoundary(e)) {
      onBoundary[edges.edge(e).a] = 1;
      onBoundary[edges.edge(e).b] = 1;
      continue;
    }
    const ShellEdges::IncidenceRange on = edges.incidences(e);
    if (angleDeg(normals[on[0].shell], normals[on[1].shell]) > settings.featureAngleDeg)
      chosen.push_back(e);
  }
  sheet.featureLines = chainEdges(edges, chosen, sheet.points.size(), onBoundary);

  std::vector<PointIndex>& points = sheet.featurePoints;
  for (const Polyline& line : sheet.featureLines)
    if (!line.closed) {
      points.push_back(line.points.front());
      points.push_back(line.points.back());
    }
  appendCorners(sheet.boundaryLoops, sheet.points, settings.cornerAngleDeg, points);
  appendCorners(sheet.featureLines, sheet.points, settings.cornerAngleDeg, points);
  std::vector<std::uint8_t> onCurve = onBoundary;
  for (const Polyline& line : sheet.featureLines)
    for (const PointIndex p : line.points) onCurve[p] = 1;
  appendApexes(sheet, draft.corners, onCurve, settings.featureAngleDeg, points);
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
}

}  // namespace voxremesh::sheets
