// Junction curves: where a sheet met other sheets of its part (non-manifold edges) or shared
// nodes with another part.
#include "sheets/sheet_internal.h"

namespace voxremesh::sheets {

void findJunctions(SheetDraft& draft, const ModelContext& context, const PartMesh& part) {
  const ShellEdges& edges = draft.edges;
  std::vector<Index> chosen;
  for (Index e = 0; e < edges.edgeCount(); ++e) {
    const Index partEdge = draft.partEdge[e];
    const ShellEdges::Edge& nodes = part.edges.edge(partEdge);
    if (part.edges.isNonManifold(partEdge) ||
        context.sharedWithOtherPart(part.nodes[nodes.a], part.nodes[nodes.b], part.partEntry))
      chosen.push_back(e);
  }
  draft.sheet.junctionCurves = chainEdges(edges, chosen, draft.sheet.points.size(), {});
}

}  // namespace voxremesh::sheets
