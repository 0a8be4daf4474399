// Folded faces (quality.h, foldedFaces) of a mesh whose points move while its faces stay: the
// faces' edges are paired once, and each check computes only the normals and their comparison.
#pragma once

#include <cstdint>
#include <vector>

#include "voxremesh/quality.h"

namespace voxremesh::quality {

/// foldedFaces for one set of faces at any positions of their points.
class FoldCheck {
 public:
  /// Pairs the edges of `mesh`'s faces (by their indexes: a check must be given the same faces).
  /// Preconditions: faces name existing points.
  explicit FoldCheck(const QuadMesh& mesh);
  /// foldedFaces(mesh, ridges) for `mesh`, whose faces must be those given at construction (the
  /// points may have moved).
  std::vector<std::uint8_t> folded(const QuadMesh& mesh,
                                   const std::vector<MeshCurve>* ridges = nullptr) const;

 private:
  /// The two faces of a manifold edge, whether they run it opposite ways (consistently
  /// oriented), and the edge's ends.
  struct EdgePair {
    std::uint32_t first, second;
    bool opposite;
    CornerIndex low, high;
  };
  std::vector<EdgePair> pairs_;
};

}  // namespace voxremesh::quality
