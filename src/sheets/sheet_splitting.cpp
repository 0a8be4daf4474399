// The sheets of a part: their faces in the consistent orientation and their points, with the
// non-manifold edges of the part joined inside a sheet or cut apart (see sheets.h).
#include <algorithm>
#include <numeric>
#include <utility>

#include "sheets/sheet_internal.h"

namespace voxremesh::sheets {

namespace {

// A pair of faces of one component joined across a non-manifold edge.
struct Glue {
  Index edge;
  Index a, b;  // part positions
};

// Everything a part's sheets are cut from.
struct PartSplit {
  const ModelContext& context;
  const PartMesh& part;
  const Orientation& orientation;
  std::vector<Glue> glues;            // ascending by edge
  std::vector<std::uint8_t> cutNode;  // per local node: a cut runs through it (empty: none)
  std::vector<Index> faceInSheet;     // per position: its index in its sheet
  std::vector<Index> nodePoint;       // scratch per local node: point in the current sheet
};

std::array<Vec3, 4> cornerPoints(const PartSplit& split, Index position) {
  const ShellCorners& c = split.part.corners[position];
  std::array<Vec3, 4> p{};
  for (unsigned k = 0; k < c.count; ++k)
    p[k] = split.context.model.nodes[split.part.nodes[c.node[k]]].xyz;
  return p;
}

// The normal of the face at `position` in its component's orientation.
Vec3 orientedNormal(const PartSplit& split, Index position) {
  Vec3 n = faceNormal(cornerPoints(split, position), split.part.corners[position].count);
  if (split.orientation.flipped[position])
    for (double& x : n) x = -x;
  return n;
}

// Decides, for every non-manifold edge, which faces of each component are joined across it and
// which are cut apart there.
void joinOrCut(PartSplit& split) {
  const ShellEdges& edges = split.part.edges;
  const Orientation& orientation = split.orientation;
  std::vector<ShellEdges::Incidence> mine;
  for (Index e = 0; e < edges.edgeCount(); ++e) {
    if (!edges.isNonManifold(e)) continue;
    const ShellEdges::IncidenceRange on = edges.incidences(e);
    std::vector<ShellEdges::Incidence> rest(on.begin(), on.end());
    while (!rest.empty()) {
      // The incidences of the component of the first remaining one, in incidence order.
      const Index component = orientation.component[rest.front().shell];
      mine.clear();
      std::vector<ShellEdges::Incidence> others;
      for (const ShellEdges::Incidence& x : rest)
        (orientation.component[x.shell] == component ? mine : others).push_back(x);
      rest.swap(others);
      if (mine.size() < 2) continue;  // a boundary edge of that sheet
      // The most nearly flat pair running along the edge in opposite directions.
      double best = 0.0;
      std::size_t bestI = 0, bestJ = 0;
      bool found = false;
      for (std::size_t i = 0; i < mine.size(); ++i)
        for (std::size_t j = i + 1; j < mine.size(); ++j) {
          const bool ei = mine[i].forward != (orientation.flipped[mine[i].shell] != 0);
          const bool ej = mine[j].forward != (orientation.flipped[mine[j].shell] != 0);
          if (ei == ej) continue;
          const double angle =
              angleDeg(orientedNormal(split, mine[i].shell), orientedNormal(split, mine[j].shell));
          if (!found || angle < best) {
            best = angle;
            bestI = i;
            bestJ = j;
            found = true;
          }
        }
      if (found) split.glues.push_back(Glue{e, mine[bestI].shell, mine[bestJ].shell});
      if (found && mine.size() == 2) continue;
      if (split.cutNode.empty()) split.cutNode.assign(split.part.nodes.size(), 0);
      split.cutNode[edges.edge(e).a] = 1;
      split.cutNode[edges.edge(e).b] = 1;
    }
  }
}

// The face joined to `position` across part edge `e`, or kNoIndex (also across a cut,
// whose faces lie in different components).
Index partnerAcross(const PartSplit& split, Index position, Index e) {
  const ShellEdges& edges = split.part.edges;
  if (edges.isManifold(e)) {
    const ShellEdges::IncidenceRange on = edges.incidences(e);
    const Index other = on[0].shell == position ? on[1].shell : on[0].shell;
    const std::vector<Index>& component = split.orientation.component;
    return component[other] == component[position] ? other : kNoIndex;
  }
  if (!edges.isNonManifold(e)) return kNoIndex;
  auto it = std::lower_bound(split.glues.begin(), split.glues.end(), e,
                             [](const Glue& g, Index edge) { return g.edge < edge; });
  for (; it != split.glues.end() && it->edge == e; ++it) {
    if (it->a == position) return it->b;
    if (it->b == position) return it->a;
  }
  return kNoIndex;
}

// Builds one sheet from its faces (part positions, ascending).
class SheetBuilder {
 public:
  SheetBuilder(PartSplit& split, const Index* first, const Index* last)
      : split_(split), part_(split.part), positions_(first, last) {}

