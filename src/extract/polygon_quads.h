// A quad-dominant mesh of a closed polygon in space without inner points: the faces of a narrow
// sheet meshed from its boundary alone (narrow_sheet.h), one row of quads across a strip.
//
// The faces are chosen by dynamic programming over the polygon's sub-polygons (Klincsek's
// minimum-weight triangulation, extended to quads): the sub-polygon below each allowed chord i-j
// is closed by a triangle i-k-j or a convex quad i-k-l-j on allowed chords, whichever makes the
// smallest total cost. A face costs most when it fails one of the engineer's quality criteria
// (the element criteria of quality.h, all but the minimum length, which a row across a narrow
// strip cannot meet and which the caller judges against the size it used), then by how far its
// scaled Jacobian is from 1, and a triangle a little more than a quad: the mesh has as few
// failing elements as any mesh of these corners, then as few triangles. A face whose normal
// points against its corners' surface normals is never taken. Where the polygon allows very many
// chords (a wide patch), quads are not searched (the cost would grow with the fourth power of
// the chords per corner) and the faces are triangles.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "voxremesh/quality.h"

namespace voxremesh::extract {

/// Whether the chord between polygon corners i < j (not neighbours) may be an edge.
using ChordTest = std::function<bool(std::size_t i, std::size_t j)>;

/// Faces of polygonQuads: corner indices; a triangle has [3] == UINT32_MAX.
using PolygonFace = std::array<std::uint32_t, 4>;

/// True when quad q is convex (every corner turning the way of its diagonals' normal), no corner
/// flatter than 170 degrees, and its normal agrees with `up`.
bool convexQuad(const std::array<std::array<double, 3>, 4>& q, const std::array<double, 3>& up);

/// Meshes a closed polygon with quads and, where they do better, triangles, all of its corners
/// and no others (see the top of the file).
/// @param corners  the polygon's corners in order, at least 3; faces are oriented like this order
/// @param normals  per corner, the surface normal there (need not be unit), which the faces'
///                 normals must agree with
/// @param maxChord  chords longer than this are not considered (keeps the search near-linear on
///                  a strip)
/// @param chordOk  whether a chord may be an edge
/// @param criteria  the quality limits a face is scored against (targetSize unused)
/// @return the faces, or none when no mesh uses only allowed chords and agrees with the normals
std::vector<PolygonFace> polygonQuads(const std::vector<std::array<double, 3>>& corners,
                                      const std::vector<std::array<double, 3>>& normals,
                                      double maxChord, const ChordTest& chordOk,
                                      const QualitySettings& criteria);

}  // namespace voxremesh::extract
