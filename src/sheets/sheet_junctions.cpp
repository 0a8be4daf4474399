// Junction curves: where a sheet met other sheets of its part (non-manifold edges, cuts) or
// shared nodes with another part; cut where the model's seams end or change partners
// (ModelContext::seamStop).
#include "sheets/sheet_internal.h"

namespace voxremesh::sheets {

void findJunctions(SheetDraft& draft, const ModelContext& context, const PartMesh& part) {
  const ShellEdges& edges = draft.edges;
  const Sheet& sheet = draft.sheet;
  std::vector<Index> chosen;
  std::vector<std::uint8_t> stop(sheet.points.size(), 0);
  for (Index e = 0; e < edges.edgeCount(); ++e) {
    const Index partEdge = draft.partEdge[e];
    const ShellEdges::Edge& nodes = part.edges.edge(partEdge);
    const Index a = part.nodes[nodes.a], b = part.nodes[nodes.b];
    if (!part.edges.isNonManifold(partEdge) && !context.sharedWithOtherPart(a, b, part.partEntry) &&
        !context.isCut(a, b))
      continue;
    chosen.push_back(e);
    // The sheet edge's points in the order of the part edge's nodes (matched by node ID).
    const ShellEdges::Edge& points = edges.edge(e);
    const bool same = sheet.pointNodeIds[points.a] == context.model.nodes[a].id;
    stop[same ? points.a : points.b] |= context.seamStop(a) ? 1 : 0;
    stop[same ? points.b : points.a] |= context.seamStop(b) ? 1 : 0;
  }
  draft.sheet.junctionCurves = chainEdges(edges, chosen, sheet.points.size(), stop);
}

}  // namespace voxremesh::sheets
