// Pinched boundary vertices of the dual mesh: a vertex where two parts of the mesh touch at a
// corner only lies twice on the boundary, and the strip zipped along both passes would give the
// edges from it to the original loop four faces (a non-manifold mesh).
#pragma once

#include <cstddef>
#include <vector>

#include "voxremesh/quad_mesh.h"

namespace voxremesh::extract {

/// Makes the given vertices of `mesh` regular ones: the faces around a vertex form one fan (faces
/// joined across the edges at the vertex). At a vertex with several fans all but the largest (most
/// faces; on ties the one with the lowest face index) are removed; the corners of removed faces
/// are looked at in the next round, until a round removes nothing. The face order of the rest is
/// kept; points are not removed (those of removed faces may be left unused).
/// @param vertices  the vertices to look at first (any order; indices past the points ignored)
/// @return the number of faces removed
/// Throws std::invalid_argument when a face names a missing point.
std::size_t removePinchedFans(QuadMesh& mesh, std::vector<CornerIndex> vertices);

/// The points at the ends of edges of `mesh` that more than two faces share, ascending; points
/// with equal coordinates count as one (the lowest index stands for them), as after a weld.
/// Precondition: the faces name existing points.
std::vector<CornerIndex> endsOfOverfullEdges(const QuadMesh& mesh);

}  // namespace voxremesh::extract
