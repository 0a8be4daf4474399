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

}  // namespace voxremesh
