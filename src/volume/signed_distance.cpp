// The narrow-band signed distance of open sheets: meshToVolume's unsigned distance and closest
// polygon per voxel, then per active voxel the exact closest point, its side (v . pseudo-normal)
// and the invalid flag, in parallel over the leaves.
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
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

  // The band and a start polygon per voxel. meshToVolume's band is ragged near its outer edge
  // (it grows from voxels at most band - 1 voxel away), so ask for one voxel more, then trim to
  // the exact band.
  const float m2vBand = static_cast<float>(settings.bandWidthVoxels + 1.0);
  openvdb::Int32Grid::Ptr index =
      openvdb::Int32Grid::create(openvdb::Int32(openvdb::util::INVALID_IDX));
  const MeshAdapter adapter(mesh, voxelSize);
  sdf = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
      adapter, *transform, m2vBand, m2vBand, openvdb::tools::UNSIGNED_DISTANCE_FIELD, index.get());
  sdf->setTransform(transform);
  sdf->setName(kSdfGridName);
  sdf->setGridClass(openvdb::GRID_LEVEL_SET);
  openvdb::tools::changeBackground(sdf->tree(), background);

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
            // Start polygons: the voxel's own closest polygon and those of its six face
            // neighbours (meshToVolume's index can be a farther polygon where only that one's
            // rasterisation reached the voxel), sorted, without repeats.
            std::uint32_t starts[7];
            std::size_t count = 0;
            for (int n6 = -1; n6 < 6; ++n6) {
              openvdb::Int32 polygon = -1;
              if (n6 < 0) {
                if (indexLeaf && indexLeaf->isValueOn(pos)) polygon = indexLeaf->getValue(pos);
              } else if (!indexAccessor.probeValue(ijk + openvdb::util::COORD_OFFSETS[n6],
                                                   polygon)) {
                continue;
              }
              if (polygon < 0 || std::size_t(polygon) >= mesh.polygons.size()) continue;
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
            const V3 p{ijk.x() * voxelSize, ijk.y() * voxelSize, ijk.z() * voxelSize};
            const ClosestPoint c = closestPointFrom(mesh, starts, count, p, tolerance);
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
