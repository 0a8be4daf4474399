// Building a QuadMesh from the shells of a model.
#include "voxremesh/quad_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace voxremesh {

namespace {

/// Appends `shell` to `mesh` as a face, adding the points of its nodes not in `pointOfNode` yet
/// (node ID -> mesh point). Throws std::invalid_argument naming the shell and node when the model
/// does not define the node.
void appendShell(const FeModel& model, const std::unordered_map<Id, std::size_t>& nodeIndex,
                 const Shell& shell, QuadMesh& mesh,
                 std::unordered_map<Id, CornerIndex>& pointOfNode) {
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

}  // namespace

QuadMesh quadMeshFromModel(const FeModel& model, Id part) {
  const std::unordered_map<Id, std::size_t> nodeIndex = model.nodeIndex();
  QuadMesh mesh;
  mesh.part = part;
  std::unordered_map<Id, CornerIndex> pointOfNode;
  for (const Shell& shell : model.shells)
    if (part == 0 || shell.part == part) appendShell(model, nodeIndex, shell, mesh, pointOfNode);
  return mesh;
}

std::map<Id, QuadMesh> quadMeshesFromModel(const FeModel& model, const std::vector<Id>& parts) {
  const std::unordered_map<Id, std::size_t> nodeIndex = model.nodeIndex();
  std::map<Id, QuadMesh> meshes;
  std::map<Id, std::unordered_map<Id, CornerIndex>> pointOfNode;
  for (const Shell& shell : model.shells) {
    if (!std::binary_search(parts.begin(), parts.end(), shell.part)) continue;
    QuadMesh& mesh = meshes[shell.part];
    mesh.part = shell.part;
    appendShell(model, nodeIndex, shell, mesh, pointOfNode[shell.part]);
  }
  return meshes;
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

namespace {

/// Junction points by position, found again within a tolerance (a grid of cells that size).
class JunctionPointIndex {
 public:
  explicit JunctionPointIndex(double tolerance) : tolerance_(tolerance) {}

  /// The index stored for a point within the tolerance of p, else stores `index` for p and
  /// returns it.
  CornerIndex findOrAdd(const std::array<double, 3>& p, CornerIndex index) {
    const std::array<long long, 3> cell = cellOf(p);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
          if (it == cells_.end()) continue;
          for (const auto& [q, stored] : it->second)
            if (std::abs(q[0] - p[0]) <= tolerance_ && std::abs(q[1] - p[1]) <= tolerance_ &&
                std::abs(q[2] - p[2]) <= tolerance_)
              return stored;
        }
    cells_[cell].emplace_back(p, index);
    return index;
  }

 private:
  std::array<long long, 3> cellOf(const std::array<double, 3>& p) const {
    if (!(tolerance_ > 0.0)) return {0, 0, 0};
    return {static_cast<long long>(std::floor(p[0] / tolerance_)),
            static_cast<long long>(std::floor(p[1] / tolerance_)),
            static_cast<long long>(std::floor(p[2] / tolerance_))};
  }

  double tolerance_;
  std::map<std::array<long long, 3>, std::vector<std::pair<std::array<double, 3>, CornerIndex>>>
      cells_;
};

/// The tolerance within which junction points of the meshes are one: kJunctionWeldShare of the
/// extent of all their points (rounding of one node computed along two chains of its curve).
double junctionTolerance(const std::vector<QuadMesh>& meshes) {
  constexpr double kJunctionWeldShare = 1e-9;
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  std::array<double, 3> low{kInfinity, kInfinity, kInfinity};
  std::array<double, 3> high{-kInfinity, -kInfinity, -kInfinity};
  for (const QuadMesh& mesh : meshes)
    for (const auto& p : mesh.points)
      for (std::size_t c = 0; c < 3; ++c) {
        low[c] = std::min(low[c], p[c]);
        high[c] = std::max(high[c], p[c]);
      }
  const double extent =
      std::sqrt((high[0] - low[0]) * (high[0] - low[0]) + (high[1] - low[1]) * (high[1] - low[1]) +
                (high[2] - low[2]) * (high[2] - low[2]));
  return std::isfinite(extent) ? kJunctionWeldShare * extent : 0.0;
}

}  // namespace

QuadMesh joinAtJunctions(const std::vector<QuadMesh>& meshes) {
  QuadMesh joined;
  if (!meshes.empty()) joined.part = meshes.front().part;
  JunctionPointIndex junctionPoint(junctionTolerance(meshes));
  for (const QuadMesh& mesh : meshes) {
    const auto curveBase = static_cast<std::uint32_t>(joined.curves.size());
    joined.curves.insert(joined.curves.end(), mesh.curves.begin(), mesh.curves.end());
    std::vector<CornerIndex> index(mesh.points.size());
    for (std::size_t v = 0; v < mesh.points.size(); ++v) {
      PointConstraint constraint =
          mesh.constraints.empty() ? PointConstraint{} : mesh.constraints[v];
      if (constraint.curve != kNoCurve) constraint.curve += curveBase;
      const auto next = static_cast<CornerIndex>(joined.points.size());
      // A junction curve's end is often a corner (a feature point, a hard point) on one side.
      if (constraint.role == PointRole::Junction || constraint.role == PointRole::Corner) {
        index[v] = junctionPoint.findOrAdd(mesh.points[v], next);
        if (index[v] != next) continue;
      }
      index[v] = next;
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
