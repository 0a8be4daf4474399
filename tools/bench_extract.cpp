// bench_extract: voxremesh's extraction against OpenVDB's own volumeToMesh on the same grid.
//
// Per deck (default: ../shared/data/bracket.k and tools/samples/hat_rail.k, relative to the
// source root) the deck's part (the largest one when it has several) is split into sheets and
// written into a volume at three voxel sizes: 1, 0.5 and 0.25 times the part's median edge length.
// On each volume's sdf grid it times, best of --repeat runs, with 1 and with 2 threads
// (tbb::global_control):
//   ours      extractQuadMesh with the default settings (boundary strip rebuilt, features snapped)
//   dual      extractQuadMesh with rebuildBoundary and snapFeatures off (the bare dual pass)
//   openvdb   tools::volumeToMesh, isovalue 0, adaptivity 0 (quads and triangles)
// and prints the voxel size, the active voxels, the quads of ours and of OpenVDB, the three times
// and the ratios ours/openvdb and dual/openvdb. The column "same" says whether the mesh made with
// this thread count has the same points and faces as the one made with 1 thread.
//
// OpenVDB's mesh is not the same surface: volumeToMesh extracts the zero crossing of the whole
// band, past the sheet's free boundary (where the signed distance of an open sheet still changes
// sign) and next to invalid voxels, which extractQuadMesh leaves out; the quad counts show it.
//
// usage: bench_extract [--repeat N] [DECK...]
#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "volume/volume_grids.h"
#include "voxremesh/extract.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/sheets.h"
#include "voxremesh/volume.h"

namespace {

using voxremesh::bench::best;

using voxremesh::QuadMesh;

std::size_t quadCount(const QuadMesh& mesh) {
  std::size_t quads = 0;
  for (const auto& face : mesh.faces) quads += voxremesh::cornerCount(face) == 4 ? 1 : 0;
  return quads;
}

bool sameMesh(const QuadMesh& a, const QuadMesh& b) {
  return a.points == b.points && a.faces == b.faces;
}

/// The part with the most shells.
voxremesh::Id largestPart(const voxremesh::FeModel& model) {
  voxremesh::Id part = 0;
  std::size_t most = 0;
  for (const voxremesh::Id id : voxremesh::shellPartIds(model)) {
    std::size_t shells = 0;
    for (const voxremesh::Shell& shell : model.shells) shells += shell.part == id ? 1 : 0;
    if (shells > most) {
      most = shells;
      part = id;
    }
  }
  return part;
}

void benchDeck(const std::filesystem::path& path, int repeat) {
  const voxremesh::FeModel model = voxremesh::readDeck(path);
  const voxremesh::Id part = largestPart(model);
  if (part == 0) throw std::runtime_error(path.string() + " has no shells");
  const std::vector<voxremesh::Sheet> sheets = voxremesh::buildSheets(model, part);
  const double median = voxremesh::defaultTargetSize(model, part);
  std::printf("\n%s part %lld: %zu sheets, median edge %.4g, best of %d\n", path.string().c_str(),
              static_cast<long long>(part), sheets.size(), median, repeat);
  std::printf("%3s %7s %9s %8s %8s %8s %9s %9s %9s %7s %7s %5s\n", "thr", "voxel", "active",
              "quads", "dual q", "vdb q", "ours s", "dual s", "openvdb s", "o/vdb", "d/vdb",
              "same");
  for (const double factor : {1.0, 0.5, 0.25}) {
    voxremesh::VolumeSettings settings;
    settings.rule = voxremesh::VoxelSizeRule::Explicit;
    settings.voxelSize = factor * median;
    const voxremesh::Volume volume =
        voxremesh::buildVolume(sheets, settings, voxremesh::VolumeSource{path.string()});
    const openvdb::FloatGrid& sdf = *volume.impl().sdf;
    voxremesh::ExtractSettings bare;
    bare.rebuildBoundary = false;
    bare.snapFeatures = false;
    QuadMesh reference;  // ours with 1 thread
    for (const int threads : {1, 2}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                      std::size_t(threads));
      QuadMesh ours, dual;
      const double tOurs = best(repeat, [&] { ours = voxremesh::extractQuadMesh(volume); });
      const double tDual = best(repeat, [&] { dual = voxremesh::extractQuadMesh(volume, bare); });
      std::vector<openvdb::Vec3s> points;
      std::vector<openvdb::Vec3I> triangles;
      std::vector<openvdb::Vec4I> quads;
      const double tVdb = best(repeat, [&] {
        points.clear();
        triangles.clear();
        quads.clear();
        openvdb::tools::volumeToMesh(sdf, points, triangles, quads, 0.0, 0.0);
      });
      if (threads == 1) reference = ours;
      std::printf("%3d %7.4g %9llu %8zu %8zu %8zu %9.4f %9.4f %9.4f %7.2f %7.2f %5s\n", threads,
                  settings.voxelSize, static_cast<unsigned long long>(sdf.activeVoxelCount()),
                  quadCount(ours), quadCount(dual), quads.size(), tOurs, tDual, tVdb, tOurs / tVdb,
                  tDual / tVdb, sameMesh(ours, reference) ? "yes" : "NO");
      std::fflush(stdout);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5;
  std::vector<std::filesystem::path> decks;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else if (argv[i][0] == '-') {
      std::fprintf(stderr, "usage: bench_extract [--repeat N] [DECK...]\n");
      return 2;
    } else {
      decks.emplace_back(argv[i]);
    }
  }
  if (decks.empty()) decks = {"../shared/data/bracket.k", "tools/samples/hat_rail.k"};
  voxremesh::volume::initializeOpenVdb();
  try {
    for (const auto& deck : decks) benchDeck(deck, repeat);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bench_extract: %s\n", error.what());
    return 1;
  }
  return 0;
}
