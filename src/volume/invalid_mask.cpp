// Invalid voxels (Bidmon et al., Sect. 3): closest point on a free boundary with the distance
// vector leaning too far from the face normal. The flag itself is computed per voxel in the
// signed-distance pass; here are the rule and the mask grid built from per-leaf bits.
#include <openvdb/openvdb.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <memory>
#include <vector>

#include "volume/surface_mesh.h"
#include "volume/volume_build.h"

namespace voxremesh::volume {

bool isInvalidVoxel(const SurfaceMesh& mesh, const ClosestPoint& c, const V3& p,
                    double cosThreshold) {
  if (cosThreshold <= 0.0) return false;
  const V3* normal = nullptr;
  switch (c.kind) {
    case ClosestKind::Face:
      return false;  // above the inside of the sheet
    case ClosestKind::Edge:
      if (mesh.edgeTris[c.element][1] != kNone) return false;  // an inner edge
      normal = &mesh.triNormals[mesh.edgeTris[c.element][0]];
      break;
    case ClosestKind::Vertex:
      if (!mesh.vertexOnBoundary[c.element]) return false;
      normal = &mesh.vertexNormals[c.element];
      break;
  }
  const V3 v = p - c.point;
  const double distance = length(v);
  if (distance == 0.0) return false;
  // angle(v, +-normal) > threshold  <=>  |cos| < cos(threshold)
  return std::abs(dot(v, *normal)) < distance * cosThreshold;
}

openvdb::MaskGrid::Ptr maskFromLeafBits(
    const std::vector<openvdb::Coord>& origins,
    const std::vector<openvdb::MaskTree::LeafNodeType::NodeMaskType>& bits,
    const openvdb::math::Transform::Ptr& transform) {
  using MaskLeaf = openvdb::MaskTree::LeafNodeType;
  std::vector<std::unique_ptr<MaskLeaf>> leaves(origins.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, origins.size()),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t n = r.begin(); n < r.end(); ++n) {
                        if (bits[n].isOff()) continue;
                        leaves[n] = std::make_unique<MaskLeaf>(origins[n], false);
                        leaves[n]->setValueMask(bits[n]);
                      }
                    });
  openvdb::MaskGrid::Ptr grid = openvdb::MaskGrid::create();
  grid->setTransform(transform);
  // Linking finished leaves into the tree: one pointer insertion per leaf (the tree cannot take
  // concurrent insertions); the result does not depend on the order.
  openvdb::tree::ValueAccessor<openvdb::MaskTree> accessor(grid->tree());
  for (auto& leaf : leaves) {
    if (leaf) accessor.addLeaf(leaf.release());
  }
  return grid;
}

}  // namespace voxremesh::volume
