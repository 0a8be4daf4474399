// bench_optimize: the optimisation stage on a real part, next to the extraction it follows.
//
// Reads a deck (default ../shared/data/bracket.k), voxelizes its one shell part at the target size
// (default 4.5 mm, the bracket's median edge length), extracts the quad mesh and optimises it,
// timing each step (best of --repeat runs of the extraction and of the optimisation, each on a
// fresh copy of the extracted mesh). Prints the times, the quality of the extracted and the
// optimised mesh against the default criteria (failing share, triangle share, two-sided distance to
// the input shells), and the number of boundary loops (outer contour and holes) of the input and of
// both meshes. For comparison in the same run, OpenVDB's volumeToMesh on the same grid, as it is
// and with its own mesh adaptation (adaptivity 0.5, relaxation of disoriented triangles). The
// failing share is given for all criteria of quality.h and for the ones the shared data README
// measures the input decks with (warping, angles, aspect, scaled Jacobian). Options:
// --part PID (a deck with several parts), --size H, --threads N (default: all),
// --repeat N (default 3), --short-edge F (OptimizeSettings::shortEdgeFactor), --split F
// (OptimizeSettings::splitLengthFactor), --chord F (splitChordFactor), -o OUT.k (write the
// optimised mesh).
//
// usage: bench_optimize [DECK] [--part PID] [--size H] [--threads N] [--repeat N] [--short-edge F]
// [--split F] [--chord F]
// [-o OUT.k]
#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "volume/volume_grids.h"
#include "voxremesh/extract.h"
#include "voxremesh/io.h"
#include "voxremesh/optimize.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"
#include "voxremesh/sheets.h"
#include "voxremesh/volume.h"

