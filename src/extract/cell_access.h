// Reading one cell of the sdf for the extraction passes: its 8 corner values and whether it takes
// part (all corners active and valid, not excluded, not all of one sign). Internal; includes
// OpenVDB.
#pragma once

#include <openvdb/openvdb.h>

#include "voxremesh/mc33.h"

namespace voxremesh::extract {

using FloatLeaf = openvdb::FloatTree::LeafNodeType;
using SdfAccessor = openvdb::tree::ValueAccessor<const openvdb::FloatTree>;
using MaskAccessor = openvdb::tree::ValueAccessor<const openvdb::MaskTree>;

/// Corner c of a cell relative to its lowest corner (c = x + 2y + 4z).
inline openvdb::Coord cornerOffset(int c) {
  return openvdb::Coord(c & 1, (c >> 1) & 1, (c >> 2) & 1);
}

/// Reads a cell's 8 corner values; false when a corner is inactive.
inline bool readCorners(const FloatLeaf& leaf, openvdb::Index offset, const openvdb::Coord& ijk,
                        const SdfAccessor& accessor, mc33::CellValues& values) {
  const openvdb::Coord local = ijk - leaf.origin();
  if (local.x() < 7 && local.y() < 7 && local.z() < 7) {
    constexpr openvdb::Index kStride[3] = {64, 8, 1};  // LeafNode offset (x << 6) + (y << 3) + z
    for (int c = 0; c < 8; ++c) {
      const openvdb::Index o = offset + ((c & 1) ? kStride[0] : 0) + ((c & 2) ? kStride[1] : 0) +
                               ((c & 4) ? kStride[2] : 0);
      if (!leaf.isValueOn(o)) return false;
      values[static_cast<std::size_t>(c)] = leaf.getValue(o);
    }
    return true;
  }
  for (int c = 0; c < 8; ++c) {
    if (!accessor.probeValue(ijk + cornerOffset(c), values[static_cast<std::size_t>(c)]))
      return false;
  }
  return true;
}

/// Reads the 8 corner values without the activity check (the fast sign test).
inline void readValues(const FloatLeaf& leaf, openvdb::Index offset, const openvdb::Coord& ijk,
                       const SdfAccessor& accessor, mc33::CellValues& values) {
  const openvdb::Coord local = ijk - leaf.origin();
  if (local.x() < 7 && local.y() < 7 && local.z() < 7) {
    for (int c = 0; c < 8; ++c) {
      const openvdb::Index o =
          offset + ((c & 1) ? 64u : 0u) + ((c & 2) ? 8u : 0u) + ((c & 4) ? 1u : 0u);
      values[static_cast<std::size_t>(c)] = leaf.getValue(o);
    }
    return;
  }
  for (int c = 0; c < 8; ++c)
    values[static_cast<std::size_t>(c)] = accessor.getValue(ijk + cornerOffset(c));
}

/// What readCell found.
enum class CellState {
  NoSurface,  ///< all corners of one sign
  Skipped,    ///< a sign change, but a corner is inactive or invalid, or the cell is excluded
  Surface,    ///< takes part; values holds the corner values
};

/// Reads the cell whose lowest corner is voxel `ijk` (at `offset` in `leaf`) into `values` and
/// classifies it (see CellState).
inline CellState readCell(const FloatLeaf& leaf, openvdb::Index offset, const openvdb::Coord& ijk,
                          const SdfAccessor& sdf, const MaskAccessor& invalid,
                          const MaskAccessor& excluded, mc33::CellValues& values) {
  readValues(leaf, offset, ijk, sdf, values);
  int negative = 0;
  for (float v : values) negative += v < 0.0f ? 1 : 0;
  if (negative == 0 || negative == 8) return CellState::NoSurface;
  if (!readCorners(leaf, offset, ijk, sdf, values) || excluded.isValueOn(ijk))
    return CellState::Skipped;
  for (int c = 0; c < 8; ++c)
    if (invalid.isValueOn(ijk + cornerOffset(c))) return CellState::Skipped;
  return CellState::Surface;
}

/// readCell for a cell anywhere in the grid, through the accessors only.
inline CellState readCellAt(const openvdb::Coord& ijk, const SdfAccessor& sdf,
                            const MaskAccessor& invalid, const MaskAccessor& excluded,
                            mc33::CellValues& values) {
  int negative = 0;
  bool active = true;
  for (int c = 0; c < 8; ++c) {
    active = sdf.probeValue(ijk + cornerOffset(c), values[std::size_t(c)]) && active;
    negative += values[std::size_t(c)] < 0.0f ? 1 : 0;
  }
  if (negative == 0 || negative == 8) return CellState::NoSurface;
  if (!active || excluded.isValueOn(ijk)) return CellState::Skipped;
  for (int c = 0; c < 8; ++c)
    if (invalid.isValueOn(ijk + cornerOffset(c))) return CellState::Skipped;
  return CellState::Surface;
}

}  // namespace voxremesh::extract
