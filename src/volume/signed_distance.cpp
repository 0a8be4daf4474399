// The narrow-band signed distance of open sheets: meshToVolume's unsigned distance and closest
// polygon per voxel, then per active voxel the exact closest point, its side (v . pseudo-normal)
// and the invalid flag, in parallel over the leaves.
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/Morphology.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "volume/surface_mesh.h"
#include "volume/volume_build.h"

namespace voxremesh::volume {

namespace {

/// The MeshDataAdapter meshToVolume reads the polygons through (index space = world / voxel).
class MeshAdapter {
 public:
  MeshAdapter(const SurfaceMesh& mesh, double voxelSize)
      : mesh_(mesh), inverseVoxelSize_(1.0 / voxelSize) {}
  std::size_t polygonCount() const { return mesh_.polygons.size(); }
  std::size_t pointCount() const { return mesh_.points.size(); }
  std::size_t vertexCount(std::size_t n) const { return mesh_.polygons[n][3] == kNone ? 3 : 4; }
  void getIndexSpacePoint(std::size_t n, std::size_t v, openvdb::Vec3d& pos) const {
    const V3& p = mesh_.points[mesh_.polygons[n][v]];
    pos = openvdb::Vec3d(p.x * inverseVoxelSize_, p.y * inverseVoxelSize_, p.z * inverseVoxelSize_);
  }

 private:
  const SurfaceMesh& mesh_;
  double inverseVoxelSize_;
};

using FloatLeaf = openvdb::FloatTree::LeafNodeType;
using LeafBits = openvdb::MaskTree::LeafNodeType::NodeMaskType;

}  // namespace

void computeSignedDistance(const SurfaceMesh& mesh, const openvdb::math::Transform::Ptr& transform,
                           const VolumeSettings& settings, openvdb::FloatGrid::Ptr& sdf,
                           openvdb::MaskGrid::Ptr& invalid) {
  const double voxelSize = transform->voxelSize()[0];
  const double band = settings.bandWidthVoxels * voxelSize;
  const float background = static_cast<float>(band);

  // The band and a start polygon per voxel. meshToVolume grows its band only beyond two voxels,
  // and near the band's outer edge its band is ragged (it grows from voxels at most band - 1
  // voxel away, and its distances there can be too large): dilate the band by one voxel and let
  // the exact pass below decide every voxel, new ones starting from their neighbours' polygons.
  const float m2vBand = static_cast<float>(std::max(settings.bandWidthVoxels, 2.0));
  openvdb::Int32Grid::Ptr index =
      openvdb::Int32Grid::create(openvdb::Int32(openvdb::util::INVALID_IDX));
  const MeshAdapter adapter(mesh, voxelSize);
  sdf = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
      adapter, *transform, m2vBand, m2vBand, openvdb::tools::UNSIGNED_DISTANCE_FIELD, index.get());
  sdf->setTransform(transform);
  sdf->setName(kSdfGridName);
  sdf->setGridClass(openvdb::GRID_LEVEL_SET);
  if (sdf->background() != background) openvdb::tools::changeBackground(sdf->tree(), background);
  openvdb::tools::dilateActiveValues(sdf->tree(), 1, openvdb::tools::NN_FACE,
                                     openvdb::tools::IGNORE_TILES);

  // Exact distance, side and invalid flag per active voxel.
  openvdb::tree::LeafManager<openvdb::FloatTree> leaves(sdf->tree());
  const std::size_t leafCount = leaves.leafCount();
  std::vector<openvdb::Coord> origins(leafCount);
  std::vector<LeafBits> invalidBits(leafCount);
  const double tolerance = settings.tieToleranceVoxels * voxelSize;
  const double cosThreshold =
      settings.invalidAngleDeg >= 90.0 ? 0.0 : std::cos(settings.invalidAngleDeg * M_PI / 180.0);
  const openvdb::Int32Tree& indexTree = index->tree();
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, leafCount), [&](const tbb::blocked_range<std::size_t>& r) {
        openvdb::tree::ValueAccessor<const openvdb::Int32Tree> indexAccessor(indexTree);
        for (std::size_t n = r.begin(); n < r.end(); ++n) {
          FloatLeaf& leaf = leaves.leaf(n);
          origins[n] = leaf.origin();
          const auto* indexLeaf = indexAccessor.probeConstLeaf(leaf.origin());
          const FloatLeaf::NodeMaskType active = leaf.getValueMask();
          for (auto it = active.beginOn(); it; ++it) {
            const openvdb::Index pos = it.pos();
            const openvdb::Coord ijk = leaf.offsetToGlobalCoord(pos);
            const V3 p{ijk.x() * voxelSize, ijk.y() * voxelSize, ijk.z() * voxelSize};
            // Descend from the voxel's own closest polygon. A face interior reached that way is a
            // local minimum of a smooth region and taken. Otherwise (an edge or corner is
            // closest, or the voxel came with the dilation) meshToVolume's polygon can be a
            // farther one that alone reached the voxel: start from the polygons of the six face
            // neighbours too, as a sorted set so that the result depends on the set only.
            std::uint32_t starts[7];
            std::size_t count = 0;
            ClosestPoint c;
            const bool own = indexLeaf && indexLeaf->isValueOn(pos);
            const openvdb::Int32 ownPolygon = own ? indexLeaf->getValue(pos) : -1;
            if (ownPolygon >= 0 && std::size_t(ownPolygon) < mesh.polygons.size()) {
              starts[count++] = static_cast<std::uint32_t>(ownPolygon);
              c = closestPointFrom(mesh, starts, 1, p, tolerance);
            }
            if (count == 0 || c.kind != ClosestKind::Face) {
              for (int n6 = 0; n6 < 6; ++n6) {
                openvdb::Int32 polygon = -1;
                if (!indexAccessor.probeValue(ijk + openvdb::util::COORD_OFFSETS[n6], polygon) ||
                    polygon < 0 || std::size_t(polygon) >= mesh.polygons.size()) {
                  continue;
                }
                // Insert sorted, skipping repeats.
                const auto value = static_cast<std::uint32_t>(polygon);
                std::size_t at = count;
                while (at > 0 && starts[at - 1] > value) --at;
                if (at > 0 && starts[at - 1] == value) continue;
                for (std::size_t k = count; k > at; --k) starts[k] = starts[k - 1];
                starts[at] = value;
                ++count;
              }
              if (count == 0) {
                leaf.setValueOff(pos, background);
                continue;
              }
              c = closestPointFrom(mesh, starts, count, p, tolerance);
            }
            const double distance = std::sqrt(c.distance2);
            const V3 v = p - c.point;
            const double side = dot(v, pseudoNormal(mesh, c)) < 0.0 ? -1.0 : 1.0;
            if (!(distance < band)) {
              leaf.setValueOff(pos, static_cast<float>(side) * background);
              continue;
            }
            leaf.setValueOnly(pos, static_cast<float>(side * distance));
            if (isInvalidVoxel(mesh, c, p, cosThreshold)) invalidBits[n].setOn(pos);
          }
        }
      });
  // Inactive values take the side of their active neighbours (+-background), as level sets
  // expect; an open sheet has no inside, so far from the band this sign is only a convention.
  openvdb::tools::signedFloodFill(sdf->tree(), /*threaded=*/true);
  openvdb::tools::pruneLevelSet(sdf->tree(), /*threaded=*/true);
  invalid = maskFromLeafBits(origins, invalidBits, transform);
  invalid->setName(kInvalidGridName);
}

}  // namespace voxremesh::volume
