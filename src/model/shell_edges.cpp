#include "model/shell_edges.h"

#include "model/radix_sort.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace voxremesh::model {

namespace {

// Incidence payloads pack (shell position, side, forward) as shell << 3 | side << 1 | forward.
constexpr std::size_t kMaxShells = std::size_t{1} << 29;

// Maps node IDs to node indices: a direct table when the IDs are dense enough, else a sorted list.
class NodeLookup {
 public:
  explicit NodeLookup(const FeModel& model) {
    const std::size_t n = model.nodes.size();
    if (n == 0) return;
    Id lo = model.nodes[0].id, hi = lo;
    for (const Node& node : model.nodes) {
      lo = std::min(lo, node.id);
      hi = std::max(hi, node.id);
    }
    min_ = lo;
    // Compare as unsigned so that extreme IDs cannot overflow.
    const std::uint64_t span = static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo);
    if (span < 8 * std::uint64_t{n} + 1024) {
      table_.assign(span + 1, kNoIndex);
      for (std::size_t i = 0; i < n; ++i) {
        Index& slot = table_[static_cast<std::uint64_t>(model.nodes[i].id - lo)];
        if (slot != kNoIndex) duplicate(model.nodes[i].id);
        slot = static_cast<Index>(i);
      }
    } else {
      sorted_.reserve(n);
      for (std::size_t i = 0; i < n; ++i) sorted_.emplace_back(model.nodes[i].id, Index(i));
      std::sort(sorted_.begin(), sorted_.end());
      for (std::size_t i = 1; i < n; ++i)
        if (sorted_[i].first == sorted_[i - 1].first) duplicate(sorted_[i].first);
    }
  }

  // The index of node `id`, or kNoIndex.
  Index find(Id id) const {
    if (!table_.empty()) {
      if (id < min_) return kNoIndex;
      const std::uint64_t offset =
          static_cast<std::uint64_t>(id) - static_cast<std::uint64_t>(min_);
      return offset < table_.size() ? table_[offset] : kNoIndex;
    }
    const auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(id, Index{0}));
    return it != sorted_.end() && it->first == id ? it->second : kNoIndex;
  }

 private:
  [[noreturn]] static void duplicate(Id id) {
    throw std::invalid_argument("node ID " + std::to_string(id) + " is defined twice");
  }

  Id min_ = 0;
  std::vector<Index> table_;
  std::vector<std::pair<Id, Index>> sorted_;
};

}  // namespace

std::vector<ShellCorners> shellCorners(const FeModel& model) {
  if (model.nodes.size() >= kNoIndex || model.shells.size() >= kNoIndex)
    throw std::length_error("the model has more nodes or shells than voxremesh can index (2^32-2)");
  const NodeLookup lookup(model);
  std::vector<ShellCorners> corners(model.shells.size());
  for (std::size_t i = 0; i < model.shells.size(); ++i) {
    const Shell& shell = model.shells[i];
    if (shell.nodeCount != 3 && shell.nodeCount != 4)
      throw std::invalid_argument("shell " + std::to_string(shell.id) + " has " +
                                  std::to_string(shell.nodeCount) + " nodes (3 or 4 expected)");
    corners[i].count = shell.nodeCount;
    for (unsigned k = 0; k < shell.nodeCount; ++k) {
      const Index node = lookup.find(shell.nodes[k]);
      if (node == kNoIndex)
        throw std::invalid_argument("shell " + std::to_string(shell.id) + " names node " +
                                    std::to_string(shell.nodes[k]) +
                                    ", which the model does not define");
      corners[i].node[k] = node;
    }
  }
  return corners;
}

ShellEdges::ShellEdges(const std::vector<ShellCorners>& corners) {
  shells_.resize(corners.size());
  std::iota(shells_.begin(), shells_.end(), Index{0});
  build(corners);
}

ShellEdges::ShellEdges(const std::vector<ShellCorners>& corners, std::vector<Index> shells)
    : shells_(std::move(shells)) {
  build(corners);
}

