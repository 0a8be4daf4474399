// What the surface-mesh readers and writers (OBJ, OFF, STL, PLY) share: building a model from
// vertices and faces (nodes 1..n, elements 1..m, parts by name or by ID), mapping node IDs to
// vertex indices when writing, and little-endian binary helpers. Header-only, internal to src/io.
#pragma once

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "io/model_checks.h"
#include "io/text_scan.h"
#include "voxremesh/errors.h"
#include "voxremesh/fe_model.h"
#include "voxremesh/io.h"

namespace voxremesh::io::surface {

/// Appends the decimal form of an integer.
inline void appendInt(std::string& out, std::int64_t value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

/// Appends "x y z" in the shortest form that reads back exactly (no terminator).
inline void appendXyz(std::string& out, const std::array<double, 3>& xyz) {
  appendShortest(out, xyz[0]);
  out += ' ';
  appendShortest(out, xyz[1]);
  out += ' ';
  appendShortest(out, xyz[2]);
}

/// Builds an FeModel from a surface mesh read in file order. Vertices become nodes 1..n, faces
/// become shells 1..m; faces that repeat a vertex are repaired (a quad with one repeated corner
/// becomes a triangle) or dropped (fewer than three distinct corners), with a warning.
class MeshBuilder {
 public:
  /// @param format     the model's sourceFormat
  /// @param path       the file being read (named in errors)
  /// @param indexBase  0 or 1: how the format numbers vertices (for messages)
  MeshBuilder(DeckFormat format, const std::filesystem::path& path, int indexBase)
      : file_(path.string()), indexBase_(indexBase) {
    model_.sourceFormat = format;
    fileIndex_ = sources_.addFile(file_);
  }

  /// The file name used in errors.
  const std::string& file() const { return file_; }

  /// Reserves room for the expected numbers of vertices and faces.
  void reserve(std::size_t vertices, std::size_t faces) {
    model_.nodes.reserve(vertices);
    model_.shells.reserve(faces);
  }

  /// Appends a vertex; its node ID is its 1-based position. `line` is its source line (0 for
  /// binary files).
  void addVertex(const std::array<double, 3>& xyz, std::size_t line) {
    model_.nodes.push_back(Node{static_cast<Id>(model_.nodes.size() + 1), xyz});
    sources_.addNode(fileIndex_, line);
  }

  /// Number of vertices added so far.
  std::size_t vertexCount() const { return model_.nodes.size(); }

  /// The coordinates of vertex `index` (0-based; index < vertexCount()).
  const std::array<double, 3>& vertex(std::size_t index) const { return model_.nodes[index].xyz; }

  /// Makes the part called `name` the current one (created on first use; IDs are given in
  /// order of first appearance unless restored with restorePartId).
  void usePartNamed(std::string_view name) {
    const auto it = partsByName_.find(std::string(name));
    if (it != partsByName_.end()) {
      current_ = it->second;
      return;
    }
    current_ = parts_.size();
    parts_.push_back(PendingPart{std::string(name), 0, false});
    partsByName_.emplace(std::string(name), current_);
  }

  /// Makes the part with ID `id` the current one (created on first use, named from
  /// restorePartName or "part_<id>").
  void usePartId(Id id) {
    const auto it = partsById_.find(id);
    if (it != partsById_.end()) {
      current_ = it->second;
      return;
    }
    current_ = parts_.size();
    parts_.push_back(PendingPart{{}, id, true});
    partsById_.emplace(id, current_);
  }

  /// Records the ID that a file written by voxremesh gave the part called `name`.
  void restorePartId(const std::string& name, Id id) { restoredIds_[name] = id; }

  /// Records the name that a file written by voxremesh gave the part with ID `id`.
  void restorePartName(Id id, const std::string& name) { restoredNames_[id] = name; }

  /// True when a part has been selected.
  bool hasPart() const { return current_ != kNone; }

  /// Adds a face of the current part (a part must be selected).
  /// @param vertices  1-based vertex numbers (node IDs); they are checked in finish()
  /// @param count     3 or 4
  /// @param line      source line (0 for binary files)
  void addFace(const std::int64_t* vertices, int count, std::size_t line) {
    Shell shell;
    int kept = 0;
    for (int k = 0; k < count; ++k) {
      bool repeated = false;
      for (int j = 0; j < kept; ++j) repeated = repeated || shell.nodes[j] == vertices[k];
      if (!repeated) shell.nodes[kept++] = vertices[k];
    }
    if (kept < 3) {
      ++droppedFaces_;
      if (firstDroppedLine_ == 0) firstDroppedLine_ = line;
      return;
    }
    if (kept < count) ++collapsedQuads_;
    shell.nodeCount = static_cast<std::uint8_t>(kept);
    shell.part = static_cast<Id>(current_);
    model_.shells.push_back(shell);
    sources_.addShell(fileIndex_, line);
  }

  /// Number of faces kept so far.
  std::size_t faceCount() const { return model_.shells.size(); }

  /// Finishes the model: checks that every face names an existing vertex, gives the parts
  /// their IDs and names, numbers the elements 1..m and runs checkModel.
  /// Throws InputError (file and line of the face) when a face names a missing vertex, and
  /// "contains no faces" when the file has none.
  FeModel finish(Warnings& warnings) {
    if (model_.shells.empty())
      throw InputError(file_, 0,
                       "contains no faces (" + std::to_string(model_.nodes.size()) +
                           " vertices): not a surface mesh voxremesh can use");
    const auto vertexCount = static_cast<std::int64_t>(model_.nodes.size());
    for (std::size_t i = 0; i < model_.shells.size(); ++i) {
      Shell& shell = model_.shells[i];
      shell.id = static_cast<Id>(i + 1);
      for (int k = 0; k < shell.nodeCount; ++k) {
        if (shell.nodes[k] < 1 || shell.nodes[k] > vertexCount)
          throw InputError(sources_.shellFile(i), sources_.shellLine(i),
                           "face " + std::to_string(i + 1) + " names vertex " +
                               std::to_string(shell.nodes[k] - 1 + indexBase_) +
                               ", but the file defines only " + std::to_string(vertexCount) +
                               " vertices" +
                               (indexBase_ == 0 ? " (numbered from 0)" : " (numbered from 1)"));
      }
    }
    assignParts(warnings);
    if (collapsedQuads_ > 0)
      warnings.push_back(file_ + ": " + std::to_string(collapsedQuads_) +
                         " quadrilateral face(s) repeat a corner and were read as triangles");
    if (droppedFaces_ > 0)
      warnings.push_back(file_ + ": " + std::to_string(droppedFaces_) +
                         " degenerate face(s) with fewer than three distinct corners were left "
                         "out (first at " +
                         (firstDroppedLine_ > 0 ? "line " + std::to_string(firstDroppedLine_)
                                                : std::string("a binary record")) +
                         ")");
    checkModel(model_, sources_);
    return std::move(model_);
  }

 private:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

  struct PendingPart {
    std::string name;
    Id id = 0;
    bool fixedId = false;
  };

  void assignParts(Warnings& warnings) {
    // Restored and explicit IDs first, then the others in order of first appearance.
    std::set<Id> taken;
    for (PendingPart& part : parts_) {
      if (!part.fixedId) {
        const auto restored = restoredIds_.find(part.name);
        if (restored != restoredIds_.end() && !taken.count(restored->second)) {
          part.id = restored->second;
          part.fixedId = true;
        } else if (restored != restoredIds_.end()) {
          warnings.push_back(file_ + ": part '" + part.name + "' restores ID " +
                             std::to_string(restored->second) +
                             ", which another part already has; it gets a new ID");
        }
      }
      if (part.fixedId) taken.insert(part.id);
    }
    Id next = 1;
    for (PendingPart& part : parts_) {
      if (part.fixedId) continue;
      while (taken.count(next)) ++next;
      part.id = next;
      taken.insert(next);
    }
    std::vector<bool> used(parts_.size(), false);
    for (Shell& shell : model_.shells) used[static_cast<std::size_t>(shell.part)] = true;
    for (Shell& shell : model_.shells) shell.part = parts_[static_cast<std::size_t>(shell.part)].id;
    for (std::size_t i = 0; i < parts_.size(); ++i) {
      if (!used[i]) continue;
      PendingPart& part = parts_[i];
      if (part.name.empty()) {
        const auto restored = restoredNames_.find(part.id);
        part.name =
            restored != restoredNames_.end() ? restored->second : "part_" + std::to_string(part.id);
      }
      model_.parts.push_back(Part{part.id, part.name, false});
    }
  }

  FeModel model_;
  SourceMap sources_;
  std::string file_;
  std::uint32_t fileIndex_ = 0;
  int indexBase_ = 1;
  std::vector<PendingPart> parts_;
  std::unordered_map<std::string, std::size_t> partsByName_;
  std::unordered_map<Id, std::size_t> partsById_;
  std::unordered_map<std::string, Id> restoredIds_;
  std::unordered_map<Id, std::string> restoredNames_;
  std::size_t current_ = kNone;
  std::size_t droppedFaces_ = 0;
  std::size_t firstDroppedLine_ = 0;
  std::size_t collapsedQuads_ = 0;
};

/// Maps node IDs to 0-based vertex indices for writing index-based formats.
class NodeIndexer {
 public:
  /// Indexes the nodes of `model` in model order.
  /// Throws std::invalid_argument when two nodes share an ID.
  explicit NodeIndexer(const FeModel& model) {
    Id lo = std::numeric_limits<Id>::max();
    Id hi = std::numeric_limits<Id>::min();
    for (const Node& node : model.nodes) {
      lo = std::min(lo, node.id);
      hi = std::max(hi, node.id);
    }
    const std::size_t n = model.nodes.size();
    // Dense IDs (the usual case): a direct table; sparse IDs: a hash map.
    const std::uint64_t span =
        n > 0 ? static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo) : 0;
    if (n > 0 && span < 4 * static_cast<std::uint64_t>(n) + 1024) {
      offset_ = lo;
      dense_.assign(static_cast<std::size_t>(span) + 1, kMissing);
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint64_t at =
            static_cast<std::uint64_t>(model.nodes[i].id) - static_cast<std::uint64_t>(lo);
        std::size_t& slot = dense_[static_cast<std::size_t>(at)];
        if (slot != kMissing) duplicate(model.nodes[i].id);
        slot = i;
      }
    } else {
      sparse_.reserve(n);
      for (std::size_t i = 0; i < n; ++i)
        if (!sparse_.emplace(model.nodes[i].id, i).second) duplicate(model.nodes[i].id);
    }
  }

