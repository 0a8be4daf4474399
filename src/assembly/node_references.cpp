// Dispatch of the node reference scan by format, and the text that replaces a reference.
#include "assembly/node_references.h"

#include "assembly/reference_scanners.h"
#include "io/text_scan.h"

namespace voxremesh::assembly {

std::vector<NodeReference> findNodeReferences(const FeModel& model,
                                              const std::unordered_set<Id>& watched) {
  std::vector<NodeReference> references;
  if (watched.empty()) return references;
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const DeckBlock& block = model.blocks[b];
    if (block.kind != DeckBlock::Kind::Verbatim || block.text.empty()) continue;
    const ReferenceSink sink{b, watched, references};
    switch (model.sourceFormat) {
      case DeckFormat::LsDyna:
        scanLsDynaBlock(block.text, lsDynaDeckFormat(model), sink);
        break;
      case DeckFormat::Nastran:
        scanNastranBlock(block.text, sink);
        break;
      case DeckFormat::Abaqus:
        scanAbaqusBlock(block.text, sink);
        break;
      default:
        break;
    }
  }
  return references;
}

std::vector<NodeReference> findElementReferences(const FeModel& model,
                                                 const std::unordered_set<Id>& watched) {
  std::vector<NodeReference> references;
  if (watched.empty()) return references;
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const DeckBlock& block = model.blocks[b];
    if (block.kind != DeckBlock::Kind::Verbatim || block.text.empty()) continue;
    const ReferenceSink sink{b, watched, references};
    switch (model.sourceFormat) {
      case DeckFormat::LsDyna:
        scanLsDynaElementBlock(block.text, lsDynaDeckFormat(model), sink);
        break;
      case DeckFormat::Nastran:
        scanNastranLoads(block.text, sink);
        break;
      case DeckFormat::Abaqus:
        scanAbaqusElementBlock(block.text, sink);
        break;
      default:
        break;
    }
  }
  return references;
}

std::vector<ElementPressure> findElementPressures(const FeModel& model) {
  std::vector<ElementPressure> pressures;
  if (model.sourceFormat != DeckFormat::Nastran) return pressures;
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const DeckBlock& block = model.blocks[b];
    if (block.kind == DeckBlock::Kind::Verbatim && !block.text.empty())
      scanNastranPressures(block.text, b, pressures);
  }
  return pressures;
}

Id maxVerbatimElementId(const FeModel& model) {
  Id largest = 0;
  for (const DeckBlock& block : model.blocks) {
    if (block.kind != DeckBlock::Kind::Verbatim || block.text.empty()) continue;
    switch (model.sourceFormat) {
      case DeckFormat::LsDyna:
        largest = std::max(largest, lsDynaMaxElementId(block.text));
        break;
      case DeckFormat::Nastran:
        largest = std::max(largest, nastranMaxElementId(block.text));
        break;
      case DeckFormat::Abaqus:
        largest = std::max(largest, abaqusMaxElementId(block.text));
        break;
      default:
        break;
    }
  }
  return largest;
}

bool referenceText(const NodeReference& reference, Id id, std::string& text) {
  text.clear();
  if (reference.width == 0) {
    text = std::to_string(id);
    return true;
  }
  io::appendIntRight(text, id, static_cast<int>(reference.width));
  return text.size() <= reference.width;
}

void ReferenceSink::add(std::size_t offset, std::size_t length, std::size_t width, std::size_t line,
                        Id node, ReferenceKind kind, std::string_view keyword,
                        std::string reason) const {
  NodeReference reference;
  reference.block = block;
  reference.offset = offset;
  reference.length = length;
  reference.width = width;
  reference.line = line;
  reference.node = node;
  reference.kind = kind;
  reference.keyword = std::string(keyword);
  reference.reason = std::move(reason);
  references.push_back(std::move(reference));
}

void ReferenceSink::addRange(std::size_t line, Id first, Id last, Id step,
                             std::string_view keyword) const {
  if (step <= 0 || last < first) return;
  // Sorted, so that the report does not depend on the hash order of the watched set.
  std::vector<Id> covered;
  if (static_cast<std::size_t>((last - first) / step) < watched.size()) {
    for (Id id = first; id <= last; id += step)
      if (watched.count(id)) covered.push_back(id);
  } else {
    for (const Id id : watched)
      if (id >= first && id <= last && (id - first) % step == 0) covered.push_back(id);
    std::sort(covered.begin(), covered.end());
  }
  for (const Id id : covered)
    add(0, 0, 0, line, id, ReferenceKind::Range, keyword,
        "the range " + std::to_string(first) + ".." + std::to_string(last) +
            " covers a removed ID and cannot be rewritten ID by ID");
}

void ReferenceSink::scanSuspects(std::string_view line, std::size_t lineInBlock,
                                 std::size_t skipTokens, std::string_view keyword) const {
  std::size_t token = 0;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() &&
           (line[i] == ' ' || line[i] == '\t' || line[i] == ',' || line[i] == '\r'))
      ++i;
    if (i >= line.size()) break;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != ',' &&
           line[i] != '\r')
      ++i;
    std::int64_t value = 0;
    if (token++ < skipTokens) continue;
    if (io::parseInt(line.substr(start, i - start), value) && watched.count(value))
      add(0, 0, 0, lineInBlock, value, ReferenceKind::Suspect, keyword,
          std::string(keyword) + " is not read field by field; its number " +
              std::to_string(value) + " equals the ID of a removed node");
  }
}

}  // namespace voxremesh::assembly
