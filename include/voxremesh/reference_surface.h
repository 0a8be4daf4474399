// Exact closest points on a triangle/quad surface and on polylines: the original surface that the
// optimiser projects onto and that the quality stage measures distances to. Its faces are fixed;
// its points may move (movePoints), the queries' answers staying exact.
//
// The surface is the triangles of a QuadMesh's faces (a quad split into p0-p1-p2 and p0-p2-p3).
// Queries use a bounding-volume hierarchy (median splits along the longest axis of the triangle
// centroids, four triangles a leaf) and the exact point-triangle distance (Ericson, Real-Time
// Collision Detection 5.1.5). A query's answer depends only on the surface and the query point:
// on exact distance ties the triangle that comes first in face order wins, so results are the
// same for any number of threads. Boxes (of nodes and of each triangle) are grown by a few units
// in the last place, so that skipping one farther than the best answer so far never skips the
// answer, whatever the rounding of the computed closest points.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "voxremesh/quad_mesh.h"

namespace voxremesh {

/// The closest point of a surface to a query point.
struct SurfaceHit {
  std::array<double, 3> point{};  ///< the closest point
  double distance = 0.0;          ///< its distance to the query point
  std::uint32_t face = 0;         ///< the face of the source mesh it lies on
};

/// A surface of fixed faces with exact closest-point queries (see the top of the file).
class ReferenceSurface {
 public:
  /// An empty surface (closestPoint must not be called on it).
  ReferenceSurface() = default;

  /// Builds the hierarchy over the triangles of `mesh`'s faces (constraints and curves are not
  /// used). Faces with a repeated corner are kept (their triangles are degenerate segments).
  /// Throws std::invalid_argument when a face names a missing point or a coordinate is not finite.
  explicit ReferenceSurface(const QuadMesh& mesh);

  /// Takes new positions for the points of the mesh it was built on, the faces unchanged (the
  /// points' count must match): the hierarchy keeps its tree and its boxes are fitted again, so
  /// that every query gives the same answer as on a surface built anew on the moved mesh (only
  /// perhaps more slowly, as the points drift from where the tree was split). Throws
  /// std::invalid_argument when the point count differs or a coordinate is not finite.
  void movePoints(const std::vector<std::array<double, 3>>& points);

  /// True without triangles.
  bool empty() const { return tris_.empty(); }
  /// The number of triangles.
  std::size_t triangleCount() const { return tris_.size(); }

  /// The closest point of the surface to p. Precondition: !empty(). Throws std::invalid_argument
  /// when p is not finite.
  SurfaceHit closestPoint(const std::array<double, 3>& p) const;

  /// The same closest point as closestPoint(p), found faster when face `hintFace` of the source
  /// mesh (e.g. the face of the previous answer for a point that moved a little) is close to p:
  /// its triangles bound the search from the start, which then climbs from the hint's leaf to the
  /// root, searching the other subtree at each step. Any hint gives the same answer; a hint that
  /// is not a face index is ignored.
  SurfaceHit closestPoint(const std::array<double, 3>& p, std::uint32_t hintFace) const;

  /// The closest points of many queries, computed in parallel (TBB); result[i] is for queries[i].
  /// Precondition: !empty().
  std::vector<SurfaceHit> closestPoints(const std::vector<std::array<double, 3>>& queries) const;

  /// The points its triangles use (of a mesh's points, those some face names), in index order.
  std::vector<std::array<double, 3>> usedPoints() const;

 private:
  struct Node {
    std::array<double, 3> lo{}, hi{};  ///< holds the boxes of its triangles
    std::uint32_t first = 0;           ///< leaf: first index into leafTris_; inner: the left child
    std::uint32_t count = 0;           ///< leaf: number of triangles; inner: 0
    std::uint32_t right = 0;           ///< inner: the right child
  };
  /// A triangle in leaf order with its corners and its (grown) box, for the queries.
  struct LeafTriangle {
    std::array<std::array<double, 3>, 3> corners{};
    std::array<double, 3> lo{}, hi{};
    std::uint32_t triangle = 0;  ///< its index into tris_
  };
  /// Sets t's corners from points_ (t.triangle's) and its grown box.
  void fitLeafTriangle(LeafTriangle& t) const;
  std::uint32_t build(std::uint32_t begin, std::uint32_t end,
                      const std::vector<std::array<double, 3>>& centroids);

  std::vector<std::array<double, 3>> points_;
  std::vector<std::array<std::uint32_t, 3>> tris_;
  std::vector<std::uint32_t> triFace_;       ///< the source face of each triangle
  std::vector<std::uint32_t> faceTriStart_;  ///< per source face, its first triangle (+ end)
  std::vector<std::uint32_t> order_;         ///< triangles in leaf order
  std::vector<LeafTriangle> leafTris_;       ///< leafTris_[i] is triangle order_[i]
  std::vector<std::uint32_t> leafSlot_;      ///< per triangle, its index into leafTris_
  std::vector<std::uint32_t> leafNode_;      ///< per triangle, the leaf holding it
  std::vector<std::uint32_t> parent_;        ///< per node, its parent (the root: itself)
  std::vector<Node> nodes_;                  ///< nodes_[0] is the root
};

/// The closest point of segment [a, b] to p (a when the segment has zero length).
std::array<double, 3> closestPointOnSegment(const std::array<double, 3>& p,
                                            const std::array<double, 3>& a,
                                            const std::array<double, 3>& b);

/// The closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection 5.1.5);
/// a degenerate triangle gives the closest point of its edges.
std::array<double, 3> closestPointOnTriangle(const std::array<double, 3>& p,
                                             const std::array<double, 3>& a,
                                             const std::array<double, 3>& b,
                                             const std::array<double, 3>& c);

/// The closest point of a polyline to p (the first segment wins exact ties); a closed polyline
/// also has the segment from its last point back to its first. A single point is its own closest
/// point. Precondition: points is not empty (std::invalid_argument otherwise).
std::array<double, 3> closestPointOnPolyline(const std::vector<std::array<double, 3>>& points,
                                             bool closed, const std::array<double, 3>& p);

}  // namespace voxremesh
