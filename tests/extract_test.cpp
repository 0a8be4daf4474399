// The dual-quad extraction on closed analytic fields: a closed, edge- and vertex-manifold,
// consistently oriented quad mesh with the Euler characteristic of the shape, no cracks, points
// near the surface, and the same output for 1 and 2 threads.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <functional>
#include <map>

#include "support/mesh_topology.h"
#include "volume/volume_grids.h"
#include "voxremesh/extract.h"

namespace voxremesh {
namespace {

using Field = std::function<double(const openvdb::Vec3d&)>;

/// A volume whose sdf samples `field` at every voxel of the index box [-extent, extent]^3 (all
/// active), with empty masks.
Volume analyticVolume(const Field& field, double voxelSize, int extent) {
  volume::initializeOpenVdb();
  Volume volume;
  Volume::Impl& grids = volume.impl();
  grids.info.voxelSize = voxelSize;
  grids.transform = openvdb::math::Transform::createLinearTransform(voxelSize);
  grids.sdf = openvdb::FloatGrid::create(float(3.0 * voxelSize));
  grids.sdf->setTransform(grids.transform);
  grids.sdf->setGridClass(openvdb::GRID_LEVEL_SET);
  auto accessor = grids.sdf->getAccessor();
  for (int i = -extent; i <= extent; ++i)
    for (int j = -extent; j <= extent; ++j)
      for (int k = -extent; k <= extent; ++k) {
        const openvdb::Coord ijk(i, j, k);
        accessor.setValue(ijk, float(field(grids.transform->indexToWorld(ijk))));
      }
  grids.invalid = openvdb::MaskGrid::create();
  grids.feature = openvdb::MaskGrid::create();
  grids.invalid->setTransform(grids.transform);
  grids.feature->setTransform(grids.transform);
  return volume;
}

double sphere(const openvdb::Vec3d& p, double radius) {
  return p.length() - radius;
}

double torus(const openvdb::Vec3d& p, double major, double minor) {
  const double ring = std::sqrt(p.x() * p.x() + p.y() * p.y()) - major;
  return std::sqrt(ring * ring + p.z() * p.z()) - minor;
}

/// A slab with three round holes through it: genus 3.
double threeHoleSlab(const openvdb::Vec3d& p) {
  double slab = std::max({std::abs(p.x()) - 13.0, std::abs(p.y()) - 5.0, std::abs(p.z()) - 2.5});
  for (double cx : {-8.0, 0.0, 8.0}) {
    const double hole = std::sqrt((p.x() - cx) * (p.x() - cx) + p.y() * p.y()) - 2.2;
    slab = std::max(slab, -hole);
  }
  return slab;
}

/// Smooth noise clipped to a ball, so the zero set is closed.
double noiseBall(const openvdb::Vec3d& p) {
  const double noise = std::sin(0.9 * p.x()) * std::cos(0.7 * p.y() + 0.3) +
                       std::sin(0.8 * p.y() + 1.1) * std::cos(0.6 * p.z()) +
                       std::sin(0.75 * p.z() + 0.4) * std::cos(0.85 * p.x()) - 0.2;
  return std::max(noise, p.length() - 11.0);
}

void expectClosedManifold(const QuadMesh& mesh, int eulerCharacteristic) {
  const test::MeshTopology topology = test::meshTopology(mesh);
  EXPECT_GT(mesh.faces.size(), 0u);
  EXPECT_EQ(topology.boundaryEdges, 0u) << "cracks or holes";
  EXPECT_EQ(topology.nonManifoldEdges, 0u);
  EXPECT_EQ(topology.inconsistentEdges, 0u);
  EXPECT_EQ(topology.nonManifoldVertices, 0u);
  EXPECT_EQ(topology.unusedPoints, 0u);
  EXPECT_EQ(topology.eulerCharacteristic, eulerCharacteristic);
  for (const auto& face : mesh.faces) EXPECT_EQ(cornerCount(face), 4);
}

/// Every point of the mesh within `tolerance` of the zero set (|field| for a distance field).
void expectNearSurface(const QuadMesh& mesh, const Field& field, double tolerance) {
  double worst = 0.0;
  for (const auto& p : mesh.points)
    worst = std::max(worst, std::abs(field(openvdb::Vec3d(p[0], p[1], p[2]))));
  EXPECT_LT(worst, tolerance);
}

/// Normals point towards positive values: the signed volume of a closed mesh oriented outward
/// (field negative inside) is positive.
double signedVolume(const QuadMesh& mesh) {
  double volume = 0.0;
  for (const auto& face : mesh.faces) {
    const auto& a = mesh.points[face[0]];
    for (int c = 1; c + 1 < cornerCount(face); ++c) {
      const auto& b = mesh.points[face[std::size_t(c)]];
      const auto& d = mesh.points[face[std::size_t(c) + 1]];
      volume += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                 a[2] * (b[0] * d[1] - b[1] * d[0])) /
                6.0;
    }
  }
  return volume;
}

TEST(ExtractClosed, SphereIsAClosedQuadManifoldOfGenus0) {
  const double voxel = 0.5;
  const Field field = [](const openvdb::Vec3d& p) { return sphere(p, 7.3); };
  const Volume volume = analyticVolume(field, voxel, 18);
  ExtractStats stats;
  const QuadMesh mesh = extractQuadMesh(volume, {}, &stats);
  expectClosedManifold(mesh, 2);
  expectNearSurface(mesh, field, 0.25 * voxel);
  const double exact = 4.0 / 3.0 * M_PI * 7.3 * 7.3 * 7.3;
  EXPECT_NEAR(signedVolume(mesh), exact, 0.02 * exact);
  EXPECT_EQ(stats.dualQuads, mesh.faces.size());
  EXPECT_EQ(stats.tunnelCells, 0u);
}

TEST(ExtractClosed, TorusHasEulerCharacteristic0) {
  const Field field = [](const openvdb::Vec3d& p) { return torus(p, 6.0, 2.1); };
  const QuadMesh mesh = extractQuadMesh(analyticVolume(field, 0.5, 20));
  expectClosedManifold(mesh, 0);
  expectNearSurface(mesh, field, 0.25 * 0.5);
  EXPECT_GT(signedVolume(mesh), 0.0);
}

TEST(ExtractClosed, ThreeHoleSlabHasGenus3) {
  const Field field = threeHoleSlab;
  const QuadMesh mesh = extractQuadMesh(analyticVolume(field, 0.5, 32));
  expectClosedManifold(mesh, -4);
}

TEST(ExtractClosed, SmoothNoiseIsClosedManifoldWithTheTriangulationsEuler) {
  // The MC33 triangulation follows the trilinear interpolant exactly; the dual mesh has its
  // Euler characteristic, plus 2 for every tunnel cell it opens into two disks, give or take 2
  // for every pair of cells whose shared ambiguous face it resolves the other way.
  const Volume volume = analyticVolume(noiseBall, 0.6, 22);
  ExtractStats stats;
  const QuadMesh mesh = extractQuadMesh(volume, {}, &stats);
  const QuadMesh triangles = extractTriangles(volume);
  const test::MeshTopology triangleTopology = test::meshTopology(triangles);
  EXPECT_EQ(triangleTopology.boundaryEdges, 0u);
  EXPECT_EQ(triangleTopology.nonManifoldEdges, 0u);
  EXPECT_EQ(triangleTopology.inconsistentEdges, 0u);
  const int expected = triangleTopology.eulerCharacteristic + 2 * int(stats.tunnelCells);
  const int euler = test::meshTopology(mesh).eulerCharacteristic;
  expectClosedManifold(mesh, euler);
  EXPECT_EQ(stats.cutCells % 2, 0u);
  EXPECT_EQ((euler - expected) % 2, 0);
  EXPECT_LE(std::abs(euler - expected), int(stats.cutCells))
      << "cut pairs: " << stats.cutCells / 2;
  EXPECT_GT(stats.tunnelCells + stats.cutCells, 0u) << "the field should exercise both cases";
  EXPECT_GT(test::meshTopology(mesh).components, 1u) << "the noise should make several pieces";
}

TEST(ExtractClosed, TrianglesOfTheSphereAreClosed) {
  const QuadMesh mesh = extractTriangles(
      analyticVolume([](const openvdb::Vec3d& p) { return sphere(p, 4.2); }, 0.5, 12));
  const test::MeshTopology topology = test::meshTopology(mesh);
  EXPECT_EQ(topology.boundaryEdges, 0u);
  EXPECT_EQ(topology.nonManifoldEdges, 0u);
  EXPECT_EQ(topology.inconsistentEdges, 0u);
  EXPECT_EQ(topology.eulerCharacteristic, 2);
  EXPECT_GT(signedVolume(mesh), 0.0);
}

TEST(ExtractClosed, OutputDoesNotDependOnTheThreadCount) {
  const Volume volume = analyticVolume(noiseBall, 0.6, 22);
  QuadMesh one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = extractQuadMesh(volume);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = extractQuadMesh(volume);
  }
  EXPECT_EQ(one.points, two.points);
  EXPECT_EQ(one.faces, two.faces);
}

TEST(ExtractClosed, EmptyVolumeIsRefused) {
  EXPECT_THROW(extractQuadMesh(Volume()), std::invalid_argument);
  EXPECT_THROW(extractTriangles(Volume()), std::invalid_argument);
}

}  // namespace
}  // namespace voxremesh
