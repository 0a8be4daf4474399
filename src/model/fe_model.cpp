#include "voxremesh/fe_model.h"

#include <algorithm>
#include <stdexcept>

namespace voxremesh {

std::unordered_map<Id, std::size_t> FeModel::nodeIndex() const {
  std::unordered_map<Id, std::size_t> index;
  index.reserve(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (!index.emplace(nodes[i].id, i).second)
      throw std::runtime_error("duplicate node ID " + std::to_string(nodes[i].id));
  return index;
}

const Part* FeModel::findPart(Id id) const {
  const auto it =
      std::find_if(parts.begin(), parts.end(), [id](const Part& p) { return p.id == id; });
  return it == parts.end() ? nullptr : &*it;
}

Part& FeModel::partOrAdd(Id id, const std::string& name) {
  const auto it =
      std::find_if(parts.begin(), parts.end(), [id](const Part& p) { return p.id == id; });
  if (it != parts.end()) return *it;
  parts.push_back(Part{id, name, false});
  return parts.back();
}

std::uint8_t FeModel::internShellType(const std::string& name) {
  const auto it = std::find(shellTypes.begin(), shellTypes.end(), name);
  if (it != shellTypes.end()) return static_cast<std::uint8_t>(it - shellTypes.begin());
  if (shellTypes.size() >= 256) throw std::length_error("more than 255 element types in one deck");
  shellTypes.push_back(name);
  return static_cast<std::uint8_t>(shellTypes.size() - 1);
}

const char* formatName(DeckFormat format) {
  switch (format) {
    case DeckFormat::LsDyna:
      return "LS-DYNA keyword";
    case DeckFormat::Nastran:
      return "Nastran bulk data";
    case DeckFormat::Abaqus:
      return "Abaqus input";
    case DeckFormat::Obj:
      return "Wavefront OBJ";
    case DeckFormat::Off:
      return "OFF";
    case DeckFormat::Stl:
      return "STL";
    case DeckFormat::Ply:
      return "PLY";
    case DeckFormat::Vtu:
      return "VTK XML unstructured grid";
  }
  return "unknown";
}

}  // namespace voxremesh
