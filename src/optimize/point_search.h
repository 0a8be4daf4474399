// The pattern search that moves one point to lower the failures of its faces, shared by
// improveFailingElements and reconnectFailingFaces, and the compass search under it, which
// fitFarOriginalPoints uses with its own acceptance (optimize.h).
#pragma once

#include <array>
#include <vector>

#include "optimize/face_score.h"
#include "optimize/mesh_topology.h"
#include "optimize/search_engine.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"

namespace voxremesh::opt {

/// Whether the pattern search may move v: a Free point inside the surface (not on an edge with one
/// face), or a point of a Boundary or Feature curve (Corners and Junction points stay).
inline bool searchable(const QuadMesh& mesh, const Topology& t, CornerIndex v) {
  const PointRole role = roleOf(mesh, v);
  return (role == PointRole::Free && !t.boundary[v]) || role == PointRole::Boundary ||
         role == PointRole::Feature;
}

/// The directions a pattern search moves point v in: 8 unit vectors (the two axes of a basis of the
/// plane normal to the sum of its faces' normals, both ways, then the diagonals), and the mean
/// length of its edges. False (nothing set) where the normals sum to zero or the edges have no
/// length.
bool searchDirections(const QuadMesh& mesh, const Topology& t, CornerIndex v,
                      std::array<Vec3, 8>& directions, double& edge);

/// The compass search of point v: steps of a quarter of `edge`, halved while above
/// `smallestStep` x `edge`, at most `movesPerStep` moves per step length, in `directions`
/// (searchDirections). Each try puts v at place(wanted) and is taken when accept(that position)
/// says so (accept reads the mesh with v there and keeps its own record of the best so far).
/// Leaves v at the last position taken; returns whether v moved.
template <class Place, class Accept>
bool compassSearch(QuadMesh& mesh, CornerIndex v, const std::array<Vec3, 8>& directions,
                   double edge, double smallestStep, int movesPerStep, const Place& place,
                   const Accept& accept) {
  const Vec3 start = mesh.points[v];
  Vec3 position = start;
  for (double step = 0.25 * edge; step > smallestStep * edge; step *= 0.5) {
    bool improved = true;
    for (int round = 0; improved && round < movesPerStep; ++round) {
      improved = false;
      for (const Vec3& direction : directions) {
        const Vec3 wanted{position[0] + direction[0] * step, position[1] + direction[1] * step,
                          position[2] + direction[2] * step};
        mesh.points[v] = place(wanted);
        if (accept(mesh.points[v])) {
          position = mesh.points[v];
          improved = true;
          break;
        }
      }
    }
  }
  mesh.points[v] = position;
  return position != start;
}

/// Whether the search of v was in vain by `record` and no point of v's faces (topology `t` of
/// `mesh`) has changed since: a search depends only on those points' positions, so it would
/// again leave v in place.
inline bool searchUnchangedSinceVain(const VainTries<CornerIndex>& record, const QuadMesh& mesh,
                                     const Topology& t, CornerIndex v) {
  const std::uint32_t at = record.vainAt(v);
  if (at == 0) return false;
  for (const std::uint32_t* f = t.facesBegin(v); f != t.facesEnd(v); ++f)
    for (int k = 0; k < cornerCount(mesh.faces[*f]); ++k)
      if (record.changedSince(mesh.faces[*f][std::size_t(k)], at)) return false;
  return true;
}

/// The summed score of the faces around v (topology `t` of `mesh`).
Score scoreAround(const QuadMesh& mesh, const Topology& t, CornerIndex v,
                  const QualitySettings& settings);

/// Per curve of `mesh`, the positions of the fixed points (Corners, Junction points) that lie on
/// it. Preconditions: checkMesh(mesh) holds.
std::vector<std::vector<Vec3>> fixedPointsOnCurves(const QuadMesh& mesh);

/// The pattern search of one point: steps of a quarter of its mean edge length, halved while
/// above `smallestStep` (a fraction of that length, > 0), at most `movesPerStep` (>= 1) moves
/// per step length, in 8 directions of the plane normal to
/// the sum of its faces' normals; a Free point is projected on `original`, a curve point kept on
/// its curve, and a step is taken when the faces around the point score better (Score::betterThan).
/// Returns whether the point moved.
/// @param mesh          the mesh; `t` its topology; v a point of it
/// @param fixedOnCurve  fixedPointsOnCurves of the mesh whose curves the constraints name: a curve
///                      point never comes within a twentieth of an edge of a fixed point of its
///                      curve (the two would coincide past a sharp turn or the end of a line)
/// @param curves        indexCurves of that mesh
/// @param frozen        when given, the positions the fold check reads for the points round v's
///                      faces (the faces across their edges), v's excepted: positions taken
///                      before searches of other points that may move those points began, so
///                      that the check does not depend on how far those have got
/// Preconditions: v is not a Corner; its curve, if any, is indexed in both lists.
bool improvePoint(QuadMesh& mesh, const Topology& t, const ReferenceSurface& original,
                  const QualitySettings& settings,
                  const std::vector<std::vector<Vec3>>& fixedOnCurve,
                  const std::vector<PolylineIndex>& curves, CornerIndex v,
                  double smallestStep = 0.01, int movesPerStep = 8,
                  const std::vector<Vec3>* frozen = nullptr);

}  // namespace voxremesh::opt
