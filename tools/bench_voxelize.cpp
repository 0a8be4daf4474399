// bench_voxelize: voxremesh's volume stage against OpenVDB's own meshToVolume on one generated
// part, at three voxel sizes.
//
// The part is a hat-section rail (flange, wall, top, wall, flange; sharp 90+ degree bends) of
// 1000 mm with a gentle wave along its length, meshed with about 20k quads of 3 mm. Per voxel size
// it times (best of --repeat runs):
//   openvdb   tools::meshToVolume, unsigned distance, the same band, no closest-polygon grid
//   voxremesh buildVolume: sheet mesh, signed distance with the exact closest point per voxel,
//             invalid and feature masks (everything it returns)
// and prints both times, their ratio, the active voxel counts, and a breakdown of voxremesh's
// time. Options: --threads N (default: all), --repeat N (default 3), --rss (build once at the
// finest size and print the peak resident memory per active voxel, for the memory estimate).
//
// usage: bench_voxelize [--threads N] [--repeat N] [--rss]
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <sys/resource.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "volume/surface_mesh.h"
#include "volume/volume_build.h"
#include "volume/volume_grids.h"
#include "voxremesh/volume.h"

namespace {

using voxremesh::bench::best;

using voxremesh::PointIndex;
using voxremesh::Sheet;

/// The hat-section rail: the profile (x, z) extruded along y with a wave, quads of about `size`.
Sheet hatRail(double size) {
  const std::vector<std::array<double, 2>> profile{{-60.0, 0.0}, {-40.0, 0.0}, {-30.0, 40.0},
                                                   {30.0, 40.0}, {40.0, 0.0},  {60.0, 0.0}};
  const double length = 1000.0;
  // Points along the profile, with a node on every corner.
  std::vector<std::array<double, 2>> section;
  std::vector<int> corners;
  for (std::size_t s = 0; s + 1 < profile.size(); ++s) {
    const double dx = profile[s + 1][0] - profile[s][0], dz = profile[s + 1][1] - profile[s][1];
    const int n = std::max(1, int(std::lround(std::hypot(dx, dz) / size)));
    if (s > 0) corners.push_back(int(section.size()));
    for (int k = 0; k < n; ++k) {
      section.push_back({profile[s][0] + dx * k / n, profile[s][1] + dz * k / n});
    }
  }
  section.push_back(profile.back());
  const int nu = int(section.size()) - 1;
  const int nv = int(std::lround(length / size));
  Sheet sheet;
  sheet.part = 1;
  for (int j = 0; j <= nv; ++j) {
    const double y = length * j / nv;
    const double wave = 5.0 * std::sin(2.0 * M_PI * y / 500.0);
    for (int i = 0; i <= nu; ++i) {
      sheet.points.push_back({section[i][0], y, section[i][1] + wave});
    }
  }
  auto index = [&](int i, int j) { return PointIndex(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      sheet.faces.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)});
    }
  }
  for (int c : corners) {
    voxremesh::Polyline line;
    for (int j = 0; j <= nv; ++j) line.points.push_back(index(c, j));
    sheet.featureLines.push_back(line);
    sheet.featurePoints.push_back(index(c, 0));
    sheet.featurePoints.push_back(index(c, nv));
  }
  voxremesh::Polyline loop;
  loop.closed = true;
  for (int i = 0; i < nu; ++i) loop.points.push_back(index(i, 0));
  for (int j = 0; j < nv; ++j) loop.points.push_back(index(nu, j));
  for (int i = nu; i > 0; --i) loop.points.push_back(index(i, nv));
  for (int j = nv; j > 0; --j) loop.points.push_back(index(0, j));
  sheet.boundaryLoops.push_back(loop);
  for (int i : {0, nu}) {
    sheet.featurePoints.push_back(index(i, 0));
    sheet.featurePoints.push_back(index(i, nv));
  }
  return sheet;
}

/// meshToVolume's view of the rail, the same polygons voxremesh hands it.
struct Adapter {
  const Sheet* sheet;
  double inverseVoxelSize;
  std::size_t polygonCount() const { return sheet->faces.size(); }
  std::size_t pointCount() const { return sheet->points.size(); }
  std::size_t vertexCount(std::size_t n) const {
    return sheet->faces[n][3] == voxremesh::kNoPoint ? 3 : 4;
  }
  void getIndexSpacePoint(std::size_t n, std::size_t v, openvdb::Vec3d& pos) const {
    const auto& p = sheet->points[sheet->faces[n][v]];
    pos = openvdb::Vec3d(p[0], p[1], p[2]) * inverseVoxelSize;
  }
};

}  // namespace

