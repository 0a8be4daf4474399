// reportDeck: counts, sizes and topology of a model's shells per part and in total.
#include "voxremesh/deck_report.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <utility>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "model/radix_sort.h"
#include "model/shell_edges.h"
#include "voxremesh/errors.h"

namespace voxremesh {

using model::Index;
using model::kNoIndex;
using model::ShellCorners;
using model::ShellEdges;

double BoundingBox::diagonal() const {
  if (empty()) return 0.0;
  return std::hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
}

namespace {

using Point = std::array<double, 3>;

double distance(const Point& p, const Point& q) {
  return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
}

Point minus(const Point& p, const Point& q) {
  return {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
}

double crossNorm(const Point& u, const Point& v) {
  return std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                    u[0] * v[1] - u[1] * v[0]);
}

// Zero or tiny area: twice the area is at most 2 x tolerance x the longest side.
bool isDegenerate(const FeModel& model, const ShellCorners& c, double tolerance) {
  std::array<Point, 4> p;
  for (unsigned k = 0; k < c.count; ++k) p[k] = model.nodes[c.node[k]].xyz;
  double longest = 0.0;
  for (unsigned k = 0; k < c.count; ++k)
    longest = std::max(longest, distance(p[k], p[(k + 1) % c.count]));
  const double twiceArea = c.count == 3 ? crossNorm(minus(p[1], p[0]), minus(p[2], p[0]))
                                        : crossNorm(minus(p[2], p[0]), minus(p[3], p[1]));
  return twiceArea <= 2.0 * tolerance * longest;
}

// Coincidence of the nodes used by shells, found once for the model; each row then counts the
// duplicates among its own nodes from it.
//
// Nodes at exactly the same position form a group (so that a pile of k nodes costs k, not k^2);
// nodes with non-finite coordinates stay alone. Two groups whose positions are within the
// tolerance form a near pair. Within a row, the coincident nodes are then the connected
// components of its nodes' groups joined by near pairs.
struct Coincidence {
  std::vector<Index> groupOf;                  // per model node; kNoIndex when unused
  std::vector<Index> representative;           // per group: its first node
  std::vector<Index> nearBegin{0};             // per group: CSR into nearTo
  std::vector<Index> nearTo;                   // groups of near pairs, the higher of each pair
  std::vector<std::pair<Index, Index>> pairs;  // examples: node index pairs, ascending
};

// Builds the coincidence of `nodes` (ascending node indices) within `tolerance`.
//
// Sort-based: the nodes are sorted by cell (cells of at least kCellScale x tolerance, coarse
// enough that a cell index fits 21 bits per axis), so each cell is a run of the sorted list. A node
// within the tolerance of another lies in the same cell or in a neighbour across a face, edge or
// corner that the node itself is within the tolerance of; only those neighbours are looked up
// (about 1.5 cells per node instead of 27), each pair of cells from its lower cell only.
Coincidence findCoincidence(const FeModel& model, const std::vector<Index>& nodes, double tolerance,
                            const BoundingBox& box, std::size_t maxExamples) {
  constexpr double kCellScale = 16.0;
  constexpr int kAxisBits = 21;
  constexpr std::int64_t kAxisMax = (std::int64_t{1} << kAxisBits) - 1;
  Coincidence result;
  result.groupOf.assign(model.nodes.size(), kNoIndex);
  const double extent =
      box.empty()
          ? 0.0
          : std::max({box.max[0] - box.min[0], box.max[1] - box.min[1], box.max[2] - box.min[2]});
  double cell = std::max(kCellScale * tolerance, std::ldexp(extent, -(kAxisBits - 1)));
  if (!(cell > 0.0) || !std::isfinite(cell)) cell = 1.0;  // one point, or nothing finite
  // A node is near a cell face when closer than the tolerance, plus a margin for the rounding of
  // cell coordinates up to 2^21.
  const double near = tolerance / cell + 1e-8;
  // Dense clusters of distinct positions (a tolerance far too large for the mesh) would take
  // quadratic time: stop with a clear message instead.
  const std::uint64_t budget = 100'000'000 + 200 * std::uint64_t{nodes.size()};
  std::uint64_t comparisons = 0;
  auto spend = [&](std::uint64_t work) {
    comparisons += work;
    if (comparisons > budget)
      throw SettingError("the nodes are too densely packed for a coincidence tolerance of " +
                         std::to_string(tolerance) + " (more than " + std::to_string(budget) +
                         " comparisons); give a smaller tolerance");
  };

  // Cell codes of the finite nodes; the others stay alone.
  std::vector<std::uint64_t> codes;
  std::vector<std::uint32_t> order;  // positions in `nodes`
  codes.reserve(nodes.size());
  order.reserve(nodes.size());
  auto axisCell = [&](double coordinate, int k) {
    const double u = std::floor((coordinate - box.min[k]) / cell);
    return std::min<std::int64_t>(std::max<std::int64_t>(static_cast<std::int64_t>(u), 0),
                                  kAxisMax);
  };
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Point& p = model.nodes[nodes[i]].xyz;
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) continue;
    codes.push_back(std::uint64_t(axisCell(p[0], 0)) << (2 * kAxisBits) |
                    std::uint64_t(axisCell(p[1], 1)) << kAxisBits |
                    std::uint64_t(axisCell(p[2], 2)));
    order.push_back(static_cast<std::uint32_t>(i));
  }
  model::radixSortPairs(codes, order, ~std::uint64_t{0} >> (64 - 3 * kAxisBits));

