// Quad meshes from a model's shells (voxremesh/quad_mesh.h): one part at a time or several in one
// pass give the same meshes.
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>
#include <vector>

#include "support/test_support.h"
#include "voxremesh/quad_mesh.h"

using namespace voxremesh;

namespace {

/// Three parts of a strip of unit quads along x (part 1: x 0..2, part 2: x 2..3, part 3: x 3..4),
/// sharing the nodes where they meet; part 2's quad comes first in the model.
FeModel threeParts() {
  FeModel model;
  for (int i = 0; i <= 4; ++i) {
    test::addNode(model, Id(1 + i), i, 0.0);
    test::addNode(model, Id(11 + i), i, 1.0);
  }
  test::addShell(model, 1, 2, {3, 4, 14, 13});
  test::addShell(model, 2, 1, {1, 2, 12, 11});
  test::addShell(model, 3, 3, {4, 5, 15, 14});
  test::addShell(model, 4, 1, {2, 3, 13, 12});
  return model;
}

}  // namespace

TEST(QuadMesh, SeveralPartsInOnePassAreEachPartsOwnMesh) {
  const FeModel model = threeParts();
  const std::map<Id, QuadMesh> meshes = quadMeshesFromModel(model, {1, 2, 7});
  ASSERT_EQ(meshes.size(), 2u);  // part 7 has no shells; part 3 was not asked for
  for (const Id part : {Id(1), Id(2)}) {
    const QuadMesh alone = quadMeshFromModel(model, part);
    const QuadMesh& together = meshes.at(part);
    EXPECT_EQ(together.part, part);
    EXPECT_EQ(together.points, alone.points);
    EXPECT_EQ(together.faces, alone.faces);
  }
  EXPECT_EQ(meshes.at(1).faces.size(), 2u);
  EXPECT_EQ(meshes.at(1).points.size(), 6u);
}

TEST(QuadMesh, AShellNamingAnUndefinedNodeIsRefusedInOnePassToo) {
  FeModel model = threeParts();
  test::addShell(model, 5, 2, {3, 4, 99, 13});
  EXPECT_THROW(quadMeshFromModel(model, 2), std::invalid_argument);
  EXPECT_THROW(quadMeshesFromModel(model, {2}), std::invalid_argument);
  EXPECT_NO_THROW(quadMeshesFromModel(model, {1, 3}));
}
