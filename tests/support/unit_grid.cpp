// unitGrid and its jitter (unit_grid.h).
#include "support/unit_grid.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "voxremesh/quality.h"

namespace voxremesh::test {

QuadMesh unitGrid(int n) {
  QuadMesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) mesh.points.push_back({double(i), double(j), 0.0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      mesh.faces.push_back({gridPoint(n, i, j), gridPoint(n, i + 1, j), gridPoint(n, i + 1, j + 1),
                            gridPoint(n, i, j + 1)});
  mesh.constraints.resize(mesh.points.size());
  return mesh;
}

void jitterInnerPoints(QuadMesh& mesh, int n, unsigned seed, double amount) {
  unsigned state = seed;
  auto next = [&state] {  // uniform in [-0.5, 0.5)
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1u << 24) - 0.5;
  };
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) {
      auto& p = mesh.points[gridPoint(n, i, j)];
      p[0] += 2.0 * amount * next();
      p[1] += 2.0 * amount * next();
    }
}

std::size_t foldedCount(const QuadMesh& mesh) {
  const std::vector<std::uint8_t> folded = foldedFaces(mesh);
  return std::size_t(std::count(folded.begin(), folded.end(), std::uint8_t(1)));
}

}  // namespace voxremesh::test
