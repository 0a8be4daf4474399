// The dual-quad pass over the active leaves (see dual_mesh.h). Three parallel passes over the
// leaves, as OpenVDB's VolumeToMesh: (1) per leaf, the surface cells with their MC33 loops and
// loop vertices; (2) a prefix sum gives every leaf its range of global cell and point indices,
// and a cell index grid (same topology as the sdf) lets a cell find its neighbours' vertices;
// (3) per leaf, the quads of the grid edges each cell owns (the three edges leaving its lowest
// corner), concatenated in leaf order.
#include "extract/dual_mesh.h"

#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <numeric>

#include "extract/cell_access.h"
#include "voxremesh/mc33.h"

namespace voxremesh::extract {

namespace {

using Int32Tree = openvdb::Int32Tree;

constexpr std::uint64_t kNoLoop = 0xF;
/// Bit 63 of a packed cell: the value at the cell's lowest corner is negative.
constexpr std::uint64_t kCorner0Negative = std::uint64_t{1} << 63;

/// The vertex slot of each of a cell's 12 edges, 4 bits each (kNoLoop: no crossing), plus the
/// sign of corner 0 in bit 63.
std::uint64_t packEdgeSlots(const std::array<std::int8_t, mc33::kEdgeCount>& slotOfEdge,
                            bool corner0Negative) {
  std::uint64_t packed = 0;
  for (int e = 0; e < mc33::kEdgeCount; ++e) {
    const std::uint64_t slot =
        slotOfEdge[std::size_t(e)] < 0 ? kNoLoop : std::uint64_t(slotOfEdge[std::size_t(e)]);
    packed |= slot << (4 * e);
  }
  return corner0Negative ? (packed | kCorner0Negative) : packed;
}

/// The face two edges of a cell share, or -1.
int sharedFace(int e1, int e2) {
  for (int f = 0; f < mc33::kFaceCount; ++f) {
    bool has1 = false, has2 = false;
    for (int k = 0; k < 4; ++k) {
      has1 = has1 || mc33::kFaceEdges[std::size_t(f)][std::size_t(k)] == e1;
      has2 = has2 || mc33::kFaceEdges[std::size_t(f)][std::size_t(k)] == e2;
    }
    if (has1 && has2) return f;
  }
  return -1;
}

/// Per loop, a bit per face on which the loop has two arcs (it winds around an ambiguous face).
std::array<std::uint8_t, mc33::kMaxLoops> doubleArcFaces(const mc33::CellTopology& topology) {
  std::array<std::uint8_t, mc33::kMaxLoops> result{};
  for (int l = 0; l < topology.loopCount; ++l) {
    std::array<int, mc33::kFaceCount> arcs{};
    const int size = topology.loopSize(l);
    for (int i = 0; i < size; ++i) {
      const int f = sharedFace(topology.loopEdge(l, i), topology.loopEdge(l, (i + 1) % size));
      if (f >= 0 && ++arcs[std::size_t(f)] == 2) result[std::size_t(l)] |= std::uint8_t(1u << f);
    }
  }
  return result;
}

/// The cell across face f (2a + s) of the cell at ijk.
openvdb::Coord neighbourAcross(const openvdb::Coord& ijk, int face) {
  openvdb::Coord c = ijk;
  c[face / 2] += (face & 1) ? 1 : -1;
  return c;
}

/// The vertices of a cell: one per loop, except that a loop with two arcs on a face whose
/// neighbour cell also has one loop with both arcs of that face is cut at those arcs into two
/// chains, a vertex each. (Left whole, the two cells' vertices would be joined by four quads.)
/// The two cells cut the same way: outside the face, the loop joins the face's crossings in the
/// only non-crossing pairing, so both cells get the chains {b..c} and {d..a} for arcs (a,b), (c,d).
struct CellVertices {
  int count = 0;
  bool cut = false;
  std::array<std::int8_t, mc33::kEdgeCount> slotOfEdge{-1, -1, -1, -1, -1, -1,
                                                       -1, -1, -1, -1, -1, -1};
};

CellVertices cellVertices(const mc33::CellTopology& topology, const openvdb::Coord& ijk,
                          const SdfAccessor& sdf, const MaskAccessor& invalid,
                          const MaskAccessor& excluded) {
  const std::array<std::uint8_t, mc33::kMaxLoops> doubles = doubleArcFaces(topology);
  CellVertices result;
  for (int l = 0; l < topology.loopCount; ++l) {
    std::uint8_t cutFaces = 0;
    for (int f = 0; f < mc33::kFaceCount; ++f) {
      if (!(doubles[std::size_t(l)] & (1u << f))) continue;
      mc33::CellValues values{};
      if (readCellAt(neighbourAcross(ijk, f), sdf, invalid, excluded, values) != CellState::Surface)
        continue;
      const int opposite = f ^ 1;
      for (std::uint8_t mask : doubleArcFaces(mc33::cellTopology(values)))
        if (mask & (1u << opposite)) cutFaces |= std::uint8_t(1u << f);
    }
    const int size = topology.loopSize(l);
    result.cut = result.cut || cutFaces != 0;
    if (!cutFaces) {
      for (int i = 0; i < size; ++i)
        result.slotOfEdge[std::size_t(topology.loopEdge(l, i))] = std::int8_t(result.count);
      ++result.count;
      continue;
    }
    // Start after a cut arc; a new chain begins after every cut arc.
    int start = 0;
    for (int i = 0; i < size; ++i) {
      const int f = sharedFace(topology.loopEdge(l, i), topology.loopEdge(l, (i + 1) % size));
      if (f >= 0 && (cutFaces & (1u << f))) {
        start = (i + 1) % size;
        break;
      }
    }
    for (int k = 0; k < size; ++k) {
      const int i = (start + k) % size;
      result.slotOfEdge[std::size_t(topology.loopEdge(l, i))] = std::int8_t(result.count);
      const int f = sharedFace(topology.loopEdge(l, i), topology.loopEdge(l, (i + 1) % size));
      if (f >= 0 && (cutFaces & (1u << f))) ++result.count;
    }
  }
  return result;
}

int edgeLoop(std::uint64_t packed, int edge) {
  return static_cast<int>((packed >> (4 * edge)) & kNoLoop);
}

/// The surface cells of one leaf (pass 1).
struct LeafCells {
  std::vector<openvdb::Coord> cells;
  std::vector<std::uint64_t> edgeLoops;
  std::vector<std::uint32_t> firstPoint;  ///< leaf-local index of each cell's first point
  std::vector<std::array<double, 3>> points;
  std::vector<openvdb::Coord> pointCells;
  std::uint64_t tunnels = 0;
  std::uint64_t skipped = 0;
  std::uint64_t cutCells = 0;
  std::vector<std::array<std::uint32_t, 4>> quads;  ///< pass 3
};

/// Pass 1 for one leaf.
void collectLeafCells(const FloatLeaf& leaf, const SdfAccessor& sdf, const MaskAccessor& invalid,
                      const MaskAccessor& excluded, const openvdb::math::Transform& transform,
                      LeafCells& out) {
  mc33::CellValues values{};
  for (auto it = leaf.cbeginValueOn(); it; ++it) {
    const openvdb::Coord ijk = it.getCoord();
    const openvdb::Index offset = it.pos();
    const CellState state = readCell(leaf, offset, ijk, sdf, invalid, excluded, values);
    if (state == CellState::NoSurface) continue;
    if (state == CellState::Skipped) {
      ++out.skipped;
      continue;
    }
    const mc33::CellTopology topology = mc33::cellTopology(values);
    if (topology.loopCount > topology.componentCount) ++out.tunnels;
    const mc33::CellPoints points = mc33::cellPoints(values, topology);
    const CellVertices vertices = cellVertices(topology, ijk, sdf, invalid, excluded);
    out.cutCells += vertices.cut ? 1 : 0;
    out.cells.push_back(ijk);
    out.edgeLoops.push_back(packEdgeSlots(vertices.slotOfEdge, values[0] < 0.0f));
    out.firstPoint.push_back(static_cast<std::uint32_t>(out.points.size()));
    for (int v = 0; v < vertices.count; ++v) {
      openvdb::Vec3d sum(0.0);
      int count = 0;
      for (int e = 0; e < mc33::kEdgeCount; ++e) {
        if (vertices.slotOfEdge[std::size_t(e)] != v) continue;
        const mc33::CellPoint& p = points.edgePoints[std::size_t(e)];
        sum += openvdb::Vec3d(p[0], p[1], p[2]);
        ++count;
      }
      const openvdb::Vec3d index = ijk.asVec3d() + sum / double(count);
      const openvdb::Vec3d world = transform.indexToWorld(index);
      out.points.push_back({world[0], world[1], world[2]});
      out.pointCells.push_back(ijk);
    }
  }
}

/// The two axes other than `axis`, ordered so that p x q = axis (right-handed).
void otherAxes(int axis, int& p, int& q) {
  p = (axis + 1) % 3;
  q = (axis + 2) % 3;
}

/// The local edge (0..11) of the grid edge along `axis` in the cell displaced by (dp, dq) from
/// the edge's first voxel towards -p, -q (dp, dq in {0, 1}): edges of an axis are numbered by
/// the other two coordinates in ascending axis order (x-edges by y + 2z, y-edges by x + 2z,
/// z-edges by x + 2y), and the edge sits at coordinate dp on p and dq on q inside that cell.
int localEdge(int axis, int p, int dp, int dq) {
  // For axis y, p = z and q = x, so the lower axis (x) is q.
  const bool pIsLower = p < (3 - axis - p);
  const int lower = pIsLower ? dp : dq;
  const int upper = pIsLower ? dq : dp;
  return 4 * axis + lower + 2 * upper;
}

}  // namespace

DualMesh buildDualMesh(const openvdb::FloatGrid& sdf, const openvdb::MaskTree& invalidVoxels,
                       const openvdb::MaskTree& excludedCells) {
  openvdb::tree::LeafManager<const openvdb::FloatTree> leaves(sdf.tree());
  const std::size_t leafCount = leaves.leafCount();
  std::vector<LeafCells> perLeaf(leafCount);
  const openvdb::math::Transform& transform = sdf.transform();

  // Pass 1: surface cells and their points, per leaf.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leafCount),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      SdfAccessor sdfAccessor(sdf.tree());
                      MaskAccessor invalid(invalidVoxels);
                      MaskAccessor excluded(excludedCells);
                      for (std::size_t n = range.begin(); n < range.end(); ++n) {
                        collectLeafCells(leaves.leaf(n), sdfAccessor, invalid, excluded, transform,
                                         perLeaf[n]);
                      }
                    });

  // Pass 2: prefix sums, global cell arrays and the cell index grid.
  std::vector<std::size_t> cellBegin(leafCount + 1, 0), pointBegin(leafCount + 1, 0);
  for (std::size_t n = 0; n < leafCount; ++n) {
    cellBegin[n + 1] = cellBegin[n] + perLeaf[n].cells.size();
    pointBegin[n + 1] = pointBegin[n] + perLeaf[n].points.size();
  }
  DualMesh mesh;
  mesh.points.resize(pointBegin[leafCount]);
  mesh.pointCells.resize(pointBegin[leafCount]);
  std::vector<std::uint64_t> cellEdgeLoops(cellBegin[leafCount]);
  std::vector<std::uint32_t> cellFirstPoint(cellBegin[leafCount]);
  Int32Tree cellIndex(sdf.tree(), std::int32_t(-1), openvdb::TopologyCopy());
  openvdb::tree::LeafManager<Int32Tree> indexLeaves(cellIndex);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leafCount),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t n = range.begin(); n < range.end(); ++n) {
                        const LeafCells& cells = perLeaf[n];
                        auto& indexLeaf = indexLeaves.leaf(n);
                        indexLeaf.fill(-1);
                        std::copy(cells.points.begin(), cells.points.end(),
                                  mesh.points.begin() + std::ptrdiff_t(pointBegin[n]));
                        std::copy(cells.pointCells.begin(), cells.pointCells.end(),
                                  mesh.pointCells.begin() + std::ptrdiff_t(pointBegin[n]));
                        for (std::size_t c = 0; c < cells.cells.size(); ++c) {
                          const std::size_t global = cellBegin[n] + c;
                          cellEdgeLoops[global] = cells.edgeLoops[c];
                          cellFirstPoint[global] =
                              static_cast<std::uint32_t>(pointBegin[n] + cells.firstPoint[c]);
                          indexLeaf.setValueOnly(cells.cells[c], static_cast<std::int32_t>(global));
                        }
                      }
                    });

  // Pass 3: quads of the edges each cell owns, per leaf.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leafCount),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      openvdb::tree::ValueAccessor<const Int32Tree> index(cellIndex);
                      for (std::size_t n = range.begin(); n < range.end(); ++n) {
                        LeafCells& cells = perLeaf[n];
                        for (std::size_t c = 0; c < cells.cells.size(); ++c) {
                          const std::uint64_t own = cells.edgeLoops[c];
                          const openvdb::Coord& ijk = cells.cells[c];
                          for (int axis = 0; axis < 3; ++axis) {
                            if (edgeLoop(own, 4 * axis) == int(kNoLoop)) continue;
                            int p = 0, q = 0;
                            otherAxes(axis, p, q);
                            // Cells counter-clockwise around +axis: offsets (dp, dq) = (0,0),
                            // (1,0), (1,1), (0,1).
                            constexpr int kDp[4] = {0, 1, 1, 0};
                            constexpr int kDq[4] = {0, 0, 1, 1};
                            std::array<std::uint32_t, 4> quad{};
                            bool complete = true;
                            for (int k = 0; k < 4 && complete; ++k) {
                              openvdb::Coord cell = ijk;
                              cell[p] -= kDp[k];
                              cell[q] -= kDq[k];
                              const std::int32_t global =
                                  k == 0 ? std::int32_t(cellBegin[n] + c) : index.getValue(cell);
                              if (global < 0) {
                                complete = false;
                                break;
                              }
                              const int loop = edgeLoop(cellEdgeLoops[std::size_t(global)],
                                                        localEdge(axis, p, kDp[k], kDq[k]));
                              quad[std::size_t(k)] =
                                  cellFirstPoint[std::size_t(global)] + std::uint32_t(loop);
                            }
                            if (!complete) continue;
                            // Corner 0 negative: the positive side is +axis, keep the
                            // counter-clockwise order.
                            if (!(own & kCorner0Negative)) std::swap(quad[1], quad[3]);
                            cells.quads.push_back(quad);
                          }
                        }
                      }
                    });

  std::vector<std::size_t> quadBegin(leafCount + 1, 0);
  for (std::size_t n = 0; n < leafCount; ++n) {
    quadBegin[n + 1] = quadBegin[n] + perLeaf[n].quads.size();
    mesh.surfaceCells += perLeaf[n].cells.size();
    mesh.tunnelCells += perLeaf[n].tunnels;
    mesh.skippedCells += perLeaf[n].skipped;
    mesh.cutCells += perLeaf[n].cutCells;
  }
  mesh.quads.resize(quadBegin[leafCount]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leafCount),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t n = range.begin(); n < range.end(); ++n) {
                        std::copy(perLeaf[n].quads.begin(), perLeaf[n].quads.end(),
                                  mesh.quads.begin() + std::ptrdiff_t(quadBegin[n]));
                      }
                    });
  return mesh;
}

}  // namespace voxremesh::extract