void ShellEdges::build(const std::vector<ShellCorners>& corners) {
  const std::size_t n = shells_.size();
  if (n >= kMaxShells) throw std::length_error("more than 2^29 shells in one edge adjacency");
  Index maxNode = 0;
  std::size_t sideCount = 0;
  for (const Index s : shells_) {
    const ShellCorners& c = corners[s];
    sideCount += c.count;
    for (unsigned k = 0; k < c.count; ++k) maxNode = std::max(maxNode, c.node[k]);
  }
  // One entry per non-collapsed side: its edge (a < b) and payload shell << 3 | side << 1 |
  // forward, generated in payload order.
  struct Side {
    Index a, b;
    std::uint32_t payload;
  };
  std::vector<Side> sides;
  sides.reserve(sideCount);
  for (std::size_t k = 0; k < n; ++k) {
    const ShellCorners& c = corners[shells_[k]];
    for (unsigned side = 0; side < c.count; ++side) {
      const Index p = c.node[side];
      const Index q = c.node[(side + 1) % c.count];
      if (p == q) continue;
      const bool forward = p < q;
      sides.push_back({forward ? p : q, forward ? q : p,
                       static_cast<std::uint32_t>(k << 3 | side << 1 | (forward ? 1u : 0u))});
    }
  }
  // Sort by (a, b, payload). Dense node ranges: counting sort by a, then each bucket (a few sides)
  // by (b, payload). Sparse ones (a small part of a big model): radix sort of a * span + b.
  const std::size_t span = std::size_t{maxNode} + 1;
  std::vector<Side> sorted(sides.size());
  if (span <= 2 * sides.size() + 1024) {
    std::vector<Index> begin(span + 1, 0);
    for (const Side& side : sides) ++begin[side.a + 1];
    std::partial_sum(begin.begin(), begin.end(), begin.begin());
    std::vector<Index> fill(begin.begin(), begin.end() - 1);
    for (const Side& side : sides) sorted[fill[side.a]++] = side;
    auto less = [](const Side& x, const Side& y) {
      return x.b < y.b || (x.b == y.b && x.payload < y.payload);
    };
    for (std::size_t a = 0; a < span; ++a) {
      Side* first = sorted.data() + begin[a];
      Side* last = sorted.data() + begin[a + 1];
      if (last - first < 2) continue;  // (no pointer past an empty bucket, which may be null)
      if (last - first > 16) {
        std::sort(first, last, less);
        continue;
      }
      for (Side* i = first + 1; i < last; ++i)  // insertion sort: buckets are tiny
        for (Side* j = i; j > first && less(*j, *(j - 1)); --j) std::swap(*j, *(j - 1));
    }
  } else {
    std::vector<std::uint64_t> keys(sides.size());
    std::vector<std::uint32_t> order(sides.size());
    for (std::size_t i = 0; i < sides.size(); ++i) {
      keys[i] = std::uint64_t{sides[i].a} * span + sides[i].b;
      order[i] = static_cast<std::uint32_t>(i);
    }
    radixSortPairs(keys, order, std::uint64_t{span} * span - 1);  // stable: payload order kept
    for (std::size_t i = 0; i < sides.size(); ++i) sorted[i] = sides[order[i]];
  }

  shellEdges_.assign(4 * n, kNoIndex);
  incidences_.resize(sorted.size());
  edges_.clear();
  incidenceBegin_.clear();
  incidenceBegin_.reserve(sorted.size() / 2 + 2);
  edges_.reserve(sorted.size() / 2 + 1);
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const Side& side = sorted[i];
    if (i == 0 || side.a != sorted[i - 1].a || side.b != sorted[i - 1].b) {
      incidenceBegin_.push_back(static_cast<Index>(i));
      edges_.push_back(Edge{side.a, side.b});
    }
    Incidence& incidence = incidences_[i];
    incidence.shell = side.payload >> 3;
    incidence.side = static_cast<std::uint8_t>((side.payload >> 1) & 3u);
    incidence.forward = (side.payload & 1u) != 0;
    shellEdges_[4 * std::size_t{incidence.shell} + incidence.side] =
        static_cast<Index>(edges_.size() - 1);
  }
  incidenceBegin_.push_back(static_cast<Index>(sorted.size()));
}

bool ShellEdges::hasInconsistentOrientation(Index e) const {
  std::size_t forward = 0, backward = 0;
  for (const Incidence& incidence : incidences(e)) (incidence.forward ? forward : backward)++;
  return forward >= 2 || backward >= 2;
}

std::vector<Index> ShellEdges::boundaryEdges() const {
  std::vector<Index> result;
  for (Index e = 0; e < edges_.size(); ++e)
    if (isBoundary(e)) result.push_back(e);
  return result;
}

std::vector<Index> ShellEdges::nonManifoldEdges() const {
  std::vector<Index> result;
  for (Index e = 0; e < edges_.size(); ++e)
    if (isNonManifold(e)) result.push_back(e);
  return result;
}

std::vector<Index> ShellEdges::inconsistentEdges() const {
  std::vector<Index> result;
  for (Index e = 0; e < edges_.size(); ++e)
    if (hasInconsistentOrientation(e)) result.push_back(e);
  return result;
}

namespace {

// The boundary edge reached from boundary edge `start` by walking around node v through the shells
// across manifold edges, or kNoIndex when the walk ends at a non-manifold edge or collapsed side.
Index fanPartner(const ShellEdges& adjacency, Index start, Index v) {
  ShellEdges::Incidence at = adjacency.incidences(start)[0];
  for (std::size_t steps = 0; steps <= adjacency.shellCount(); ++steps) {
    // The other side of this shell at v.
    Index next = kNoIndex;
    unsigned nextSide = 0;
    for (unsigned side = 0; side < 4 && next == kNoIndex; ++side) {
      const Index f = adjacency.shellEdge(at.shell, side);
      if (f == kNoIndex || side == at.side) continue;
      const ShellEdges::Edge& candidate = adjacency.edge(f);
      if (candidate.a == v || candidate.b == v) {
        next = f;
        nextSide = side;
      }
    }
    if (next == kNoIndex || adjacency.isNonManifold(next)) return kNoIndex;
    if (adjacency.isBoundary(next)) return next == start ? kNoIndex : next;
    // Continue with the other shell on this manifold edge.
    const auto across = adjacency.incidences(next);
    const bool firstIsHere = across[0].shell == at.shell && across[0].side == nextSide;
    const ShellEdges::Incidence other = firstIsHere ? across[1] : across[0];
    if (other.shell == at.shell) return kNoIndex;  // one shell on both sides of an edge
    at = other;
  }
  return kNoIndex;
}

}  // namespace

