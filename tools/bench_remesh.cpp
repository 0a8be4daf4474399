// bench_remesh: the whole-deck remesh, timed next to OpenVDB's own tools on the same parts.
//
// The deck is either a real one (--deck FILE) or generated: the shipped sample part (--part,
// default tools/samples/hat_rail.k relative to the working folder: run it from the source root;
// 3562 shells, 5 mm) copied into a grid of parts, each copy its own part with its own nodes, until
// the deck holds at least --elements shells (default 1,000,000), written to a .k file. The remesh
// is timed as `voxremesh remesh deck.k -o out.k` does it: read, remesh (per part: sheets + volume,
// extraction, optimisation; parts in parallel), assembly, write. Prints the total time, the time
// per stage (the volume, extraction and optimisation times are each part's own, isolated from the
// others' work, summed over the parts: part-seconds, next to the wall time of the parallel
// remesh), the element counts and the peak resident memory.
//
// In the same run, for comparison, OpenVDB's own tools do the volume and surface work of every
// remeshed part (parts in parallel, the same thread count and voxel size): meshToVolume (unsigned
// distance, band 3) and volumeToMesh (adaptivity 0) at half a voxel, the nearest the ecosystem has
// to our pipeline. The parts' shells are gathered once, before either side is timed.
//
// With --scaling, the remesh runs with 1 thread and with --threads (default: all cores), each
// --repeat times (default 1) in turn, and prints the best time of each, their ratio and whether
// the written decks are byte for byte the same.
//
// usage: bench_remesh [--deck FILE | --elements N] [--part FILE] [--threads N] [--size H]
//                     [--keep DIR] [--scaling] [--repeat N] [--help]
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <sys/resource.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <vector>

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

/// OpenVDB's own volume and surface of every remeshed part, from its shells in `shells` (see
/// the top of the file); returns the wall time and adds the quads it made to `quads`.
double openvdbPipeline(const std::map<Id, QuadMesh>& shells, const RemeshReport& report,
                       int threads, std::size_t& quads) {
  openvdb::initialize();
  std::vector<const RemeshedPart*> parts;
  for (const RemeshedPart& part : report.parts)
    if (shells.count(part.plan.part)) parts.push_back(&part);
  std::vector<std::size_t> counts(parts.size(), 0);
  const auto start = std::chrono::steady_clock::now();
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t(0), parts.size(), [&](std::size_t i) {
      const double h = parts[i]->plan.targetSize;
      const auto transform = openvdb::math::Transform::createLinearTransform(h);
      const ShellAdapter adapter{&shells.at(parts[i]->plan.part), 1.0 / h};
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

struct Options {
  std::size_t elements = 1000000;
  std::filesystem::path deck;  ///< a real deck; empty: the generated one
  std::filesystem::path part = "tools/samples/hat_rail.k";
  std::filesystem::path keep;
  RemeshSettings settings;
  bool scaling = false;
  int repeat = 1;
};

constexpr const char* kUsage =
    "usage: bench_remesh [--deck FILE | --elements N] [--part FILE] [--threads N] [--size H]\n"
    "                    [--keep DIR] [--scaling] [--repeat N] [--help]\n"
    "  --deck FILE     remesh this deck (default: copies of --part up to --elements shells)\n"
    "  --elements N    shells of the generated deck (default 1000000)\n"
    "  --part FILE     the part the generated deck copies (default tools/samples/hat_rail.k)\n"
    "  --threads N     threads (default: all cores)\n"
    "  --size H        target element size (default: per part, its median edge length)\n"
    "  --keep DIR      write the decks to DIR and keep them (default: a temporary folder)\n"
    "  --scaling       time the remesh with 1 thread and with --threads, compare the outputs\n"
    "  --repeat N      runs of each side for --scaling, best time kept (default 1)\n";

/// Reads the options; false (after printing the usage) for --help or a bad option, with `status`
/// the exit status to give.
bool parseOptions(int argc, char** argv, Options& options, int& status) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--help" || arg == "-h") {
      std::fputs(kUsage, stdout);
      status = 0;
      return false;
    } else if (arg == "--scaling") {
      options.scaling = true;
    } else if (arg == "--elements" && hasValue) {
      options.elements = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--deck" && hasValue) {
      options.deck = argv[++i];
    } else if (arg == "--part" && hasValue) {
      options.part = argv[++i];
    } else if (arg == "--threads" && hasValue) {
      options.settings.threads = std::atoi(argv[++i]);
    } else if (arg == "--size" && hasValue) {
      options.settings.targetSize = std::atof(argv[++i]);
    } else if (arg == "--keep" && hasValue) {
      options.keep = argv[++i];
    } else if (arg == "--repeat" && hasValue) {
      options.repeat = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "bench_remesh: bad option %s\n%s", arg.c_str(), kUsage);
      status = 2;
      return false;
    }
  }
  return true;
}

