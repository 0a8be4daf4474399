#include "io/model_checks.h"

#include <unordered_map>
#include <unordered_set>

#include "voxremesh/errors.h"

namespace voxremesh::io {

std::uint32_t SourceMap::addFile(const std::string& file) {
  files_.push_back(file);
  return static_cast<std::uint32_t>(files_.size() - 1);
}

std::string SourceMap::nodeLocation(std::size_t i) const {
  if (i >= nodes_.size()) return "?";
  return files_[nodes_[i].file] + ":" + std::to_string(nodes_[i].line);
}

std::string SourceMap::shellLocation(std::size_t i) const {
  if (i >= shells_.size()) return "?";
  return files_[shells_[i].file] + ":" + std::to_string(shells_[i].line);
}

std::vector<Id> addUndefinedParts(FeModel& model) {
  std::unordered_set<Id> known;
  for (const Part& part : model.parts) known.insert(part.id);
  std::vector<Id> missing;
  for (std::size_t i = 0; i < model.shells.size(); ++i) {
    const Id part = model.shells[i].part;
    if (i > 0 && part == model.shells[i - 1].part) continue;  // runs of one part are common
    if (known.insert(part).second) missing.push_back(part);
  }
  for (const Id id : missing) model.parts.push_back(Part{id, {}, false});
  return missing;
}

std::string listIds(const std::vector<Id>& ids, std::size_t shown) {
  std::string list;
  for (std::size_t i = 0; i < ids.size() && i < shown; ++i)
    list += (i ? ", " : "") + std::to_string(ids[i]);
  if (ids.size() > shown) list += ", ...";
  return list;
}

void checkModel(const FeModel& model, const SourceMap& sources) {
  std::unordered_map<Id, std::size_t> nodeIndex;
  nodeIndex.reserve(model.nodes.size());
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    if (model.nodes[i].id <= 0)
      throw InputError(sources.nodeFile(i), sources.nodeLine(i),
                       "node ID " + std::to_string(model.nodes[i].id) + " is not positive");
    const auto [it, inserted] = nodeIndex.emplace(model.nodes[i].id, i);
    if (!inserted) {
      throw InputError(sources.nodeFile(i), sources.nodeLine(i),
                       "duplicate node ID " + std::to_string(model.nodes[i].id) +
                           " (first defined at " + sources.nodeLocation(it->second) + ")");
    }
  }
  std::unordered_map<Id, std::size_t> shellIndex;
  shellIndex.reserve(model.shells.size());
  for (std::size_t i = 0; i < model.shells.size(); ++i) {
    const Shell& shell = model.shells[i];
    if (shell.id <= 0)
      throw InputError(sources.shellFile(i), sources.shellLine(i),
                       "element ID " + std::to_string(shell.id) + " is not positive");
    if (shell.part <= 0)
      throw InputError(sources.shellFile(i), sources.shellLine(i),
                       "part ID " + std::to_string(shell.part) + " of element " +
                           std::to_string(shell.id) + " is not positive");
    const auto [it, inserted] = shellIndex.emplace(shell.id, i);
    if (!inserted)
      throw InputError(sources.shellFile(i), sources.shellLine(i),
                       "duplicate element ID " + std::to_string(shell.id) + " (first defined at " +
                           sources.shellLocation(it->second) + ")");
    for (int k = 0; k < shell.nodeCount; ++k) {
      if (!nodeIndex.count(shell.nodes[k]))
        throw InputError(sources.shellFile(i), sources.shellLine(i),
                         "element " + std::to_string(shell.id) + " names node " +
                             std::to_string(shell.nodes[k]) + ", which the deck does not define");
      for (int j = 0; j < k; ++j)
        if (shell.nodes[j] == shell.nodes[k])
          throw InputError(sources.shellFile(i), sources.shellLine(i),
                           "element " + std::to_string(shell.id) + " names node " +
                               std::to_string(shell.nodes[k]) + " twice");
    }
  }
}

}  // namespace voxremesh::io
