// bench_remesh: the whole-deck remesh on a generated deck of about a million shells.
//
// The deck is the shipped sample part (--part, default tools/samples/hat_rail.k relative to the
// working folder: run it from the source root; 3562 shells, 5 mm) copied into
// a grid of parts, each copy its own part with its own nodes, until the deck holds at least
// --elements shells (default 1,000,000). It is written to a .k file and then timed like
// `voxremesh remesh deck.k -o out.k`: read, remesh (per part: sheets + volume, extraction; parts
// in parallel), assembly, write. Prints the total time, the time per stage (the volume and
// extraction times are summed over the parts, i.e. CPU-side work, next to the wall time of the
// parallel remesh), the element counts and the peak resident memory. In the same run, for
// comparison, OpenVDB's own tools do the volume and surface work of every part (parts in
// parallel, the same thread count and voxel size): meshToVolume (unsigned distance, band 3) and
// volumeToMesh (adaptivity 0) at half a voxel, the nearest the ecosystem has to our pipeline.
//
// usage: bench_remesh [--elements N] [--threads N] [--size H] [--keep DIR] [--part FILE]
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <sys/resource.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "bench_timing.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/quad_mesh.h"

using namespace voxremesh;

namespace {

using voxremesh::bench::secondsSince;

FeModel replicate(const FeModel& part, std::size_t copies) {
  FeModel deck;
  Id maxNode = 0, maxShell = 0;
  for (const Node& node : part.nodes) maxNode = std::max(maxNode, node.id);
  for (const Shell& shell : part.shells) maxShell = std::max(maxShell, shell.id);
  deck.nodes.reserve(part.nodes.size() * copies);
  deck.shells.reserve(part.shells.size() * copies);
  for (std::size_t c = 0; c < copies; ++c) {
    const double dx = 500.0 * static_cast<double>(c % 20), dy = 250.0 * static_cast<double>(c / 20);
    const Id nodeOffset = static_cast<Id>(c) * maxNode, shellOffset = static_cast<Id>(c) * maxShell;
    for (const Node& node : part.nodes)
      deck.nodes.push_back(
          Node{node.id + nodeOffset, {node.xyz[0] + dx, node.xyz[1] + dy, node.xyz[2]}});
    for (Shell shell : part.shells) {
      shell.id += shellOffset;
      shell.part = static_cast<Id>(c + 1);
      for (int k = 0; k < shell.nodeCount; ++k)
        shell.nodes[static_cast<std::size_t>(k)] += nodeOffset;
      shell.type = 0;
      shell.extras = -1;
      deck.shells.push_back(shell);
    }
    deck.partOrAdd(static_cast<Id>(c + 1), "rail " + std::to_string(c + 1));
  }
  return deck;
}

/// meshToVolume's view of a part's shells in index space.
struct ShellAdapter {
  const QuadMesh* mesh;
  double inverseVoxelSize;
  std::size_t polygonCount() const { return mesh->faces.size(); }
  std::size_t pointCount() const { return mesh->points.size(); }
  std::size_t vertexCount(std::size_t n) const { return std::size_t(cornerCount(mesh->faces[n])); }
  void getIndexSpacePoint(std::size_t n, std::size_t v, openvdb::Vec3d& pos) const {
    const auto& p = mesh->points[mesh->faces[n][v]];
    pos = openvdb::Vec3d(p[0], p[1], p[2]) * inverseVoxelSize;
  }
};

/// OpenVDB's own volume and surface of every remeshed part (see the top of the file); returns
/// the wall time and adds the quads it made to `quads`.
double openvdbPipeline(const FeModel& deck, const RemeshReport& report, int threads,
                       std::size_t& quads) {
  openvdb::initialize();
  std::vector<std::size_t> counts(report.parts.size(), 0);
  const auto start = std::chrono::steady_clock::now();
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t(0), report.parts.size(), [&](std::size_t i) {
      const double h = report.parts[i].plan.targetSize;
      const QuadMesh shells = quadMeshFromModel(deck, report.parts[i].plan.part);
      const auto transform = openvdb::math::Transform::createLinearTransform(h);
      const ShellAdapter adapter{&shells, 1.0 / h};
      const openvdb::FloatGrid::Ptr grid = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
          adapter, *transform, 3.0f, 3.0f, openvdb::tools::UNSIGNED_DISTANCE_FIELD);
      std::vector<openvdb::Vec3s> points;
      std::vector<openvdb::Vec3I> triangles;
      std::vector<openvdb::Vec4I> surfaceQuads;
      openvdb::tools::volumeToMesh(*grid, points, triangles, surfaceQuads, 0.5 * h, 0.0);
      counts[i] = surfaceQuads.size();
    });
  });
  const double wall = secondsSince(start);
  for (const std::size_t c : counts) quads += c;
  return wall;
}

long peakMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t elements = 1000000;
  RemeshSettings settings;
  std::filesystem::path keep;
  std::filesystem::path source = "tools/samples/hat_rail.k";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--elements"))
      elements = std::strtoull(argv[i + 1], nullptr, 10);
    else if (!std::strcmp(argv[i], "--threads"))
      settings.threads = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--size"))
      settings.targetSize = std::atof(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--keep"))
      keep = argv[i + 1];
    else {
      std::fprintf(stderr,
                   "usage: bench_remesh [--elements N] [--threads N] [--size H] [--keep DIR] "
                   "[--part FILE]\n");
      return 2;
    }
  }
  const std::filesystem::path dir =
      keep.empty() ? std::filesystem::temp_directory_path() / "voxremesh-bench-remesh" : keep;
  std::filesystem::create_directories(dir);
  const FeModel part = readDeck(source);
  const std::size_t copies = (elements + part.shells.size() - 1) / part.shells.size();
  writeDeck(replicate(part, copies), dir / "deck.k");

  const auto total = std::chrono::steady_clock::now();
  auto stage = std::chrono::steady_clock::now();
  FeModel deck = readDeck(dir / "deck.k");
  const double readSeconds = secondsSince(stage);
  const FeModel original = deck;
  const std::size_t before = deck.shells.size();
  stage = std::chrono::steady_clock::now();
  const RemeshReport report = remeshDeck(deck, settings);
  const double remeshSeconds = secondsSince(stage);
  stage = std::chrono::steady_clock::now();
  writeDeck(deck, dir / "out.k");
  const double writeSeconds = secondsSince(stage);
  const double totalSeconds = secondsSince(total);
  double volume = 0, extract = 0, optimize = 0;
  for (const RemeshedPart& p : report.parts) {
    volume += p.volumeSeconds;
    extract += p.extractSeconds;
    optimize += p.optimizeSeconds;
  }
  std::printf("deck: %zu parts, %zu shells -> %zu shells\n", report.parts.size(), before,
              deck.shells.size());
  std::printf(
      "total %.2f s: read %.2f s, remesh %.2f s (wall; summed over parts: sheets+volume "
      "%.2f s, extract %.2f s, optimise %.2f s; assembly %.2f s), write %.2f s\n",
      totalSeconds, readSeconds, remeshSeconds, volume, extract, optimize, report.assemblySeconds,
      writeSeconds);
  std::printf("peak memory %ld MB (before the OpenVDB comparison)\n", peakMegabytes());
  std::size_t vdbQuads = 0;
  const double vdbSeconds = openvdbPipeline(original, report, settings.threads, vdbQuads);
  std::printf(
      "OpenVDB meshToVolume + volumeToMesh of the same parts: %.2f s wall (%zu quads, both "
      "sides of each sheet); voxremesh remesh / OpenVDB = %.2f\n",
      vdbSeconds, vdbQuads, remeshSeconds / vdbSeconds);
  if (keep.empty()) std::filesystem::remove_all(dir);
  return 0;
}
