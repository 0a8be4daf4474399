// How far faces stray from the original surface between their corners: the measure the steps
// that change faces or pull points (reconnectFailingFaces, fitFarOriginalPoints) guard with.
#pragma once

#include <array>
#include <vector>

#include "voxremesh/quad_mesh.h"
#include "voxremesh/reference_surface.h"

namespace voxremesh::opt {

/// The largest distance from `original` of the centre of one of `faces` (corner indexes into
/// `mesh`) or of the middle of one of their edges; 0 for no faces. Precondition: the faces name
/// points of `mesh`; `original` is not empty.
double chordError(const QuadMesh& mesh, const std::vector<std::array<CornerIndex, 4>>& faces,
                  const ReferenceSurface& original);

/// chordError of the faces round one point as only that point moves: the middles of the faces'
/// edges that do not touch it are measured once, at construction; each call measures the rest
/// (the faces' centres and the middles of the edges at the point, each edge once). The same
/// value as chordError of the faces with the mesh as it is at the call.
class ChordAroundPoint {
 public:
  /// Preconditions: as chordError's; `faces` are faces of `mesh` round point v; `original`
  /// outlives this object.
  ChordAroundPoint(const QuadMesh& mesh, const std::vector<std::array<CornerIndex, 4>>& faces,
                   CornerIndex v, const ReferenceSurface& original);
  /// chordError(mesh, faces, original), for `mesh` as at construction but for v's position.
  double operator()(const QuadMesh& mesh) const;

 private:
  const std::vector<std::array<CornerIndex, 4>>& faces_;
  const ReferenceSurface& original_;
  std::vector<std::array<CornerIndex, 2>> edgesAtPoint_;  ///< each edge at v once
  double fixedLargest_ = 0.0;  ///< over the middles of the edges away from v
};

}  // namespace voxremesh::opt
