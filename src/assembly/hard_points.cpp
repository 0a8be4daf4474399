// hardPointNodes: the nodes that other keywords use as points (deck_assembly.h).
#include <string>
#include <string_view>
#include <unordered_set>

#include "assembly/node_references.h"
#include "voxremesh/deck_assembly.h"

namespace voxremesh {

namespace {

/// The keyword names a region of nodes (a set, a list, per-node data over an area) rather than
/// points that an element, a constraint, a load or an output is attached to.
bool isRegionKeyword(const std::string& keyword) {
  for (const std::string_view prefix : {"*SET_", "*INITIAL_", "*NSET"})
    if (keyword.compare(0, prefix.size(), prefix) == 0) return true;
  for (const std::string_view name :
       {"SET1", "SET3", "SPC1", "ASET1", "BSET1", "CSET1", "QSET1", "OMIT1", "TEMP", "TEMPD"})
    if (keyword == name) return true;
  return false;
}

}  // namespace

std::unordered_set<Id> hardPointNodes(const FeModel& model,
                                      const std::unordered_set<Id>& candidates) {
  std::unordered_set<Id> nodes;
  for (const assembly::NodeReference& reference : assembly::findNodeReferences(model, candidates))
    if (reference.kind == assembly::ReferenceKind::Field && !isRegionKeyword(reference.keyword))
      nodes.insert(reference.node);
  return nodes;
}

}  // namespace voxremesh
