// Marching Cubes 33 cell topology: for one cell of a scalar grid (8 corner values, iso value 0),
// which sign-changing edges belong to the same piece of the isosurface of the trilinear
// interpolant, the boundary polygons of those pieces, their points and a triangulation
// (Chernyaev 1995; Lewiner et al. 2003; Vega et al. 2019). Used by the dual-quad extraction (one
// vertex per component, at the centroid of its edge crossing points) and for triangle output.
//
// Conventions
// - Cell coordinates: the cell is the unit cube [0,1]^3. Corner c sits at (c & 1, (c >> 1) & 1,
//   (c >> 2) & 1), i.e. c = x + 2y + 4z: 0 (0,0,0), 1 (1,0,0), 2 (0,1,0), 3 (1,1,0), 4 (0,0,1),
//   5 (1,0,1), 6 (0,1,1), 7 (1,1,1). For grid voxel (i,j,k) as corner 0, corner c is voxel
//   (i + x, j + y, k + z).
// - Edges (kEdgeCorners): 0..3 run along x, 4..7 along y, 8..11 along z; edge 4a + m joins the two
//   corners that differ in axis a only, its first corner being the one with coordinate 0 on that
//   axis, m numbering the edges of an axis by the other two coordinates (x-edges by y + 2z, y-edges
//   by x + 2z, z-edges by x + 2y): 0 (0-1), 1 (2-3), 2 (4-5), 3 (6-7), 4 (0-2), 5 (1-3), 6 (4-6),
//   7 (5-7), 8 (0-4), 9 (1-5), 10 (2-6), 11 (3-7).
// - Faces (kFaceCorners, kFaceEdges): face 2a + s is the face where axis a has coordinate s: 0 x=0,
//   1 x=1, 2 y=0, 3 y=1, 4 z=0, 5 z=1. Its corners are listed counter-clockwise seen from outside
//   the cell; face edge k joins face corners k and k+1 (mod 4).
// - Sign: a corner is inside (negative) when its value is < 0; a value exactly 0 (also -0)
//   counts as positive. The same tie rule holds for the face decisions: a face saddle whose value
//   is exactly 0 joins the positive corners (and so does an interior saddle at 0, up to rounding).
//   In other words the topology is that of the level set F = -e for an infinitesimally small
//   e > 0. All face decisions are exact (no rounding), so two cells that share a face (the same 4
//   values) always decide it the same way: no cracks.
// - Components: the connected pieces of {F = 0} inside the closed cell, F the trilinear interpolant
//   of the corner values. Each meets the cell's faces in one or more closed loops of edge crossing
//   points (a disk has one loop, a tunnel two). Components, loops and the edges inside a loop are
//   in a canonical order: a loop starts at its smallest edge, loops are ordered by their first
//   edge, components by their smallest edge.
// - Orientation: loops run counter-clockwise seen from the positive side, i.e. as the boundary of
//   their component oriented with its normal towards the positive values (the direction of the
//   gradient); triangles are oriented the same way.
//
// How the topology is decided (see src/mc33/cell_topology.cpp for the derivation)
// - Faces: F on a face is bilinear; where a face has its negative corners on one diagonal and the
//   positive ones on the other, the asymptotic decider joins the negative corners when the product
//   of the negative corners' values exceeds the product of the positive ones (the face saddle
//   value is negative), else the positive corners. The zero crossings on each face are joined into
//   arcs accordingly; the arcs chain into the loops.
// - Interior: two loops are the same component when the negative regions and the positive regions
//   of the cell they separate are the same 3D regions. Those are found by joining corners along
//   edges and faces, and through the interior by following the cell's bilinear slices z = t: two
//   diagonally opposite z-edges are joined when some slice has them of one sign, the other two
//   z-edges of the other, and its saddle on their side (a quadratic in t, solved exactly up to
//   rounding). This settles the tunnels of MC33 cases 4, 6, 7, 10, 12 and 13.
//
// Everything here is thread-safe (pure functions on constant tables), allocation-free after the
// first call (which builds cellTopology's tables, 41 kB, with thread-safe static initialisation)
// and meant to run for every surface cell of a grid: cellTopology takes about 10 ns on the surface
// cells of a level set and 40 ns on cells of uniformly random values (one core, Release build).
#pragma once

