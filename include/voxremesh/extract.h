// The extraction stage: from a Volume to a quad-dominant surface mesh (Bidmon et al., Sect. 4).
//
// Dual quads. For every cell of the sdf grid (the cube whose lowest corner is voxel (i,j,k)) whose
// eight corners are active, valid (not in the invalid mask) and not all of one sign, MC33
// (mc33.h) decides the surface components inside the cell; each component loop gets one vertex,
// the mean of its edge crossing points. (A component with two loops, an MC33 tunnel, gets one
// vertex per loop: a single vertex would make the mesh non-manifold there; the face decisions,
// and so the absence of cracks, are unchanged, and the interior ambiguity is resolved without
// the tunnel. Likewise, where two neighbouring cells each have one loop through both arcs of
// their shared face, both loops are cut at that face into two vertices each, which resolves that
// face the other way in both cells; otherwise four quads would share one edge.) For every grid edge
// whose two voxels differ in sign and whose four surrounding cells all have vertices, one quad
// joins the vertices of the four cells that hold that edge's crossing, counter-clockwise seen from
// the positive side. Cells crossed by a boundary loop of the volume (closed cube) get no vertex
// either, so that the mesh stops short of every boundary, holes of one element included.
//
// Junctions. Where a boundary loop runs along a junction curve of the volume (a T-junction with
// another sheet of the part, a seam with another part), the boundary strip's nodes there are the
// ones the junction curve prescribes, computed from the curve alone (src/extract/junction_nodes.h:
// about one per voxel size, through the curve's corners), with bit-identical coordinates and role
// Junction: the meshes extracted on every side of the junction share those nodes once welded.
//
// The work runs over the active leaves of the sdf with TBB (tree::LeafManager; counts, prefix
// sums, fill), like OpenVDB's VolumeToMesh; the output does not depend on the thread count.
#pragma once

#include <cstddef>
#include <cstdint>

#include "voxremesh/quad_mesh.h"
#include "voxremesh/volume.h"

namespace voxremesh {

/// The narrow band, in voxels each side, that holds every distance the extraction reads: a cell
/// the surface passes through has its corners within sqrt(3) voxels of it, and a cell with an
/// inactive corner gets no vertex (see the top of the file). remeshDeck builds its volumes with
/// this band (RemeshSettings::volume); a wider one gives the same mesh at a higher cost.
inline constexpr double kExtractionBandVoxels = 2.0;

/// Settings of the extraction stage.
struct ExtractSettings {
  /// Rebuild the strip between the dual mesh and the volume's boundary loops (paper Fig. 7).
  bool rebuildBoundary = true;
  /// Move the vertices of cells marked in the feature mask onto the feature lines and points.
  bool snapFeatures = true;
  /// The spacing of the nodes on junction curves; 0: the voxel size. Sheets or parts that share
  /// a junction curve get the same nodes on it only with the same spacing (remeshDeck gives
  /// parts that share nodes the smallest target size among them).
  double junctionSpacing = 0.0;
};

/// What the extraction did, for reports and tests.
struct ExtractStats {
  std::uint64_t surfaceCells = 0;  ///< valid cells with at least one component
  std::uint64_t tunnelCells = 0;   ///< cells with an MC33 tunnel (split into one vertex per loop)
  std::uint64_t skippedCells = 0;  ///< sign-changing cells left out (invalid, inactive, boundary)
  /// Cells whose loop was cut in two at an ambiguous face because the cell across it also has
  /// one loop through both arcs of that face (two cells each; see the top of the file).
  std::uint64_t cutCells = 0;
  std::uint64_t dualVertices = 0;     ///< vertices of the dual mesh
  std::uint64_t dualQuads = 0;        ///< quads of the dual mesh
  std::uint64_t stripQuads = 0;       ///< quads of the rebuilt boundary strip
  std::uint64_t stripTriangles = 0;   ///< triangles of the rebuilt boundary strip
  std::uint64_t snappedVertices = 0;  ///< vertices moved onto feature lines or points
  std::uint64_t junctionNodes = 0;    ///< boundary nodes placed on junction curves
  /// Nodes inside the surface along the bridges of the boundary strip (a neck between two loops
  /// the dual mesh did not pass, longer than 1.5 voxels), each laid on the zero level set.
  std::uint64_t bridgeNodes = 0;
  /// Quads of the ladders the strip lays across such necks, from the bridge outwards while the
  /// two loops run side by side (part of stripQuads).
  std::uint64_t ladderQuads = 0;
  /// Dual faces removed where a vertex of the dual boundary is passed twice and the strip built
  /// from both passes gave an edge more than two faces (the smaller fans there; the strip is then
  /// built again).
  std::uint64_t pinchedFaces = 0;
};

/// Extracts the quad mesh of a volume (see the top of the file).
/// @param volume    a non-empty volume (buildVolume or readVolume)
/// @param settings  see ExtractSettings
/// @param stats     when not null, receives the counts of ExtractStats
/// @return the mesh in world coordinates; points on boundary loops, feature lines and feature
///         points carry their constraints, and curves holds the volume's curves
/// Throws std::invalid_argument for an empty volume; std::runtime_error when the boundary strip
/// cannot be rebuilt (naming the loop).
QuadMesh extractQuadMesh(const Volume& volume, const ExtractSettings& settings = {},
                         ExtractStats* stats = nullptr);

/// The MC33 triangulation of the same valid cells (mc33::cellTriangles), for inspection and
/// comparison: crossing points shared between neighbouring cells, every point free.
/// Throws std::invalid_argument for an empty volume.
QuadMesh extractTriangles(const Volume& volume);

}  // namespace voxremesh