  /// Appends " i j k [l]": the vertex indices of the shell's corners, counted from `base`.
  /// Throws like index() for a corner that names a missing node.
  void appendCorners(std::string& out, const Shell& shell, std::int64_t base = 0) const {
    for (int c = 0; c < shell.nodeCount; ++c) {
      out += ' ';
      appendInt(out, static_cast<std::int64_t>(
                         index(shell.nodes[static_cast<std::size_t>(c)], shell.id)) +
                         base);
    }
  }

  /// The 0-based index of node `id`.
  /// Throws std::invalid_argument naming the element when the node does not exist.
  std::size_t index(Id id, Id element) const {
    if (!dense_.empty()) {
      const std::uint64_t at = static_cast<std::uint64_t>(id) - static_cast<std::uint64_t>(offset_);
      if (id >= offset_ && at < dense_.size()) {
        const std::size_t i = dense_[static_cast<std::size_t>(at)];
        if (i != kMissing) return i;
      }
    } else {
      const auto it = sparse_.find(id);
      if (it != sparse_.end()) return it->second;
    }
    throw std::invalid_argument("element " + std::to_string(element) + " names node " +
                                std::to_string(id) + ", which the model does not have");
  }

 private:
  static constexpr std::size_t kMissing = std::numeric_limits<std::size_t>::max();
  [[noreturn]] static void duplicate(Id id) {
    throw std::invalid_argument("two nodes share the ID " + std::to_string(id));
  }
  Id offset_ = 0;
  std::vector<std::size_t> dense_;
  std::unordered_map<Id, std::size_t> sparse_;
};