#include <array>
#include <cstdint>

namespace voxremesh::mc33 {

/// The 8 corner values of a cell, indexed by corner (c = x + 2y + 4z). Precondition wherever used:
/// the values are finite.
using CellValues = std::array<float, 8>;

/// A point in cell coordinates ([0,1]^3).
using CellPoint = std::array<float, 3>;

constexpr int kCornerCount = 8;
constexpr int kEdgeCount = 12;
constexpr int kFaceCount = 6;
/// At most 4 components per cell (4 corners of one sign cut off separately, MC33 case 13.1).
constexpr int kMaxComponents = 4;
/// At most 4 loops per cell (every loop has at least 3 of the 12 edges).
constexpr int kMaxLoops = 4;
/// At most 16 triangles per cell (see cellTriangles; the trilinear interpolant needs at most 12).
constexpr int kMaxTriangles = 16;
/// Marks an edge without a zero crossing in CellTopology::edgeComponent.
constexpr std::int8_t kNoComponent = -1;

/// The two corners each edge joins; the first has coordinate 0 along the edge's axis.
constexpr std::array<std::array<std::uint8_t, 2>, kEdgeCount> kEdgeCorners = {{{0, 1},
                                                                               {2, 3},
                                                                               {4, 5},
                                                                               {6, 7},
                                                                               {0, 2},
                                                                               {1, 3},
                                                                               {4, 6},
                                                                               {5, 7},
                                                                               {0, 4},
                                                                               {1, 5},
                                                                               {2, 6},
                                                                               {3, 7}}};

/// The corners of each face, counter-clockwise seen from outside the cell.
constexpr std::array<std::array<std::uint8_t, 4>, kFaceCount> kFaceCorners = {
    {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}}};

/// The edges of each face: edge k joins kFaceCorners[f][k] and kFaceCorners[f][(k + 1) % 4].
constexpr std::array<std::array<std::uint8_t, 4>, kFaceCount> kFaceEdges = {
    {{8, 6, 10, 4}, {5, 11, 7, 9}, {0, 9, 2, 8}, {10, 3, 11, 1}, {4, 1, 5, 0}, {2, 7, 3, 6}}};

/// The topology of the isosurface F = 0 in one cell (see the conventions at the top of the file).
struct CellTopology {
  /// Number of surface components, 0..4.
  std::uint8_t componentCount = 0;
  /// Number of loops, componentCount..4 (a tunnel component has two loops).
  std::uint8_t loopCount = 0;
  /// Per edge: the component its zero crossing belongs to, or kNoComponent without a crossing.
  std::array<std::int8_t, kEdgeCount> edgeComponent{
      kNoComponent, kNoComponent, kNoComponent, kNoComponent, kNoComponent, kNoComponent,
      kNoComponent, kNoComponent, kNoComponent, kNoComponent, kNoComponent, kNoComponent};
  /// The edges of all loops, loop after loop; loop l is loopEdges[loopBegin[l] .. loopBegin[l+1]),
  /// in cyclic order (counter-clockwise seen from the positive side).
  std::array<std::uint8_t, kEdgeCount> loopEdges{};
  /// Start of each loop in loopEdges; loopBegin[loopCount] is the number of crossing edges.
  std::array<std::uint8_t, kMaxLoops + 1> loopBegin{};
  /// The component of each loop.
  std::array<std::uint8_t, kMaxLoops> loopComponent{};

