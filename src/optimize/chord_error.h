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

}  // namespace voxremesh::opt
