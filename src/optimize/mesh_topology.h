// What the optimisation steps share: precondition checks, the connectivity of a QuadMesh (faces
// and edge neighbours per point, boundary points, edge lookup), constrained positions, merging
// two points under the constraint and manifold rules, and compaction after topology changes.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "geometry/polyline_index.h"
#include "geometry/vec3.h"
#include "voxremesh/quad_mesh.h"
#include "voxremesh/reference_surface.h"

namespace voxremesh::opt {

using geom::Vec3;

/// Throws std::invalid_argument when a point has a non-finite coordinate, a face names a missing
/// point or repeats a corner, or the
/// constraints are neither empty nor one per point, or a curve constraint names a missing or
/// empty curve.
void checkMesh(const QuadMesh& mesh);

/// The role of point v as the optimisation steps treat it: Free when the mesh has no
/// constraints; a Junction point is a Corner (fixed and never merged into another point, so that
/// the meshes of two sheets sharing the junction curve stay conforming).
inline PointRole roleOf(const QuadMesh& mesh, CornerIndex v) {
  if (mesh.constraints.empty()) return PointRole::Free;
  const PointRole role = mesh.constraints[v].role;
  return role == PointRole::Junction ? PointRole::Corner : role;
}

/// The connectivity of a mesh at one moment. Lists are ascending.
struct Topology {
  std::vector<std::uint32_t> faceStart, faceList;  ///< point -> faces using it
  std::vector<std::uint32_t> nbrStart, nbrList;    ///< point -> points sharing an edge with it
  std::vector<std::uint32_t> nbrFaces;  ///< per nbrList entry: the number of faces of that edge
  std::vector<std::uint8_t> boundary;   ///< point lies on an edge with one face

  std::size_t faceCount(CornerIndex v) const { return faceStart[v + 1] - faceStart[v]; }
  const std::uint32_t* facesBegin(CornerIndex v) const { return faceList.data() + faceStart[v]; }
  const std::uint32_t* facesEnd(CornerIndex v) const { return faceList.data() + faceStart[v + 1]; }
  std::size_t degree(CornerIndex v) const { return nbrStart[v + 1] - nbrStart[v]; }
  const std::uint32_t* nbrsBegin(CornerIndex v) const { return nbrList.data() + nbrStart[v]; }
  const std::uint32_t* nbrsEnd(CornerIndex v) const { return nbrList.data() + nbrStart[v + 1]; }
  /// Number of faces with edge (a, b) (0 when a and b share no edge).
  std::size_t edgeFaces(CornerIndex a, CornerIndex b) const;
};

/// Builds the connectivity of the mesh (faces flagged in `deleted`, when given, are left out):
/// counting sorts, neighbour lists sorted per point in parallel; deterministic.
Topology buildTopology(const QuadMesh& mesh, const std::vector<std::uint8_t>* deleted = nullptr);

/// Where point v may be when it would like to be at `wanted`: Corner: where it is; curve point:
/// the closest point of its curve; Free: wanted.
Vec3 constrainedPosition(const QuadMesh& mesh, CornerIndex v, const Vec3& wanted);

/// Closest-point indexes of the curves of `mesh`, result[c] for mesh.curves[c]. They hold copies
/// of the curves: valid while the points and faces of the mesh change, stale once its curves do.
std::vector<PolylineIndex> indexCurves(const QuadMesh& mesh);

/// constrainedPosition(mesh, v, wanted), the same position bit for bit, with the closest curve
/// point from `curves` (indexCurves of the mesh whose curves the constraints name, built since
/// those curves last changed) instead of a scan of the curve. A patch cut out of a mesh may keep
/// its constraints and leave its own curves empty: only `curves` is read. Throws
/// std::invalid_argument when v is a curve point whose curve has no index in `curves`.
Vec3 constrainedPosition(const QuadMesh& mesh, const std::vector<PolylineIndex>& curves,
                         CornerIndex v, const Vec3& wanted);

/// The outcome of merging two points: the point that stays and its new position.
struct Merge {
  CornerIndex keep = 0;
  CornerIndex remove = 0;
  Vec3 position{};
};

/// How two points may merge under the constraints: two Free points at their midpoint (the lower
/// index stays); a Free point into a constrained one (at its position); a curve point into a
/// Corner; two points of the same curve at the midpoint's closest curve point. Nothing otherwise.
std::optional<Merge> mergeUnderConstraints(const QuadMesh& mesh, CornerIndex u, CornerIndex v);

/// The link condition for merging u and v: every face holding both is in `collapsing`; the
/// common neighbours of u and v are exactly the points those faces predict (the third corner of a
/// triangle with edge uv, the other two corners of a quad with diagonal uv); and when both are on
/// the boundary, uv is a boundary edge.
bool mergeKeepsManifold(const QuadMesh& mesh, const Topology& topology, CornerIndex u,
                        CornerIndex v);

/// Replaces `merge.remove` by `merge.keep` in the faces of `topology` that use it, moves `keep`
/// to the merge position and reduces the faces that now repeat a point (a quad with a repeated
/// neighbour becomes a triangle; a triangle with one, or a quad with a repeated diagonal, is
/// flagged in `deleted`).
void applyMerge(QuadMesh& mesh, const Topology& topology, const Merge& merge,
                std::vector<std::uint8_t>& deleted);

/// Merges u and v in one round of topology changes when neither neighbourhood is locked,
/// mergeKeepsManifold holds and mergeUnderConstraints allows it; a merged Free point is projected
/// on `surface` when that is given. Then locks both neighbourhoods and applies the merge.
/// Returns whether it merged.
bool tryMerge(QuadMesh& mesh, const Topology& topology, CornerIndex u, CornerIndex v,
              std::vector<std::uint8_t>& locked, std::vector<std::uint8_t>& deleted,
              const ReferenceSurface* surface = nullptr);

/// Marks the points of every face around v (its closed neighbourhood) in `locked`.
void lockNeighbourhood(const QuadMesh& mesh, const Topology& topology, CornerIndex v,
                       std::vector<std::uint8_t>& locked);

/// True when a point of a face around v is marked in `locked`.
bool neighbourhoodLocked(const QuadMesh& mesh, const Topology& topology, CornerIndex v,
                         const std::vector<std::uint8_t>& locked);

/// Erases the faces flagged in `deleted` (keeping the order of the others).
void eraseFaces(QuadMesh& mesh, const std::vector<std::uint8_t>& deleted);

/// The area of a face: |d1 x d2| / 2 for a quad (d the diagonals), |e0 x e1| / 2 for a triangle.
double faceArea(const QuadMesh& mesh, const std::array<CornerIndex, 4>& face);

}  // namespace voxremesh::opt