namespace {

using voxremesh::bench::secondsSince;

using namespace voxremesh;
using Clock = std::chrono::steady_clock;

/// The share of elements failing one of the criteria the shared data README measures the input
/// decks with (warping, angles, aspect, scaled Jacobian): 5.1 % for the bracket itself.
double readmeShare(const QualityReport& r) {
  std::uint32_t mask = 0;
  for (const Criterion c : {Criterion::Warping, Criterion::AspectRatio, Criterion::QuadMinAngle,
                            Criterion::QuadMaxAngle, Criterion::TriaMinAngle,
                            Criterion::TriaMaxAngle, Criterion::ScaledJacobian})
    mask |= 1u << static_cast<int>(c);
  std::size_t failing = 0;
  for (const std::uint32_t failures : r.elementFailures) failing += (failures & mask) ? 1 : 0;
  return r.elements ? double(failing) / double(r.elements) : 0.0;
}

void printQuality(const char* name, const QuadMesh& mesh, const QuadMesh& original,
                  double targetSize) {
  QualitySettings settings;
  settings.targetSize = targetSize;
  const QualityReport r = assessQuality(mesh, settings, &original);
  settings.jacobianAtGaussPoints = true;
  const double gaussShare = assessQuality(mesh, settings).failingAnyShare;
  std::printf(
      "%-10s %5zu elements, %5.2f %% trias, %5.2f %% failing any criterion (%5.2f %% with "
      "the Jacobian at the Gauss points), %5.2f %% any of the README's, distance max "
      "%.3f mean %.3f (limit %.3f), %zu boundary loops\n",
      name, r.elements, 100.0 * r.triangleShare, 100.0 * r.failingAnyShare, 100.0 * gaussShare,
      100.0 * readmeShare(r), r.distance->max(),
      std::max(r.distance->meanToOriginal, r.distance->meanFromOriginal), r.distanceLimit,
      topologyCounts(mesh).boundaryLoops);
  std::printf("          failing:");
  for (const CriterionSummary& c : r.criteria)
    if (c.failing) std::printf(" %s %zu", criterionName(c.criterion), c.failing);
  std::printf("\n");
}

int run(int argc, char** argv) {
  std::string deck = "../shared/data/bracket.k", out;
  double size = 4.5;
  int threads = 0, repeat = 3;
  double shortEdge = -1.0, split = -1.0, chord = -1.0;
  Id part = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--size" && hasValue)
      size = std::atof(argv[++i]);
    else if (arg == "--threads" && hasValue)
      threads = std::atoi(argv[++i]);
    else if (arg == "--repeat" && hasValue)
      repeat = std::max(1, std::atoi(argv[++i]));
    else if (arg == "--part" && hasValue)
      part = std::atoll(argv[++i]);
    else if (arg == "--short-edge" && hasValue)
      shortEdge = std::atof(argv[++i]);
    else if (arg == "--split" && hasValue)
      split = std::atof(argv[++i]);
    else if (arg == "--chord" && hasValue)
      chord = std::atof(argv[++i]);
    else if (arg == "-o" && hasValue)
      out = argv[++i];
    else if (!arg.empty() && arg[0] != '-')
      deck = arg;
    else {
      std::fprintf(stderr,
                   "usage: bench_optimize [DECK] [--part PID] [--size H] [--threads N] [--repeat "
                   "N] [--short-edge F] [--split F] [--chord F] [-o OUT.k]\n");
      return 2;
    }
  }
  std::unique_ptr<tbb::global_control> control;
  if (threads > 0)
    control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                    std::size_t(threads));

  const FeModel model = readDeck(deck);
  const std::vector<Sheet> sheets = part ? buildSheets(model, part) : buildAllSheets(model);
  if (sheets.empty()) throw std::runtime_error(deck + " has no shells of that part");
  for (const Sheet& sheet : sheets)
    if (sheet.part != sheets[0].part)
      throw std::runtime_error(deck + " has several parts: choose one with --part");
  const QuadMesh input = quadMeshFromModel(model, sheets[0].part);

  VolumeSettings volumeSettings;
  volumeSettings.targetElementSize = size;
  Clock::time_point t = Clock::now();
  const Volume volume = buildVolume(sheets, volumeSettings);
  const double voxelizeSeconds = secondsSince(t);
  ExtractStats extractStats;
  ExtractSettings extractSettings;
  QuadMesh extracted;
  t = Clock::now();
  try {
    extracted = extractQuadMesh(volume, extractSettings, &extractStats);
  } catch (const std::runtime_error& error) {
    // The boundary strip cannot always be rebuilt yet: measure the dual mesh without it.
    std::printf("note: %s\n      extracting without the boundary strip\n", error.what());
    extractSettings.rebuildBoundary = false;
    t = Clock::now();
    extracted = extractQuadMesh(volume, extractSettings, &extractStats);
  }
  double extractSeconds = secondsSince(t);
  // The extraction's best of --repeat runs too, as for the optimisation.
  for (int r = 1; r < repeat; ++r) {
    t = Clock::now();
    const QuadMesh again = extractQuadMesh(volume, extractSettings);
    extractSeconds = std::min(extractSeconds, secondsSince(t));
  }
  // OpenVDB's own counterpart on the same grid: volumeToMesh as it is (adaptivity 0), and with
  // its mesh adaptation (adaptivity 0.5, which merges cells where the surface is flat, and the
  // relaxation of disoriented triangles): what the ecosystem spends on a better mesh.
  const openvdb::FloatGrid& sdf = *volume.impl().sdf;
  auto vdbSeconds = [&](double adaptivity, bool relax, std::size_t& polygons) {
    double fastest = 0.0;
    for (int r = 0; r < repeat; ++r) {
      std::vector<openvdb::Vec3s> points;
      std::vector<openvdb::Vec3I> triangles;
      std::vector<openvdb::Vec4I> quads;
      const Clock::time_point start = Clock::now();
      openvdb::tools::volumeToMesh(sdf, points, triangles, quads, 0.0, adaptivity, relax);
      const double seconds = secondsSince(start);
      fastest = r == 0 ? seconds : std::min(fastest, seconds);
      polygons = triangles.size() + quads.size();
    }
    return fastest;
  };
  std::size_t plainPolygons = 0, adaptedPolygons = 0;
  const double vdbPlainSeconds = vdbSeconds(0.0, false, plainPolygons);
  const double vdbAdaptedSeconds = vdbSeconds(0.5, true, adaptedPolygons);
  t = Clock::now();
  const ReferenceSurface surface(input);
  const double surfaceSeconds = secondsSince(t);

  OptimizeSettings settings;
  settings.quality.targetSize = size;
  if (shortEdge >= 0.0) settings.shortEdgeFactor = shortEdge;
  if (split >= 0.0) settings.splitLengthFactor = split;
  if (chord >= 0.0) settings.splitChordFactor = chord;
  OptimizeStats best;
  QuadMesh optimised;
  for (int r = 0; r < repeat; ++r) {
    QuadMesh mesh = extracted;
    OptimizeStats stats;
    optimizeQuadMesh(mesh, surface, settings, &stats);
    if (r == 0 || stats.totalSeconds < best.totalSeconds) best = stats;
    optimised = std::move(mesh);
  }

  std::printf("%s: part %lld, %zu shells, target size %.3g, %d thread(s)\n", deck.c_str(),
              static_cast<long long>(sheets[0].part), input.faces.size(), size,
              threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  std::printf("  voxelize            %8.4f s\n", voxelizeSeconds);
  std::printf("  extract (best of %d) %7.4f s  (%zu quads, %zu strip trias)\n", repeat,
              extractSeconds, std::size_t(extractStats.dualQuads + extractStats.stripQuads),
              std::size_t(extractStats.stripTriangles));
  std::printf("  reference surface   %8.4f s\n", surfaceSeconds);
  std::printf("  optimise (best of %d):\n", repeat);
  std::printf("    edge splitting    %8.4f s  (%zu edges)\n", best.splitSeconds, best.edgesSplit);
  std::printf("    clean-up          %8.4f s  (%zu zero-area, %zu doublets, %zu folded)\n",
              best.cleanupSeconds, best.cleanup.zeroAreaFaces, best.cleanup.valence2Points,
              best.cleanup.foldedCurveFaces);
  std::printf("    rhombic collapse  %8.4f s  (%zu quads)\n", best.rhombicSeconds,
              best.rhombicCollapsed);
  std::printf("    relaxation        %8.4f s\n", best.relaxSeconds);
  std::printf("    triangle merging  %8.4f s  (%zu pairs)\n", best.mergeSeconds,
              best.trianglesMerged);
  std::printf("    failing elements  %8.4f s  (%zu moves)\n", best.improveSeconds,
              best.improvedMoves);
  std::printf("    edge rotation     %8.4f s  (%zu edges)\n", best.rotateSeconds,
              best.edgesRotated);
  std::printf("    reconnection      %8.4f s  (%zu neighbourhoods)\n", best.reconnectSeconds,
              best.reconnected);
  std::printf("    warping removal   %8.4f s  (%d iterations, %zu -> %zu warped)\n",
              best.warpingSeconds, best.warping.iterations, best.warping.warpedBefore,
              best.warping.warpedAfter);
  std::printf("    distance fitting  %8.4f s  (%zu points pulled)\n", best.fitSeconds,
              best.farPulls);
  std::printf("    quad splitting    %8.4f s  (%zu failing, %zu inverted)\n", best.quadSplitSeconds,
              best.failingSplit, best.invertedSplit);
  std::printf("    total             %8.4f s  = %.2f x the extraction\n", best.totalSeconds,
              best.totalSeconds / extractSeconds);
  std::printf(
      "  openvdb volumeToMesh (best of %d): %.4f s (%zu polygons); with adaptivity 0.5 and "
      "relaxation %.4f s (%zu polygons); the optimisation costs %.1f x the adapted "
      "volumeToMesh\n",
      repeat, vdbPlainSeconds, plainPolygons, vdbAdaptedSeconds, adaptedPolygons,
      best.totalSeconds / std::max(1e-9, vdbAdaptedSeconds));
  printQuality("input", input, input, size);
  printQuality("extracted", extracted, input, size);
  printQuality("optimised", optimised, input, size);
  if (!out.empty()) writeDeck(modelFromQuadMesh(optimised, sheets[0].part), out);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bench_optimize: %s\n", error.what());
    return 1;
  }
}