  // Cells: runs of equal codes. Within a cell, nodes at one position form a group whose
  // representative is its first node (the run keeps node order).
  std::vector<std::uint64_t> cellCodes;
  std::vector<Index> cellBegin;                   // into reps
  std::vector<Index> reps;                        // group per representative, grouped by cell
  std::vector<std::pair<Index, Index>> examples;  // (node, node)
  for (std::size_t i = 0; i < codes.size();) {
    std::size_t last = i + 1;
    while (last < codes.size() && codes[last] == codes[i]) ++last;
    cellCodes.push_back(codes[i]);
    cellBegin.push_back(Index(reps.size()));
    const std::size_t firstRep = reps.size();
    for (std::size_t k = i; k < last; ++k) {
      const Index v = nodes[order[k]];
      const Point& p = model.nodes[v].xyz;
      Index same = kNoIndex;
      spend(reps.size() - firstRep);
      for (std::size_t r = firstRep; r < reps.size() && same == kNoIndex; ++r)
        if (model.nodes[result.representative[reps[r]]].xyz == p) same = reps[r];
      if (same != kNoIndex) {
        result.groupOf[v] = same;
        examples.emplace_back(result.representative[same], v);
        continue;
      }
      result.groupOf[v] = Index(result.representative.size());
      reps.push_back(result.groupOf[v]);
      result.representative.push_back(v);
    }
    i = last;
  }
  cellBegin.push_back(Index(reps.size()));
  // Nodes with non-finite coordinates: a group each.
  for (const Index v : nodes)
    if (result.groupOf[v] == kNoIndex) {
      result.groupOf[v] = Index(result.representative.size());
      result.representative.push_back(v);
    }

