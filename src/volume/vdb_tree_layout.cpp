// The layout check of one grid's tree (vdb_tree_layout.h). The layout followed is OpenVDB 10's
// Tree::readTopology and readBuffers: tree/RootNode.h, InternalNode.h, LeafNode.h,
// LeafNodeBool.h, LeafNodeMask.h, and io/Compression.h readCompressedValues (a byte saying what
// stands for the inactive values, then those values, a selection mask, and the stored values:
// plain, or in a zip or blosc block that starts with an Int64 byte count, negative for bytes
// stored uncompressed). io::File marks its stream seekable, so a leaf's data blocks skip their
// copy of the value mask and the values stored are counted by the mask of the topology.
// OpenVDB throws when a zip or blosc block does not decompress to its values (after allocating
// nodes it then leaks), and reads a bool grid's bytes into bools, so each block is decompressed
// here and each byte OpenVDB reads into a bool must be 0 or 1.
#include "volume/vdb_tree_layout.h"

#include <blosc.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <bitset>
#include <map>
#include <vector>

namespace voxremesh::volume {

namespace {

constexpr std::uint32_t kCompressZip = 0x1;         // io::COMPRESS_ZIP
constexpr std::uint32_t kCompressActiveMask = 0x2;  // io::COMPRESS_ACTIVE_MASK
constexpr std::uint32_t kCompressBlosc = 0x4;       // io::COMPRESS_BLOSC

// The per-node byte of readCompressedValues (io/Compression.h, NO_MASK_AND_ONE_INACTIVE_VAL...).
constexpr std::int8_t kOneInactiveValue = 2;
constexpr std::int8_t kMaskAndNoInactiveValue = 3;
constexpr std::int8_t kMaskAndOneInactiveValue = 4;
constexpr std::int8_t kMaskAndTwoInactiveValues = 5;
constexpr std::int8_t kAllValues = 6;

constexpr std::uint64_t kCoordBytes = 12;        // an origin: three Int32
constexpr std::uint64_t kLeafMaskBytes = 64;     // NodeMask<3>
constexpr std::uint64_t kBloscHeaderBytes = 16;  // BLOSC_MIN_HEADER_LENGTH
constexpr std::uint64_t kBloscSizeAt = 12;       // the header's compressed size (cbytes)
constexpr std::uint64_t kBloscValuesAt = 4;      // the header's uncompressed size (nbytes)

/// How a leaf stores its values.
enum class LeafKind {
  kValues,  ///< LeafNode<T>: value mask, then compressed values
  kBool,    ///< LeafNode<bool>: value mask, origin, value bits
  kMask     ///< LeafNode<ValueMask>: value mask, origin
};

/// A value type OpenVDB 10 registers grids of.
struct ValueKind {
  const char* name;         ///< as in the tree type, Tree_<name>_5_4_3
  std::uint32_t bytes;      ///< sizeof the nodes' ValueType (bool for masks)
  std::uint32_t halfBytes;  ///< of its half-float form when saved as half; 0: not a real type
  LeafKind leaf;
};

constexpr ValueKind kValueKinds[] = {
    {"float", 4, 2, LeafKind::kValues},  {"double", 8, 2, LeafKind::kValues},
    {"int32", 4, 0, LeafKind::kValues},  {"int64", 8, 0, LeafKind::kValues},
    {"vec3i", 12, 0, LeafKind::kValues}, {"vec3s", 12, 6, LeafKind::kValues},
    {"vec3d", 24, 6, LeafKind::kValues}, {"bool", 1, 0, LeafKind::kBool},
    {"mask", 1, 0, LeafKind::kMask}};

/// The value kind of a tree type; nullptr for a type the walk leaves to OpenVDB.
const ValueKind* findValueKind(const std::string& treeType) {
  for (const ValueKind& kind : kValueKinds)
    if (treeType == std::string("Tree_") + kind.name + "_5_4_3") return &kind;
  return nullptr;
}

/// The number of bits set in `bytes` bytes of a node mask.
std::uint32_t countOn(const unsigned char* mask, std::size_t bytes) {
  std::uint32_t on = 0;
  for (std::size_t k = 0; k < bytes; ++k)
    on += static_cast<std::uint32_t>(std::bitset<8>(mask[k]).count());
  return on;
}

/// The fewest bytes the topology of an internal node of 2^(3 log2Dim) values takes: its two
/// masks and the byte before its values.
std::uint64_t minInternalBytes(unsigned log2Dim) {
  return 2 * ((1u << (3 * log2Dim)) / 8) + 1;
}

/// The words of the messages about one kind of node, built once per tree.
struct NodeWords {
  explicit NodeWords(const std::string& name)
      : node(name),
        valueMask("the value mask of " + name),
        metadata("the value metadata byte of " + name),
        inactive("the inactive values of " + name),
        selection("the selection mask of " + name),
        values("the values of " + name),
        blockSize("the size of a compressed block of " + name) {}

