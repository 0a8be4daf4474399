// The sheets of one part as one triangle mesh with the adjacency and pseudo-normals the signed
// distance needs: quads split into triangles 0-1-2 and 0-2-3 (the split OpenVDB's meshToVolume
// uses), edges with their incident triangles, angle-weighted vertex pseudo-normals, and the exact
// closest point of a query point found by local descent from a start polygon.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "voxremesh/sheets.h"

namespace voxremesh::volume {

/// A small double-precision 3-vector for the geometry kernels.
struct V3 {
  double x = 0.0, y = 0.0, z = 0.0;
};
inline V3 operator+(const V3& a, const V3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline V3 operator-(const V3& a, const V3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline V3 operator*(const V3& a, double s) {
  return {a.x * s, a.y * s, a.z * s};
}
inline double dot(const V3& a, const V3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline V3 cross(const V3& a, const V3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const V3& a) {
  return std::sqrt(dot(a, a));
}
/// a / |a|, or the zero vector for a zero vector.
inline V3 normalized(const V3& a) {
  const double l = length(a);
  return l > 0.0 ? a * (1.0 / l) : V3{};
}

constexpr std::uint32_t kNone = 0xffffffffu;

/// Where the closest point lies.
enum class ClosestKind : std::uint8_t { Face, Edge, Vertex };

/// The closest point of the mesh to a query point.
struct ClosestPoint {
  V3 point;                        ///< the closest point
  double distance2 = 0.0;          ///< squared distance to the query point
  std::uint32_t triangle = kNone;  ///< a triangle containing the point (for Face: the one)
  ClosestKind kind = ClosestKind::Face;
  std::uint32_t element = kNone;  ///< triangle, edge or vertex index by kind
};

/// One triangle mesh made of all sheets of a part.
struct SurfaceMesh {
  std::vector<V3> points;
  /// Source polygons (the sheets' faces in sheet order), corners into points; [3] == kNone for
  /// triangles. These are what meshToVolume voxelizes; its polygon index refers to this list.
  std::vector<std::array<std::uint32_t, 4>> polygons;
  std::vector<std::uint32_t> polygonSheet;               ///< sheet index of each polygon
  std::vector<std::uint32_t> sheetPointOffset;           ///< index of each sheet's first point
  std::vector<std::uint32_t> polygonFirstTri;            ///< polygons.size() + 1 offsets into tris
  std::vector<std::array<std::uint32_t, 3>> tris;        ///< corners, orientation of the sheet
  std::vector<std::uint32_t> triPolygon;                 ///< the polygon each triangle comes from
  std::vector<V3> triNormals;                            ///< unit, zero for degenerate triangles
  std::vector<std::array<std::uint32_t, 3>> triEdges;    ///< edge k joins corners k and k+1
  std::vector<std::array<std::uint32_t, 2>> edgePoints;  ///< endpoints, lower index first
  std::vector<std::array<std::uint32_t, 2>> edgeTris;    ///< [1] == kNone on a free boundary
  std::vector<V3> edgeNormals;    ///< pseudo-normal: sum of the incident triangle normals, unit
  std::vector<V3> vertexNormals;  ///< angle-weighted pseudo-normal, unit
  std::vector<std::uint8_t> vertexOnBoundary;
  std::vector<std::uint32_t> vertexTriStart;  ///< points.size() + 1 offsets into vertexTris
  std::vector<std::uint32_t> vertexTris;

  double area = 0.0;
  double minEdgeLength = 0.0;   ///< shortest non-degenerate element edge (quad diagonals
                                ///< excluded; 0 without edges)
  double meanEdgeLength = 0.0;  ///< mean length of the distinct element edges
  V3 boundsMin, boundsMax;      ///< bounding box of the points (zero without points)
};

/// Builds the triangle mesh of the sheets (all of one part).
/// Throws std::invalid_argument naming sheet and face when a face refers to a missing point, a
/// coordinate is not finite, an edge has more than two faces or two faces run through an edge in
/// the same direction (the sheet is not consistently oriented), or sheets are of different parts.
SurfaceMesh buildSurfaceMesh(const std::vector<Sheet>& sheets);

/// The exact closest point of the mesh to p, found by descending from the triangles of each start
/// polygon (the closest polygons of the voxel and its neighbours according to meshToVolume) to
/// adjacent triangles while that brings p closer, and taking the closest result (on exact ties
/// the earlier start). Pass the starts sorted and without repeats so that the result depends on
/// the set only. Where the closest point of a triangle lies on one of its edges or corners but
/// the part of (p - closest) tangential to the triangle is at most tangentialTolerance, it counts
/// as the triangle's interior (the element wins the tie). Edge and vertex results are recomputed
/// from the edge's endpoints in canonical order, so they do not depend on the start triangle.
/// Precondition: count >= 1, every start < mesh.polygons.size().
ClosestPoint closestPointFrom(const SurfaceMesh& mesh, const std::uint32_t* startPolygons,
                              std::size_t count, const V3& p, double tangentialTolerance);

/// The pseudo-normal at a closest point: the triangle normal on a face, the edge or vertex
/// pseudo-normal on an edge or vertex.
inline const V3& pseudoNormal(const SurfaceMesh& mesh, const ClosestPoint& c) {
  switch (c.kind) {
    case ClosestKind::Face:
      return mesh.triNormals[c.element];
    case ClosestKind::Edge:
      return mesh.edgeNormals[c.element];
    case ClosestKind::Vertex:
      break;
  }
  return mesh.vertexNormals[c.element];
}

}  // namespace voxremesh::volume
