// optimizeQuadMesh: the optimisation steps in order, with per-step timings.
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "optimize/steps.h"
#include "voxremesh/errors.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void checkOptimizeSettings(const OptimizeSettings& s) {
  checkQualitySettings(s.quality);
  if (s.warpingDeg && !(*s.warpingDeg >= 0.0 && *s.warpingDeg <= 180.0))
    throw SettingError("optimize: warpingDeg " + std::to_string(*s.warpingDeg) +
                       " is outside 0 .. 180");
  if (s.warpingIterations < 0 || s.relaxIterations < 0 || s.improveSweeps < 0 ||
      s.reconnectRounds < 0 || s.fitPasses < 0)
    throw SettingError("optimize: iteration counts must be >= 0");
  if (!(s.relaxDamping > 0.0 && s.relaxDamping <= 0.7))
    throw SettingError("optimize: relaxDamping " + std::to_string(s.relaxDamping) +
                       " is outside (0, 0.7]");
  if (!std::isfinite(s.shortEdgeFactor) || s.shortEdgeFactor < 0.0 || s.shortEdgeFactor > 1.0)
    throw SettingError("optimize: shortEdgeFactor " + std::to_string(s.shortEdgeFactor) +
                       " is outside 0 .. 1");
  if (!std::isfinite(s.splitLengthFactor) || s.splitLengthFactor < 0.0 ||
      (s.splitLengthFactor > 0.0 && s.splitLengthFactor < 1.0))
    throw SettingError("optimize: splitLengthFactor " + std::to_string(s.splitLengthFactor) +
                       " is neither 0 nor >= 1");
  if (!std::isfinite(s.splitChordFactor) || s.splitChordFactor < 0.0)
    throw SettingError("optimize: splitChordFactor " + std::to_string(s.splitChordFactor) +
                       " is not finite and >= 0");
  if (!(s.splitFailingShare >= 0.0 && s.splitFailingShare <= 1.0))
    throw SettingError("optimize: splitFailingShare " + std::to_string(s.splitFailingShare) +
                       " is outside 0 .. 1");
  if (!(s.warpingMoveFactor > 0.0))
    throw SettingError("optimize: warpingMoveFactor " + std::to_string(s.warpingMoveFactor) +
                       " is not > 0");
  if (!std::isfinite(s.zeroAreaFactor) || s.zeroAreaFactor < 0.0)
    throw SettingError("optimize: zeroAreaFactor " + std::to_string(s.zeroAreaFactor) +
                       " is not finite and >= 0");
}

}  // namespace