  std::string node, valueMask, metadata, inactive, selection, values, blockSize;
};

/// A zlib inflate stream (as uncompress runs it), ended when it goes out of scope.
struct Inflater {
  Inflater() { started = inflateInit(&stream) == Z_OK; }
  ~Inflater() {
    if (started) inflateEnd(&stream);
  }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;

  z_stream stream{};
  bool started = false;
};

/// Why the inflate `stream` of a block, stopped with `status` when it ended, failed, filled the
/// values or ran out of the block's bytes, is not the `expected` bytes of its values; empty when
/// it is.
std::string unzipProblem(const z_stream& stream, int status, std::uint64_t expected) {
  const std::uint64_t produced = stream.total_out;
  if (status == Z_STREAM_END)
    return produced == expected ? std::string() : "it holds " + std::to_string(produced) + " bytes";
  if (status == Z_OK)
    return "the block ends inside its zlib stream, after " + std::to_string(produced) + " bytes";
  if (status == Z_BUF_ERROR && produced == expected) return "it holds more bytes";
  return std::string("zlib: ") + (stream.msg != nullptr ? stream.msg : zError(status));
}

/// A child of the root as its topology was read: its origin and its leaves' active-value counts.
struct RootChild {
  std::array<std::int32_t, 3> origin{};
  std::vector<std::uint16_t> leafActive;
};

/// Walks one tree: topology() from the reader's position, then buffers() right after it.
class TreeWalker {
 public:
  /// Precondition: `reader` stands at the tree's start; `kind` and `grid` outlive the walker.
  TreeWalker(LayoutReader& reader, const ValueKind& kind, const TreeGrid& grid)
      : reader_(reader),
        kind_(kind),
        grid_(grid),
        root_("the root of " + grid.which),
        internal_("an internal node of " + grid.which),
        leaf_("a leaf of " + grid.which) {}

  /// Tree::readTopology: the buffer count, then RootNode::readTopology (background, tile and
  /// child counts, tiles, then per child its origin and InternalNode::readTopology). Throws
  /// InputError for a count or field that does not fit before the grid's data blocks.
  void topology();

  /// Tree::readBuffers: per child of the root in the order of the root's table (by origin, the
  /// last child read at an origin), per leaf its data. Throws InputError for a block or field
  /// that does not fit before the grid's end.
  void buffers();

 private:
  /// InternalNode::readTopology of a node of 2^(3 log2Dim) values (log2Dim 5 or 4): child mask,
  /// value mask, the node's values, then its children; the leaves' active counts go to `child`.
  /// Throws InputError for more children than the bytes left before the data blocks hold, or for
  /// anything values() refuses.
  void internalTopology(unsigned log2Dim, RootChild& child);

  /// readCompressedValues of a node of `count` values of which `active` are active, whose masks
  /// take `maskBytes`; `node` names the node for messages. Throws InputError for a field or block
  /// that does not fit before `end`, or a block block() refuses.
  void values(std::uint32_t count, std::uint32_t active, std::size_t maskBytes, std::uint64_t end,
              const NodeWords& node);

  /// A zip or blosc block (bloscFromStream, unzipFromStream) of values that take `storedBytes`
  /// uncompressed. Throws InputError when its size does not fit before `end`, when it is stored
  /// uncompressed in another number of bytes, when it does not decompress to `storedBytes` bytes
  /// (see unzip and unblosc), or when bools() or checkBools() refuse its values.
  void block(std::uint64_t storedBytes, std::uint64_t end, bool blosc, const NodeWords& node);

