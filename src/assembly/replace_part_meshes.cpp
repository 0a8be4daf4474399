// replacePartMeshes: the remeshed parts put back into their deck (see deck_assembly.h).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "assembly/nearest_point.h"
#include "assembly/node_references.h"
#include "assembly/node_regions.h"
#include "voxremesh/deck_assembly.h"

namespace voxremesh {

namespace {

using Point = std::array<double, 3>;

/// Hash of the exact bits of a coordinate triple (bit-identical points are equal keys; +0 and -0
/// are told apart, as "bit-identical" says).
struct PointBits {
  std::array<std::uint64_t, 3> bits{};
  explicit PointBits(const Point& p) {
    for (int a = 0; a < 3; ++a) std::memcpy(&bits[static_cast<std::size_t>(a)], &p[a], 8);
  }
  bool operator==(const PointBits& other) const { return bits == other.bits; }
};

struct PointBitsHash {
  std::size_t operator()(const PointBits& key) const {
    std::uint64_t h = 1469598103934665603ull;
    for (const std::uint64_t b : key.bits) h = (h ^ b) * 1099511628211ull + (h >> 29);
    return static_cast<std::size_t>(h);
  }
};

void checkMeshes(const FeModel& model, const std::vector<QuadMesh>& meshes) {
  std::set<Id> withShells;
  for (const Shell& shell : model.shells) withShells.insert(shell.part);
  std::set<Id> seen;
  for (const QuadMesh& mesh : meshes) {
    const std::string part = "part " + std::to_string(mesh.part);
    if (mesh.part == 0) throw std::invalid_argument("a remeshed mesh names no part (part 0)");
    if (!withShells.count(mesh.part))
      throw std::invalid_argument(part + " has no shells in the model to replace");
    if (!seen.insert(mesh.part).second)
      throw std::invalid_argument(part + " is given twice among the remeshed parts");
    for (const Point& p : mesh.points)
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        throw std::invalid_argument("the new mesh of " + part + " has a non-finite coordinate");
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      for (int c = 0; c < cornerCount(mesh.faces[f]); ++c)
        if (mesh.faces[f][static_cast<std::size_t>(c)] >= mesh.points.size())
          throw std::invalid_argument("face " + std::to_string(f) + " of the new mesh of " + part +
                                      " names point " +
                                      std::to_string(mesh.faces[f][static_cast<std::size_t>(c)]) +
                                      " of " + std::to_string(mesh.points.size()));
  }
}

Point centroid(const FeModel& model, const std::unordered_map<Id, std::size_t>& nodeIndex,
               const Shell& shell) {
  Point sum{0, 0, 0};
  for (int c = 0; c < shell.nodeCount; ++c) {
    const Point& p = model.nodes[nodeIndex.at(shell.nodes[static_cast<std::size_t>(c)])].xyz;
    for (int a = 0; a < 3; ++a) sum[static_cast<std::size_t>(a)] += p[static_cast<std::size_t>(a)];
  }
  for (double& v : sum) v /= shell.nodeCount;
  return sum;
}

/// What a remeshed part's new shells inherit from its old ones.
struct PartTemplate {
  std::uint8_t type = 0;
  std::vector<Point> centroids;      ///< of the old shells, when some had extras
  std::vector<std::int32_t> extras;  ///< their extras index (-1: none)
};

}  // namespace

AssemblyReport replacePartMeshes(FeModel& model, const std::vector<QuadMesh>& newParts,
                                 const std::unordered_set<Id>& hardPoints) {
  checkMeshes(model, newParts);
  const std::unordered_map<Id, std::size_t> nodeIndex = model.nodeIndex();
  for (const Shell& shell : model.shells)
    for (int c = 0; c < shell.nodeCount; ++c)
      if (!nodeIndex.count(shell.nodes[static_cast<std::size_t>(c)]))
        throw std::invalid_argument("shell " + std::to_string(shell.id) + " names node " +
                                    std::to_string(shell.nodes[static_cast<std::size_t>(c)]) +
                                    ", which the model does not define");

  AssemblyReport report;
  std::unordered_map<Id, std::size_t> meshOfPart;
  for (std::size_t m = 0; m < newParts.size(); ++m) meshOfPart[newParts[m].part] = m;

  // Old and kept-shell nodes; the parts each old node belonged to; the templates of new shells.
  std::unordered_set<Id> keptShellNodes;
  for (const Shell& shell : model.shells)
    if (!meshOfPart.count(shell.part))
      for (int c = 0; c < shell.nodeCount; ++c)
        keptShellNodes.insert(shell.nodes[static_cast<std::size_t>(c)]);
  std::unordered_set<Id> oldNodes;   // the nodes of the remeshed parts' shells that go
  std::unordered_set<Id> partNodes;  // all nodes of those shells
  std::vector<Shell> oldShells;      // those shells
  std::unordered_map<Id, std::vector<std::size_t>> meshesOfOldNode;
  std::unordered_map<Id, std::vector<std::size_t>> meshesOfSeamNode;  // kept nodes they shared
  std::vector<PartTemplate> templates(newParts.size());
  std::vector<std::map<std::uint8_t, std::size_t>> typeCounts(newParts.size());
  std::vector<bool> anyExtras(newParts.size(), false);
  report.parts.resize(newParts.size());
  for (std::size_t m = 0; m < newParts.size(); ++m) report.parts[m].part = newParts[m].part;
  for (const Shell& shell : model.shells) {
    const auto it = meshOfPart.find(shell.part);
    if (it == meshOfPart.end()) continue;
    const std::size_t m = it->second;
    ++report.parts[m].shellsBefore;
    ++typeCounts[m][shell.type];
    anyExtras[m] = anyExtras[m] || shell.extras >= 0;
    oldShells.push_back(shell);
    for (int c = 0; c < shell.nodeCount; ++c) {
      const Id node = shell.nodes[static_cast<std::size_t>(c)];
      partNodes.insert(node);
      if (keptShellNodes.count(node)) {
        std::vector<std::size_t>& meshes = meshesOfSeamNode[node];
        if (std::find(meshes.begin(), meshes.end(), m) == meshes.end()) meshes.push_back(m);
        continue;
      }
      oldNodes.insert(node);
      std::vector<std::size_t>& meshes = meshesOfOldNode[node];
      if (std::find(meshes.begin(), meshes.end(), m) == meshes.end()) meshes.push_back(m);
    }
  }
  for (std::size_t m = 0; m < newParts.size(); ++m) {
    std::size_t most = 0;
    for (const auto& [type, count] : typeCounts[m])
      if (count > most) {
        most = count;
        templates[m].type = type;
      }
  }
  for (const Shell& shell : model.shells) {
    const auto it = meshOfPart.find(shell.part);
    if (it == meshOfPart.end() || !anyExtras[it->second]) continue;
    templates[it->second].centroids.push_back(centroid(model, nodeIndex, shell));
    templates[it->second].extras.push_back(shell.extras);
  }

  // New node IDs (above every node ID of the input) and the merging rules (a) and (b).
  Id maxNode = 0;
  for (const Node& node : model.nodes) maxNode = std::max(maxNode, node.id);
  Id maxElement = assembly::maxVerbatimElementId(model);
  for (const Shell& shell : model.shells) maxElement = std::max(maxElement, shell.id);
  // Rule (a): the seam nodes (kept-shell nodes the remeshed parts' shells used) by position, in
  // ascending ID order.
  std::unordered_map<PointBits, std::vector<Id>, PointBitsHash> keptAt;
  for (const Node& node : model.nodes)
    if (meshesOfSeamNode.count(node.id)) keptAt[PointBits(node.xyz)].push_back(node.id);
  for (auto& [key, ids] : keptAt) std::sort(ids.begin(), ids.end());
  // The seam node of mesh m at a point's position, or 0.
  const auto seamNodeAt = [&](const PointBits& key, std::size_t m) -> Id {
    const auto found = keptAt.find(key);
    if (found == keptAt.end()) return 0;
    for (const Id id : found->second) {
      const std::vector<std::size_t>& meshes = meshesOfSeamNode.at(id);
      if (std::find(meshes.begin(), meshes.end(), m) != meshes.end()) return id;
    }
    return 0;
  };
  // Rule (c): the hard points among the old nodes, by position, with the meshes of their parts.
  std::unordered_map<PointBits, std::pair<Id, std::vector<std::size_t>>, PointBitsHash> hardAt;
  for (const Node& node : model.nodes) {
    if (!hardPoints.count(node.id) || !oldNodes.count(node.id)) continue;
    const auto [it, inserted] =
        hardAt.emplace(PointBits(node.xyz), std::make_pair(node.id, meshesOfOldNode.at(node.id)));
    if (!inserted && node.id < it->second.first)
      it->second = std::make_pair(node.id, meshesOfOldNode.at(node.id));
  }
  std::unordered_set<Id> hardKept;
  std::unordered_map<PointBits, std::pair<Id, std::size_t>, PointBitsHash> junctionAt;
  std::vector<std::vector<Id>> pointIds(newParts.size());
  std::vector<Node> addedNodes;
  Id nextNode = maxNode + 1;
  for (std::size_t m = 0; m < newParts.size(); ++m) {
    const QuadMesh& mesh = newParts[m];
    pointIds[m].resize(mesh.points.size());
    for (std::size_t p = 0; p < mesh.points.size(); ++p) {
      const PointBits key(mesh.points[p]);
      if (const Id seam = seamNodeAt(key, m)) {
        pointIds[m][p] = seam;
        ++report.seamPoints;
        continue;
      }
      if (const auto hard = hardAt.find(key); hard != hardAt.end()) {
        const std::vector<std::size_t>& meshes = hard->second.second;
        if (std::find(meshes.begin(), meshes.end(), m) != meshes.end()) {
          pointIds[m][p] = hard->second.first;
          hardKept.insert(hard->second.first);
          continue;
        }
      }
      const bool junction =
          !mesh.constraints.empty() && mesh.constraints[p].role == PointRole::Junction;
      if (junction) {
        const auto found = junctionAt.find(key);
        if (found != junctionAt.end() && found->second.second != m) {
          pointIds[m][p] = found->second.first;
          ++report.mergedJunctionPoints;
          continue;
        }
      }
      pointIds[m][p] = nextNode;
      addedNodes.push_back(Node{nextNode, mesh.points[p]});
      if (junction) junctionAt.emplace(key, std::make_pair(nextNode, m));
      ++nextNode;
    }
  }
  report.newNodes = addedNodes.size();
  report.hardPointsKept = hardKept.size();
  for (const Id node : hardKept) oldNodes.erase(node);
  if (!addedNodes.empty()) report.firstNewNodeId = maxNode + 1;

  // Node references of the verbatim keywords: points are rewritten to the nearest new node (or
  // reported, their node kept); lists and per-node data of regions cover the region's new nodes.
  const std::vector<assembly::NodeReference> references =
      assembly::findNodeReferences(model, partNodes);
  std::map<std::tuple<std::size_t, std::size_t, int>, std::vector<const assembly::NodeReference*>>
      regions;  // by block, card or keyword in it, role
  std::vector<assembly::NearestPoint> searches;
  searches.reserve(newParts.size());
  for (const QuadMesh& mesh : newParts) searches.emplace_back(mesh.points);
  std::unordered_set<Id> keptOld;
  std::vector<std::vector<assembly::TextEdit>> edits(model.blocks.size());
  for (const assembly::NodeReference& reference : references) {
    if (reference.role != assembly::NodeRole::Point &&
        reference.kind == assembly::ReferenceKind::Field) {
      regions[{reference.block, reference.group, static_cast<int>(reference.role)}].push_back(
          &reference);
      continue;
    }
    if (!oldNodes.count(reference.node)) continue;  // a node that stays
    const DeckBlock& block = model.blocks[reference.block];
    const bool located = block.line > 0;
    const std::size_t line = located ? block.line + reference.line - 1 : reference.line;
    const auto unmapped = [&](const std::string& reason) {
      report.unmapped.push_back(
          UnmappedReference{reference.keyword, block.file, line, !located, reference.node, reason});
      keptOld.insert(reference.node);
    };
    if (reference.kind != assembly::ReferenceKind::Field) {
      unmapped(reference.reason);
      continue;
    }
    const Point& old = model.nodes[nodeIndex.at(reference.node)].xyz;
    Id bestId = 0;
    Id bestPart = 0;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (const std::size_t m : meshesOfOldNode.at(reference.node)) {
      double distance = 0;
      const std::size_t p = searches[m].nearest(old, &distance);
      if (p == std::numeric_limits<std::size_t>::max()) continue;
      const Id id = pointIds[m][p];
      if (distance < bestDistance || (distance == bestDistance && id < bestId)) {
        bestDistance = distance;
        bestId = id;
        bestPart = newParts[m].part;
      }
    }
    if (bestId == 0) {
      unmapped("the new mesh of its part has no points");
      continue;
    }
    std::string text;
    if (!assembly::referenceText(reference, bestId, text)) {
      unmapped("the new node ID " + std::to_string(bestId) + " does not fit the field's " +
               std::to_string(reference.width) + " columns");
      continue;
    }
    edits[reference.block].push_back(
        assembly::TextEdit{reference.offset, reference.length, std::move(text)});
    report.remaps.push_back(NodeRemap{reference.keyword, block.file, line, !located, reference.node,
                                      bestId, bestPart, bestDistance});
  }
  if (!regions.empty()) {
    const assembly::NewNodeSites sites(model, newParts, pointIds, maxNode + 1);
    for (const auto& [key, group] : regions) {
      std::unordered_set<Id> members;
      std::unordered_map<Id, const assembly::NodeReference*> referenceOf;
      for (const assembly::NodeReference* reference : group) {
        members.insert(reference->node);
        referenceOf.emplace(reference->node, reference);
      }
      const std::vector<assembly::RegionMember> added =
          assembly::regionMembers(sites, members, model, nodeIndex, oldShells, oldNodes);
      const std::size_t b = std::get<0>(key);
      DeckBlock& block = model.blocks[b];
      for (assembly::TextEdit& edit : assembly::regionEdits(block.text, group, added, oldNodes))
        edits[b].push_back(std::move(edit));
      const bool located = block.line > 0;
      for (const assembly::RegionMember& member : added) {
        const assembly::NodeReference& source = *referenceOf.at(member.source);
        report.remaps.push_back(NodeRemap{
            source.keyword, block.file, located ? block.line + source.line - 1 : source.line,
            !located, member.source, member.node, member.part, member.distance});
      }
    }
  }
  // References to removed shells: sets list the new shells most of whose area lies on their
  // members; per-shell records (loads) are repeated for the new shells on their shell.
  std::unordered_set<Id> oldShellIds;
  for (const Shell& shell : oldShells) oldShellIds.insert(shell.id);
  const std::vector<assembly::NodeReference> shellReferences =
      assembly::findElementReferences(model, oldShellIds);
  if (!shellReferences.empty()) {
    const std::vector<assembly::RegionMember> hosts =
        assembly::hostShells(model, newParts, maxElement + 1);
    std::map<std::tuple<std::size_t, std::size_t, int>,
             std::vector<const assembly::NodeReference*>>
        shellRegions;  // by block, card or keyword in it, role
    for (const assembly::NodeReference& reference : shellReferences) {
      if (reference.kind != assembly::ReferenceKind::Field) {
        const DeckBlock& block = model.blocks[reference.block];
        const bool located = block.line > 0;
        report.unmapped.push_back(UnmappedReference{
            reference.keyword, block.file,
            located ? block.line + reference.line - 1 : reference.line, !located, reference.node,
            "shell " + std::to_string(reference.node) + ": " + reference.reason});
        continue;
      }
      shellRegions[{reference.block, reference.group, static_cast<int>(reference.role)}].push_back(
          &reference);
    }
    for (const auto& [key, group] : shellRegions) {
      const std::size_t b = std::get<0>(key);
      const std::vector<assembly::RegionMember> added =
          group.front()->role == assembly::NodeRole::Record
              ? hosts
              : assembly::shellSetMembers(hosts, group);
      for (assembly::TextEdit& edit :
           assembly::regionEdits(model.blocks[b].text, group, added, oldShellIds))
        edits[b].push_back(std::move(edit));
      if (group.front()->role == assembly::NodeRole::Record)
        report.elementLoadsRewritten += group.size();
      else
        report.elementSetMembersRewritten += group.size();
    }
  }
  // Apply the edits of each block from its end, so that earlier offsets stay valid.
  for (std::size_t b = 0; b < edits.size(); ++b) {
    std::stable_sort(edits[b].begin(), edits[b].end(),
                     [](const assembly::TextEdit& x, const assembly::TextEdit& y) {
                       return x.offset > y.offset;
                     });
    for (const assembly::TextEdit& edit : edits[b])
      model.blocks[b].text.replace(edit.offset, edit.length, edit.text);
  }

  // Shells: kept ones in order, then the new ones; extras by the nearest old centroid.
  std::vector<Shell> shells;
  shells.reserve(model.shells.size());
  for (const Shell& shell : model.shells)
    if (!meshOfPart.count(shell.part)) shells.push_back(shell);
  Id nextElement = maxElement + 1;
  for (std::size_t m = 0; m < newParts.size(); ++m) {
    const QuadMesh& mesh = newParts[m];
    const PartTemplate& tmpl = templates[m];
    const assembly::NearestPoint oldCentroids(tmpl.centroids);
    for (const auto& face : mesh.faces) {
      Shell shell;
      shell.id = nextElement++;
      shell.part = mesh.part;
      shell.type = tmpl.type;
      shell.nodeCount = static_cast<std::uint8_t>(cornerCount(face));
      Point sum{0, 0, 0};
      for (int c = 0; c < shell.nodeCount; ++c) {
        const CornerIndex p = face[static_cast<std::size_t>(c)];
        shell.nodes[static_cast<std::size_t>(c)] = pointIds[m][p];
        for (int a = 0; a < 3; ++a)
          sum[static_cast<std::size_t>(a)] += mesh.points[p][static_cast<std::size_t>(a)];
      }
      if (!tmpl.centroids.empty()) {
        for (double& v : sum) v /= shell.nodeCount;
        shell.extras = tmpl.extras[oldCentroids.nearest(sum)];
      }
      (shell.nodeCount == 4 ? report.parts[m].quadsAfter : report.parts[m].triasAfter) += 1;
      shells.push_back(shell);
    }
    report.parts[m].shellsAfter = mesh.faces.size();
  }
  if (nextElement > maxElement + 1) report.firstNewElementId = maxElement + 1;
  model.shells = std::move(shells);

  // Nodes: old nodes removed unless still referenced; the new ones appended.
  std::vector<Node> nodes;
  nodes.reserve(model.nodes.size() + addedNodes.size());
  for (const Node& node : model.nodes) {
    if (oldNodes.count(node.id) && !keptOld.count(node.id)) {
      ++report.removedNodes;
      model.nodeExtras.erase(node.id);
      continue;
    }
    nodes.push_back(node);
  }
  report.keptOldNodes = keptOld.size();
  nodes.insert(nodes.end(), addedNodes.begin(), addedNodes.end());
  model.nodes = std::move(nodes);
  return report;
}

}  // namespace voxremesh