/// One timed remesh of the deck file as the CLI does it: read, remesh, write to `out`.
struct RemeshRun {
  double read = 0.0, remesh = 0.0, write = 0.0, total = 0.0;
  std::size_t before = 0, after = 0;
  RemeshReport report;
};

RemeshRun timedRemesh(const std::filesystem::path& in, const std::filesystem::path& out,
                      const RemeshSettings& settings) {
  RemeshRun run;
  const auto total = std::chrono::steady_clock::now();
  auto stage = std::chrono::steady_clock::now();
  FeModel deck = readDeck(in);
  run.read = secondsSince(stage);
  run.before = deck.shells.size();
  stage = std::chrono::steady_clock::now();
  run.report = remeshDeck(deck, settings);
  run.remesh = secondsSince(stage);
  stage = std::chrono::steady_clock::now();
  writeDeck(deck, out);
  run.write = secondsSince(stage);
  run.total = secondsSince(total);
  run.after = deck.shells.size();
  return run;
}

bool sameBytes(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::ifstream x(a, std::ios::binary), y(b, std::ios::binary);
  return std::equal(std::istreambuf_iterator<char>(x), std::istreambuf_iterator<char>(),
                    std::istreambuf_iterator<char>(y), std::istreambuf_iterator<char>());
}

/// --scaling: the remesh with 1 thread and with `threads`, best of `repeat` each, in turn.
void compareThreads(const std::filesystem::path& in, const std::filesystem::path& dir,
                    RemeshSettings settings, int repeat) {
  const int threads = settings.threads > 0 ? settings.threads : tbb::info::default_concurrency();
  double one = std::numeric_limits<double>::infinity(), many = one;
  for (int r = 0; r < repeat; ++r) {
    settings.threads = 1;
    one = std::min(one, timedRemesh(in, dir / "out_1.k", settings).total);
    settings.threads = threads;
    many = std::min(many, timedRemesh(in, dir / "out_n.k", settings).total);
  }
  std::printf(
      "remesh with 1 thread %.2f s, with %d threads %.2f s (best of %d each): %.2f x; "
      "outputs %s\n",
      one, threads, many, repeat, one / many,
      sameBytes(dir / "out_1.k", dir / "out_n.k") ? "byte for byte the same" : "DIFFER");
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  int status = 0;
  if (!parseOptions(argc, argv, options, status)) return status;
  try {
    const std::filesystem::path dir =
        options.keep.empty() ? std::filesystem::temp_directory_path() / "voxremesh-bench-remesh"
                             : options.keep;
    std::filesystem::create_directories(dir);
    std::filesystem::path in = options.deck;
    if (in.empty()) {
      const FeModel part = readDeck(options.part);
      const std::size_t copies = (options.elements + part.shells.size() - 1) / part.shells.size();
      in = dir / "deck.k";
      writeDeck(replicate(part, copies), in);
    }
    if (options.scaling) {
      compareThreads(in, dir, options.settings, options.repeat);
    } else {
      const RemeshRun run = timedRemesh(in, dir / "out.k", options.settings);
      double volume = 0, extract = 0, optimize = 0, accept = 0, whole = 0;
      for (const RemeshedPart& p : run.report.parts) {
        volume += p.volumeSeconds;
        extract += p.extractSeconds;
        optimize += p.optimizeSeconds;
        accept += p.acceptSeconds;
        whole += p.totalSeconds;
      }
      std::printf("deck: %zu parts, %zu shells -> %zu shells\n", run.report.parts.size(),
                  run.before, run.after);
      std::printf(
          "total %.2f s: read %.2f s, remesh %.2f s wall, write %.2f s\n"
          "part-seconds (each part's own): %.2f, of which volume %.2f, extract %.2f, optimise "
          "%.2f, acceptance %.2f, other (sheets, plans, seams) %.2f; assembly %.2f s\n",
          run.total, run.read, run.remesh, run.write, whole, volume, extract, optimize, accept,
          whole - volume - extract - optimize - accept, run.report.assemblySeconds);
      std::printf("peak memory %ld MB (before the OpenVDB comparison)\n", peakMegabytes());
      const FeModel original = readDeck(in);
      std::vector<Id> parts;
      for (const RemeshedPart& p : run.report.parts) parts.push_back(p.plan.part);
      std::sort(parts.begin(), parts.end());
      const std::map<Id, QuadMesh> shells = quadMeshesFromModel(original, parts);
      std::size_t vdbQuads = 0;
      const double vdbSeconds =
          openvdbPipeline(shells, run.report, options.settings.threads, vdbQuads);
      std::printf(
          "OpenVDB meshToVolume + volumeToMesh of the same parts: %.2f s wall (%zu quads, "
          "both sides of each sheet); voxremesh remesh / OpenVDB = %.2f\n",
          vdbSeconds, vdbQuads, run.remesh / vdbSeconds);
    }
    if (options.keep.empty()) std::filesystem::remove_all(dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_remesh: %s\n", e.what());
    return 1;
  }
  return 0;
}
