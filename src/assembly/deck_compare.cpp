// compareDecks: what a deck and its remeshed version carry, and what was lost (deck_compare.h).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "assembly/node_references.h"
#include "geometry/vec3.h"
#include "pipeline/remesh_part.h"
#include "voxremesh/deck_assembly.h"
#include "voxremesh/deck_compare.h"
#include "voxremesh/pipeline.h"

namespace voxremesh {

namespace {

using geom::Vec3;
using geom::operator+;
using geom::operator-;
using geom::operator*;
using Vec = Vec3;

/// Node positions by ID.
using Positions = std::unordered_map<Id, Vec>;

Positions positionsOf(const FeModel& model) {
  Positions positions;
  for (const Node& node : model.nodes)
    if (!positions.emplace(node.id, node.xyz).second)
      throw std::runtime_error("node " + std::to_string(node.id) + " is defined twice");
  return positions;
}

/// A shell's area times its unit normal (half of geom::elementNormal).
Vec areaVector(const Shell& shell, const Positions& positions) {
  const auto at = [&](int c) { return positions.at(shell.nodes[std::size_t(c)]); };
  const bool triangle = shell.nodeCount == 3;
  return geom::elementNormal(at(0), at(1), at(2), at(triangle ? 2 : 3), triangle) * 0.5;
}

/// Per part: shells and area.
std::map<Id, std::pair<std::size_t, double>> partAreas(const FeModel& model,
                                                       const Positions& positions) {
  std::map<Id, std::pair<std::size_t, double>> parts;
  for (const Shell& shell : model.shells) {
    auto& [count, area] = parts[shell.part];
    ++count;
    area += geom::norm(areaVector(shell, positions));
  }
  return parts;
}

void compareParts(const FeModel& before, const FeModel& after, const Positions& oldPositions,
                  const Positions& newPositions, DeckComparison& result) {
  const auto areasBefore = partAreas(before, oldPositions);
  const auto areasAfter = partAreas(after, newPositions);
  for (const auto& [part, counts] : areasBefore) {
    PartComparison row{part, counts.first, 0, counts.second, 0.0};
    const auto found = areasAfter.find(part);
    if (found != areasAfter.end()) row.shellsAfter = found->second.first;
    if (found != areasAfter.end()) row.areaAfter = found->second.second;
    result.parts.push_back(row);
    if (row.shellsAfter == 0)
      result.losses.push_back("part " + std::to_string(part) + " has no shells any more");
    else if (std::abs(row.areaAfter - row.areaBefore) > kAreaTolerance * row.areaBefore)
      result.losses.push_back("part " + std::to_string(part) + ": area " +
                              pipeline::formatNumber(row.areaBefore) + " became " +
                              pipeline::formatNumber(row.areaAfter));
  }
  for (const auto& [part, counts] : areasAfter)
    if (!areasBefore.count(part))
      result.parts.push_back({part, 0, counts.first, 0.0, counts.second});
  std::sort(result.parts.begin(), result.parts.end(),
            [](const PartComparison& a, const PartComparison& b) { return a.part < b.part; });
}

void compareSeams(const FeModel& before, const FeModel& after, DeckComparison& result) {
  const DeckSeams seamsBefore = deckSeams(before), seamsAfter = deckSeams(after);
  std::map<std::pair<Id, Id>, std::pair<std::size_t, std::size_t>> pairs;
  for (const auto& [key, count] : seamsBefore.sharedNodes) pairs[key].first = count;
  for (const auto& [key, count] : seamsAfter.sharedNodes) pairs[key].second = count;
  for (const auto& [key, counts] : pairs) {
    result.seams.push_back({key.first, key.second, counts.first, counts.second});
    if (counts.first > 0 && counts.second == 0)
      result.losses.push_back("parts " + std::to_string(key.first) + " and " +
                              std::to_string(key.second) + " shared " +
                              std::to_string(counts.first) + " nodes and share none");
  }
  result.tJunctionEdgesBefore = seamsBefore.tJunctionEdges;
  result.tJunctionEdgesAfter = seamsAfter.tJunctionEdges;
  result.hangingNodesBefore = seamsBefore.hangingNodes;
  result.hangingNodesAfter = seamsAfter.hangingNodes;
  if (seamsAfter.hangingNodes > seamsBefore.hangingNodes)
    result.losses.push_back("nodes inside an edge of a part they share a seam with: " +
                            std::to_string(seamsAfter.hangingNodes) + " (" +
                            std::to_string(seamsBefore.hangingNodes) + " before)");
}

void compareHardPoints(const FeModel& before, const Positions& oldPositions,
                       const Positions& newPositions, DeckComparison& result) {
  std::unordered_set<Id> shellNodes;
  for (const Shell& shell : before.shells)
    shellNodes.insert(shell.nodes.begin(), shell.nodes.begin() + shell.nodeCount);
  const std::unordered_set<Id> hard = hardPointNodes(before, shellNodes);
  std::vector<Id> sorted(hard.begin(), hard.end());
  std::sort(sorted.begin(), sorted.end());
  Vec low{1e300, 1e300, 1e300}, high{-1e300, -1e300, -1e300};
  for (const auto& [id, xyz] : oldPositions)
    for (std::size_t c = 0; c < 3; ++c)
      low[c] = std::min(low[c], xyz[c]), high[c] = std::max(high[c], xyz[c]);
  const double tolerance = oldPositions.empty() ? 0.0 : 1e-6 * geom::norm(high - low);
  result.hardPoints = sorted.size();
  for (const Id node : sorted) {
    const auto found = newPositions.find(node);
    if (found == newPositions.end()) {
      ++result.hardPointsMissing;
      continue;
    }
    const double move = geom::norm(found->second - oldPositions.at(node));
    result.largestHardPointMove = std::max(result.largestHardPointMove, move);
    if (move > tolerance) ++result.hardPointsMoved;
  }
  if (result.hardPointsMissing > 0)
    result.losses.push_back(std::to_string(result.hardPointsMissing) + " of " +
                            std::to_string(result.hardPoints) +
                            " hard points (nodes other keywords use) are missing");
  if (result.hardPointsMoved > 0)
    result.losses.push_back(std::to_string(result.hardPointsMoved) + " of " +
                            std::to_string(result.hardPoints) + " hard points moved (up to " +
                            pipeline::formatNumber(result.largestHardPointMove) + ")");
}

/// The sets of a deck: per (block, group) of its member references, in order.
struct NodeSet {
  std::string keyword;
  std::size_t line = 0;
  std::vector<Id> entries;
};

std::vector<NodeSet> nodeSets(const std::vector<assembly::NodeReference>& references) {
  std::map<std::pair<std::size_t, std::size_t>, NodeSet> sets;
  for (const assembly::NodeReference& reference : references) {
    if (reference.role != assembly::NodeRole::Member ||
        reference.kind != assembly::ReferenceKind::Field)
      continue;
    NodeSet& set = sets[{reference.block, reference.group}];
    if (set.entries.empty()) set.keyword = reference.keyword, set.line = reference.line;
    set.entries.push_back(reference.node);
  }
  std::vector<NodeSet> result;
  for (auto& [key, set] : sets) result.push_back(std::move(set));
  return result;
}

/// The area of the shells of `model` whose nodes are all in `members`.
double coveredArea(const FeModel& model, const Positions& positions,
                   const std::unordered_set<Id>& members) {
  double area = 0.0;
  for (const Shell& shell : model.shells)
    if (std::all_of(shell.nodes.begin(), shell.nodes.begin() + shell.nodeCount,
                    [&](Id node) { return members.count(node) > 0; }))
      area += geom::norm(areaVector(shell, positions));
  return area;
}

void compareSets(const FeModel& before, const FeModel& after, const Positions& oldPositions,
                 const Positions& newPositions,
                 const std::vector<assembly::NodeReference>& oldReferences,
                 const std::vector<assembly::NodeReference>& newReferences,
                 DeckComparison& result) {
  const std::vector<NodeSet> setsBefore = nodeSets(oldReferences);
  const std::vector<NodeSet> setsAfter = nodeSets(newReferences);
  std::map<std::string, std::size_t> seen;  // keyword -> sets of it matched so far
  std::map<std::string, std::vector<const NodeSet*>> afterByKeyword;
  for (const NodeSet& set : setsAfter) afterByKeyword[set.keyword].push_back(&set);
  for (const NodeSet& set : setsBefore) {
    const std::size_t index = seen[set.keyword]++;
    const std::vector<const NodeSet*>& candidates = afterByKeyword[set.keyword];
    const NodeSet* match = index < candidates.size() ? candidates[index] : nullptr;
    SetComparison row;
    row.keyword = set.keyword;
    row.line = set.line;
    const std::unordered_set<Id> membersBefore(set.entries.begin(), set.entries.end());
    row.membersBefore = membersBefore.size();
    row.repeatedBefore = set.entries.size() - membersBefore.size();
    row.areaBefore = coveredArea(before, oldPositions, membersBefore);
    if (match) {
      const std::unordered_set<Id> membersAfter(match->entries.begin(), match->entries.end());
      row.membersAfter = membersAfter.size();
      row.repeatedAfter = match->entries.size() - membersAfter.size();
      row.areaAfter = coveredArea(after, newPositions, membersAfter);
    }
    const std::string name = set.keyword + " (line " + std::to_string(set.line) + ")";
    if (row.membersAfter == 0)
      result.losses.push_back(name + ": its " + std::to_string(row.membersBefore) +
                              " nodes are gone");
    else if (row.repeatedAfter > row.repeatedBefore)
      result.losses.push_back(name + ": " + std::to_string(row.repeatedAfter) +
                              " repeated members (" + std::to_string(row.repeatedBefore) +
                              " before)");
    result.sets.push_back(std::move(row));
  }
}

/// Per (keyword, part): the part's shell nodes and those with a record of the keyword.
std::map<std::pair<std::string, Id>, std::pair<std::size_t, std::size_t>> recordCoverage(
    const FeModel& model, const std::vector<assembly::NodeReference>& references) {
  std::map<std::string, std::unordered_set<Id>> recorded;
  for (const assembly::NodeReference& reference : references)
    if (reference.role == assembly::NodeRole::Record &&
        reference.kind == assembly::ReferenceKind::Field)
      recorded[reference.keyword].insert(reference.node);
  std::map<Id, std::set<Id>> nodesOfPart;
  for (const Shell& shell : model.shells)
    nodesOfPart[shell.part].insert(shell.nodes.begin(), shell.nodes.begin() + shell.nodeCount);
  std::map<std::pair<std::string, Id>, std::pair<std::size_t, std::size_t>> coverage;
  for (const auto& entry : recorded) {
    const std::unordered_set<Id>& withRecord = entry.second;
    for (const auto& [part, partNodes] : nodesOfPart) {
      const std::size_t covered = static_cast<std::size_t>(std::count_if(
          partNodes.begin(), partNodes.end(), [&](Id node) { return withRecord.count(node) > 0; }));
      coverage[{entry.first, part}] = {partNodes.size(), covered};
    }
  }
  return coverage;
}

void compareCoverage(const FeModel& before, const FeModel& after,
                     const std::vector<assembly::NodeReference>& oldReferences,
                     const std::vector<assembly::NodeReference>& newReferences,
                     DeckComparison& result) {
  const auto coverageBefore = recordCoverage(before, oldReferences);
  const auto coverageAfter = recordCoverage(after, newReferences);
  for (const auto& [key, counts] : coverageBefore) {
    if (counts.second == 0) continue;
    CoverageComparison row{key.first, key.second, counts.first, counts.second, 0, 0};
    const auto found = coverageAfter.find(key);
    if (found != coverageAfter.end())
      row.nodesAfter = found->second.first, row.coveredAfter = found->second.second;
    const bool fullBefore = row.coveredBefore == row.nodesBefore;
    if ((fullBefore && row.coveredAfter < row.nodesAfter) || row.coveredAfter == 0)
      result.losses.push_back(key.first + " on part " + std::to_string(key.second) + ": " +
                              std::to_string(row.coveredBefore) + " of " +
                              std::to_string(row.nodesBefore) + " nodes before, " +
                              std::to_string(row.coveredAfter) + " of " +
                              std::to_string(row.nodesAfter) + " after");
    result.coverage.push_back(std::move(row));
  }
}

/// The total force of a deck's PLOAD4 cards on its shells; `cards` receives their number.
Vec pressureForce(const FeModel& model, const Positions& positions, std::size_t& cards) {
  const std::vector<assembly::ElementPressure> loads = assembly::findElementPressures(model);
  cards = loads.size();
  std::vector<const Shell*> byId;
  for (const Shell& shell : model.shells) byId.push_back(&shell);
  std::sort(byId.begin(), byId.end(), [](const Shell* a, const Shell* b) { return a->id < b->id; });
  Vec force{0.0, 0.0, 0.0};
  for (const assembly::ElementPressure& load : loads) {
    auto it = std::lower_bound(byId.begin(), byId.end(), load.first,
                               [](const Shell* shell, std::int64_t id) { return shell->id < id; });
    for (; it != byId.end() && (*it)->id <= load.last; ++it) {
      const Shell& shell = **it;
      double mean = 0.0;
      for (int c = 0; c < shell.nodeCount; ++c) mean += load.pressure[std::size_t(c)];
      mean /= shell.nodeCount;
      force = force + areaVector(shell, positions) * mean;
    }
  }
  return force;
}

void compareLoads(const FeModel& before, const FeModel& after, const Positions& oldPositions,
                  const Positions& newPositions, DeckComparison& result) {
  result.forceBefore = pressureForce(before, oldPositions, result.loadCardsBefore);
  result.forceAfter = pressureForce(after, newPositions, result.loadCardsAfter);
  const double change = geom::norm(result.forceAfter - result.forceBefore);
  const double size = geom::norm(result.forceBefore);
  if (change > kLoadTolerance * size)
    result.losses.push_back("the total pressure force changed by " +
                            pipeline::formatNumber(change) + " (" +
                            pipeline::formatNumber(100.0 * change / std::max(size, 1e-300)) +
                            " % of " + pipeline::formatNumber(size) + ")");
}

void findDangling(const FeModel& before, const FeModel& after, const Positions& newPositions,
                  const std::vector<assembly::NodeReference>& newReferences,
                  DeckComparison& result) {
  for (const assembly::NodeReference& reference : newReferences)
    if (reference.kind == assembly::ReferenceKind::Field && !newPositions.count(reference.node))
      result.dangling.push_back({reference.keyword, reference.line, reference.node, false});
  std::unordered_set<Id> newShells, removedShells;
  for (const Shell& shell : after.shells) newShells.insert(shell.id);
  for (const Shell& shell : before.shells)
    if (!newShells.count(shell.id)) removedShells.insert(shell.id);
  for (const assembly::NodeReference& reference :
       assembly::findElementReferences(after, removedShells))
    result.dangling.push_back({reference.keyword, reference.line, reference.node, true});
  if (!result.dangling.empty())
    result.losses.push_back(std::to_string(result.dangling.size()) +
                            " references name a node or shell the deck does not have (first: " +
                            result.dangling.front().keyword + ", line " +
                            std::to_string(result.dangling.front().line) + ")");
}

}  // namespace

DeckComparison compareDecks(const FeModel& before, const FeModel& after) {
  DeckComparison result;
  const Positions oldPositions = positionsOf(before), newPositions = positionsOf(after);
  compareParts(before, after, oldPositions, newPositions, result);
  compareSeams(before, after, result);
  compareHardPoints(before, oldPositions, newPositions, result);
  std::unordered_set<Id> watched;
  for (const auto& [id, xyz] : oldPositions) watched.insert(id);
  for (const auto& [id, xyz] : newPositions) watched.insert(id);
  const auto oldReferences = assembly::findNodeReferences(before, watched);
  const auto newReferences = assembly::findNodeReferences(after, watched);
  compareSets(before, after, oldPositions, newPositions, oldReferences, newReferences, result);
  compareCoverage(before, after, oldReferences, newReferences, result);
  compareLoads(before, after, oldPositions, newPositions, result);
  findDangling(before, after, newPositions, newReferences, result);
  return result;
}

}  // namespace voxremesh