std::vector<BoundaryChain> boundaryChains(const ShellEdges& adjacency) {
  const std::vector<Index> boundary = adjacency.boundaryEdges();
  const std::size_t count = boundary.size();
  // Ends are numbered 2 * slot + end, end 0 at node a, end 1 at node b of boundary[slot].
  std::vector<std::uint64_t> nodes;
  std::vector<std::uint32_t> ends;
  nodes.reserve(2 * count);
  ends.reserve(2 * count);
  std::uint64_t maxNode = 0;
  for (std::size_t slot = 0; slot < count; ++slot) {
    const ShellEdges::Edge& e = adjacency.edge(boundary[slot]);
    nodes.push_back(e.a);
    ends.push_back(static_cast<std::uint32_t>(2 * slot));
    nodes.push_back(e.b);
    ends.push_back(static_cast<std::uint32_t>(2 * slot + 1));
    maxNode = std::max<std::uint64_t>(maxNode, e.b);
  }
  radixSortPairs(nodes, ends, maxNode);

  std::vector<Index> link(2 * count, kNoIndex);
  auto join = [&](std::uint32_t x, std::uint32_t y) {
    link[x] = y;
    link[y] = x;
  };
  std::vector<Index> slotOfEdge;  // filled lazily: only needed at nodes with > 2 boundary edges
  for (std::size_t first = 0; first < nodes.size();) {
    std::size_t last = first + 1;
    while (last < nodes.size() && nodes[last] == nodes[first]) ++last;
    const std::size_t here = last - first;
    if (here == 2) {
      join(ends[first], ends[first + 1]);
    } else if (here > 2) {
      if (slotOfEdge.empty()) {
        slotOfEdge.assign(adjacency.edgeCount(), kNoIndex);
        for (std::size_t slot = 0; slot < count; ++slot) slotOfEdge[boundary[slot]] = Index(slot);
      }
      const Index v = static_cast<Index>(nodes[first]);
      auto endAt = [&](Index edge) {
        const Index slot = slotOfEdge[edge];
        return static_cast<std::uint32_t>(2 * slot + (adjacency.edge(edge).a == v ? 0 : 1));
      };
      std::vector<std::uint32_t> leftover;
      for (std::size_t i = first; i < last; ++i) {
        const std::uint32_t end = ends[i];
        if (link[end] != kNoIndex) continue;
        const Index partner = fanPartner(adjacency, boundary[end / 2], v);
        if (partner != kNoIndex && link[endAt(partner)] == kNoIndex) {
          join(end, endAt(partner));
        } else {
          leftover.push_back(end);
        }
      }
      for (std::size_t i = 0; i + 1 < leftover.size(); i += 2) join(leftover[i], leftover[i + 1]);
    }
    first = last;
  }

  std::vector<BoundaryChain> chains;
  std::vector<bool> visited(count, false);
  auto walk = [&](std::size_t slot, unsigned in) {
    BoundaryChain chain;
    const std::size_t start = slot;
    for (;;) {
      visited[slot] = true;
      const ShellEdges::Edge& e = adjacency.edge(boundary[slot]);
      chain.edges.push_back(boundary[slot]);
      chain.nodes.push_back(in == 0 ? e.a : e.b);
      const Index next = link[2 * slot + (1 - in)];
      if (next == kNoIndex) {
        chain.nodes.push_back(in == 0 ? e.b : e.a);
        break;
      }
      slot = next / 2;
      in = next % 2;
      if (slot == start) {
        chain.closed = true;
        break;
      }
    }
    chains.push_back(std::move(chain));
  };
  auto shellDirection = [&](std::size_t slot) -> unsigned {
    return adjacency.incidences(boundary[slot])[0].forward ? 0 : 1;
  };
  for (std::size_t slot = 0; slot < count; ++slot) {
    if (visited[slot]) continue;
    const bool freeA = link[2 * slot] == kNoIndex, freeB = link[2 * slot + 1] == kNoIndex;
    if (freeA && freeB)
      walk(slot, shellDirection(slot));
    else if (freeA)
      walk(slot, 0);
    else if (freeB)
      walk(slot, 1);
  }
  for (std::size_t slot = 0; slot < count; ++slot)
    if (!visited[slot]) walk(slot, shellDirection(slot));
  std::stable_sort(chains.begin(), chains.end(),
                   [](const BoundaryChain& x, const BoundaryChain& y) {
                     return x.edges.front() < y.edges.front();
                   });
  return chains;
}

}  // namespace voxremesh::model