  /// Number of edges of loop l (precondition: l < loopCount).
  int loopSize(int l) const { return loopBegin[l + 1] - loopBegin[l]; }
  /// Edge i of loop l (precondition: l < loopCount, i < loopSize(l)).
  int loopEdge(int l, int i) const { return loopEdges[loopBegin[l] + i]; }
  /// Bit e set for every edge e of component c.
  std::uint16_t componentEdgeMask(int c) const;
  /// Number of loops of component c: 1 for a disk, 2 for a tunnel.
  int componentLoopCount(int c) const;
};

/// Decides the topology of the isosurface F = 0 of the trilinear interpolant F of `values` in the
/// cell: components, the component of every crossing edge, and the loops in cyclic order.
/// Preconditions: finite values. Deterministic, exact on faces; thread-safe; no allocation after
/// the first call.
CellTopology cellTopology(const CellValues& values) noexcept;

/// The zero crossing on `edge` as a parameter in [0,1] from the edge's first corner (kEdgeCorners):
/// a / (a - b) for the corner values a, b (linear interpolation). Depends only on the edge's two
/// values, so neighbouring cells agree. Preconditions: edge in 0..11 with a sign change (one value
/// < 0, the other >= 0); finite values. A zero value gives 0 or 1 (the crossing at that corner).
float edgeCrossing(const CellValues& values, int edge) noexcept;

/// The zero crossing on `edge` in cell coordinates. Preconditions as edgeCrossing.
CellPoint edgePoint(const CellValues& values, int edge) noexcept;

/// The points the dual-quad pass and the triangulation use.
struct CellPoints {
  /// The zero crossing of every crossing edge (edgePoint); (0,0,0) on edges without one.
  std::array<CellPoint, kEdgeCount> edgePoints{};
  /// Per component: the mean of its edges' crossing points (all loops); (0,0,0) past
  /// componentCount.
  std::array<CellPoint, kMaxComponents> centroids{};
};

/// The edge crossing points and component centroids of a cell.
/// Preconditions: `topology` is cellTopology(values); finite values.
CellPoints cellPoints(const CellValues& values, const CellTopology& topology) noexcept;

/// Triangles of a cell's isosurface, on the points of CellPoints: vertex v < 12 is the crossing
/// point of edge v, vertex 12 + c the interior vertex of component c (its centroid).
struct CellTriangles {
  std::uint8_t count = 0;
  /// Vertex triples, oriented like the loops (normal towards the positive side).
  std::array<std::array<std::uint8_t, 3>, kMaxTriangles> triangles{};
  /// The component of each triangle.
  std::array<std::uint8_t, kMaxTriangles> component{};
  /// Bit c set when component c uses its interior vertex 12 + c.
  std::uint8_t interiorVertexMask = 0;
};

/// Vertex id of component c's interior vertex in CellTriangles.
constexpr std::uint8_t interiorVertex(int c) {
  return static_cast<std::uint8_t>(kEdgeCount + c);
}

/// Triangulates each component over its edge crossing points, following its loops:
/// - a disk with 3 points is one triangle; with 4 points two triangles split along the shorter
///   diagonal; with more points a fan from its first point, unless some cell face carries two arcs
///   of the loop (the loop winds around an ambiguous face; a fan could lie in the face or fold
///   over): then a fan around the interior vertex (the component's centroid);
/// - a tunnel (two loops) is a band of n1 + n2 triangles zipping the two loops together (an
///   annulus), the one with the shortest edges between the loops among those without a triangle
///   lying in a cell face. cellTopology never yields more than two loops per component; for a
///   topology that has more, each further loop replaces the last triangle by a band from the loop
///   to that triangle's boundary.
/// Every component's triangles form a connected surface whose boundary is exactly its loops, with
/// Euler characteristic 2 - loops, oriented consistently with the loops; no triangle lies in a
/// face of the cell (so neighbouring cells' triangles never overlap).
/// Preconditions: `topology` and `points` belong to the same cell (cellTopology, cellPoints).
CellTriangles cellTriangles(const CellTopology& topology, const CellPoints& points) noexcept;

}  // namespace voxremesh::mc33