  /// Inflates the zip block of `bytes` bytes at the position (its size field at `at`) into
  /// values_. Throws InputError at `at` unless it is one zlib stream of exactly `storedBytes`.
  void unzip(std::uint64_t at, std::uint64_t bytes, std::uint64_t storedBytes, std::uint64_t end,
             const NodeWords& node);

  /// Decompresses the blosc block of `bytes` bytes at the position (its size field at `at`) into
  /// values_. Throws InputError at `at` when it is shorter than its header, when its header
  /// claims more bytes than it holds or other values than `storedBytes` bytes, or when
  /// blosc_decompress_ctx does not give those bytes.
  void unblosc(std::uint64_t at, std::uint64_t bytes, std::uint64_t storedBytes, std::uint64_t end,
               const NodeWords& node);

  /// The root's tiles (RootNode::readTopology): per tile its origin, value and active flag.
  /// Throws InputError for a flag, or a bool value, other than 0 or 1 (see bools).
  void rootTiles(std::uint32_t count, std::uint64_t end);

  /// Whether the nodes' values are bools (bool and mask grids), each byte of which OpenVDB reads
  /// into a bool.
  bool boolValues() const { return kind_.leaf != LeafKind::kValues; }

  /// Reads `count` bytes of `what` stored as bools before `end`. Throws InputError at the first
  /// byte other than 0 or 1, or like LayoutReader::bytes.
  void bools(std::uint64_t count, std::uint64_t end, const std::string& what);

  /// Throws InputError at `at` (a compressed block) when one of the `count` bytes decompressed
  /// into values_ is neither 0 nor 1; `what` names the values.
  void checkBools(std::uint64_t count, std::uint64_t at, const std::string& what) const;

  /// LeafNode::readBuffers of a leaf whose topology mask has `active` bits set. Throws
  /// InputError for its data not fitting before the grid's end, or as values() does.
  void leafBuffers(std::uint16_t active);

