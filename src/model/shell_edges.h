// Edge adjacency of FE shells: the unique undirected edges of a set of shells, the shells on each
// edge with the direction in which each traverses it, and each shell's edges. The deck report and
// the later sheet stages (consistent orientation, splitting at non-manifold edges, boundary loops)
// build on it.
//
// Everything here works on node and shell *indices* (positions in FeModel::nodes and
// FeModel::shells), not on IDs. The order of edges and incidences depends only on the input, never
// on hashing or threads: edges are sorted by (lower node index, higher node index), the incidences
// of an edge by (shell position, side).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "voxremesh/fe_model.h"

namespace voxremesh::model {

/// A node, shell or edge index. Models are limited to 2^32 - 2 nodes and shells.
using Index = std::uint32_t;

/// "No such index" (e.g. the edge of a collapsed side).
inline constexpr Index kNoIndex = ~Index{0};

/// A shell's corners as indices into FeModel::nodes.
struct ShellCorners {
  std::array<Index, 4> node{};  ///< node[3] is unused for triangles
  std::uint8_t count = 4;       ///< 3 or 4
};

/// Maps the node IDs of every shell of `model` to node indices (result[i] belongs to shells[i]).
/// Throws std::invalid_argument naming the IDs when a shell names a node the model does not
/// define, when two nodes share an ID or when a shell's nodeCount is not 3 or 4;
/// std::length_error when the model has more nodes or shells than Index can address.
std::vector<ShellCorners> shellCorners(const FeModel& model);

/// Edge adjacency of a set of shells (all shells of a model, or a subset such as one part).
///
/// Side s of a shell runs from its corner s to corner (s + 1) mod count. A side whose two corners
/// are the same node (a collapsed side) has no edge. Shells are addressed by their *position* in
/// the set (0 .. shellCount() - 1); shellIndex() maps a position back to the model's shell index.
class ShellEdges {
 public:
  /// An undirected edge: two node indices, a < b.
  struct Edge {
    Index a = 0;
    Index b = 0;
  };

  /// One shell's use of an edge.
  struct Incidence {
    Index shell = 0;        ///< position of the shell in the set
    std::uint8_t side = 0;  ///< which side of the shell the edge is
    bool forward = false;   ///< the shell traverses the edge from a to b
  };

  /// A contiguous range of incidences.
  struct IncidenceRange {
    const Incidence* first = nullptr;
    const Incidence* last = nullptr;
    const Incidence* begin() const { return first; }
    const Incidence* end() const { return last; }
    std::size_t size() const { return static_cast<std::size_t>(last - first); }
    const Incidence& operator[](std::size_t i) const { return first[i]; }
  };

  /// An empty adjacency (no shells).
  ShellEdges() = default;

  /// Builds the adjacency of all shells: position i is corners[i].
  /// Throws std::length_error beyond 2^29 shells.
  explicit ShellEdges(const std::vector<ShellCorners>& corners);

  /// Builds the adjacency of the shells corners[shells[0]], corners[shells[1]], ...
  /// Preconditions: the entries of `shells` are distinct valid indices into `corners`.
  /// Throws std::length_error beyond 2^29 shells.
  ShellEdges(const std::vector<ShellCorners>& corners, std::vector<Index> shells);

  /// Number of unique undirected edges.
  std::size_t edgeCount() const { return edges_.size(); }
  /// Number of shells in the set.
  std::size_t shellCount() const { return shells_.size(); }
  /// The model's shell index (into the `corners` given to the constructor) of position `shell`.
  Index shellIndex(Index shell) const { return shells_[shell]; }
  /// The model's shell indices of all positions.
  const std::vector<Index>& shells() const { return shells_; }

  /// Edge `e`. Precondition: e < edgeCount().
  const Edge& edge(Index e) const { return edges_[e]; }
  /// The shells on edge `e`, ordered by (shell position, side). Precondition: e < edgeCount().
  IncidenceRange incidences(Index e) const {
    return {incidences_.data() + incidenceBegin_[e], incidences_.data() + incidenceBegin_[e + 1]};
  }
  /// Number of shells on edge `e` (a shell using it on two sides counts twice).
  std::size_t valence(Index e) const { return incidenceBegin_[e + 1] - incidenceBegin_[e]; }
  /// The edge of side `side` (0..3) of the shell at position `shell`; kNoIndex for a collapsed
  /// side and for side 3 of a triangle.
  Index shellEdge(Index shell, unsigned side) const {
    return shellEdges_[4 * std::size_t{shell} + side];
  }

  /// Edge `e` belongs to exactly one shell.
  bool isBoundary(Index e) const { return valence(e) == 1; }
  /// Edge `e` belongs to exactly two shells.
  bool isManifold(Index e) const { return valence(e) == 2; }
  /// Edge `e` belongs to three or more shells.
  bool isNonManifold(Index e) const { return valence(e) >= 3; }
  /// Two of the shells on edge `e` traverse it in the same direction. On a manifold edge this
  /// means the two shells' normals disagree; every non-manifold edge has such a pair (three or
  /// more shells cannot alternate between two directions).
  bool hasInconsistentOrientation(Index e) const;

  /// All boundary edges, ascending.
  std::vector<Index> boundaryEdges() const;
  /// All non-manifold edges, ascending.
  std::vector<Index> nonManifoldEdges() const;
  /// All edges with inconsistent orientation (see hasInconsistentOrientation), ascending.
  std::vector<Index> inconsistentEdges() const;

 private:
  void build(const std::vector<ShellCorners>& corners);

  std::vector<Index> shells_;
  std::vector<Edge> edges_;
  std::vector<Index> incidenceBegin_{0};
  std::vector<Incidence> incidences_;
  std::vector<Index> shellEdges_;
};

/// A chain of boundary edges: closed (a loop) or open (it ends at nodes where boundary edges meet
/// non-manifold edges, or at a collapsed side).
struct BoundaryChain {
  std::vector<Index> edges;  ///< edge indices in walking order
  std::vector<Index>
      nodes;  ///< node indices in walking order; closed: one per edge, open: one more
  bool closed = false;
};

/// Chains the boundary edges of `adjacency` into loops and open chains; every boundary edge
/// belongs to exactly one chain.
///
/// At a node with exactly two boundary edges they are joined. At a node with more (shells touching
/// at a single node, like a bow-tie), each boundary edge is joined to the boundary edge reached by
/// walking around the node through its shells across manifold edges (so each fan of shells around
/// the node keeps its own contour); boundary edges whose walk ends at a non-manifold edge are
/// joined in ascending edge order, and an odd one left over ends an open chain, as does a node's
/// single boundary edge.
///
/// A closed loop starts at its lowest edge and runs the way that edge's shell traverses it; an open
/// chain starts at the lower of its two end edges and runs away from its free end (a chain of one
/// edge runs the way its shell traverses it). The result is ordered by first edge. Deterministic:
/// depends only on the adjacency.
std::vector<BoundaryChain> boundaryChains(const ShellEdges& adjacency);

}  // namespace voxremesh::model
