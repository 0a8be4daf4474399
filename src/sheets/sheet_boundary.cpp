// Boundary loops of a sheet: its boundary edges chained as the deck report chains them.
#include <utility>

#include "sheets/sheet_internal.h"

namespace voxremesh::sheets {

void findBoundaryLoops(SheetDraft& draft) {
  // Every edge of a sheet's points has one face or two running along it in opposite directions,
  // and no face names a point twice, so every chain closes; boundaryChains runs each loop the way
  // its first edge's face does, which in a consistently oriented sheet is the way all its faces
  // run along it.
  for (model::BoundaryChain& chain : model::boundaryChains(draft.edges)) {
    Polyline loop;
    loop.points = std::move(chain.nodes);
    loop.closed = chain.closed;
    draft.sheet.boundaryLoops.push_back(std::move(loop));
  }
}

}  // namespace voxremesh::sheets
