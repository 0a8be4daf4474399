// The patches of a narrow sheet (see sheet_patches.h).
#include "extract/sheet_patches.h"

#include <map>
#include <set>
#include <string>
#include <utility>

#include "extract/narrow_sheet.h"
#include "geometry/disjoint_sets.h"

namespace voxremesh::extract {

namespace {

using Edge = std::pair<PointIndex, PointIndex>;

Edge edgeKey(PointIndex a, PointIndex b) {
  return a < b ? Edge{a, b} : Edge{b, a};
}

int corners(const std::array<PointIndex, 4>& face) {
  return face[3] == kNoPoint ? 3 : 4;
}

/// The inner junction edges of a sheet, and its feature-line edges when asked (see sheetPatches).
std::set<Edge> cutEdges(const Sheet& sheet, bool atFeatureLines) {
  std::set<Edge> cuts;
  const auto addEdges = [&](const Polyline& curve) {
    const std::size_t n = curve.points.size();
    for (std::size_t i = 0; i + 1 < n + (curve.closed ? 1 : 0); ++i)
      cuts.insert(edgeKey(curve.points[i], curve.points[(i + 1) % n]));
  };
  for (const Polyline& curve : sheet.junctionCurves) addEdges(curve);
  if (atFeatureLines)
    for (const Polyline& line : sheet.featureLines) addEdges(line);
  return cuts;
}

/// The boundary loops of one patch: its faces' directed edges whose reverse is not in the patch,
/// chained (each loop from its lowest point, loops by their lowest point).
std::vector<std::vector<PointIndex>> patchLoops(const Sheet& sheet,
                                                const std::vector<std::size_t>& faces) {
  std::set<Edge> directed;
  for (const std::size_t f : faces)
    for (int c = 0; c < corners(sheet.faces[f]); ++c)
      directed.insert({sheet.faces[f][std::size_t(c)],
                       sheet.faces[f][std::size_t((c + 1) % corners(sheet.faces[f]))]});
  std::map<PointIndex, PointIndex> next;
  for (const auto& [a, b] : directed) {
    if (directed.count({b, a}) != 0) continue;
    if (!next.emplace(a, b).second)
      throw NarrowSheetRefusal("a patch of it touches itself at a point");
  }
  if (next.empty()) throw NarrowSheetRefusal("a patch of it has no boundary");
  std::vector<std::vector<PointIndex>> loops;
  std::set<PointIndex> visited;
  for (const auto& [start, unused] : next) {
    if (visited.count(start) != 0) continue;
    std::vector<PointIndex> loop{start};
    visited.insert(start);
    for (PointIndex p = next.at(start); p != start; p = next.at(p)) {
      loop.push_back(p);
      visited.insert(p);
      if (loop.size() > next.size()) throw NarrowSheetRefusal("a patch of it has a broken loop");
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

/// The points of `edges` as one path from a point of loops[0] to a point of loops[1], its inner
/// points on neither loop; empty when `loops` is no ring or `edges` are not such a path.
std::vector<PointIndex> ringRung(const std::vector<std::vector<PointIndex>>& loops,
                                 const std::vector<Edge>& edges) {
  if (loops.size() != 2) return {};
  std::map<PointIndex, std::vector<PointIndex>> next;
  for (const auto& [a, b] : edges) {
    next[a].push_back(b);
    next[b].push_back(a);
  }
  const std::set<PointIndex> first(loops[0].begin(), loops[0].end()),
      second(loops[1].begin(), loops[1].end());
  PointIndex start = kNoPoint;
  for (const auto& [p, neighbours] : next)
    if (neighbours.size() == 1 && first.count(p) != 0) start = p;
  if (start == kNoPoint) return {};
  std::vector<PointIndex> path{start};
  for (PointIndex previous = kNoPoint, at = start; path.size() <= edges.size();) {
    const std::vector<PointIndex>& around = next.at(at);
    const PointIndex to = around[0] != previous ? around[0]
                          : around.size() > 1   ? around[1]
                                                : kNoPoint;
    if (to == kNoPoint) return {};
    path.push_back(to);
    previous = at;
    at = to;
    const std::size_t degree = next.at(at).size();
    if (second.count(at) != 0) break;
    if (degree != 2 || first.count(at) != 0) return {};
  }
  if (path.size() != edges.size() + 1 || second.count(path.back()) == 0 ||
      next.at(path.back()).size() != 1)
    return {};
  return path;
}

/// The Euler characteristic V - E + F of a patch.
long eulerCharacteristic(const Sheet& sheet, const std::vector<std::size_t>& faces) {
  std::set<Edge> edges;
  std::set<PointIndex> points;
  for (const std::size_t f : faces) {
    const int n = corners(sheet.faces[f]);
    for (int c = 0; c < n; ++c) {
      points.insert(sheet.faces[f][std::size_t(c)]);
      edges.insert(
          edgeKey(sheet.faces[f][std::size_t(c)], sheet.faces[f][std::size_t((c + 1) % n)]));
    }
  }
  return long(points.size()) - long(edges.size()) + long(faces.size());
}

}  // namespace

std::vector<SheetPatch> sheetPatches(const Sheet& sheet, bool atFeatureLines) {
  const std::set<Edge> cuts = cutEdges(sheet, atFeatureLines);
  std::map<Edge, std::vector<std::size_t>> edgeFaces;
  for (std::size_t f = 0; f < sheet.faces.size(); ++f)
    for (int c = 0; c < corners(sheet.faces[f]); ++c)
      edgeFaces[edgeKey(sheet.faces[f][std::size_t(c)],
                        sheet.faces[f][std::size_t((c + 1) % corners(sheet.faces[f]))])]
          .push_back(f);
  DisjointSets pieces(sheet.faces.size());
  for (const auto& [edge, faces] : edgeFaces)
    if (faces.size() == 2 && cuts.count(edge) == 0) pieces.join(faces[0], faces[1]);
  // Cuts with the same piece on both sides, by the piece's root.
  std::map<std::size_t, std::vector<Edge>> innerCuts;
  for (const Edge& cut : cuts) {
    const auto it = edgeFaces.find(cut);
    if (it != edgeFaces.end() && it->second.size() == 2 &&
        pieces.find(it->second[0]) == pieces.find(it->second[1]))
      innerCuts[pieces.find(it->second[0])].push_back(cut);
  }
  std::map<std::size_t, std::size_t> patchOfRoot;
  std::vector<SheetPatch> patches;
  for (std::size_t f = 0; f < sheet.faces.size(); ++f) {
    const auto [it, added] = patchOfRoot.emplace(pieces.find(f), patches.size());
    if (added) patches.emplace_back();
    patches[it->second].faces.push_back(f);
  }
  for (SheetPatch& patch : patches) {
    const long euler = eulerCharacteristic(sheet, patch.faces);
    patch.loops = patchLoops(sheet, patch.faces);
    if (!(euler == 1 && patch.loops.size() == 1) && !(euler == 0 && patch.loops.size() == 2))
      throw NarrowSheetRefusal("it is neither a disk nor a ring (Euler characteristic " +
                               std::to_string(euler) + ", " + std::to_string(patch.loops.size()) +
                               " boundary loops)");
    const auto inner = innerCuts.find(pieces.find(patch.faces.front()));
    if (inner == innerCuts.end()) continue;
    patch.rung = ringRung(patch.loops, inner->second);
    if (patch.rung.empty())
      throw NarrowSheetRefusal(atFeatureLines ? "a junction curve or feature line ends inside it"
                                              : "a junction curve ends inside it");
  }
  return patches;
}

}  // namespace voxremesh::extract
