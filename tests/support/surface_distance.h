// Brute-force distances for tests: point to a mesh's faces (quads split 0-1-2, 0-2-3), point to a
// set of segments. Exact and slow (every face for every point): an oracle independent of the
// library's own search structures.
#pragma once

#include <array>
#include <vector>

#include "voxremesh/quad_mesh.h"

namespace voxremesh::test {

using Point3 = std::array<double, 3>;

/// Distance from p to the closest point of the triangle abc.
double pointTriangleDistance(const Point3& p, const Point3& a, const Point3& b, const Point3& c);

/// Distance from p to the segment ab.
double pointSegmentDistance(const Point3& p, const Point3& a, const Point3& b);

/// Distance from p to the closest face of the mesh.
double distanceToMesh(const Point3& p, const QuadMesh& mesh);

/// The distinct edges of a mesh used by at least minFaces and at most maxFaces faces, as
/// segments, in ascending order of their point indices.
std::vector<std::array<Point3, 2>> edgeSegments(const QuadMesh& mesh, int minFaces, int maxFaces);

/// The boundary edges of a mesh (edges of one face), as segments.
std::vector<std::array<Point3, 2>> boundarySegments(const QuadMesh& mesh);

/// All edges of a mesh's faces, as segments (shared edges once per face).
std::vector<std::array<Point3, 2>> faceEdgeSegments(const QuadMesh& mesh);

/// Distance from p to the closest of the segments.
double distanceToSegments(const Point3& p, const std::vector<std::array<Point3, 2>>& segments);

}  // namespace voxremesh::test