/// The name a part is written under: its own, or "part_<id>" when it has none or is missing.
inline std::string partLabel(const FeModel& model, Id id) {
  const Part* part = model.findPart(id);
  if (part && !part->name.empty()) return part->name;
  return "part_" + std::to_string(id);
}

/// Adds a warning when the model carries per-node or per-element data (LS-DYNA/Nastran extras)
/// that `format` cannot hold.
inline void warnExtrasLost(const FeModel& model, const char* format, Warnings& warnings) {
  std::size_t shells = 0;
  for (const Shell& shell : model.shells) shells += shell.extras >= 0;
  if (shells > 0)
    warnings.push_back(std::to_string(shells) +
                       " element(s) carry thickness, angle or offset data that " + format +
                       " cannot hold; it is left out");
  if (!model.nodeExtras.empty())
    warnings.push_back(std::to_string(model.nodeExtras.size()) +
                       " node(s) carry constraint or coordinate-system fields that " + format +
                       " cannot hold; they are left out");
}

/// Appends `value` as little-endian bytes.
template <typename T>
void appendLittleEndian(std::string& out, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  const std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  if (first != 1) std::reverse(bytes, bytes + sizeof(T));
  out.append(reinterpret_cast<const char*>(bytes), sizeof(T));
}

/// Reads a value stored with the given byte order at `data` (no alignment needed).
template <typename T>
T readBytes(const char* data, bool littleEndian) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, data, sizeof(T));
  const std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  const bool hostLittle = first == 1;
  if (hostLittle != littleEndian) std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

/// Splits `line` at blanks (space, tab, CR) into at most `capacity` tokens; returns how many
/// tokens the line has (which may exceed capacity: only the first `capacity` are stored).
inline std::size_t splitBlanks(std::string_view line, std::string_view* tokens,
                               std::size_t capacity) {
  std::size_t count = 0;
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i >= n) break;
    const std::size_t start = i;
    while (i < n && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (count < capacity) tokens[count] = line.substr(start, i - start);
    ++count;
  }
  return count;
}

/// The text of `s` quoted for an error message, shortened to 60 characters.
inline std::string quoted(std::string_view s) {
  if (s.size() > 60) return "'" + std::string(s.substr(0, 57)) + "...'";
  return "'" + std::string(s) + "'";
}

}  // namespace voxremesh::io::surface
