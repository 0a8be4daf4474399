// What the optimisation steps compute of a whole mesh and share while it still holds: the
// topology, and the criteria each face fails. optimizeQuadMesh keeps one for all its steps, so
// that a step finds what an earlier one built when the mesh has not changed since (nothing is
// built again from scratch per step); each public step keeps its own.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "optimize/mesh_topology.h"
#include "voxremesh/quality.h"

namespace voxremesh::opt {

/// The topology and per-face failures of the meshes it is asked about, each found again only
/// where the mesh differs from the one it was found for (compared by value: the same results as
/// building them anew, whatever changed the mesh in between).
class MeshCache {
 public:
  /// @param settings  the criteria of failures() (which they must pass checkQualitySettings for)
  explicit MeshCache(const QualitySettings& settings = {}) : settings_(settings) {}

  /// The topology of `mesh` (buildTopology): the one built before when the mesh has the same
  /// faces and number of points, else built anew. The reference holds until the next call.
  const Topology& topology(const QuadMesh& mesh);

  /// Per face of `mesh`, the criteria it fails under the settings (faceFailures): kept for a face
  /// with the same corners at the same positions as when last found, found anew for the others.
  /// The reference holds until the next call.
  const std::vector<std::uint32_t>& failures(const QuadMesh& mesh);

 private:
  QualitySettings settings_;
  bool hasTopology_ = false;
  std::size_t topologyPoints_ = 0;
  std::vector<std::array<CornerIndex, 4>> topologyFaces_;  ///< the faces topology_ is of
  Topology topology_;
  std::vector<std::array<CornerIndex, 4>> failureFaces_;  ///< the faces failures_ are of
  std::vector<std::array<double, 3>> failurePoints_;      ///< their points' positions then
  std::vector<std::uint32_t> failures_;
};

}  // namespace voxremesh::opt
