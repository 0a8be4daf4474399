// mergeCoincidentNodes: a part's unmerged coincident nodes made one (remesh_part.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "pipeline/remesh_part.h"

namespace voxremesh::pipeline {

namespace {

/// The nodes used by the shells of `part` and by no other shell of the model, ascending.
std::vector<Id> ownNodes(const FeModel& model, Id part) {
  std::unordered_set<Id> own, shared;
  for (const Shell& shell : model.shells)
    for (int c = 0; c < shell.nodeCount; ++c)
      (shell.part == part ? own : shared).insert(shell.nodes[std::size_t(c)]);
  std::vector<Id> nodes;
  for (const Id node : own)
    if (!shared.count(node)) nodes.push_back(node);
  std::sort(nodes.begin(), nodes.end());
  return nodes;
}

/// Removes corners that repeat the one before them (cyclically): a quad with two merged corners
/// becomes a triangle, a sliver fewer than 3 corners.
void dropRepeatedCorners(Shell& shell) {
  std::array<Id, 4> corners{};
  int count = 0;
  for (int c = 0; c < shell.nodeCount; ++c) {
    const Id node = shell.nodes[std::size_t(c)];
    if (count == 0 || corners[std::size_t(count - 1)] != node) corners[std::size_t(count++)] = node;
  }
  while (count > 1 && corners[std::size_t(count - 1)] == corners[0]) --count;
  shell.nodes = corners;
  shell.nodeCount = static_cast<std::uint8_t>(count);
}

}  // namespace

std::size_t mergeCoincidentNodes(FeModel& model, Id part, double tolerance) {
  const std::vector<Id> nodes = ownNodes(model, part);
  const std::unordered_map<Id, std::size_t> index = model.nodeIndex();
  using Cell = std::array<long long, 3>;
  const double cell = tolerance;
  const auto cellOf = [&](const std::array<double, 3>& p) {
    Cell c{};
    for (int k = 0; k < 3; ++k)
      c[std::size_t(k)] = std::llround(std::floor(p[std::size_t(k)] / cell));
    return c;
  };
  // Nodes in cells of the tolerance's size; a node's partner lies in its cell or a neighbour.
  std::map<Cell, std::vector<Id>> cells;
  for (const Id node : nodes) cells[cellOf(model.nodes[index.at(node)].xyz)].push_back(node);
  std::unordered_map<Id, Id> merged;  // node -> the smallest ID coinciding with it
  for (const Id node : nodes) {
    if (merged.count(node)) continue;
    const std::array<double, 3>& p = model.nodes[index.at(node)].xyz;
    const Cell home = cellOf(p);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto found = cells.find({home[0] + dx, home[1] + dy, home[2] + dz});
          if (found == cells.end()) continue;
          for (const Id other : found->second) {
            if (other <= node || merged.count(other)) continue;
            const std::array<double, 3>& q = model.nodes[index.at(other)].xyz;
            if (std::abs(q[0] - p[0]) <= tolerance && std::abs(q[1] - p[1]) <= tolerance &&
                std::abs(q[2] - p[2]) <= tolerance)
              merged[other] = node;
          }
        }
  }
  if (merged.empty()) return 0;
  for (Shell& shell : model.shells) {
    if (shell.part != part) continue;
    for (int c = 0; c < shell.nodeCount; ++c) {
      const auto it = merged.find(shell.nodes[std::size_t(c)]);
      if (it != merged.end()) shell.nodes[std::size_t(c)] = it->second;
    }
    dropRepeatedCorners(shell);
  }
  // Shells that shrank to a line (slivers between the doubled rows) have no area to remesh.
  model.shells.erase(std::remove_if(model.shells.begin(), model.shells.end(),
                                    [](const Shell& shell) { return shell.nodeCount < 3; }),
                     model.shells.end());
  return merged.size();
}

}  // namespace voxremesh::pipeline
