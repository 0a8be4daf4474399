// unitGrid (unit_grid.h).
#include "support/unit_grid.h"

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

}  // namespace voxremesh::test
