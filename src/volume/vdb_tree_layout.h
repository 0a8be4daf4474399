// The layout check of one grid's tree in a .vdb file (vdb_layout.h walks the rest of the file):
// OpenVDB allocates the node counts and compressed block sizes the tree states, so each is checked
// against the grid's bytes first. Internal to src/volume.
#pragma once

#include <cstdint>
#include <string>

#include "volume/vdb_layout_reader.h"

namespace voxremesh::volume {

/// What the tree walk needs of a grid, from its descriptor and its header in the file.
struct TreeGrid {
  std::string which;                ///< "grid 2", for messages
  std::uint32_t compression = 0;    ///< the grid's compression flags (io::COMPRESS_*)
  bool halfFloat = false;           ///< its metadata is_saved_as_half_float, as OpenVDB reads it
  std::uint64_t blockPosition = 0;  ///< where its data blocks start: its topology ends there
  std::uint64_t endPosition = 0;    ///< where the grid ends: its data blocks end there
};

/// Whether checkTreeLayout walks trees of `treeType`, a grid descriptor's type without the
/// "_HalfFloat" suffix: Tree_<value>_5_4_3 for the value types OpenVDB 10 registers grids of
/// (float, double, int32, int64, vec3i, vec3s, vec3d, bool, mask).
bool isWalkedTreeType(const std::string& treeType);

/// Walks the tree that starts at the reader's position as OpenVDB 10's io::File reads it
/// (Tree::readTopology, then readBuffers with the leaf value masks of the topology): the root's
/// tiles and children, each internal node's masks and values, each leaf's mask and values. Every
/// node count and compressed block size must fit in the grid's bytes: the topology before
/// `grid.blockPosition`, the data blocks before `grid.endPosition`. Each zip or blosc block must
/// decompress to exactly its values' bytes, and each byte OpenVDB reads into a bool (a tile's
/// active flag; a bool or mask grid's background, tile and internal-node values) must be 0 or 1.
/// Precondition: isWalkedTreeType(treeType); file format version 222 to 224.
/// Throws InputError naming the file and the byte offset of the first count, size or field that
/// runs past its bound, of a block that does not decompress to its values, or of a bool byte
/// other than 0 or 1 (for a compressed block: the block's).
void checkTreeLayout(LayoutReader& reader, const std::string& treeType, const TreeGrid& grid);

}  // namespace voxremesh::volume
