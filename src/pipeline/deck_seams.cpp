// deckSeams: the seams of a deck (pipeline.h).
#include <algorithm>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

#include "pipeline/remesh_part.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/quad_mesh.h"
#include "voxremesh/quality.h"

namespace voxremesh {

namespace {

/// A node closer than this share of the shorter median edge of two parts to an edge of the other
/// lies on that edge.
constexpr double kOnEdgeShare = 0.005;

/// The nodes lying inside an edge of another part they share a seam with (see DeckSeams).
std::size_t hangingNodes(const FeModel& deck,
                         const std::map<std::pair<Id, Id>, std::size_t>& sharedNodes) {
  std::vector<Id> parts;
  for (const auto& [pair, count] : sharedNodes) {
    parts.push_back(pair.first);
    parts.push_back(pair.second);
  }
  std::sort(parts.begin(), parts.end());
  parts.erase(std::unique(parts.begin(), parts.end()), parts.end());
  const std::map<Id, QuadMesh> meshes = quadMeshesFromModel(deck, parts);
  std::map<Id, double> median;
  for (const auto& [part, mesh] : meshes) median[part] = medianEdgeLength(mesh);
  std::size_t hanging = 0;
  for (const auto& [pair, count] : sharedNodes) {
    const QuadMesh &a = meshes.at(pair.first), &b = meshes.at(pair.second);
    const double tolerance = kOnEdgeShare * std::min(median.at(pair.first), median.at(pair.second));
    hanging += pipeline::hangingPoints(a, b, tolerance) + pipeline::hangingPoints(b, a, tolerance);
  }
  return hanging;
}

}  // namespace

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
  seams.hangingNodes = hangingNodes(deck, seams.sharedNodes);
  return seams;
}

}  // namespace voxremesh