int main(int argc, char** argv) {
  int threads = 0, repeat = 3;
  bool rss = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--rss")) {
      rss = true;
    } else {
      std::fprintf(stderr, "usage: bench_voxelize [--threads N] [--repeat N] [--rss]\n");
      return 2;
    }
  }
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) {
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  std::size_t(threads));
  }
  voxremesh::volume::initializeOpenVdb();
  const Sheet rail = hatRail(3.0);
  const std::vector<Sheet> sheets{rail};
  const double band = 3.0;
  const double sizes[] = {3.0, 1.5, 0.75};

  if (rss) {
    voxremesh::VolumeSettings settings;
    settings.rule = voxremesh::VoxelSizeRule::Explicit;
    settings.voxelSize = sizes[2];
    rusage before{};
    getrusage(RUSAGE_SELF, &before);
    const voxremesh::Volume volume = voxremesh::buildVolume(sheets, settings);
    rusage after{};
    getrusage(RUSAGE_SELF, &after);
    const double active = double(volume.impl().sdf->activeVoxelCount());
    const double estimated = voxremesh::estimateVolume(sheets, sizes[2], settings).activeVoxels;
    std::printf(
        "voxel %.3g: %.0f active voxels (estimated %.0f), peak RSS %.1f MB (%.1f MB "
        "before), %.1f bytes per active voxel\n",
        sizes[2], active, estimated, after.ru_maxrss / 1024.0, before.ru_maxrss / 1024.0,
        (after.ru_maxrss - before.ru_maxrss) * 1024.0 / active);
    return 0;
  }

  std::printf("hat-section rail: %zu quads, %zu points, band %.0f voxels, %s threads, best of %d\n",
              rail.faces.size(), rail.points.size(), band,
              threads > 0 ? std::to_string(threads).c_str() : "all", repeat);
  std::printf("%8s %12s %12s %10s %10s %7s | %8s %8s %8s %8s\n", "voxel", "active(vdb)",
              "active(vxr)", "openvdb s", "voxrem s", "ratio", "mesh s", "sdf s", "feature s",
              "ns/voxel");
  for (const double h : sizes) {
    const auto transform = openvdb::math::Transform::createLinearTransform(h);
    const Adapter adapter{&rail, 1.0 / h};
    openvdb::FloatGrid::Ptr reference;
    const double tVdb = best(repeat, [&] {
      reference = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
          adapter, *transform, float(band), float(band), openvdb::tools::UNSIGNED_DISTANCE_FIELD);
    });
    voxremesh::VolumeSettings settings;
    settings.rule = voxremesh::VoxelSizeRule::Explicit;
    settings.voxelSize = h;
    settings.bandWidthVoxels = band;
    voxremesh::Volume volume;
    const double tOurs = best(repeat, [&] { volume = voxremesh::buildVolume(sheets, settings); });

    // Breakdown of the same work, step by step.
    voxremesh::volume::SurfaceMesh mesh;
    const double tMesh = best(repeat, [&] { mesh = voxremesh::volume::buildSurfaceMesh(sheets); });
    openvdb::FloatGrid::Ptr sdf;
    openvdb::MaskGrid::Ptr invalid;
    const double tSdf = best(repeat, [&] {
      voxremesh::volume::computeSignedDistance(mesh, transform, settings, sdf, invalid);
    });
    const double tFeature = best(repeat, [&] {
      voxremesh::volume::buildFeatureMask(volume.featureLines(), volume.featurePoints(), transform);
    });
    const double active = double(volume.impl().sdf->activeVoxelCount());
    std::printf("%8.3g %12llu %12llu %10.4f %10.4f %7.2f | %8.4f %8.4f %8.4f %8.3f\n", h,
                static_cast<unsigned long long>(reference->activeVoxelCount()),
                static_cast<unsigned long long>(volume.impl().sdf->activeVoxelCount()), tVdb, tOurs,
                tOurs / tVdb, tMesh, tSdf, tFeature, tOurs / active * 1e9);
    std::fflush(stdout);
  }
  return 0;
}
