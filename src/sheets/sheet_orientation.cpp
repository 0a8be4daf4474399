// Components of a part across manifold edges and their consistent orientation.
#include <algorithm>
#include <string>

#include "sheets/sheet_internal.h"
#include "voxremesh/errors.h"

namespace voxremesh::sheets {

namespace {

[[noreturn]] void notOrientable(const FeModel& model, const PartMesh& part, Index from, Index to,
                                Index edge) {
  const ShellEdges::Edge& e = part.edges.edge(edge);
  const Id a = model.nodes[part.nodes[e.a]].id, b = model.nodes[part.nodes[e.b]].id;
  const Id shell = model.shells[part.shells[to]].id;
  const Id neighbour = model.shells[part.shells[from]].id;
  throw InputError({}, 0,
                   part.label + " cannot be oriented consistently (a Moebius-like sheet): shell " +
                       std::to_string(shell) +
                       " would have to be flipped both ways; the conflict closes at the edge "
                       "between nodes " +
                       std::to_string(std::min(a, b)) + " and " + std::to_string(std::max(a, b)) +
                       ", shared with shell " + std::to_string(neighbour));
}

}  // namespace

Orientation orientComponents(const ModelContext& context, const PartMesh& part) {
  const ShellEdges& edges = part.edges;
  const std::size_t n = part.corners.size();
  Orientation result;
  result.component.assign(n, kNoIndex);
  result.flipped.assign(n, 0);
  std::vector<Index> queue;
  queue.reserve(n);
  for (Index seed = 0; seed < n; ++seed) {
    if (result.component[seed] != kNoIndex) continue;
    const Index component = result.componentCount++;
    result.component[seed] = component;
    queue.clear();
    queue.push_back(seed);
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const Index f = queue[head];
      for (unsigned side = 0; side < part.corners[f].count; ++side) {
        const Index e = edges.shellEdge(f, side);
        if (!edges.isManifold(e)) continue;
        const ShellEdges::Edge& ends = edges.edge(e);
        if (context.isCut(part.nodes[ends.a], part.nodes[ends.b])) continue;
        const ShellEdges::IncidenceRange on = edges.incidences(e);
        const bool firstIsMine = on[0].shell == f && on[0].side == side;
        const ShellEdges::Incidence& mine = firstIsMine ? on[0] : on[1];
        const ShellEdges::Incidence& other = firstIsMine ? on[1] : on[0];
        // Consistent when the two faces run along the edge in opposite directions.
        const std::uint8_t required =
            result.flipped[f] ^ static_cast<std::uint8_t>(mine.forward == other.forward);
        const Index g = other.shell;
        if (result.component[g] == kNoIndex) {
          result.component[g] = component;
          result.flipped[g] = required;
          queue.push_back(g);
        } else if (result.flipped[g] != required) {
          notOrientable(context.model, part, f, g, e);
        }
      }
    }
    // Keep the orientation of the majority of the original faces; on a tie, the seed's.
    std::size_t flips = 0;
    for (const Index f : queue) flips += result.flipped[f];
    if (2 * flips > queue.size())
      for (const Index f : queue) result.flipped[f] ^= 1;
  }
  return result;
}

}  // namespace voxremesh::sheets