  LayoutReader& reader_;
  const ValueKind& kind_;
  const TreeGrid& grid_;
  const std::string root_;
  const NodeWords internal_, leaf_;
  std::vector<RootChild> children_;
  std::vector<unsigned char> values_;  ///< a block's values, decompressed
  std::vector<unsigned char> packed_;  ///< a blosc block, as blosc_decompress_ctx reads it
};

void TreeWalker::topology() {
  const std::uint64_t end = grid_.blockPosition;
  reader_.skip(sizeof(std::int32_t), end, "the buffer count of the tree of " + grid_.which);
  if (boolValues())
    bools(kind_.bytes, end, "the background value of " + root_);
  else
    reader_.skip(kind_.bytes, end, "the background value of " + root_);
  const std::uint64_t countsAt = reader_.position();
  const auto tiles = reader_.require<std::uint32_t>(end, "the tile count of " + root_);
  const auto children = reader_.require<std::uint32_t>(end, "the child count of " + root_);
  const std::uint64_t tileBytes = kCoordBytes + kind_.bytes + 1;  // origin, value, active flag
  if (tiles > reader_.left(end) / tileBytes)
    reader_.failAt(countsAt, root_ + " claims " + std::to_string(tiles) + " tiles of " +
                                 std::to_string(tileBytes) + " bytes each, but only " +
                                 std::to_string(reader_.left(end)) + " bytes remain before byte " +
                                 std::to_string(end));
  rootTiles(tiles, end);
  const std::uint64_t childBytes = kCoordBytes + minInternalBytes(5);
  if (children > reader_.left(end) / childBytes)
    reader_.failAt(countsAt + sizeof(std::uint32_t),
                   root_ + " claims " + std::to_string(children) + " child nodes of at least " +
                       std::to_string(childBytes) + " bytes each, but only " +
                       std::to_string(reader_.left(end)) + " bytes remain before byte " +
                       std::to_string(end));
  for (std::uint32_t k = 0; k < children; ++k) {
    RootChild child;
    std::memcpy(child.origin.data(),
                reader_.bytes(kCoordBytes, end, "the origin of a child of " + root_), kCoordBytes);
    internalTopology(5, child);
    children_.push_back(std::move(child));
  }
}

void TreeWalker::internalTopology(unsigned log2Dim, RootChild& child) {
  const std::uint64_t end = grid_.blockPosition;
  const std::uint32_t size = 1u << (3 * log2Dim);
  const std::size_t maskBytes = size / 8;
  const std::uint64_t at = reader_.position();
  const std::uint32_t childCount =
      countOn(reader_.bytes(maskBytes, end, "the child mask of " + internal_.node), maskBytes);
  const std::uint32_t active =
      countOn(reader_.bytes(maskBytes, end, internal_.valueMask), maskBytes);
  values(size, active, maskBytes, end, internal_);
  const std::uint64_t childBytes = log2Dim > 4 ? minInternalBytes(log2Dim - 1) : kLeafMaskBytes;
  if (childCount > reader_.left(end) / childBytes)
    reader_.failAt(at, internal_.node + " claims " + std::to_string(childCount) +
                           " child nodes of at least " + std::to_string(childBytes) +
                           " bytes each, but only " + std::to_string(reader_.left(end)) +
                           " bytes remain before byte " + std::to_string(end));
  for (std::uint32_t k = 0; k < childCount; ++k) {
    if (log2Dim > 4) {
      internalTopology(log2Dim - 1, child);
      continue;
    }
    const unsigned char* mask = reader_.bytes(kLeafMaskBytes, end, leaf_.valueMask);
    child.leafActive.push_back(static_cast<std::uint16_t>(countOn(mask, kLeafMaskBytes)));
  }
}

void TreeWalker::values(std::uint32_t count, std::uint32_t active, std::size_t maskBytes,
                        std::uint64_t end, const NodeWords& node) {
  const auto metadata = reader_.require<std::int8_t>(end, node.metadata);
  if (metadata == kOneInactiveValue || metadata == kMaskAndOneInactiveValue ||
      metadata == kMaskAndTwoInactiveValues) {
    // Inactive values are stored at full size, also when the grid is saved as half floats.
    const std::uint32_t inactive = metadata == kMaskAndTwoInactiveValues ? 2 : 1;
    if (boolValues())
      bools(std::uint64_t{inactive} * kind_.bytes, end, node.inactive);
    else
      reader_.skip(std::uint64_t{inactive} * kind_.bytes, end, node.inactive);
  }
  if (metadata == kMaskAndNoInactiveValue || metadata == kMaskAndOneInactiveValue ||
      metadata == kMaskAndTwoInactiveValues)
    reader_.skip(maskBytes, end, node.selection);
  const bool activeOnly = (grid_.compression & kCompressActiveMask) != 0 && metadata != kAllValues;
  const std::uint64_t stored = activeOnly ? active : count;
  const bool half = grid_.halfFloat && kind_.halfBytes > 0;
  if (half && stored == 0) return;  // HalfReader reads nothing for no values
  const std::uint64_t storedBytes = stored * (half ? kind_.halfBytes : kind_.bytes);
  if ((grid_.compression & (kCompressBlosc | kCompressZip)) != 0)
    block(storedBytes, end, (grid_.compression & kCompressBlosc) != 0, node);
  else if (boolValues())
    bools(storedBytes, end, node.values);
  else
    reader_.skip(storedBytes, end, node.values);
}

void TreeWalker::block(std::uint64_t storedBytes, std::uint64_t end, bool blosc,
                       const NodeWords& node) {
  const std::uint64_t at = reader_.position();
  const auto stated = reader_.require<std::int64_t>(end, node.blockSize);
  // A size of 0 or less: the values' bytes are stored uncompressed.
  const std::uint64_t bytes =
      stated <= 0 ? 0 - static_cast<std::uint64_t>(stated) : static_cast<std::uint64_t>(stated);
  if (bytes > reader_.left(end))
    reader_.failAt(at, "a compressed block of " + node.node + " claims " + std::to_string(bytes) +
                           " bytes, but only " + std::to_string(reader_.left(end)) +
                           " remain before byte " + std::to_string(end));
  if (stated <= 0) {
    // OpenVDB 10 reads uncompressed bytes into the values' buffer before comparing their number.
    if (bytes != storedBytes)
      reader_.failAt(at, "an uncompressed block of " + node.node + " claims " +
                             std::to_string(bytes) + " bytes, but its values take " +
                             std::to_string(storedBytes));
    if (boolValues()) bools(bytes, end, node.values);
    reader_.seek(at + sizeof(std::int64_t) + bytes);
    return;
  }
  if (blosc)
    unblosc(at, bytes, storedBytes, end, node);
  else
    unzip(at, bytes, storedBytes, end, node);
  if (boolValues()) checkBools(storedBytes, at, node.values);
  reader_.seek(at + sizeof(std::int64_t) + bytes);
}

void TreeWalker::unzip(std::uint64_t at, std::uint64_t bytes, std::uint64_t storedBytes,
                       std::uint64_t end, const NodeWords& node) {
  values_.resize(std::max<std::uint64_t>(storedBytes, 1));  // zlib wants somewhere to write
  Inflater inflater;
  if (!inflater.started) reader_.failAt(at, "zlib cannot start to decompress a block");
  z_stream& stream = inflater.stream;
  stream.next_out = values_.data();
  stream.avail_out = static_cast<uInt>(storedBytes);
  int status = Z_OK;
  for (std::uint64_t left = bytes; left > 0 && status == Z_OK;) {
    const auto chunk =
        static_cast<std::size_t>(std::min<std::uint64_t>(left, LayoutReader::kMaxBytes));
    stream.next_in = const_cast<Bytef*>(reader_.bytes(chunk, end, node.values));
    stream.avail_in = static_cast<uInt>(chunk);
    status = inflate(&stream, Z_NO_FLUSH);
    left -= chunk;
  }
  const std::string problem = unzipProblem(stream, status, storedBytes);
  if (!problem.empty())
    reader_.failAt(at, "the zip block of " + node.node + " does not decompress to the " +
                           std::to_string(storedBytes) + " bytes of its values (" + problem + ")");
}

void TreeWalker::unblosc(std::uint64_t at, std::uint64_t bytes, std::uint64_t storedBytes,
                         std::uint64_t end, const NodeWords& node) {
  // blosc_decompress reads as many bytes as the block's header says it holds.
  if (bytes < kBloscHeaderBytes)
    reader_.failAt(at, "a blosc block of " + node.node + " holds " + std::to_string(bytes) +
                           " bytes, fewer than its " + std::to_string(kBloscHeaderBytes) +
                           "-byte header");
  const unsigned char* header = reader_.bytes(kBloscHeaderBytes, end, "a blosc header");
  packed_.assign(header, header + kBloscHeaderBytes);
  std::uint32_t compressed = 0, valueBytes = 0;
  std::memcpy(&compressed, packed_.data() + kBloscSizeAt, sizeof compressed);
  std::memcpy(&valueBytes, packed_.data() + kBloscValuesAt, sizeof valueBytes);
  if (compressed > bytes)
    reader_.failAt(at, "the header of a blosc block of " + node.node + " claims " +
                           std::to_string(compressed) + " bytes, but the block holds " +
                           std::to_string(bytes));
  if (valueBytes != storedBytes)
    reader_.failAt(at, "the header of a blosc block of " + node.node + " claims " +
                           std::to_string(valueBytes) + " bytes of values, but they take " +
                           std::to_string(storedBytes));
  for (std::uint64_t left = compressed > kBloscHeaderBytes ? compressed - kBloscHeaderBytes : 0;
       left > 0;) {
    const auto chunk =
        static_cast<std::size_t>(std::min<std::uint64_t>(left, LayoutReader::kMaxBytes));
    const unsigned char* data = reader_.bytes(chunk, end, node.values);
    packed_.insert(packed_.end(), data, data + chunk);
    left -= chunk;
  }
  values_.resize(std::max<std::uint64_t>(storedBytes, 1));
  const int got = blosc_decompress_ctx(packed_.data(), values_.data(), storedBytes, 1);
  if (got < 0 || static_cast<std::uint64_t>(got) != storedBytes)
    reader_.failAt(
        at, "the blosc block of " + node.node + " does not decompress to the " +
                std::to_string(storedBytes) + " bytes of its values (blosc: " +
                (got < 0 ? "error " + std::to_string(got) : std::to_string(got) + " bytes") + ")");
}

void TreeWalker::rootTiles(std::uint32_t count, std::uint64_t end) {
  const std::string origin = "the origin of a tile of " + root_,
                    value = "the value of a tile of " + root_,
                    active = "the active flag of a tile of " + root_;
  for (std::uint32_t k = 0; k < count; ++k) {
    reader_.skip(kCoordBytes, end, origin);
    if (boolValues())
      bools(kind_.bytes, end, value);
    else
      reader_.skip(kind_.bytes, end, value);
    bools(1, end, active);
  }
}

void TreeWalker::bools(std::uint64_t count, std::uint64_t end, const std::string& what) {
  for (std::uint64_t left = count; left > 0;) {
    const std::uint64_t at = reader_.position();
    const auto chunk =
        static_cast<std::size_t>(std::min<std::uint64_t>(left, LayoutReader::kMaxBytes));
    const unsigned char* data = reader_.bytes(chunk, end, what);
    const unsigned char* bad =
        std::find_if(data, data + chunk, [](unsigned char byte) { return byte > 1; });
    if (bad != data + chunk)
      reader_.failAt(at + static_cast<std::uint64_t>(bad - data),
                     "a byte of " + what + " is " + std::to_string(*bad) +
                         ", but it is read into a bool (0 or 1)");
    left -= chunk;
  }
}

void TreeWalker::checkBools(std::uint64_t count, std::uint64_t at, const std::string& what) const {
  const auto last = values_.begin() + static_cast<std::ptrdiff_t>(count);
  const auto bad = std::find_if(values_.begin(), last, [](unsigned char byte) { return byte > 1; });
  if (bad != last)
    reader_.failAt(at, "decompressed byte " + std::to_string(bad - values_.begin()) + " of " +
                           what + " is " + std::to_string(*bad) +
                           ", but it is read into a bool (0 or 1)");
}

void TreeWalker::buffers() {
  const std::uint64_t end = grid_.endPosition;
  std::map<std::array<std::int32_t, 3>, std::size_t> table;  // the root's: the last one read wins
  for (std::size_t k = 0; k < children_.size(); ++k) table[children_[k].origin] = k;
  std::uint64_t leaves = 0;
  for (const auto& entry : table) leaves += children_[entry.second].leafActive.size();
  const std::uint64_t leafBytes = kind_.leaf == LeafKind::kBool   ? 2 * kLeafMaskBytes + kCoordBytes
                                  : kind_.leaf == LeafKind::kMask ? kLeafMaskBytes + kCoordBytes
                                                                  : kLeafMaskBytes + 1;
  if (leaves > reader_.left(end) / leafBytes)
    reader_.fail("the topology of " + grid_.which + " has " + std::to_string(leaves) +
                 " leaf nodes of at least " + std::to_string(leafBytes) +
                 " bytes each in its data blocks, but only " + std::to_string(reader_.left(end)) +
                 " bytes remain before byte " + std::to_string(end));
  for (const auto& entry : table)
    for (const std::uint16_t active : children_[entry.second].leafActive) leafBuffers(active);
}

void TreeWalker::leafBuffers(std::uint16_t active) {
  const std::uint64_t end = grid_.endPosition;
  switch (kind_.leaf) {
    case LeafKind::kBool:
      reader_.skip(2 * kLeafMaskBytes + kCoordBytes, end, leaf_.values);
      return;
    case LeafKind::kMask:
      reader_.skip(kLeafMaskBytes + kCoordBytes, end, leaf_.values);
      return;
    case LeafKind::kValues:
      reader_.skip(kLeafMaskBytes, end, leaf_.valueMask);
      values(512, active, kLeafMaskBytes, end, leaf_);
      return;
  }
}

}  // namespace

bool isWalkedTreeType(const std::string& treeType) {
  return findValueKind(treeType) != nullptr;
}

void checkTreeLayout(LayoutReader& reader, const std::string& treeType, const TreeGrid& grid) {
  const ValueKind* kind = findValueKind(treeType);
  if (kind == nullptr) return;
  TreeWalker walker(reader, *kind, grid);
  walker.topology();
  walker.buffers();
}

}  // namespace voxremesh::volume
