// extractTriangles: the MC33 triangulation of the valid cells (see extract.h). Per leaf in
// parallel: the triangles of each surface cell with their vertices named by keys (a grid edge, or
// a cell's component); then the keys are sorted and numbered, which shares every crossing point
// between the cells around its edge and makes the output independent of the thread count.
#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <stdexcept>

#include "extract/cell_access.h"
#include "volume/volume_grids.h"
#include "voxremesh/extract.h"

namespace voxremesh {

namespace {

using VertexKey = std::uint64_t;

/// 20 bits per coordinate, offset so that negative coordinates fit; grids beyond +-2^19 voxels
/// are refused.
constexpr int kCoordBits = 20;
constexpr std::int64_t kCoordOffset = std::int64_t{1} << (kCoordBits - 1);

VertexKey packCoord(const openvdb::Coord& c) {
  VertexKey key = 0;
  for (int a = 0; a < 3; ++a) {
    const std::int64_t v = std::int64_t{c[a]} + kCoordOffset;
    if (v < 0 || v >= (std::int64_t{1} << kCoordBits))
      throw std::runtime_error("extractTriangles: the grid is wider than 2^19 voxels");
    key = (key << kCoordBits) | VertexKey(v);
  }
  return key;
}

/// Key of the crossing on the grid edge along `axis` from voxel `first`: (coord, axis), bit 63 0.
VertexKey edgeKey(const openvdb::Coord& first, int axis) {
  return (packCoord(first) << 2) | VertexKey(axis);
}

/// Key of component c's interior vertex in the cell at `cell`: bit 63 set.
VertexKey interiorKey(const openvdb::Coord& cell, int component) {
  return (VertexKey{1} << 63) | (packCoord(cell) << 2) | VertexKey(component);
}

struct KeyedPoint {
  VertexKey key;
  std::array<double, 3> position;
};

struct LeafTriangles {
  std::vector<KeyedPoint> points;
  std::vector<std::array<VertexKey, 3>> triangles;
};

}  // namespace

QuadMesh extractTriangles(const Volume& volume) {
  if (volume.empty()) throw std::invalid_argument("extractTriangles: the volume is empty");
  const Volume::Impl& grids = volume.impl();
  const openvdb::FloatGrid& sdf = *grids.sdf;
  const openvdb::MaskTree noCells(false);
  openvdb::tree::LeafManager<const openvdb::FloatTree> leaves(sdf.tree());
  std::vector<LeafTriangles> perLeaf(leaves.leafCount());

  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, leaves.leafCount()),
      [&](const tbb::blocked_range<std::size_t>& range) {
        extract::SdfAccessor sdfAccessor(sdf.tree());
        extract::MaskAccessor invalid(grids.invalid->tree()), excluded(noCells);
        mc33::CellValues values{};
        for (std::size_t n = range.begin(); n < range.end(); ++n) {
          const extract::FloatLeaf& leaf = leaves.leaf(n);
          LeafTriangles& out = perLeaf[n];
          for (auto it = leaf.cbeginValueOn(); it; ++it) {
            const openvdb::Coord ijk = it.getCoord();
            if (extract::readCell(leaf, it.pos(), ijk, sdfAccessor, invalid, excluded, values) !=
                extract::CellState::Surface)
              continue;
            const mc33::CellTopology topology = mc33::cellTopology(values);
            const mc33::CellPoints points = mc33::cellPoints(values, topology);
            const mc33::CellTriangles triangles = mc33::cellTriangles(topology, points);
            std::array<VertexKey, mc33::kEdgeCount + mc33::kMaxComponents> keys{};
            auto addPoint = [&](VertexKey key, const mc33::CellPoint& p) {
              const openvdb::Vec3d world =
                  sdf.transform().indexToWorld(ijk.asVec3d() + openvdb::Vec3d(p[0], p[1], p[2]));
              out.points.push_back({key, {world[0], world[1], world[2]}});
              return key;
            };
            for (int e = 0; e < mc33::kEdgeCount; ++e) {
              if (topology.edgeComponent[std::size_t(e)] == mc33::kNoComponent) continue;
              const int axis = e / 4;
              const openvdb::Coord first =
                  ijk + extract::cornerOffset(mc33::kEdgeCorners[std::size_t(e)][0]);
              keys[std::size_t(e)] =
                  addPoint(edgeKey(first, axis), points.edgePoints[std::size_t(e)]);
            }
            for (int c = 0; c < topology.componentCount; ++c) {
              if (triangles.interiorVertexMask & (1u << c))
                keys[std::size_t(mc33::interiorVertex(c))] =
                    addPoint(interiorKey(ijk, c), points.centroids[std::size_t(c)]);
            }
            for (int t = 0; t < triangles.count; ++t) {
              const auto& tri = triangles.triangles[std::size_t(t)];
              out.triangles.push_back({keys[tri[0]], keys[tri[1]], keys[tri[2]]});
            }
          }
        }
      });

  // Number the keys: sorted, unique (the cells around an edge compute the same crossing point).
  std::vector<KeyedPoint> all;
  for (const LeafTriangles& leaf : perLeaf)
    all.insert(all.end(), leaf.points.begin(), leaf.points.end());
  tbb::parallel_sort(all.begin(), all.end(),
                     [](const KeyedPoint& a, const KeyedPoint& b) { return a.key < b.key; });
  all.erase(std::unique(all.begin(), all.end(),
                        [](const KeyedPoint& a, const KeyedPoint& b) { return a.key == b.key; }),
            all.end());
  QuadMesh mesh;
  mesh.part = volume.info().part;
  mesh.points.reserve(all.size());
  for (const KeyedPoint& p : all) mesh.points.push_back(p.position);
  auto indexOf = [&](VertexKey key) {
    const auto it = std::lower_bound(all.begin(), all.end(), key,
                                     [](const KeyedPoint& p, VertexKey k) { return p.key < k; });
    return static_cast<CornerIndex>(it - all.begin());
  };
  for (const LeafTriangles& leaf : perLeaf)
    for (const auto& t : leaf.triangles)
      mesh.faces.push_back({indexOf(t[0]), indexOf(t[1]), indexOf(t[2]), kNoCorner});
  mesh.constraints.assign(mesh.points.size(), PointConstraint{});
  return mesh;
}

}  // namespace voxremesh
