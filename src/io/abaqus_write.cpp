// Abaqus input (.inp) writer: the source's verbatim blocks in order with regenerated *NODE and
// *ELEMENT blocks at their places, or a fresh flat deck for a model from another format.
#include <algorithm>
#include <charconv>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "io/abaqus_syntax.h"
#include "io/formats.h"
#include "io/text_scan.h"

namespace voxremesh::io {

namespace {

using abaqus::ElementClass;

void appendId(std::string& out, Id value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

/// The labels parts are written under: valid Abaqus labels, quoted where needed, and distinct
/// (Abaqus labels are case-insensitive).
class PartLabels {
 public:
  PartLabels(const FeModel& model, Warnings& warnings) {
    std::unordered_map<std::string, Id> owners;
    auto add = [&](Id id, const std::string& given) {
      std::string name = given.empty() ? "PART_" + std::to_string(id) : given;
      for (char& c : name) {
        if (c == '\n' || c == '\r' || c == '\t') c = ' ';
        if (c == '"') c = '\'';
      }
      if (name != given && !given.empty())
        warnings.push_back("part " + std::to_string(id) + " '" + given +
                           "': characters Abaqus labels cannot hold were replaced: '" + name + "'");
      const auto owner = owners.find(toUpper(name));
      if (owner != owners.end() && owner->second != id) {
        const std::string unique = name + "_" + std::to_string(id);
        warnings.push_back("part " + std::to_string(id) + " '" + name + "' has the name of part " +
                           std::to_string(owner->second) +
                           " (Abaqus labels ignore case); written as '" + unique + "'");
        name = unique;
      }
      if (name.size() > 80)
        warnings.push_back("part " + std::to_string(id) + " '" + name +
                           "' is longer than the 80 characters Abaqus allows for labels");
      owners.emplace(toUpper(name), id);
      names_.emplace(id, name);
    };
    for (const Part& part : model.parts)
      if (!names_.count(part.id)) add(part.id, part.name);
    for (const Shell& shell : model.shells)
      if (!names_.count(shell.part)) add(shell.part, {});
  }

  /// The label's text (without quotes).
  const std::string& name(Id part) const { return names_.at(part); }

 private:
  std::unordered_map<Id, std::string> names_;
};

void appendLabel(std::string& out, const std::string& name) {
  if (abaqus::isPlainLabel(name)) {
    out += name;
  } else {
    out += '"';
    out += name;
    out += '"';
  }
}

/// The Abaqus element type a shell is written with: its own when that is an Abaqus 3-/4-node
/// surface type of its node count (or the family's counterpart), else S3R / S4R.
class ShellTypes {
 public:
  explicit ShellTypes(const FeModel& model) {
    std::vector<std::string> names = model.shellTypes;
    names.push_back({});  // for a type index beyond the table: the defaults
    for (const std::string& name : names) {
      const std::string upper = toUpper(name);
      const ElementClass kind = abaqus::classifyElementType(upper);
      std::string tria = "S3R";
      std::string quad = "S4R";
      if (kind == ElementClass::Shell3) {
        tria = upper;
        const std::string_view other = abaqus::counterpartType(upper);
        if (!other.empty()) quad = std::string(other);
      } else if (kind == ElementClass::Shell4) {
        quad = upper;
        const std::string_view other = abaqus::counterpartType(upper);
        if (!other.empty()) tria = std::string(other);
      }
      trias_.push_back(tria);
      quads_.push_back(quad);
    }
  }

  const std::string& of(const Shell& shell) const {
    const std::size_t i = shell.type < trias_.size() ? shell.type : trias_.size() - 1;
    return shell.nodeCount == 3 ? trias_[i] : quads_[i];
  }

 private:
  std::vector<std::string> trias_;
  std::vector<std::string> quads_;
};

void writeNodes(const FeModel& model, std::string& out) {
  out += "*NODE\n";
  for (const Node& node : model.nodes) {
    appendId(out, node.id);
    for (double v : node.xyz) {
      out += ", ";
      appendShortest(out, v);
    }
    out += '\n';
  }
}

void writeShells(const FeModel& model, std::string& out, const PartLabels& labels,
                 const ShellTypes& types) {
  std::size_t i = 0;
  while (i < model.shells.size()) {
    const Shell& first = model.shells[i];
    const std::string& type = types.of(first);
    const std::string& label = labels.name(first.part);
    out += abaqus::kPartComment;
    appendId(out, first.part);
    out += " \"" + label + "\"\n";
    out += "*ELEMENT, TYPE=" + type + ", ELSET=";
    appendLabel(out, label);
    out += '\n';
    for (; i < model.shells.size(); ++i) {
      const Shell& shell = model.shells[i];
      if (shell.part != first.part || &types.of(shell) != &type) break;
      appendId(out, shell.id);
      for (int k = 0; k < shell.nodeCount; ++k) {
        out += ", ";
        appendId(out, shell.nodes[static_cast<std::size_t>(k)]);
      }
      out += '\n';
    }
  }
}

/// True when a verbatim block has a *STEP keyword line (geometry must come before it).
bool hasStep(const DeckBlock& block) {
  std::size_t start = 0;
  const std::string& text = block.text;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view line = trim(std::string_view(text).substr(start, end - start));
    if (istartsWith(line, "*STEP")) return true;
    start = end + 1;
  }
  return false;
}

}  // namespace

void writeAbaqus(const FeModel& model, std::string& out, Warnings& warnings) {
  const PartLabels labels(model, warnings);
  const ShellTypes types(model);
  std::size_t verbatimSize = 0;
  for (const DeckBlock& block : model.blocks) verbatimSize += block.text.size();
  out.reserve(out.size() + verbatimSize + model.nodes.size() * 64 + model.shells.size() * 48);

  bool nodesWritten = false;
  bool shellsWritten = false;
  auto geometry = [&](bool nodes, bool shells) {
    if (!out.empty() && out.back() != '\n') out += '\n';
    if (nodes && !nodesWritten) {
      writeNodes(model, out);
      nodesWritten = true;
    }
    if (shells && !shellsWritten) {
      writeShells(model, out, labels, types);
      shellsWritten = true;
    }
  };

  if (model.sourceFormat == DeckFormat::Abaqus) {
    for (const DeckBlock& block : model.blocks) {
      switch (block.kind) {
        case DeckBlock::Kind::Verbatim:
          // A model without geometry blocks gets its geometry before the first step.
          if (!shellsWritten && hasStep(block)) geometry(true, true);
          if (!out.empty() && out.back() != '\n') out += '\n';
          out += block.text;
          break;
        case DeckBlock::Kind::Nodes:
          geometry(true, false);
          break;
        case DeckBlock::Kind::Shells:
          geometry(true, true);
          break;
      }
    }
    geometry(true, true);
    return;
  }

  out += "*HEADING\nvoxremesh export of a ";
  out += formatName(model.sourceFormat);
  out += " model\n";
  geometry(true, true);
  std::size_t extras = 0;
  for (const Shell& shell : model.shells) extras += shell.extras >= 0;
  if (extras > 0)
    warnings.push_back(std::to_string(extras) +
                       " element(s) carry thickness, angle or offset data that Abaqus element "
                       "lines cannot hold; give it with *SHELL SECTION");
  if (!model.nodeExtras.empty())
    warnings.push_back(std::to_string(model.nodeExtras.size()) +
                       " node(s) carry constraint or coordinate-system fields that Abaqus *NODE "
                       "lines cannot hold; they are left out");
}

}  // namespace voxremesh::io