  // Near pairs of representatives (none at tolerance 0: representatives differ in position):
  // within a cell, and from a cell to the higher neighbours its representative is near.
  std::vector<std::pair<Index, Index>> nearPairs;  // (lower group, higher group)
  auto check = [&](Index g, Index h) {
    spend(1);
    const Index a = result.representative[g], b = result.representative[h];
    if (!(distance(model.nodes[a].xyz, model.nodes[b].xyz) <= tolerance)) return;
    nearPairs.emplace_back(std::min(g, h), std::max(g, h));
    examples.emplace_back(std::min(a, b), std::max(a, b));
  };
  for (std::size_t c = 0; c < cellCodes.size() && tolerance > 0.0; ++c) {
    for (Index r = cellBegin[c]; r < cellBegin[c + 1]; ++r) {
      for (Index s = cellBegin[c]; s < r; ++s) check(reps[s], reps[r]);
      const Index v = result.representative[reps[r]];
      const Point& p = model.nodes[v].xyz;
      std::array<int, 3> lo{}, hi{};
      const std::uint64_t code = cellCodes[c];
      const std::array<std::int64_t, 3> own{std::int64_t(code >> (2 * kAxisBits)),
                                            std::int64_t((code >> kAxisBits) & kAxisMax),
                                            std::int64_t(code & kAxisMax)};
      for (int k = 0; k < 3; ++k) {
        const double fraction = (p[k] - box.min[k]) / cell - double(own[k]);
        lo[k] = fraction < near && own[k] > 0 ? -1 : 0;
        hi[k] = fraction > 1.0 - near && own[k] < kAxisMax ? 1 : 0;
      }
      for (int dx = lo[0]; dx <= hi[0]; ++dx)
        for (int dy = lo[1]; dy <= hi[1]; ++dy)
          for (int dz = lo[2]; dz <= hi[2]; ++dz) {
            const std::uint64_t neighbour = std::uint64_t(own[0] + dx) << (2 * kAxisBits) |
                                            std::uint64_t(own[1] + dy) << kAxisBits |
                                            std::uint64_t(own[2] + dz);
            if (neighbour <= code) continue;  // the lower cell looks up the higher one
            const auto it = std::lower_bound(cellCodes.begin() + c + 1, cellCodes.end(), neighbour);
            if (it == cellCodes.end() || *it != neighbour) continue;
            const std::size_t n = std::size_t(it - cellCodes.begin());
            for (Index s = cellBegin[n]; s < cellBegin[n + 1]; ++s) check(reps[r], reps[s]);
          }
    }
  }
  std::sort(nearPairs.begin(), nearPairs.end());
  result.nearBegin.assign(result.representative.size() + 1, 0);
  for (const auto& pair : nearPairs) ++result.nearBegin[pair.first + 1];
  std::partial_sum(result.nearBegin.begin(), result.nearBegin.end(), result.nearBegin.begin());
  for (const auto& pair : nearPairs) result.nearTo.push_back(pair.second);  // sorted: CSR order
  std::sort(examples.begin(), examples.end());
  if (examples.size() > maxExamples) examples.resize(maxExamples);
  result.pairs = std::move(examples);
  return result;
}

// Min, median, max of `values` (reordered).
LengthStats lengthStats(std::vector<double>& values) {
  LengthStats stats;
  stats.count = values.size();
  if (values.empty()) return stats;
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  stats.min = *lo;
  stats.max = *hi;
  const std::size_t half = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + half, values.end());
  stats.median = values[half];
  if (values.size() % 2 == 0)
    stats.median = 0.5 * (stats.median + *std::max_element(values.begin(), values.begin() + half));
  return stats;
}

// Arrays over all model nodes and coincidence groups, reused from row to row so that a row costs
// time in proportion to its own size. One per thread.
struct Scratch {
  Scratch(std::size_t modelNodes, std::size_t groups)
      : stamp(modelNodes, 0), uses(modelNodes, 0), groupStamp(groups, 0), parent(groups, 0) {}
  Index currentStamp = 0;
  std::vector<Index> stamp;       // == currentStamp: the node is used by the current row
  std::vector<Index> uses;        // shells of the current row using the node
  std::vector<Index> groupStamp;  // == currentStamp: the group has a node in the current row
  std::vector<Index> parent;      // union-find over groups
};

// Everything a row needs that is computed once per model.
struct ModelData {
  const FeModel& model;
  const std::vector<ShellCorners>& corners;
  const std::vector<bool>& degenerate;
  const Coincidence& coincidence;
  std::size_t maxExamples;
};

EdgeExample edgeExample(const FeModel& model, const ShellEdges& adjacency, Index e) {
  EdgeExample example;
  const Id a = model.nodes[adjacency.edge(e).a].id, b = model.nodes[adjacency.edge(e).b].id;
  example.nodes = {std::min(a, b), std::max(a, b)};
  for (const auto& incidence : adjacency.incidences(e))
    example.shells.push_back(model.shells[adjacency.shellIndex(incidence.shell)].id);
  return example;
}

// Duplicate nodes among `nodes` (a row's nodes): the row's nodes minus its groups of coincident
// nodes (components of its coincidence groups joined by near pairs).
std::size_t countDuplicates(const Coincidence& coincidence, const std::vector<Index>& nodes,
                            Scratch& scratch) {
  const Index stamp = scratch.currentStamp;
  std::vector<Index> groups;
  for (const Index v : nodes) {
    const Index g = coincidence.groupOf[v];
    if (scratch.groupStamp[g] == stamp) continue;
    scratch.groupStamp[g] = stamp;
    scratch.parent[g] = g;
    groups.push_back(g);
  }
  auto find = [&](Index x) {
    while (scratch.parent[x] != x) x = scratch.parent[x] = scratch.parent[scratch.parent[x]];
    return x;
  };
  std::size_t components = groups.size();
  for (const Index g : groups)
    for (Index k = coincidence.nearBegin[g]; k < coincidence.nearBegin[g + 1]; ++k) {
      const Index h = coincidence.nearTo[k];
      if (scratch.groupStamp[h] != stamp) continue;
      const Index x = find(g), y = find(h);
      if (x == y) continue;
      scratch.parent[std::max(x, y)] = std::min(x, y);
      --components;
    }
  return nodes.size() - components;
}