  SheetDraft build() {
    const Orientation& orientation = split_.orientation;
    const std::size_t faceCount = positions_.size();
    draft_.positions = positions_;
    draft_.sheet.part = part_.part;
    draft_.sheet.faceShellIds.reserve(faceCount);
    draft_.sheet.faceFlipped.reserve(faceCount);
    nodes_.resize(faceCount);
    for (std::size_t i = 0; i < faceCount; ++i) {
      const Index position = positions_[i];
      const ShellCorners& c = part_.corners[position];
      ShellCorners& o = nodes_[i];
      o.count = c.count;
      o.node = c.node;
      if (orientation.flipped[position]) std::reverse(o.node.begin() + 1, o.node.begin() + c.count);
      draft_.sheet.faceShellIds.push_back(split_.context.model.shells[part_.shells[position]].id);
      draft_.sheet.faceFlipped.push_back(orientation.flipped[position] != 0);
    }
    assignKeys();
    for (;;) {
      numberPoints();
      draft_.edges = ShellEdges(draft_.corners);
      if (!separateBadEdges()) break;
    }
    draft_.partEdge.assign(draft_.edges.edgeCount(), kNoIndex);
    for (Index i = 0; i < faceCount; ++i)
      for (unsigned k = 0; k < draft_.corners[i].count; ++k)
        draft_.partEdge[draft_.edges.shellEdge(i, k)] = partEdge(i, k);
    return std::move(draft_);
  }

 private:
  // The part edge under side k (corner k to k + 1 in the sheet's orientation) of face i.
  Index partEdge(Index i, unsigned k) const {
    const Index position = positions_[i];
    const unsigned m = nodes_[i].count;
    const unsigned side = split_.orientation.flipped[position] ? (2 * m - k - 1) % m : k;
    return part_.edges.shellEdge(position, side);
  }

