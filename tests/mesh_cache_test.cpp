// The optimisation's mesh cache (src/optimize/mesh_cache.h): whatever happens to the mesh between
// two questions (points moved, faces cut or erased, points erased), its topology and failures are
// those built anew for the mesh as it is.
#include <gtest/gtest.h>

#include <random>

#include "optimize/face_score.h"
#include "optimize/mesh_cache.h"

namespace {

using voxremesh::CornerIndex;
using voxremesh::QuadMesh;
using voxremesh::QualitySettings;
using voxremesh::opt::MeshCache;

/// An n x n grid of unit quads in the plane z = 0.
QuadMesh grid(int n) {
  QuadMesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) mesh.points.push_back({double(i), double(j), 0.0});
  const auto at = [&](int i, int j) { return CornerIndex(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      mesh.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
  return mesh;
}

void expectSameTopology(const voxremesh::opt::Topology& a, const voxremesh::opt::Topology& b) {
  EXPECT_EQ(a.faceStart, b.faceStart);
  EXPECT_EQ(a.faceList, b.faceList);
  EXPECT_EQ(a.nbrStart, b.nbrStart);
  EXPECT_EQ(a.nbrList, b.nbrList);
  EXPECT_EQ(a.nbrFaces, b.nbrFaces);
  EXPECT_EQ(a.boundary, b.boundary);
}

/// The cache's answers against answers found anew.
void expectCurrent(MeshCache& cache, const QuadMesh& mesh, const QualitySettings& settings) {
  expectSameTopology(cache.topology(mesh), voxremesh::opt::buildTopology(mesh));
  const std::vector<std::uint32_t> failures = cache.failures(mesh);
  ASSERT_EQ(failures.size(), mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    EXPECT_EQ(failures[f], voxremesh::opt::faceFailures(mesh, mesh.faces[f], settings)) << f;
}

TEST(MeshCache, AnswersAsIfBuiltAnewWhateverChangedTheMesh) {
  QualitySettings settings;
  settings.targetSize = 1.0;
  QuadMesh mesh = grid(12);
  MeshCache cache(settings);
  expectCurrent(cache, mesh, settings);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> jitter(-0.35, 0.35);
  std::size_t failing = 0;
  for (int round = 0; round < 4; ++round) {
    // Points moved (some faces now fail, some pass again).
    for (CornerIndex v = CornerIndex(round); v < mesh.points.size(); v += 5)
      mesh.points[v] = {mesh.points[v][0] + jitter(random), mesh.points[v][1] + jitter(random),
                        jitter(random)};
    expectCurrent(cache, mesh, settings);
    for (const std::uint32_t f : cache.failures(mesh)) failing += f != 0;
    // A quad cut into two triangles in place (same face count, other corners).
    const auto quad = mesh.faces[std::size_t(7 * round + 3)];
    mesh.faces[std::size_t(7 * round + 3)] = {quad[0], quad[1], quad[2], voxremesh::kNoCorner};
    mesh.faces.push_back({quad[2], quad[3], quad[0], voxremesh::kNoCorner});
    expectCurrent(cache, mesh, settings);
    // A face erased (the later ones shift down) and the last point dropped when unused.
    mesh.faces.erase(mesh.faces.begin() + 11 * round);
    voxremesh::eraseUnusedPoints(mesh);
    expectCurrent(cache, mesh, settings);
  }
  EXPECT_GT(failing, 0u);  // the moves made faces fail: the masks were not all empty
}

}  // namespace