// The statistics of the shells in `adjacency`; fills `examples` when not null.
MeshStats rowStats(const ModelData& data, const ShellEdges& adjacency, Scratch& scratch,
                   ReportExamples* examples) {
  const FeModel& model = data.model;
  MeshStats stats;
  const Index stamp = ++scratch.currentStamp;
  std::vector<Index> nodes;
  std::vector<double> sides;
  sides.reserve(4 * adjacency.shellCount());
  for (const Index s : adjacency.shells()) {
    const ShellCorners& c = data.corners[s];
    (c.count == 4 ? stats.quads : stats.trias)++;
    if (data.degenerate[s]) {
      ++stats.degenerateElements;
      if (examples && examples->degenerateElements.size() < data.maxExamples)
        examples->degenerateElements.push_back(model.shells[s].id);
    }
    for (unsigned k = 0; k < c.count; ++k) {
      const Index v = c.node[k];
      sides.push_back(distance(model.nodes[v].xyz, model.nodes[c.node[(k + 1) % c.count]].xyz));
      if (scratch.stamp[v] != stamp) {
        scratch.stamp[v] = stamp;
        scratch.uses[v] = 0;
        nodes.push_back(v);
      }
      // Count each shell once per node even if it names the node twice.
      bool repeated = false;
      for (unsigned m = 0; m < k; ++m) repeated = repeated || c.node[m] == v;
      if (!repeated) ++scratch.uses[v];
    }
  }
  stats.nodes = nodes.size();
  for (const Index v : nodes) {
    const Point& p = model.nodes[v].xyz;
    if (stats.box.empty()) {
      stats.box.min = stats.box.max = p;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      stats.box.min[k] = std::min(stats.box.min[k], p[k]);
      stats.box.max[k] = std::max(stats.box.max[k], p[k]);
    }
  }
  stats.edgeLength = lengthStats(sides);

  for (const Index s : adjacency.shells()) {
    const ShellCorners& c = data.corners[s];
    bool alone = true;
    for (unsigned k = 0; k < c.count && alone; ++k) alone = scratch.uses[c.node[k]] == 1;
    if (!alone) continue;
    ++stats.freeElements;
    if (examples && examples->freeElements.size() < data.maxExamples)
      examples->freeElements.push_back(model.shells[s].id);
  }

  stats.edges = adjacency.edgeCount();
  for (Index e = 0; e < adjacency.edgeCount(); ++e) {
    const std::size_t valence = adjacency.valence(e);
    if (valence == 1) ++stats.boundaryEdges;
    if (valence >= 3) {
      ++stats.nonManifoldEdges;
      if (examples && examples->nonManifoldEdges.size() < data.maxExamples)
        examples->nonManifoldEdges.push_back(edgeExample(model, adjacency, e));
    }
    if (adjacency.hasInconsistentOrientation(e)) {
      ++stats.inconsistentEdges;
      if (valence == 2 && examples && examples->inconsistentEdges.size() < data.maxExamples)
        examples->inconsistentEdges.push_back(edgeExample(model, adjacency, e));
    }
  }
  for (const model::BoundaryChain& chain : model::boundaryChains(adjacency))
    (chain.closed ? stats.boundaryLoops : stats.openBoundaryChains)++;

  stats.duplicateNodes = countDuplicates(data.coincidence, nodes, scratch);
  if (examples)
    for (const auto& [i, j] : data.coincidence.pairs)
      examples->duplicateNodes.push_back({{model.nodes[i].id, model.nodes[j].id},
                                          distance(model.nodes[i].xyz, model.nodes[j].xyz)});
  return stats;
}

}  // namespace

