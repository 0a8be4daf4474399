// The quad-dominant surface mesh that the extraction, optimisation and quality stages pass along:
// points, faces (quads and triangles), and for every point the curve it must stay on (a feature
// line, a boundary loop, a junction curve) or whether it is fixed (a corner).
//
// Conventions
// - faces[f] lists the corners counter-clockwise seen from the side the surface normal points to
//   (for a mesh extracted from a Volume: towards positive signed distance, the side the original
//   sheet's face normals pointed to). A triangle has faces[f][3] == kNoCorner.
// - constraints is either empty (every point free) or has one entry per point.
// - A point with role Feature, Boundary or Junction lies on curves[constraint.curve] and may only
//   move along it; a Corner point must not move; a Free point moves on the surface.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

#include "voxremesh/fe_model.h"

namespace voxremesh {

/// Index of a point in QuadMesh::points.
using CornerIndex = std::uint32_t;

/// Marks the unused fourth corner of a triangle in QuadMesh::faces.
constexpr CornerIndex kNoCorner = std::numeric_limits<CornerIndex>::max();

/// Marks "no curve" in PointConstraint::curve.
constexpr std::uint32_t kNoCurve = std::numeric_limits<std::uint32_t>::max();

/// What a point of the mesh is bound to.
enum class PointRole : std::uint8_t {
  Free,      ///< an interior point of the surface
  Feature,   ///< on a feature line (sharp edge)
  Boundary,  ///< on a boundary loop (free edge, hole)
  Junction,  ///< on a curve shared with another sheet or part (must stay conforming)
  Corner,    ///< a feature point or boundary corner: fixed
};

/// The constraint of one point.
struct PointConstraint {
  PointRole role = PointRole::Free;
  std::uint32_t curve = kNoCurve;  ///< index into QuadMesh::curves for Feature/Boundary/Junction
};

/// A curve points are bound to, in world coordinates; closed curves do not repeat their first
/// point.
struct MeshCurve {
  std::vector<std::array<double, 3>> points;
  bool closed = false;
  PointRole role = PointRole::Feature;
};

/// A quad-dominant surface mesh with point constraints (see the conventions above).
struct QuadMesh {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<CornerIndex, 4>> faces;
  std::vector<PointConstraint> constraints;  ///< empty, or one per point
  std::vector<MeshCurve> curves;
  Id part = 0;  ///< the part the mesh belongs to (0 when unknown)
};

/// Number of corners of a face: 3 for a triangle, 4 for a quad.
inline int cornerCount(const std::array<CornerIndex, 4>& face) {
  return face[3] == kNoCorner ? 3 : 4;
}

/// Builds the mesh of the shells of one part of a model (or of all shells when part is 0): points
/// are the nodes the shells use in order of first use, faces the shells in model order, every
/// point free. Throws std::invalid_argument naming the shell and node when a shell names a node the
/// model does not define.
QuadMesh quadMeshFromModel(const FeModel& model, Id part = 0);

/// The meshes of several parts of a model, built as quadMeshFromModel builds each, in one pass
/// over its shells (cheaper than one call per part on a deck of many parts).
/// @param parts  the parts wanted, ascending IDs; a part without shells gets no mesh
/// @return per part with shells, its mesh (QuadMesh::part set)
/// Throws std::invalid_argument as quadMeshFromModel does.
std::map<Id, QuadMesh> quadMeshesFromModel(const FeModel& model, const std::vector<Id>& parts);

/// A model holding the mesh as one part: nodes 1..n in point order, shells 1..m in face order,
/// part `part` (defined, unnamed). Preconditions: every face names existing points.
FeModel modelFromQuadMesh(const QuadMesh& mesh, Id part = 1);

/// Removes the points no face uses, keeping the order of the others and their constraints, and
/// renumbers the faces. Preconditions: every face names existing points.
void eraseUnusedPoints(QuadMesh& mesh);

/// Joins the meshes of the sheets of one part into one mesh: points, constraints, faces and
/// curves concatenated in the given order (curve indices and faces renumbered), then points with
/// role Junction or Corner (a junction curve's end is often a corner on one side) at the same
/// place merged into the first of them, so that sheets extracted separately share their nodes
/// along the junction curves again (a T-junction edge then has three faces). The same place: within
/// 1e-9 of the extent of all the meshes' points (one junction node computed along two chains of its
/// curve may differ in its last bits). The part is the first mesh's. Preconditions: every face
/// names existing points; constraints empty or one per point.
QuadMesh joinAtJunctions(const std::vector<QuadMesh>& meshes);

}  // namespace voxremesh
