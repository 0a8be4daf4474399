// The polygon two faces make around the edge they share, and its cuts along other diagonals: what
// the search engine's recuts (reconnectFailingFaces) choose between, and whether a cut
// folds a face.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "optimize/mesh_topology.h"
#include "voxremesh/quad_mesh.h"

namespace voxremesh::opt {

using Face = std::array<CornerIndex, 4>;

/// The polygon round faces f and g, which share the edge (a, b) with a followed by b in f:
/// f's corners from b round to a, then g's after a up to before b, so oriented like f. Empty when
/// g runs the edge from a to b too (the two are oriented against each other) or the polygon would
/// repeat a corner.
std::vector<CornerIndex> polygonAroundEdge(const Face& f, const Face& g, CornerIndex a,
                                           CornerIndex b);

/// The corner the diagonal from corner i of a polygon of n corners (4 to 6) goes to in a cut
/// into a quad and the rest: i + 2 for 4 corners, i + 3 otherwise (modulo n).
std::size_t diagonalEnd(std::size_t n, std::size_t i);

/// The two faces a polygon of 4, 5 or 6 corners is cut into along the diagonal from corner i to
/// diagonalEnd(n, i): a triangle pair for 4 corners, a quad and a triangle for 5, two quads for
/// 6, oriented like the polygon.
std::array<Face, 2> cutPolygon(const std::vector<CornerIndex>& polygon, std::size_t i);

/// True when neither face of `cut` (the faces that replace faces f and g, which may be one face)
/// points more than 120 degrees (the fold criterion's angle, quality.h) away from a face across
/// one of its edges: the other face of the cut, or a face outside found through `topology` (faces
/// changed since it was built may be missed). A cut along a diagonal outside a non-convex
/// polygon, or across a bend, folds a face, which can pass every criterion of its own.
bool cutKeepsOrientation(const QuadMesh& mesh, const Topology& topology, std::uint32_t f,
                         std::uint32_t g, const std::array<Face, 2>& cut);

}  // namespace voxremesh::opt
