// Topology checks of a QuadMesh for the extraction and optimisation tests.
#pragma once

#include <cstddef>

#include "voxremesh/quad_mesh.h"

namespace voxremesh::test {

/// Counts that say whether a mesh is a clean, oriented 2-manifold (with boundary).
struct MeshTopology {
  std::size_t edges = 0;
  std::size_t boundaryEdges = 0;        ///< edges of one face
  std::size_t nonManifoldEdges = 0;     ///< edges of three or more faces
  std::size_t inconsistentEdges = 0;    ///< edges two faces traverse in the same direction
  std::size_t nonManifoldVertices = 0;  ///< vertices whose faces form more than one fan
  std::size_t unusedPoints = 0;         ///< points no face uses
  std::size_t boundaryLoops = 0;        ///< closed chains of boundary edges
  std::size_t components = 0;           ///< face-connected pieces (across edges)
  int eulerCharacteristic = 0;          ///< used points - edges + faces
};

/// Computes the counts of MeshTopology.
MeshTopology meshTopology(const QuadMesh& mesh);

}  // namespace voxremesh::test
