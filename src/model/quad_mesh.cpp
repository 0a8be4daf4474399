// Building a QuadMesh from the shells of a model.
#include "voxremesh/quad_mesh.h"

#include <stdexcept>
#include <string>
#include <unordered_map>

namespace voxremesh {

QuadMesh quadMeshFromModel(const FeModel& model, Id part) {
  const std::unordered_map<Id, std::size_t> nodeIndex = model.nodeIndex();
  QuadMesh mesh;
  mesh.part = part;
  std::unordered_map<Id, CornerIndex> pointOfNode;
  for (const Shell& shell : model.shells) {
    if (part != 0 && shell.part != part) continue;
    std::array<CornerIndex, 4> face{kNoCorner, kNoCorner, kNoCorner, kNoCorner};
    for (int c = 0; c < shell.nodeCount; ++c) {
      const Id node = shell.nodes[static_cast<std::size_t>(c)];
      auto [it, inserted] =
          pointOfNode.try_emplace(node, static_cast<CornerIndex>(mesh.points.size()));
      if (inserted) {
        const auto found = nodeIndex.find(node);
        if (found == nodeIndex.end()) {
          throw std::invalid_argument("shell " + std::to_string(shell.id) + " names node " +
                                      std::to_string(node) + ", which the model does not define");
        }
        mesh.points.push_back(model.nodes[found->second].xyz);
      }
      face[static_cast<std::size_t>(c)] = it->second;
    }
    mesh.faces.push_back(face);
  }
  return mesh;
}

FeModel modelFromQuadMesh(const QuadMesh& mesh, Id part) {
  FeModel model;
  model.nodes.reserve(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    model.nodes.push_back({static_cast<Id>(i + 1), mesh.points[i]});
  model.shells.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    Shell shell;
    shell.id = static_cast<Id>(f + 1);
    shell.part = part;
    shell.nodeCount = static_cast<std::uint8_t>(cornerCount(mesh.faces[f]));
    for (int c = 0; c < shell.nodeCount; ++c)
      shell.nodes[std::size_t(c)] = static_cast<Id>(mesh.faces[f][std::size_t(c)]) + 1;
    model.shells.push_back(shell);
  }
  model.partOrAdd(part);
  return model;
}

}  // namespace voxremesh
