// What buildSheets computes once per model (corners, the parts in output order, the nodes that
// several parts share) and the faces of one part.
#include <algorithm>
#include <unordered_map>
#include <utility>

#include "sheets/sheet_internal.h"

namespace voxremesh::sheets {

namespace {

/// Shells of another part than `part` meeting along segment u-v point at most this far (degrees)
/// from it with an edge at u: a seam whose two sides have different nodes along it.
constexpr double kSeamDirectionDeg = 15.0;

/// True when a shell of a part entry other than `part` has an edge from node u to v, or from u
/// within kSeamDirectionDeg of the direction to v.
bool otherPartEdgeTowards(const ModelContext& context, Index u, Index v, Index part) {
  const auto xyz = [&](Index n) { return context.model.nodes[n].xyz; };
  const Vec3 towards{xyz(v)[0] - xyz(u)[0], xyz(v)[1] - xyz(u)[1], xyz(v)[2] - xyz(u)[2]};
  for (Index i = context.shellsBegin[u]; i < context.shellsBegin[u + 1]; ++i) {
    const Index s = context.shellsAt[i];
    if (context.shellEntry[s] == part) continue;
    const ShellCorners& c = context.corners[s];
    for (unsigned k = 0; k < c.count; ++k) {
      if (c.node[k] != u) continue;
      for (const Index w : {c.node[(k + 1) % c.count], c.node[(k + c.count - 1) % c.count]}) {
        if (w == v) return true;
        const Vec3 edge{xyz(w)[0] - xyz(u)[0], xyz(w)[1] - xyz(u)[1], xyz(w)[2] - xyz(u)[2]};
        if (w != u && angleDeg(edge, towards) < kSeamDirectionDeg) return true;
      }
    }
  }
  return false;
}

}  // namespace

bool ModelContext::sharedWithOtherPart(Index u, Index v, Index part) const {
  if (sharedBegin.empty() || sharedBegin[u] == sharedBegin[u + 1] ||
      sharedBegin[v] == sharedBegin[v + 1])
    return false;
  // An edge u-v of another part is found from both ends.
  return otherPartEdgeTowards(*this, u, v, part) && otherPartEdgeTowards(*this, v, u, part);
}

bool ModelContext::isCut(Index u, Index v) const {
  const std::array<Index, 2> key{std::min(u, v), std::max(u, v)};
  return std::binary_search(sheetCuts.begin(), sheetCuts.end(), key);
}

bool ModelContext::seamStop(Index v) const {
  // The edges at v: the other node, how many shells have the edge, and their part entries.
  struct EdgeAtNode {
    Index other;
    Index shells = 0;
    std::vector<Index> entries;
  };
  std::vector<EdgeAtNode> edges;
  for (Index i = shellsBegin[v]; i < shellsBegin[v + 1]; ++i) {
    const Index s = shellsAt[i];
    const ShellCorners& c = corners[s];
    for (unsigned k = 0; k < c.count; ++k) {
      if (c.node[k] != v) continue;
      for (const Index other : {c.node[(k + 1) % c.count], c.node[(k + c.count - 1) % c.count]}) {
        if (other == v) continue;
        auto it = std::find_if(edges.begin(), edges.end(),
                               [&](const EdgeAtNode& e) { return e.other == other; });
        if (it == edges.end()) it = edges.insert(edges.end(), EdgeAtNode{other, 0, {}});
        ++it->shells;
        if (std::find(it->entries.begin(), it->entries.end(), shellEntry[s]) == it->entries.end())
          it->entries.push_back(shellEntry[s]);
      }
    }
  }
  std::vector<const EdgeAtNode*> seams;
  for (EdgeAtNode& e : edges) {
    if (e.shells < 3 && e.entries.size() < 2 && !isCut(v, e.other)) continue;
    std::sort(e.entries.begin(), e.entries.end());
    seams.push_back(&e);
  }
  return seams.size() != 2 || seams[0]->entries != seams[1]->entries ||
         seams[0]->shells != seams[1]->shells;
}

ModelContext makeModelContext(const FeModel& model) {
  ModelContext context{model, model::shellCorners(model), {}, {}, {}, {}, {}, {}, {}, {}, {}};

  // Entries: the model's parts in order, then undefined parts named by shells, ascending; parts
  // without shells are dropped afterwards.
  std::unordered_map<Id, Index> entryOf;
  std::vector<Id> ids;
  std::vector<std::string> names;
  for (const Part& part : model.parts)
    if (entryOf.emplace(part.id, Index(ids.size())).second) {
      ids.push_back(part.id);
      names.push_back(part.name);
    }
  std::vector<Id> undefined;
  for (const Shell& shell : model.shells)
    if (entryOf.find(shell.part) == entryOf.end()) {
      entryOf.emplace(shell.part, kNoIndex);
      undefined.push_back(shell.part);
    }
  std::sort(undefined.begin(), undefined.end());
  for (const Id id : undefined) {
    entryOf[id] = Index(ids.size());
    ids.push_back(id);
    names.emplace_back();
  }
  std::vector<std::vector<Index>> shells(ids.size());
  std::vector<Index> entryOfShell(model.shells.size());
  Id lastPart = 0;
  Index lastEntry = 0;
  for (std::size_t s = 0; s < model.shells.size(); ++s) {
    if (s == 0 || model.shells[s].part != lastPart) {
      lastPart = model.shells[s].part;
      lastEntry = entryOf[lastPart];
    }
    shells[lastEntry].push_back(Index(s));
    entryOfShell[s] = lastEntry;
  }
  std::vector<Index> compact(ids.size(), kNoIndex);
  for (std::size_t e = 0; e < ids.size(); ++e) {
    if (shells[e].empty()) continue;
    compact[e] = Index(context.partIds.size());
    context.partIds.push_back(ids[e]);
    context.partNames.push_back(std::move(names[e]));
    context.partShells.push_back(std::move(shells[e]));
  }
  for (Index& entry : entryOfShell) entry = compact[entry];
  context.shellEntry = entryOfShell;

  // The shells at each node (CSR).
  context.shellsBegin.assign(model.nodes.size() + 1, 0);
  for (const ShellCorners& c : context.corners)
    for (unsigned k = 0; k < c.count; ++k) ++context.shellsBegin[c.node[k] + 1];
  for (std::size_t v = 0; v < model.nodes.size(); ++v)
    context.shellsBegin[v + 1] += context.shellsBegin[v];
  context.shellsAt.resize(context.shellsBegin.back());
  {
    std::vector<Index> fill(context.shellsBegin.begin(), context.shellsBegin.end() - 1);
    for (std::size_t s = 0; s < model.shells.size(); ++s) {
      const ShellCorners& c = context.corners[s];
      for (unsigned k = 0; k < c.count; ++k) context.shellsAt[fill[c.node[k]]++] = Index(s);
    }
  }

  // Nodes used by several parts: first mark them, then list their parts.
  std::vector<Index> firstEntry(model.nodes.size(), kNoIndex);
  std::vector<std::uint8_t> shared(model.nodes.size(), 0);
  bool anyShared = false;
  for (std::size_t s = 0; s < model.shells.size(); ++s) {
    const ShellCorners& c = context.corners[s];
    for (unsigned k = 0; k < c.count; ++k) {
      Index& first = firstEntry[c.node[k]];
      if (first == kNoIndex) {
        first = entryOfShell[s];
      } else if (first != entryOfShell[s]) {
        shared[c.node[k]] = 1;
        anyShared = true;
      }
    }
  }
  if (!anyShared) return context;
  std::vector<std::pair<Index, Index>> pairs;  // (node, entry)
  for (std::size_t s = 0; s < model.shells.size(); ++s) {
    const ShellCorners& c = context.corners[s];
    for (unsigned k = 0; k < c.count; ++k)
      if (shared[c.node[k]]) pairs.emplace_back(c.node[k], entryOfShell[s]);
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  context.sharedBegin.assign(model.nodes.size() + 1, 0);
  for (const auto& pair : pairs) ++context.sharedBegin[pair.first + 1];
  for (std::size_t v = 0; v < model.nodes.size(); ++v)
    context.sharedBegin[v + 1] += context.sharedBegin[v];
  context.sharedParts.reserve(pairs.size());
  for (const auto& pair : pairs) context.sharedParts.push_back(pair.second);
  return context;
}

void setSheetCuts(ModelContext& context, const SheetSettings& settings) {
  context.sheetCuts.clear();
  if (!settings.sheetCuts) {
    context.sheetCuts = findSheetCuts(context);
    return;
  }
  const std::unordered_map<Id, std::size_t> indexOf = context.model.nodeIndex();
  for (const std::array<Id, 2>& cut : *settings.sheetCuts) {
    const auto a = indexOf.find(cut[0]), b = indexOf.find(cut[1]);
    if (a == indexOf.end() || b == indexOf.end()) continue;
    context.sheetCuts.push_back(
        {Index(std::min(a->second, b->second)), Index(std::max(a->second, b->second))});
  }
  std::sort(context.sheetCuts.begin(), context.sheetCuts.end());
}

PartMesh makePartMesh(const ModelContext& context, Index partEntry, std::vector<Index>& localOf) {
  PartMesh part;
  part.partEntry = partEntry;
  part.part = context.partIds[partEntry];
  part.label = "part " + std::to_string(part.part);
  if (!context.partNames[partEntry].empty())
    part.label += " (" + context.partNames[partEntry] + ")";

  const std::vector<Index>& shells = context.partShells[partEntry];
  part.shells.reserve(shells.size());
  part.corners.reserve(shells.size());
  for (const Index s : shells) {
    const ShellCorners& given = context.corners[s];
    // Drop a corner equal to the one before it, cyclically.
    ShellCorners c;
    c.count = 0;
    for (unsigned k = 0; k < given.count; ++k)
      if (c.count == 0 || c.node[c.count - 1] != given.node[k]) c.node[c.count++] = given.node[k];
    while (c.count > 1 && c.node[c.count - 1] == c.node[0]) --c.count;
    if (c.count < 3) continue;
    bool repeats = false;
    for (unsigned i = 0; i < c.count; ++i)
      for (unsigned j = i + 1; j < c.count; ++j) repeats = repeats || c.node[i] == c.node[j];
    if (repeats) continue;
    for (unsigned k = 0; k < c.count; ++k) {
      Index& local = localOf[c.node[k]];
      if (local == kNoIndex) {
        local = Index(part.nodes.size());
        part.nodes.push_back(c.node[k]);
      }
      c.node[k] = local;
    }
    part.shells.push_back(s);
    part.corners.push_back(c);
  }
  for (const Index v : part.nodes) localOf[v] = kNoIndex;
  part.edges = ShellEdges(part.corners);
  return part;
}

}  // namespace voxremesh::sheets