  // Point keys per corner slot 4 i + k: the local node, or, at nodes a cut runs through, one key
  // per wedge (faces joined around the node), numbered from the local node count on.
  void assignKeys() {
    const std::size_t faceCount = positions_.size();
    keys_.assign(4 * faceCount, kNoIndex);
    nextKey_ = Index(part_.nodes.size());
    std::vector<Index> parent;  // union-find over slots at cut nodes (allocated when needed)
    auto find = [&](Index x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (Index i = 0; i < faceCount; ++i) {
      const ShellCorners& o = nodes_[i];
      for (unsigned k = 0; k < o.count; ++k) {
        const Index v = o.node[k];
        if (split_.cutNode.empty() || !split_.cutNode[v]) {
          keys_[4 * i + k] = v;
          continue;
        }
        if (parent.empty()) {
          parent.resize(4 * faceCount);
          std::iota(parent.begin(), parent.end(), Index{0});
        }
        // Join this slot with the slots of v in the faces joined across its two sides at v.
        for (const unsigned side : {k, (k + o.count - 1) % o.count}) {
          const Index g = partnerAcross(split_, positions_[i], partEdge(i, side));
          if (g == kNoIndex) continue;
          const Index j = split_.faceInSheet[g];
          const ShellCorners& og = nodes_[j];
          for (unsigned kk = 0; kk < og.count; ++kk) {
            if (og.node[kk] != v) continue;
            const Index x = find(4 * i + k), y = find(4 * j + kk);
            if (x != y) parent[std::max(x, y)] = std::min(x, y);
          }
        }
      }
    }
    if (parent.empty()) return;
    std::vector<Index> keyOfRoot(4 * faceCount, kNoIndex);
    for (Index i = 0; i < faceCount; ++i)
      for (unsigned k = 0; k < nodes_[i].count; ++k) {
        if (keys_[4 * i + k] != kNoIndex) continue;
        Index& key = keyOfRoot[find(4 * i + k)];
        if (key == kNoIndex) key = nextKey_++;
        keys_[4 * i + k] = key;
      }
  }

  // Numbers the points by first use in face order and fills the sheet's points and corners.
  void numberPoints() {
    const std::size_t faceCount = positions_.size();
    const Index nodeCount = Index(part_.nodes.size());
    std::vector<Index> extraPoint(nextKey_ - nodeCount, kNoIndex);
    std::vector<Index>& nodePoint = split_.nodePoint;
    Sheet& sheet = draft_.sheet;
    sheet.points.clear();
    sheet.pointNodeIds.clear();
    draft_.corners.assign(faceCount, ShellCorners{});
    const FeModel& model = split_.context.model;
    for (std::size_t i = 0; i < faceCount; ++i) {
      ShellCorners& c = draft_.corners[i];
      c.count = nodes_[i].count;
      for (unsigned k = 0; k < c.count; ++k) {
        const Index key = keys_[4 * i + k];
        Index& point = key < nodeCount ? nodePoint[key] : extraPoint[key - nodeCount];
        if (point == kNoIndex) {
          point = Index(sheet.points.size());
          const Node& node = model.nodes[part_.nodes[nodes_[i].node[k]]];
          sheet.points.push_back(node.xyz);
          sheet.pointNodeIds.push_back(node.id);
        }
        c.node[k] = point;
      }
    }
    for (std::size_t i = 0; i < faceCount; ++i)
      for (unsigned k = 0; k < nodes_[i].count; ++k) nodePoint[nodes_[i].node[k]] = kNoIndex;
    sheet.faces.resize(faceCount);
    for (std::size_t i = 0; i < faceCount; ++i) {
      const ShellCorners& c = draft_.corners[i];
      sheet.faces[i] = {c.node[0], c.node[1], c.node[2], c.count == 4 ? c.node[3] : kNoPoint};
    }
  }

  // Where an edge of the sheet's points has more than two faces, or two running the same way
  // (faces of a cut that are joined around both its ends), gives the faces there that are not
  // joined to another face of that edge their own points at its ends. Returns whether any was.
  bool separateBadEdges() {
    const ShellEdges& edges = draft_.edges;
    bool changed = false;
    for (Index e = 0; e < edges.edgeCount(); ++e) {
      const std::size_t valence = edges.valence(e);
      if (valence == 1) continue;
      const ShellEdges::IncidenceRange on = edges.incidences(e);
      if (valence == 2 && on[0].forward != on[1].forward) continue;
      for (const ShellEdges::Incidence& x : on) {
        bool joined = false;
        if (valence > 2) {
          const Index g = partnerAcross(split_, positions_[x.shell], partEdge(x.shell, x.side));
          for (const ShellEdges::Incidence& y : on)
            joined = joined || (g != kNoIndex && positions_[y.shell] == g);
        }
        if (joined) continue;
        const unsigned m = nodes_[x.shell].count;
        keys_[4 * x.shell + x.side] = nextKey_++;
        keys_[4 * x.shell + (x.side + 1u) % m] = nextKey_++;
        changed = true;
      }
    }
    return changed;
  }

  PartSplit& split_;
  const PartMesh& part_;
  std::vector<Index> positions_;
  std::vector<ShellCorners> nodes_;  // per face: local nodes in the sheet's orientation
  std::vector<Index> keys_;
  Index nextKey_ = 0;
  SheetDraft draft_;
};

}  // namespace

std::vector<SheetDraft> splitSheets(const ModelContext& context, const PartMesh& part,
                                    const Orientation& orientation) {
  PartSplit split{context, part, orientation, {}, {}, {}, {}};
  joinOrCut(split);
  // The faces of each component, ascending.
  const std::size_t n = part.corners.size();
  std::vector<Index> begin(orientation.componentCount + 1, 0);
  for (const Index c : orientation.component) ++begin[c + 1];
  std::partial_sum(begin.begin(), begin.end(), begin.begin());
  std::vector<Index> faces(n);
  split.faceInSheet.resize(n);
  {
    std::vector<Index> fill(begin.begin(), begin.end() - 1);
    for (Index position = 0; position < n; ++position) {
      const Index c = orientation.component[position];
      split.faceInSheet[position] = fill[c] - begin[c];
      faces[fill[c]++] = position;
    }
  }
  split.nodePoint.assign(part.nodes.size(), kNoIndex);
  std::vector<SheetDraft> drafts;
  drafts.reserve(orientation.componentCount);
  for (Index c = 0; c < orientation.componentCount; ++c)
    drafts.push_back(
        SheetBuilder(split, faces.data() + begin[c], faces.data() + begin[c + 1]).build());
  return drafts;
}

}  // namespace voxremesh::sheets
