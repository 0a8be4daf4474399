// Consistency checks every reader runs on the model it built, with the source line of each item
// so that an error names file and line.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "voxremesh/fe_model.h"
#include "voxremesh/io.h"

namespace voxremesh::io {

/// Where each node and shell of a model was read from (a deck may span several include files).
class SourceMap {
 public:
  /// Registers a file and returns its index for the add* calls.
  std::uint32_t addFile(const std::string& file);
  /// Records the location of the next node / shell appended to the model.
  void addNode(std::uint32_t file, std::size_t line) { nodes_.push_back({file, line}); }
  void addShell(std::uint32_t file, std::size_t line) { shells_.push_back({file, line}); }
  /// "file:line" of node / shell number i (in model order).
  std::string nodeLocation(std::size_t i) const;
  std::string shellLocation(std::size_t i) const;
  /// File and line of node number i.
  const std::string& nodeFile(std::size_t i) const { return files_[nodes_[i].file]; }
  std::size_t nodeLine(std::size_t i) const { return nodes_[i].line; }
  /// File and line of shell number i.
  const std::string& shellFile(std::size_t i) const { return files_[shells_[i].file]; }
  std::size_t shellLine(std::size_t i) const { return shells_[i].line; }

 private:
  struct Location {
    std::uint32_t file;
    std::size_t line;
  };
  std::vector<std::string> files_;
  std::vector<Location> nodes_;
  std::vector<Location> shells_;
};

/// Appends a nameless part (definedInBlocks = false) for every part ID that shells use but
/// model.parts lacks, in order of first use, and returns those IDs.
std::vector<Id> addUndefinedParts(FeModel& model);

/// "1, 2, 3, ..." of at most `shown` IDs, for messages.
std::string listIds(const std::vector<Id>& ids, std::size_t shown = 10);

/// Checks IDs and references after reading: node, shell and part IDs that are not positive,
/// duplicate node IDs, duplicate shell IDs, shells naming a node the deck does not define, shells
/// naming one node twice.
/// Throws InputError naming the file and line of the offending card (and of the first definition
/// for duplicates).
void checkModel(const FeModel& model, const SourceMap& sources);

}  // namespace voxremesh::io
