// deckSeams: the seams of a deck (pipeline.h).
#include <algorithm>
#include <unordered_map>
#include <utility>
#include <vector>

#include "voxremesh/pipeline.h"

namespace voxremesh {

DeckSeams deckSeams(const FeModel& deck) {
  DeckSeams seams;
  std::unordered_map<Id, std::vector<Id>> partsOfNode;
  std::vector<std::pair<Id, Id>> edges;  // one entry per shell side, sorted below
  for (const Shell& shell : deck.shells) {
    for (int c = 0; c < shell.nodeCount; ++c) {
      const Id node = shell.nodes[std::size_t(c)];
      std::vector<Id>& parts = partsOfNode[node];
      if (std::find(parts.begin(), parts.end(), shell.part) == parts.end())
        parts.push_back(shell.part);
      const Id next = shell.nodes[std::size_t((c + 1) % shell.nodeCount)];
      if (next != node) edges.emplace_back(std::min(node, next), std::max(node, next));
    }
  }
  for (auto& [node, parts] : partsOfNode) {
    std::sort(parts.begin(), parts.end());
    for (std::size_t i = 0; i < parts.size(); ++i)
      for (std::size_t j = i + 1; j < parts.size(); ++j) ++seams.sharedNodes[{parts[i], parts[j]}];
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {  // a run of equal entries: one edge's shells
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    seams.tJunctionEdges += j - i > 2 ? 1 : 0;
    i = j;
  }
  return seams;
}

}  // namespace voxremesh
