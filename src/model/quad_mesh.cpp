// Building a QuadMesh from the shells of a model.
#include "voxremesh/quad_mesh.h"

#include <map>
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

QuadMesh joinAtJunctions(const std::vector<QuadMesh>& meshes) {
  QuadMesh joined;
  if (!meshes.empty()) joined.part = meshes.front().part;
  std::map<std::array<double, 3>, CornerIndex> junctionPoint;
  for (const QuadMesh& mesh : meshes) {
    const auto curveBase = static_cast<std::uint32_t>(joined.curves.size());
    joined.curves.insert(joined.curves.end(), mesh.curves.begin(), mesh.curves.end());
    std::vector<CornerIndex> index(mesh.points.size());
    for (std::size_t v = 0; v < mesh.points.size(); ++v) {
      PointConstraint constraint =
          mesh.constraints.empty() ? PointConstraint{} : mesh.constraints[v];
      if (constraint.curve != kNoCurve) constraint.curve += curveBase;
      if (constraint.role == PointRole::Junction) {
        const auto [it, inserted] =
            junctionPoint.emplace(mesh.points[v], static_cast<CornerIndex>(joined.points.size()));
        if (!inserted) {
          index[v] = it->second;
          continue;
        }
      }
      index[v] = static_cast<CornerIndex>(joined.points.size());
      joined.points.push_back(mesh.points[v]);
      joined.constraints.push_back(constraint);
    }
    for (std::array<CornerIndex, 4> face : mesh.faces) {
      for (int k = 0; k < cornerCount(face); ++k)
        face[static_cast<std::size_t>(k)] = index[face[static_cast<std::size_t>(k)]];
      joined.faces.push_back(face);
    }
  }
  return joined;
}

void eraseUnusedPoints(QuadMesh& mesh) {
  std::vector<CornerIndex> newIndex(mesh.points.size(), kNoCorner);
  for (const auto& face : mesh.faces)
    for (int k = 0; k < cornerCount(face); ++k) newIndex[face[static_cast<std::size_t>(k)]] = 0;
  CornerIndex next = 0;
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    if (newIndex[v] == kNoCorner) continue;
    newIndex[v] = next;
    mesh.points[next] = mesh.points[v];
    if (!mesh.constraints.empty()) mesh.constraints[next] = mesh.constraints[v];
    ++next;
  }
  mesh.points.resize(next);
  if (!mesh.constraints.empty()) mesh.constraints.resize(next);
  for (auto& face : mesh.faces)
    for (int k = 0; k < cornerCount(face); ++k)
      face[static_cast<std::size_t>(k)] = newIndex[face[static_cast<std::size_t>(k)]];
}

}  // namespace voxremesh
