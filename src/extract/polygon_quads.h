// A quad-dominant mesh of a closed polygon in space without inner points: the faces of a narrow
// sheet meshed from its boundary alone (narrow_sheet.h), one row of quads across a strip.
//
// The polygon is first triangulated by dynamic programming over its sub-polygons (Klincsek's
// minimum-weight triangulation, O(n^3)): every triangle costs the inverse of its shape quality
// (4 sqrt(3) area / sum of squared edges, 1 for an equilateral triangle), so that slivers are
// avoided and a strip is crossed by short rungs; only allowed chords are used, and a triangle
// whose normal points against its corners' surface normals is never taken. The triangles' dual
// graph is a tree: its leaves are matched to their parents first (a maximum matching of a tree),
// each pair whose quad is convex becoming that quad.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace voxremesh::extract {

/// Whether the chord between polygon corners i < j (not neighbours) may be an edge.
using ChordTest = std::function<bool(std::size_t i, std::size_t j)>;

/// Faces of polygonQuads: corner indices; a triangle has [3] == UINT32_MAX.
using PolygonFace = std::array<std::uint32_t, 4>;

/// True when quad q is convex (every corner turning the way of its diagonals' normal), no corner
/// flatter than 170 degrees, and its normal agrees with `up`.
bool convexQuad(const std::array<std::array<double, 3>, 4>& q, const std::array<double, 3>& up);

/// Meshes a closed polygon with quads and, where no quad fits, triangles, all of its corners and
/// no others (see the top of the file).
/// @param corners  the polygon's corners in order, at least 3; faces are oriented like this order
/// @param normals  per corner, the surface normal there (need not be unit), which the faces'
///                 normals must agree with
/// @param maxChord  chords longer than this are not considered (keeps the search near-linear on
///                  a strip)
/// @param chordOk  whether a chord may be an edge
/// @return the faces, or none when no triangulation uses only allowed chords and agrees with the
///         normals
std::vector<PolygonFace> polygonQuads(const std::vector<std::array<double, 3>>& corners,
                                      const std::vector<std::array<double, 3>>& normals,
                                      double maxChord, const ChordTest& chordOk);

}  // namespace voxremesh::extract
