#include "io/model_checks.h"

#include <unordered_map>

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

void checkModel(const FeModel& model, const SourceMap& sources) {
  std::unordered_map<Id, std::size_t> nodeIndex;
  nodeIndex.reserve(model.nodes.size());
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
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
