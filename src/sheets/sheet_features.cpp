// Feature lines (edges with a large dihedral angle) and feature points (their ends and branch
// points, and corners of boundary loops and feature lines).
#include <algorithm>

#include "sheets/sheet_internal.h"

namespace voxremesh::sheets {

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
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
}

}  // namespace voxremesh::sheets
