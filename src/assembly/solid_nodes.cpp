// solidElementNodes: the nodes of a deck's solid elements (deck_assembly.h).
#include <string>
#include <unordered_set>

#include "assembly/node_references.h"
#include "voxremesh/deck_assembly.h"

namespace voxremesh {

namespace {

/// The keyword names a solid element (as findNodeReferences spells keywords).
bool isSolidKeyword(const std::string& keyword) {
  for (const char* name : {"CHEXA", "CPENTA", "CTETRA", "CPYRAM"})
    if (keyword == name) return true;
  return keyword.rfind("*ELEMENT_SOLID", 0) == 0 || keyword.rfind("*ELEMENT_TSHELL", 0) == 0;
}

}  // namespace

std::unordered_set<Id> solidElementNodes(const FeModel& model,
                                         const std::unordered_set<Id>& candidates) {
  std::unordered_set<Id> nodes;
  for (const assembly::NodeReference& reference : assembly::findNodeReferences(model, candidates))
    if (isSolidKeyword(reference.keyword)) nodes.insert(reference.node);
  return nodes;
}

}  // namespace voxremesh