void optimizeQuadMesh(QuadMesh& mesh, const ReferenceSurface& original,
                      const OptimizeSettings& settings, OptimizeStats* stats) {
  checkOptimizeSettings(settings);
  if (original.empty()) throw std::invalid_argument("optimizeQuadMesh: empty original surface");
  const Clock::time_point start = Clock::now();
  OptimizeStats s;
  QualitySettings quality = settings.quality;
  if (quality.targetSize == 0.0) quality.targetSize = medianEdgeLength(mesh);
  CleanupSettings cleanupSettings;
  cleanupSettings.zeroArea = settings.zeroAreaFactor * quality.targetSize * quality.targetSize;
  cleanupSettings.shortEdge = settings.shortEdgeFactor * quality.targetSize;
  cleanupSettings.foldedCurves = settings.collapseFoldedCurves;
  // What the steps find of the whole mesh (its topology, the faces failing) is kept for the next
  // steps while it holds.
  opt::MeshCache cache(quality);

  auto cleanUp = [&] {
    const Clock::time_point t = Clock::now();
    const CleanupResult r = cleanUpMesh(mesh, cleanupSettings, cache);
    s.cleanup.zeroAreaFaces += r.zeroAreaFaces;
    s.cleanup.shortEdges += r.shortEdges;
    s.cleanup.duplicateFaces += r.duplicateFaces;
    s.cleanup.valence2Points += r.valence2Points;
    s.cleanup.foldedCurveFaces += r.foldedCurveFaces;
    s.cleanupSeconds += secondsSince(t);
  };
  auto relax = [&] {
    const Clock::time_point t = Clock::now();
    relaxMesh(mesh, original, settings.relaxIterations, settings.relaxDamping, quality.targetSize,
              cache);
    s.relaxSeconds += secondsSince(t);
  };

  if (settings.splitLengthFactor > 0.0 && quality.targetSize > 0.0) {
    const Clock::time_point t = Clock::now();
    s.edgesSplit = splitLongEdges(mesh, settings.splitLengthFactor * quality.targetSize, &original,
                                  settings.splitChordFactor * quality.targetSize);
    s.splitSeconds = secondsSince(t);
  }
  cleanUp();
  if (settings.collapseRhombic) {
    const Clock::time_point t = Clock::now();
    s.rhombicCollapsed = collapseRhombicQuads(mesh, &original, cache);
    s.rhombicSeconds = secondsSince(t);
    cleanUp();
  }
  relax();
  if (settings.mergeTriangles && quality.targetSize > 0.0) {
    const Clock::time_point t = Clock::now();
    s.trianglesMerged = mergeTrianglePairs(mesh, quality, cache);
    s.mergeSeconds = secondsSince(t);
    relax();
  }
  // The pass over failing elements before the warping removal and again after it: the flattened
  // quads open moves the first pass could not take. It takes only moves that leave fewer
  // criteria failing around the point, warping included, so the warped count does not grow back
  // on balance.
  const bool improve = settings.improveSweeps > 0 && quality.targetSize > 0.0;
  auto improveFailing = [&] {
    const Clock::time_point t = Clock::now();
    s.improvedMoves +=
        improveFailingElements(mesh, original, quality, settings.improveSweeps, cache);
    s.improveSeconds += secondsSince(t);
  };
  // The search engine (reconnectFailingFaces) in three phases: pairs of faces recut, without
  // searches, after the first improvement pass; every edit but the quad split, with searches,
  // after the warping removal; last the quads two triangles do better than split, within the
  // triangle share, until none is (a split locks its neighbourhood for the round).
  const auto engine = [&](int rounds, int sweeps, unsigned edits) {
    ReconnectSettings reconnect;
    reconnect.rounds = rounds;
    reconnect.sweeps = sweeps;
    reconnect.edits = edits;
    reconnect.maxTriangleShare = settings.splitFailingShare;
    return reconnectFailingFaces(mesh, original, quality, reconnect, cache);
  };
  if (improve) improveFailing();
  // The recut pairs (edge rotations) after the first improvement pass, and the improvement again
  // where any was recut.
  if (settings.rotateEdges && quality.targetSize > 0.0) {
    const Clock::time_point t = Clock::now();
    s.edgesRotated = engine(5, 0, kRecutPair);
    s.rotateSeconds = secondsSince(t);
    if (s.edgesRotated > 0 && improve) improveFailing();
  }
  const Clock::time_point t = Clock::now();
  const double warpingDeg =
      settings.warpingDeg.value_or(kWarpingRemovalShare * quality.maxWarpingDeg);
  s.warping = removeWarping(mesh, warpingDeg, settings.warpingIterations,
                            settings.warpingMoveFactor * quality.targetSize, cache);
  s.warpingSeconds = secondsSince(t);
  // Folds out before the last passes, which then work on the filled regions too.
  s.foldsRefilled = refillFoldedRegions(mesh, original, quality, cache);
  if (improve) improveFailing();
  if (settings.reconnectRounds > 0 && quality.targetSize > 0.0) {
    const Clock::time_point r = Clock::now();
    s.reconnected = engine(settings.reconnectRounds, 3, ReconnectSettings{}.edits);
    s.reconnectSeconds = secondsSince(r);
  }
  if (settings.fitPasses > 0 && quality.targetSize > 0.0) {
    const Clock::time_point f = Clock::now();
    s.farPulls = fitFarOriginalPoints(mesh, original, quality, settings.fitPasses, cache);
    s.fitSeconds = secondsSince(f);
  }
  const Clock::time_point q = Clock::now();
  if (settings.splitFailingShare > 0.0 && quality.targetSize > 0.0)
    s.failingSplit = engine(20, 0, kSplitQuad);
  s.invertedSplit = splitInvertedQuads(mesh, quality.degenerateCornerDeg);
  s.quadSplitSeconds = secondsSince(q);
  // The last passes move points and split quads: a fold they leave (a sliver along a boundary edge
  // turned over as its neighbour quad is split) is cut out as the first ones were.
  s.foldsRefilled += refillFoldedRegions(mesh, original, quality, cache);
  s.totalSeconds = secondsSince(start);
  if (stats) *stats = s;
}

}  // namespace voxremesh