DeckReport reportDeck(const FeModel& model, const ReportSettings& settings) {
  if (settings.tolerance && !(std::isfinite(*settings.tolerance) && *settings.tolerance >= 0.0))
    throw SettingError("the coincidence tolerance must be zero or positive, not " +
                       std::to_string(*settings.tolerance));
  const std::vector<ShellCorners> corners = model::shellCorners(model);
  DeckReport report;
  report.modelNodes = model.nodes.size();

  // The nodes shells use, ascending; the others are unused.
  std::vector<bool> used(model.nodes.size(), false);
  for (const ShellCorners& c : corners)
    for (unsigned k = 0; k < c.count; ++k) used[c.node[k]] = true;
  std::vector<Index> usedNodes;
  BoundingBox box;
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    if (used[i]) {
      usedNodes.push_back(Index(i));
      const Point& p = model.nodes[i].xyz;
      for (int k = 0; k < 3; ++k) {
        box.min[k] = usedNodes.size() == 1 ? p[k] : std::min(box.min[k], p[k]);
        box.max[k] = usedNodes.size() == 1 ? p[k] : std::max(box.max[k], p[k]);
      }
      continue;
    }
    ++report.unusedNodes;
    if (report.examples.unusedNodes.size() < settings.maxExamples)
      report.examples.unusedNodes.push_back(model.nodes[i].id);
  }
  report.tolerance = settings.tolerance ? *settings.tolerance : 1e-6 * box.diagonal();

  std::vector<bool> degenerate(corners.size());
  for (std::size_t s = 0; s < corners.size(); ++s)
    degenerate[s] = isDegenerate(model, corners[s], report.tolerance);
  const Coincidence coincidence =
      findCoincidence(model, usedNodes, report.tolerance, box, settings.maxExamples);
  const ModelData data{model, corners, degenerate, coincidence, settings.maxExamples};

  // Rows: the model's parts in order, then undefined parts named by shells, ascending.
  std::unordered_map<Id, std::size_t> rowOf;
  for (const Part& part : model.parts)
    if (rowOf.emplace(part.id, report.parts.size()).second)
      report.parts.push_back(PartReport{part.id, part.name, true, {}});
  std::vector<Id> undefined;
  for (const Shell& shell : model.shells)
    if (rowOf.find(shell.part) == rowOf.end()) {
      rowOf.emplace(shell.part, 0);  // row assigned below
      undefined.push_back(shell.part);
    }
  std::sort(undefined.begin(), undefined.end());
  for (const Id id : undefined) {
    rowOf[id] = report.parts.size();
    report.parts.push_back(PartReport{id, {}, false, {}});
  }
  // The shells of each row, in model order.
  std::vector<std::vector<Index>> rowShells(report.parts.size());
  Id lastPart = 0;
  std::size_t lastRow = 0;
  for (std::size_t s = 0; s < model.shells.size(); ++s) {
    if (s == 0 || model.shells[s].part != lastPart) {
      lastPart = model.shells[s].part;
      lastRow = rowOf[lastPart];
    }
    rowShells[lastRow].push_back(Index(s));
  }

  // Task 0 is the total (all shells, edges model-wide), task r + 1 part row r. The rows are
  // independent, so running them in parallel gives the same report as running them in order.
  // A part holding every shell has the total's statistics, copied from it.
  tbb::enumerable_thread_specific<Scratch> scratches(
      [&] { return Scratch(model.nodes.size(), coincidence.representative.size()); });
  std::vector<bool> sameAsTotal(report.parts.size());
  for (std::size_t row = 0; row < report.parts.size(); ++row)
    sameAsTotal[row] = !model.shells.empty() && rowShells[row].size() == model.shells.size();
  tbb::parallel_for(std::size_t{0}, report.parts.size() + 1, [&](std::size_t task) {
    Scratch& scratch = scratches.local();
    if (task == 0) {
      report.total = rowStats(data, ShellEdges(corners), scratch, &report.examples);
    } else if (!sameAsTotal[task - 1]) {
      report.parts[task - 1].stats =
          rowStats(data, ShellEdges(corners, std::move(rowShells[task - 1])), scratch, nullptr);
    }
  });
  for (std::size_t row = 0; row < report.parts.size(); ++row)
    if (sameAsTotal[row]) report.parts[row].stats = report.total;
  return report;
}

}  // namespace voxremesh
