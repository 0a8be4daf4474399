// The deck report (include/voxremesh/deck_report.h) and the edge adjacency beneath it
// (src/model/shell_edges.h), on small in-memory models whose answers are known by construction.
#include "voxremesh/deck_report.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "json/json.h"
#include "model/shell_edges.h"
#include "support/test_support.h"
#include "voxremesh/errors.h"

using namespace voxremesh;
using json::Json;
using json::parseJson;
using model::BoundaryChain;
using model::Index;
using model::ShellEdges;
using test::addNode;
using test::addShell;

namespace {

// ---------------------------------------------------------------------------------------------
// Building models

// A grid of nx x ny quads in the z = 0 plane with the given x and y node coordinates; node IDs
// 1.. row by row, shell IDs 1.., all counter-clockwise (normal +z), part `part`.
FeModel grid(const std::vector<double>& xs, const std::vector<double>& ys, Id part = 1) {
  FeModel m;
  const std::size_t nx = xs.size() - 1, ny = ys.size() - 1;
  for (std::size_t j = 0; j <= ny; ++j)
    for (std::size_t i = 0; i <= nx; ++i) addNode(m, Id(j * (nx + 1) + i + 1), xs[i], ys[j]);
  auto node = [&](std::size_t i, std::size_t j) { return Id(j * (nx + 1) + i + 1); };
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      addShell(m, Id(m.shells.size() + 1), part,
               {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
  m.partOrAdd(part, "plate");
  return m;
}

std::vector<double> range(std::size_t n, double step) {
  std::vector<double> v(n + 1);
  for (std::size_t i = 0; i <= n; ++i) v[i] = step * double(i);
  return v;
}

const PartReport& part(const DeckReport& r, Id id) {
  for (const PartReport& p : r.parts)
    if (p.id == id) return p;
  throw std::runtime_error("no part " + std::to_string(id));
}

// The shells of chain `c` (model shell indices), one per boundary edge.
std::set<Index> chainShells(const ShellEdges& adjacency, const BoundaryChain& c) {
  std::set<Index> shells;
  for (const Index e : c.edges)
    shells.insert(adjacency.shellIndex(adjacency.incidences(e)[0].shell));
  return shells;
}

// Consecutive nodes of the chain are the ends of its edges, in order.
void expectChainIsConnected(const ShellEdges& adjacency, const BoundaryChain& c) {
  ASSERT_EQ(c.nodes.size(), c.edges.size() + (c.closed ? 0 : 1));
  for (std::size_t k = 0; k < c.edges.size(); ++k) {
    const ShellEdges::Edge& e = adjacency.edge(c.edges[k]);
    const Index p = c.nodes[k], q = c.nodes[(k + 1) % c.nodes.size()];
    EXPECT_TRUE((e.a == p && e.b == q) || (e.a == q && e.b == p)) << "edge " << k;
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Edge adjacency

TEST(ShellEdges, ListsUniqueEdgesWithIncidencesAndDirections) {
  const FeModel m = grid(range(2, 1.0), range(1, 1.0));  // nodes 1 2 3 / 4 5 6, quads 1 2
  const auto corners = model::shellCorners(m);
  const ShellEdges adjacency(corners);
  ASSERT_EQ(adjacency.edgeCount(), 7u);
  // Sorted by (a, b); each edge's node indices ascending.
  for (Index e = 1; e < adjacency.edgeCount(); ++e) {
    const auto& p = adjacency.edge(e - 1);
    const auto& q = adjacency.edge(e);
    EXPECT_TRUE(p.a < q.a || (p.a == q.a && p.b < q.b));
  }
  // The shared edge is node indices 1-4 (IDs 2 and 5). Quad 1 is 1 2 5 4: its side 1 runs
  // 2 -> 5 (forward); quad 2 is 2 3 6 5: its side 3 runs 5 -> 2 (backward).
  const Index shared = adjacency.shellEdge(0, 1);
  ASSERT_NE(shared, model::kNoIndex);
  EXPECT_EQ(adjacency.edge(shared).a, 1u);
  EXPECT_EQ(adjacency.edge(shared).b, 4u);
  ASSERT_EQ(adjacency.valence(shared), 2u);
  EXPECT_EQ(adjacency.shellEdge(1, 3), shared);
  EXPECT_EQ(adjacency.incidences(shared)[0].shell, 0u);
  EXPECT_EQ(adjacency.incidences(shared)[0].side, 1u);
  EXPECT_TRUE(adjacency.incidences(shared)[0].forward);
  EXPECT_EQ(adjacency.incidences(shared)[1].shell, 1u);
  EXPECT_EQ(adjacency.incidences(shared)[1].side, 3u);
  EXPECT_FALSE(adjacency.incidences(shared)[1].forward);
  EXPECT_TRUE(adjacency.isManifold(shared));
  EXPECT_FALSE(adjacency.hasInconsistentOrientation(shared));
  EXPECT_EQ(adjacency.boundaryEdges().size(), 6u);
  EXPECT_TRUE(adjacency.nonManifoldEdges().empty());
  // Every side of every shell has its edge, and the edge's nodes are the side's corners.
  for (Index s = 0; s < 2; ++s)
    for (unsigned side = 0; side < 4; ++side) {
      const Index e = adjacency.shellEdge(s, side);
      const Index p = corners[s].node[side], q = corners[s].node[(side + 1) % 4];
      EXPECT_EQ(adjacency.edge(e).a, std::min(p, q));
      EXPECT_EQ(adjacency.edge(e).b, std::max(p, q));
    }
}

TEST(ShellEdges, SubsetKeepsModelShellIndices) {
  const FeModel m = grid(range(3, 1.0), range(1, 1.0));
  const auto corners = model::shellCorners(m);
  const ShellEdges subset(corners, {2, 0});  // quads 3 and 1: no common edge
  EXPECT_EQ(subset.shellCount(), 2u);
  EXPECT_EQ(subset.shellIndex(0), 2u);
  EXPECT_EQ(subset.shellIndex(1), 0u);
  EXPECT_EQ(subset.edgeCount(), 8u);
  EXPECT_EQ(subset.boundaryEdges().size(), 8u);
}

TEST(ShellEdges, OrderDoesNotDependOnShellOrderOrSize) {
  // A large grid (radix path) and the same grid's shells reversed give the same edges.
  const FeModel m = grid(range(60, 1.0), range(40, 1.0));
  auto corners = model::shellCorners(m);
  const ShellEdges forward(corners);
  std::reverse(corners.begin(), corners.end());
  const ShellEdges backward(corners);
  ASSERT_EQ(forward.edgeCount(), backward.edgeCount());
  EXPECT_EQ(forward.edgeCount(), 61u * 40 + 60u * 41);
  for (Index e = 0; e < forward.edgeCount(); ++e) {
    EXPECT_EQ(forward.edge(e).a, backward.edge(e).a);
    EXPECT_EQ(forward.edge(e).b, backward.edge(e).b);
    EXPECT_EQ(forward.valence(e), backward.valence(e));
  }
}

TEST(ShellEdges, RejectsShellsNamingMissingNodes) {
  FeModel m = grid(range(1, 1.0), range(1, 1.0));
  m.shells[0].nodes[2] = 99;
  try {
    model::shellCorners(m);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("shell 1 names node 99"), std::string::npos) << e.what();
  }
  m.shells[0].nodes[2] = 4;
  m.nodes[1].id = 1;  // duplicate ID
  EXPECT_THROW(model::shellCorners(m), std::invalid_argument);
}

TEST(ShellEdges, SparseNodeIdsMapToTheRightNodes) {
  FeModel m = grid(range(1, 1.0), range(1, 1.0));
  const Id big[] = {9000000000001, 5, 77000000000, -3};
  for (std::size_t i = 0; i < 4; ++i) {
    for (Id& n : m.shells[0].nodes)
      if (n == m.nodes[i].id) n = big[i];
    m.nodes[i].id = big[i];
  }
  const auto corners = model::shellCorners(m);
  for (unsigned k = 0; k < 4; ++k) EXPECT_EQ(m.nodes[corners[0].node[k]].id, m.shells[0].nodes[k]);
}

// ---------------------------------------------------------------------------------------------
// Topology findings

TEST(DeckReport, TwoQuadsConsistentlyOriented) {
  const DeckReport r = reportDeck(grid(range(2, 1.0), range(1, 1.0)));
  EXPECT_EQ(r.total.nodes, 6u);
  EXPECT_EQ(r.total.quads, 2u);
  EXPECT_EQ(r.total.trias, 0u);
  EXPECT_EQ(r.total.edges, 7u);
  EXPECT_EQ(r.total.boundaryEdges, 6u);
  EXPECT_EQ(r.total.boundaryLoops, 1u);
  EXPECT_EQ(r.total.openBoundaryChains, 0u);
  EXPECT_EQ(r.total.nonManifoldEdges, 0u);
  EXPECT_EQ(r.total.inconsistentEdges, 0u);
  EXPECT_EQ(r.total.freeElements, 0u);
  EXPECT_EQ(r.total.degenerateElements, 0u);
  EXPECT_EQ(r.total.duplicateNodes, 0u);
  EXPECT_TRUE(r.examples.inconsistentEdges.empty());
}

TEST(DeckReport, TwoQuadsInconsistentlyOriented) {
  FeModel m = grid(range(2, 1.0), range(1, 1.0));
  m.shells[1].nodes = {2, 5, 6, 3};  // clockwise: runs 2 -> 5 like quad 1
  const DeckReport r = reportDeck(m);
  EXPECT_EQ(r.total.inconsistentEdges, 1u);
  EXPECT_EQ(r.total.nonManifoldEdges, 0u);
  EXPECT_EQ(r.total.boundaryEdges, 6u);
  EXPECT_EQ(r.total.boundaryLoops, 1u);
  ASSERT_EQ(r.examples.inconsistentEdges.size(), 1u);
  EXPECT_EQ(r.examples.inconsistentEdges[0].nodes, (std::array<Id, 2>{2, 5}));
  EXPECT_EQ(r.examples.inconsistentEdges[0].shells, (std::vector<Id>{1, 2}));
}

TEST(DeckReport, FlippingEveryOtherQuadMakesEveryInteriorEdgeInconsistent) {
  FeModel m = grid(range(7, 1.0), range(5, 1.0));
  for (std::size_t s = 0; s < m.shells.size(); ++s) {
    const std::size_t i = s % 7, j = s / 7;
    if ((i + j) % 2) std::reverse(m.shells[s].nodes.begin(), m.shells[s].nodes.end());
  }
  const DeckReport r = reportDeck(m);
  const std::size_t interior = 6 * 5 + 7 * 4;
  EXPECT_EQ(r.total.inconsistentEdges, interior);
  EXPECT_EQ(r.total.edges, interior + 2 * (7 + 5));
  EXPECT_EQ(r.total.boundaryEdges, 2u * (7 + 5));
  EXPECT_EQ(r.total.boundaryLoops, 1u);
}

TEST(DeckReport, TJunctionOfThreeQuadsIsNonManifold) {
  FeModel m;
  addNode(m, 1, 0, 0, 0);
  addNode(m, 2, 1, 0, 0);
  addNode(m, 3, 0, 1, 0);  // quad A in +y
  addNode(m, 4, 1, 1, 0);
  addNode(m, 5, 0, -1, 0);  // quad B in -y
  addNode(m, 6, 1, -1, 0);
  addNode(m, 7, 0, 0, 1);  // quad C in +z
  addNode(m, 8, 1, 0, 1);
  addShell(m, 1, 1, {1, 2, 4, 3});
  addShell(m, 2, 1, {2, 1, 5, 6});
  addShell(m, 3, 1, {1, 2, 8, 7});
  const DeckReport r = reportDeck(m);
  EXPECT_EQ(r.total.edges, 10u);
  EXPECT_EQ(r.total.nonManifoldEdges, 1u);
  // A non-manifold edge always has two shells running the same way.
  EXPECT_EQ(r.total.inconsistentEdges, 1u);
  EXPECT_EQ(r.total.boundaryEdges, 9u);
  ASSERT_EQ(r.examples.nonManifoldEdges.size(), 1u);
  EXPECT_EQ(r.examples.nonManifoldEdges[0].nodes, (std::array<Id, 2>{1, 2}));
  EXPECT_EQ(r.examples.nonManifoldEdges[0].shells, (std::vector<Id>{1, 2, 3}));
  EXPECT_TRUE(r.examples.inconsistentEdges.empty());  // listed with the non-manifold ones
  // Three boundary edges meet at nodes 1 and 2: one chain must end there. The two lowest edges at
  // node 1 (to nodes 3 and 5) are joined, as are those at node 2 (to 4 and 6): quads A and B form
  // a loop, quad C's three boundary edges an open chain.
  EXPECT_EQ(r.total.boundaryLoops, 1u);
  EXPECT_EQ(r.total.openBoundaryChains, 1u);
  const auto corners = model::shellCorners(m);
  const ShellEdges adjacency(corners);
  const auto chains = model::boundaryChains(adjacency);
  ASSERT_EQ(chains.size(), 2u);
  for (const BoundaryChain& c : chains) {
    expectChainIsConnected(adjacency, c);
    if (c.closed) {
      EXPECT_EQ(c.edges.size(), 6u);
      EXPECT_EQ(chainShells(adjacency, c), (std::set<Index>{0, 1}));
    } else {
      EXPECT_EQ(c.edges.size(), 3u);
      EXPECT_EQ(chainShells(adjacency, c), (std::set<Index>{2}));
    }
  }
}

TEST(DeckReport, PlateWithSquareHoleHasTwoBoundaryLoops) {
  FeModel m = grid(range(3, 1.0), range(3, 1.0));
  m.shells.erase(m.shells.begin() + 4);  // the middle quad
  const DeckReport r = reportDeck(m);
  EXPECT_EQ(r.total.quads, 8u);
  EXPECT_EQ(r.total.nodes, 16u);
  EXPECT_EQ(r.total.boundaryEdges, 16u);
  EXPECT_EQ(r.total.boundaryLoops, 2u);
  EXPECT_EQ(r.total.openBoundaryChains, 0u);
  const auto corners = model::shellCorners(m);
  const ShellEdges adjacency(corners);
  const auto chains = model::boundaryChains(adjacency);
  ASSERT_EQ(chains.size(), 2u);
  std::multiset<std::size_t> lengths;
  for (const BoundaryChain& c : chains) {
    EXPECT_TRUE(c.closed);
    lengths.insert(c.edges.size());
    expectChainIsConnected(adjacency, c);
    // Each loop follows its shells' direction: each edge from nodes[k] to nodes[k+1] is run the
    // same way by its shell.
    for (std::size_t k = 0; k < c.edges.size(); ++k) {
      const auto& incidence = adjacency.incidences(c.edges[k])[0];
      EXPECT_EQ(incidence.forward, adjacency.edge(c.edges[k]).a == c.nodes[k]);
    }
  }
  EXPECT_EQ(lengths, (std::multiset<std::size_t>{4, 12}));
  EXPECT_LT(chains[0].edges.front(), chains[1].edges.front());  // ordered by first edge
}

TEST(DeckReport, BowTieOfTwoTriasKeepsOneLoopPerTriangle) {
  // Both trias touch at node 1. Pairing node 1's boundary edges by ascending edge (to nodes 2, 3,
  // 4, 5) would join the triangles into one figure-eight; the fan rule keeps each triangle's own.
  FeModel m;
  addNode(m, 1, 0, 0);
  addNode(m, 2, 1, 0.5);
  addNode(m, 3, -1, 0.5);
  addNode(m, 4, 1, -0.5);
  addNode(m, 5, -1, -0.5);
  addShell(m, 1, 1, {1, 4, 2});
  addShell(m, 2, 1, {1, 3, 5});
  const DeckReport r = reportDeck(m);
  EXPECT_EQ(r.total.trias, 2u);
  EXPECT_EQ(r.total.boundaryEdges, 6u);
  EXPECT_EQ(r.total.boundaryLoops, 2u);
  EXPECT_EQ(r.total.openBoundaryChains, 0u);
  EXPECT_EQ(r.total.freeElements, 0u);  // they share node 1
  const auto corners = model::shellCorners(m);
  const ShellEdges adjacency(corners);
  for (const BoundaryChain& c : model::boundaryChains(adjacency)) {
    EXPECT_EQ(c.edges.size(), 3u);
    EXPECT_EQ(chainShells(adjacency, c).size(), 1u);
    expectChainIsConnected(adjacency, c);
  }
}

TEST(DeckReport, BowTieOfTwoFansWalksAcrossManifoldEdges) {
  // Two fans of two trias each touch at node 1; each fan's contour is a loop of 4 edges.
  FeModel m;
  addNode(m, 1, 0, 0);
  addNode(m, 2, 1, 1);
  addNode(m, 3, 1.5, 0);
  addNode(m, 4, -1, 1);
  addNode(m, 5, 1, -1);
  addNode(m, 6, -1.5, 0);
  addNode(m, 7, -1, -1);
  addShell(m, 1, 1, {1, 3, 2});
  addShell(m, 2, 1, {1, 5, 3});
  addShell(m, 3, 1, {1, 4, 6});
  addShell(m, 4, 1, {1, 6, 7});
  const auto corners = model::shellCorners(m);
  const ShellEdges adjacency(corners);
  const auto chains = model::boundaryChains(adjacency);
  ASSERT_EQ(chains.size(), 2u);
  EXPECT_EQ(chainShells(adjacency, chains[0]), (std::set<Index>{0, 1}));
  EXPECT_EQ(chainShells(adjacency, chains[1]), (std::set<Index>{2, 3}));
  for (const BoundaryChain& c : chains) {
    EXPECT_TRUE(c.closed);
    EXPECT_EQ(c.edges.size(), 4u);
    expectChainIsConnected(adjacency, c);
  }
  EXPECT_EQ(reportDeck(m).total.boundaryLoops, 2u);
}

TEST(DeckReport, CoincidentNodesWithDistinctIdsAreDuplicates) {
  // Two quads side by side that should share the edge x = 1 but have their own nodes there.
  FeModel m;
  addNode(m, 1, 0, 0);
  addNode(m, 2, 1, 0);
  addNode(m, 3, 1, 1);
  addNode(m, 4, 0, 1);
  addNode(m, 12, 1, 0);
  addNode(m, 13, 1, 1);
  addNode(m, 14, 2, 1);
  addNode(m, 15, 2, 0);
  addShell(m, 1, 1, {1, 2, 3, 4});
  addShell(m, 2, 1, {12, 15, 14, 13});
  DeckReport r = reportDeck(m);
  EXPECT_EQ(r.total.duplicateNodes, 2u);
  EXPECT_EQ(r.total.boundaryEdges, 8u);  // not connected: each quad has its own boundary
  EXPECT_EQ(r.total.freeElements, 2u);
  ASSERT_EQ(r.examples.duplicateNodes.size(), 2u);
  EXPECT_EQ(r.examples.duplicateNodes[0].nodes, (std::array<Id, 2>{2, 12}));
  EXPECT_EQ(r.examples.duplicateNodes[1].nodes, (std::array<Id, 2>{3, 13}));
  EXPECT_EQ(r.examples.duplicateNodes[0].distance, 0.0);

  // A third node at the same place: a group of three counts two.
  addNode(m, 22, 1, 0);
  addShell(m, 3, 1, {22, 15, 14});
  r = reportDeck(m);
  EXPECT_EQ(r.total.duplicateNodes, 3u);
  EXPECT_EQ(part(r, 1).stats.duplicateNodes, 3u);
}

TEST(DeckReport, DuplicateToleranceIsHonoured) {
  FeModel m = grid(range(1, 1.0), range(1, 1.0));
  addNode(m, 10, 1.0 + 0.5e-3, 0.0);  // within 1e-3 of node 2
  addNode(m, 11, 0.0, 1.0 + 2e-3);    // 2e-3 from node 3
  addShell(m, 2, 1, {10, 11, 2});
  ReportSettings settings;
  settings.tolerance = 1e-3;
  DeckReport r = reportDeck(m, settings);
  EXPECT_EQ(r.tolerance, 1e-3);
  EXPECT_EQ(r.total.duplicateNodes, 1u);
  ASSERT_EQ(r.examples.duplicateNodes.size(), 1u);
  EXPECT_EQ(r.examples.duplicateNodes[0].nodes, (std::array<Id, 2>{2, 10}));
  EXPECT_NEAR(r.examples.duplicateNodes[0].distance, 0.5e-3, 1e-12);
  settings.tolerance = 3e-3;
  EXPECT_EQ(reportDeck(m, settings).total.duplicateNodes, 2u);
  // Default: 1e-6 x the diagonal of the shell nodes' box; none of these is that close.
  r = reportDeck(m);
  EXPECT_DOUBLE_EQ(r.tolerance, 1e-6 * std::hypot(1.0 + 0.5e-3, 1.0 + 2e-3));
  EXPECT_EQ(r.total.duplicateNodes, 0u);
  // Zero: exactly equal coordinates only.
  addNode(m, 12, 1.0, 1.0);  // same place as node 4
  addNode(m, 13, 1e-12, 0.0);
  addShell(m, 3, 1, {12, 13, 10});
  settings.tolerance = 0.0;
  r = reportDeck(m, settings);
  EXPECT_EQ(r.total.duplicateNodes, 1u);
  ASSERT_EQ(r.examples.duplicateNodes.size(), 1u);
  EXPECT_EQ(r.examples.duplicateNodes[0].nodes, (std::array<Id, 2>{4, 12}));
  settings.tolerance = -1.0;
  EXPECT_THROW(reportDeck(m, settings), SettingError);
  settings.tolerance = std::nan("");
  EXPECT_THROW(reportDeck(m, settings), SettingError);
}

TEST(DeckReport, DuplicateSearchAcrossCellBordersMatchesBruteForce) {
  // Random points with many near pairs: the spatial hash must find exactly the brute-force pairs.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(0.0, 1.0);
  std::uniform_real_distribution<double> jitter(-0.011, 0.011);
  FeModel m;
  for (int i = 0; i < 600; ++i) {
    const double x = coordinate(random), y = coordinate(random), z = coordinate(random);
    addNode(m, 2 * i + 1, x, y, z);
    addNode(m, 2 * i + 2, x + jitter(random), y + jitter(random), z + jitter(random));
  }
  for (std::size_t i = 0; i + 2 < m.nodes.size(); i += 3)
    addShell(m, Id(i + 1), 1, {m.nodes[i].id, m.nodes[i + 1].id, m.nodes[i + 2].id});
  ReportSettings settings;
  settings.tolerance = 0.01;
  settings.maxExamples = 100000;
  const DeckReport r = reportDeck(m, settings);
  std::size_t pairs = 0;
  std::vector<std::size_t> parent(m.nodes.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
  std::function<std::size_t(std::size_t)> root = [&](std::size_t x) {
    return parent[x] == x ? x : parent[x] = root(parent[x]);
  };
  std::size_t merged = 0;
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    for (std::size_t j = i + 1; j < m.nodes.size(); ++j) {
      const auto& p = m.nodes[i].xyz;
      const auto& q = m.nodes[j].xyz;
      if (std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) > 0.01) continue;
      ++pairs;
      if (root(i) != root(j)) {
        parent[root(j)] = root(i);
        ++merged;
      }
    }
  ASSERT_GT(pairs, 100u);  // the test means something
  EXPECT_EQ(r.examples.duplicateNodes.size(), pairs);
  EXPECT_EQ(r.total.duplicateNodes, merged);
}

TEST(DeckReport, ATolerancePackingTooManyNodesIsRefused) {
  // 15000 distinct nodes in a 1e-3 cube: with tolerance 1 all are coincident, and counting them
  // would compare each with each.
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(0.0, 1e-3);
  FeModel m;
  for (int i = 0; i < 15000; ++i)
    addNode(m, i + 1, coordinate(random), coordinate(random), coordinate(random));
  for (int i = 0; i + 2 < 15000; i += 3) addShell(m, i + 1, 1, {i + 1, i + 2, i + 3});
  ReportSettings settings;
  settings.tolerance = 1.0;
  try {
    reportDeck(m, settings);
    FAIL() << "no exception";
  } catch (const SettingError& e) {
    EXPECT_NE(std::string(e.what()).find("give a smaller tolerance"), std::string::npos);
  }
  // The default tolerance (1e-6 x the diagonal) separates them.
  EXPECT_EQ(reportDeck(m).total.duplicateNodes, 0u);
}

TEST(DeckReport, PilesOfIdenticalNodesAreCheap) {
  // 20000 shells each with their own nodes, all at the same three positions: two piles of
  // coincident nodes per corner position, found in linear time.
  FeModel m;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    addNode(m, 3 * i + 1, 0, 0);
    addNode(m, 3 * i + 2, 1, 0);
    addNode(m, 3 * i + 3, 0, 1);
    addShell(m, i + 1, 1 + i % 2, {3 * i + 1, 3 * i + 2, 3 * i + 3});
  }
  m.partOrAdd(1);
  m.partOrAdd(2);
  const DeckReport r = reportDeck(m);
  EXPECT_EQ(r.total.duplicateNodes, 3u * (n - 1));
  EXPECT_EQ(r.parts[0].stats.duplicateNodes, 3u * (n / 2 - 1));
  EXPECT_EQ(r.total.freeElements, std::size_t(n));
  EXPECT_EQ(r.total.boundaryLoops, std::size_t(n));
  ASSERT_EQ(r.examples.duplicateNodes.size(), 10u);
  EXPECT_EQ(r.examples.duplicateNodes[0].nodes, (std::array<Id, 2>{1, 4}));
}

TEST(DeckReport, UnusedNodesAreCountedButNotPartOfTheMesh) {
  FeModel m = grid(range(1, 1.0), range(1, 1.0));
  addNode(m, 1000001, 50, 50, 50);  // e.g. an SPH particle
  const DeckReport r = reportDeck(m);
  EXPECT_EQ(r.modelNodes, 5u);
  EXPECT_EQ(r.unusedNodes, 1u);
  EXPECT_EQ(r.examples.unusedNodes, (std::vector<Id>{1000001}));
  EXPECT_EQ(r.total.nodes, 4u);
  EXPECT_EQ(r.total.box.max, (std::array<double, 3>{1, 1, 0}));  // the particle is not in the box
  const std::string table = formatReportTable(r);
  EXPECT_NE(table.find("unused nodes (no shell uses them): 1"), std::string::npos) << table;
  EXPECT_NE(table.find("SPH"), std::string::npos) << table;
}

TEST(DeckReport, FreeFloatingElementSharesNoNode) {
  FeModel m = grid(range(2, 1.0), range(1, 1.0));
  addNode(m, 21, 5, 5);
  addNode(m, 22, 6, 5);
  addNode(m, 23, 5, 6);
  addShell(m, 99, 1, {21, 22, 23});
  const DeckReport r = reportDeck(m);
  EXPECT_EQ(r.total.freeElements, 1u);
  EXPECT_EQ(r.examples.freeElements, (std::vector<Id>{99}));
  EXPECT_EQ(r.total.boundaryLoops, 2u);
}

TEST(DeckReport, DegenerateElementsHaveNoArea) {
  FeModel m = grid(range(2, 1.0), range(1, 1.0));
  addNode(m, 31, 3, 0);
  addNode(m, 32, 4, 0);
  addNode(m, 33, 5, 0);
  addShell(m, 50, 1, {31, 32, 33});  // collinear
  addNode(m, 34, 3, 2);
  addNode(m, 35, 4, 2);
  addNode(m, 36, 4, 2);  // coincides with 35: a triangle-shaped quad, still has area
  addNode(m, 37, 3, 3);
  addShell(m, 51, 1, {34, 35, 36, 37});
  addNode(m, 38, 6, 0);
  addNode(m, 39, 7, 0);
  addNode(m, 40, 7, 1);
  addNode(m, 41, 6, 1);
  addShell(m, 52, 1, {38, 40, 39, 41});  // symmetric bow-tie quad: diagonals parallel
  addNode(m, 42, 9, 0);
  addNode(m, 43, 10, 0);
  addNode(m, 44, 9.5, 1e-9);  // a sliver 1e-9 high
  addShell(m, 53, 1, {42, 43, 44});
  ReportSettings settings;
  settings.tolerance = 1e-6;
  const DeckReport r = reportDeck(m, settings);
  EXPECT_EQ(r.total.degenerateElements, 3u);
  EXPECT_EQ(r.examples.degenerateElements, (std::vector<Id>{50, 52, 53}));
  settings.tolerance = 1e-10;  // now the sliver is high enough
  EXPECT_EQ(reportDeck(m, settings).examples.degenerateElements, (std::vector<Id>{50, 52}));
}

TEST(DeckReport, TwoPartsSharingAnEdge) {
  FeModel m = grid(range(2, 1.0), range(1, 1.0));
  m.shells[1].part = 2;
  m.partOrAdd(2, "second");
  const DeckReport r = reportDeck(m);
  ASSERT_EQ(r.parts.size(), 2u);
  EXPECT_EQ(r.parts[0].id, 1);
  EXPECT_EQ(r.parts[1].id, 2);
  EXPECT_EQ(r.parts[1].name, "second");
  for (const PartReport& p : r.parts) {
    EXPECT_EQ(p.stats.quads, 1u);
    EXPECT_EQ(p.stats.nodes, 4u);
    EXPECT_EQ(p.stats.edges, 4u);
    EXPECT_EQ(p.stats.boundaryEdges, 4u);  // the shared edge is each part's boundary
    EXPECT_EQ(p.stats.boundaryLoops, 1u);
    EXPECT_EQ(p.stats.freeElements, 1u);  // alone within its part
  }
  EXPECT_EQ(r.total.edges, 7u);  // the shared edge once
  EXPECT_EQ(r.total.boundaryEdges, 6u);
  EXPECT_EQ(r.total.nodes, 6u);
  EXPECT_EQ(r.total.freeElements, 0u);
}

TEST(DeckReport, PartsInModelOrderThenUndefinedOnesAscending) {
  FeModel m = grid(range(4, 1.0), range(1, 1.0));
  m.parts.clear();
  m.partOrAdd(7, "seven");
  m.partOrAdd(3, "three, no shells");
  m.shells[0].part = 7;
  m.shells[1].part = 40;
  m.shells[2].part = 7;
  m.shells[3].part = 12;
  const DeckReport r = reportDeck(m);
  ASSERT_EQ(r.parts.size(), 4u);
  EXPECT_EQ(r.parts[0].id, 7);
  EXPECT_EQ(r.parts[0].stats.quads, 2u);
  EXPECT_EQ(r.parts[1].id, 3);
  EXPECT_EQ(r.parts[1].stats.shells(), 0u);
  EXPECT_TRUE(r.parts[1].stats.box.empty());
  EXPECT_EQ(r.parts[2].id, 12);
  EXPECT_FALSE(r.parts[2].defined);
  EXPECT_EQ(r.parts[3].id, 40);
  EXPECT_EQ(r.total.quads, 4u);
}

TEST(DeckReport, EdgeLengthStatisticsOnAKnownGrid) {
  // Columns 1, 2 and 3 wide, rows 2.5 high: each quad has two sides of its width and two of 2.5.
  // Sides: 1 1 2 2 3 3 and six of 2.5 (per row) -> median 2.5; min 1, max 3.
  const DeckReport r = reportDeck(grid({0, 1, 3, 6}, {0, 2.5}));
  EXPECT_EQ(r.total.edgeLength.count, 12u);
  EXPECT_EQ(r.total.edgeLength.min, 1.0);
  EXPECT_EQ(r.total.edgeLength.max, 3.0);
  EXPECT_EQ(r.total.edgeLength.median, 2.5);
  // An even count with different middle values gives their mean: sides 1 1 1 1 4 4 4 4.
  const DeckReport narrow = reportDeck(grid({0, 1, 2}, {0, 4}));
  EXPECT_EQ(narrow.total.edgeLength.median, 2.5);
  const DeckReport box = reportDeck(grid({-2, 1, 3, 6}, {10, 12.5}));
  EXPECT_EQ(box.total.box.min, (std::array<double, 3>{-2, 10, 0}));
  EXPECT_EQ(box.total.box.max, (std::array<double, 3>{6, 12.5, 0}));
  EXPECT_DOUBLE_EQ(box.total.box.diagonal(), std::hypot(8.0, 2.5));
}

TEST(DeckReport, ResultDoesNotDependOnElementOrder) {
  FeModel m = grid(range(20, 1.0), range(15, 0.7));
  for (std::size_t s = 0; s < m.shells.size(); s += 3)
    std::reverse(m.shells[s].nodes.begin(), m.shells[s].nodes.end());
  m.shells.erase(m.shells.begin() + 150);  // an interior quad: a hole
  for (std::size_t s = 0; s < m.shells.size(); s += 5) m.shells[s].part = 2;
  const DeckReport a = reportDeck(m);
  std::mt19937 random(3);
  std::shuffle(m.shells.begin(), m.shells.end(), random);
  std::shuffle(m.nodes.begin(), m.nodes.end(), random);
  const DeckReport b = reportDeck(m);
  for (const auto* r : {&a, &b}) ASSERT_EQ(r->parts.size(), 2u);
  auto same = [](const MeshStats& x, const MeshStats& y) {
    EXPECT_EQ(x.nodes, y.nodes);
    EXPECT_EQ(x.edges, y.edges);
    EXPECT_EQ(x.boundaryEdges, y.boundaryEdges);
    EXPECT_EQ(x.boundaryLoops, y.boundaryLoops);
    EXPECT_EQ(x.openBoundaryChains, y.openBoundaryChains);
    EXPECT_EQ(x.inconsistentEdges, y.inconsistentEdges);
    EXPECT_EQ(x.freeElements, y.freeElements);
    EXPECT_EQ(x.edgeLength.median, y.edgeLength.median);
  };
  same(a.total, b.total);
  same(a.parts[0].stats, b.parts[0].stats);
  same(a.parts[1].stats, b.parts[1].stats);
  EXPECT_GT(a.total.inconsistentEdges, 0u);
  EXPECT_EQ(a.total.boundaryLoops, 2u);  // outer contour and the hole
}

// ---------------------------------------------------------------------------------------------
// Rendering

TEST(DeckReportJson, IsValidJsonWithStableKeysAndFullPrecision) {
  FeModel m = grid({0, 0.1, 1.0 / 3.0}, {0, 1e-7});
  m.parts[0].name =
      "Bl\xC3\xA4"
      "ch \"A\\B\"\n\ttab\x01 latin\xE4 end";
  addNode(m, 77, 9, 9, 9);
  const DeckReport r = reportDeck(m);
  const std::string text = formatReportJson(r);
  const Json doc = parseJson(text);
  EXPECT_EQ(doc.keys(), (std::vector<std::string>{"model", "parts", "total", "examples"}));
  EXPECT_EQ(doc["model"].keys(),
            (std::vector<std::string>{"nodes", "unusedNodes", "shells", "parts", "tolerance"}));
  EXPECT_EQ(doc["model"]["nodes"].number, 7);
  EXPECT_EQ(doc["model"]["unusedNodes"].number, 1);
  const Json& p = doc["parts"].items.at(0);
  EXPECT_EQ(p.keys(),
            (std::vector<std::string>{
                "id", "name", "defined", "nodes", "quads", "trias", "boundingBox", "edgeLength",
                "edges", "boundaryEdges", "boundaryLoops", "openBoundaryChains", "nonManifoldEdges",
                "inconsistentEdges", "duplicateNodes", "freeElements", "degenerateElements"}));
  EXPECT_EQ(p["name"].text,
            "Bl\xC3\xA4"
            "ch \"A\\B\"\n\ttab\x01 latin\xC3\xA4 end");
  EXPECT_TRUE(p["defined"].boolean);
  EXPECT_EQ(p["quads"].number, 2);
  // Full precision: the numbers read back exactly.
  EXPECT_EQ(p["boundingBox"]["max"].items.at(0).number, 1.0 / 3.0);
  EXPECT_EQ(p["boundingBox"]["max"].items.at(1).number, 1e-7);
  EXPECT_EQ(p["edgeLength"]["min"].number, r.parts[0].stats.edgeLength.min);
  EXPECT_EQ(p["edgeLength"]["median"].number, r.parts[0].stats.edgeLength.median);
  EXPECT_EQ(doc["model"]["tolerance"].number, r.tolerance);
  EXPECT_EQ(doc["total"]["boundaryEdges"].number, 6);
  EXPECT_EQ(doc["examples"]["unusedNodes"].items.at(0).number, 77);
  // Same report, same text.
  EXPECT_EQ(formatReportJson(reportDeck(m)), text);
}

TEST(DeckReportJson, EmptyPartsAndExamplesAreValid) {
  FeModel m = grid(range(3, 1.0), range(1, 1.0));
  m.shells[1].nodes = {2, 6, 7, 3};  // flipped
  m.partOrAdd(5, "empty");
  const DeckReport r = reportDeck(m);
  const Json doc = parseJson(formatReportJson(r));
  const Json& empty = doc["parts"].items.at(1);
  EXPECT_EQ(empty["boundingBox"].type, Json::Type::Null);
  EXPECT_EQ(empty["edgeLength"].type, Json::Type::Null);
  const Json& flipped = doc["examples"]["inconsistentEdges"];
  ASSERT_EQ(flipped.items.size(), 2u);
  EXPECT_EQ(flipped.items[0]["nodes"].items.at(0).number, 2);
  EXPECT_EQ(flipped.items[0]["shells"].items.size(), 2u);
  EXPECT_EQ(doc["examples"]["nonManifoldEdges"].items.size(), 0u);
}

TEST(DeckReportJson, AModelWithoutShellsRendersToo) {
  FeModel m;
  addNode(m, 1, 0, 0);
  m.partOrAdd(3, "empty");
  const DeckReport r = reportDeck(m);
  EXPECT_EQ(r.total.shells(), 0u);
  EXPECT_EQ(r.unusedNodes, 1u);
  EXPECT_EQ(r.tolerance, 0.0);
  const Json doc = parseJson(formatReportJson(r));
  EXPECT_EQ(doc["total"]["boundingBox"].type, Json::Type::Null);
  EXPECT_EQ(doc["parts"].items.size(), 1u);
  EXPECT_NE(formatReportTable(r).find("(no shells)"), std::string::npos);
}

TEST(DeckReportTable, ShowsEveryPartTheTotalAndTheFindings) {
  FeModel m = grid(range(2, 1.0), range(1, 1.0));
  m.shells[1].part = 2;
  m.partOrAdd(2, "a part name that is much longer than the name column");
  m.shells[1].nodes = {2, 5, 6, 3};
  const DeckReport r = reportDeck(m);
  const std::string table = formatReportTable(r);
  EXPECT_NE(table.find("plate"), std::string::npos);
  EXPECT_NE(table.find("a part name that is much lo~"), std::string::npos) << table;
  EXPECT_EQ(table.find("longer than the name column"), std::string::npos);
  EXPECT_NE(table.find("total"), std::string::npos);
  EXPECT_NE(table.find("edges with inconsistent orientation: 1"), std::string::npos) << table;
  EXPECT_NE(table.find("nodes 2-5: shells 1 2"), std::string::npos) << table;
  // Every line of a table section has its columns aligned: the rows have the same width as the
  // header's rule.
  const std::size_t sizes = table.find("Sizes");
  const std::size_t rule = table.find("  ---", sizes);
  const std::size_t ruleEnd = table.find('\n', rule);
  const std::size_t headerStart = table.rfind('\n', rule - 2) + 1;
  EXPECT_EQ(rule - headerStart - 1, ruleEnd - rule) << table;
}

// ---------------------------------------------------------------------------------------------
// Performance

TEST(DeckReportPerformance, OneMillionElementGrid) {
  const std::size_t n = 1000;
  FeModel m = grid(range(n, 1.0), range(n, 1.0));
  for (std::size_t s = m.shells.size() / 2; s < m.shells.size(); ++s) m.shells[s].part = 2;
  m.partOrAdd(2, "upper half");
  const auto start = std::chrono::steady_clock::now();
  const DeckReport r = reportDeck(m);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("reportDeck on %zu quads, 2 parts: %.3f s\n", m.shells.size(), seconds);
  EXPECT_EQ(r.total.quads, n * n);
  EXPECT_EQ(r.total.edges, 2 * n * (n + 1));
  EXPECT_EQ(r.total.boundaryEdges, 4 * n);
  EXPECT_EQ(r.total.boundaryLoops, 1u);
  EXPECT_EQ(r.total.inconsistentEdges, 0u);
  for (const PartReport& p : r.parts) {
    EXPECT_EQ(p.stats.boundaryEdges, 2 * n + 2 * (n / 2));
    EXPECT_EQ(p.stats.boundaryLoops, 1u);
  }
  EXPECT_EQ(r.total.edgeLength.median, 1.0);
  // Not a speed measurement (bench_io measures that): quadratic work would take many minutes,
  // while a loaded machine under the sanitizers takes about 15 s.
  EXPECT_LT(seconds, 60.0);
}

TEST(DeckReportPerformance, OneMillionElementsInFourHundredParts) {
  const std::size_t n = 1000;
  FeModel m = grid(range(n, 1.0), range(n, 1.0));
  m.parts.clear();
  // Parts of 2500 quads: 20 x 125 blocks, in a shuffled order of IDs.
  for (std::size_t s = 0; s < m.shells.size(); ++s) {
    const std::size_t i = s % n, j = s / n;
    m.shells[s].part = Id((i / 125) * 50 + j / 20 + 1) * 7919 % 100003;
  }
  const auto start = std::chrono::steady_clock::now();
  const DeckReport r = reportDeck(m);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("reportDeck on %zu quads, %zu parts: %.3f s\n", m.shells.size(), r.parts.size(),
              seconds);
  ASSERT_EQ(r.parts.size(), 400u);
  for (const PartReport& p : r.parts) {
    EXPECT_FALSE(p.defined);
    EXPECT_EQ(p.stats.quads, 2500u);
    EXPECT_EQ(p.stats.boundaryEdges, 2u * (125 + 20));
    EXPECT_EQ(p.stats.boundaryLoops, 1u);
  }
  EXPECT_TRUE(std::is_sorted(r.parts.begin(), r.parts.end(),
                             [](const PartReport& a, const PartReport& b) { return a.id < b.id; }));
  EXPECT_EQ(r.total.boundaryEdges, 4 * n);
  EXPECT_LT(seconds, 60.0);  // quadratic work would take many minutes (see above)
}
