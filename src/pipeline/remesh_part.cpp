// remeshPart: one part through its sheets and volumes, at finer voxels until its mesh passes the
// acceptance, else kept (remesh_part.h).
#include <algorithm>
#include <chrono>
#include <exception>
#include <limits>
#include <new>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "extract/narrow_sheet.h"
#include "pipeline/remesh_part.h"
#include "pipeline/seam_spacing.h"
#include "voxremesh/deck_compare.h"
#include "voxremesh/errors.h"

namespace voxremesh::pipeline {

namespace {

/// A junction node is a node of the part's mesh when a point lies within this share of the
/// target size of it in every coordinate (sheets welded at a junction may differ in last bits).
constexpr double kJunctionNodeShare = 1e-6;
/// A narrow sheet's chords may lie this share of the target size from it: half the distance limit.
constexpr double kNarrowChordShare = 0.125;
/// A narrow sheet's edges across it may be this many times its width (or spacing) long.
constexpr double kNarrowChordWidths = 3.0;

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// How one sheet is meshed in an attempt: from its boundary alone (narrow_sheet.h) with nodes
/// `size` apart, made once when planning (`boundaryMesh`, the same for every attempt), or
/// through a volume of voxel `size`.
struct SheetPlan {
  bool fromBoundary = false;
  double size = 0.0;
  QuadMesh boundaryMesh;
};

/// What the sheets of one part must keep: per sheet, the hard points inside it (placeHardPoints).
using SheetHardPoints = std::vector<std::vector<Point3>>;

/// The element size a boundary-meshed sheet's mesh is judged against: its node spacing, or
/// where the sheet is narrower, twice its narrowest element (LS-DYNA characteristic length),
/// which a row of elements across a strip cannot make wider than the strip.
double boundaryMeshSize(const QuadMesh& mesh, double spacing) {
  double narrowest = std::numeric_limits<double>::infinity();
  for (const ElementQuality& quality : elementQualities(mesh))
    narrowest = std::min(narrowest, quality.minLength);
  return std::min(spacing, 2.0 * narrowest);
}

/// One sheet's mesh from its boundary alone (narrow_sheet.h), nodes `spacing` apart along it
/// (with `followShortPieces`, nodes on free stretches also following short pieces across:
/// NarrowSheetSettings::followShortPieces); the hard points inside the sheet are snapped to nodes
/// inside the mesh (a grid's); then, when `optimize` and settings.optimize, optimised at the
/// spacing as a volume's mesh is, its minimum length judged as the part's acceptance judges it
/// (at boundaryMeshSize); where the split of failing quads is on (the search engine's kSplitQuad
/// phase), it splits every quad whose triangles fail fewer criteria, whatever the triangle share:
/// the rows chose their faces for fewer failing elements first and fewer triangles only then
/// (polygon_quads.h), and their optimisation keeps that order. Throws extract::NarrowSheetRefusal
/// when the sheet cannot be meshed so, or a hard point finds no node inside the mesh within
/// `spacing`.
QuadMesh meshFromBoundary(const Sheet& sheet, const QuadMesh& surface,
                          const ReferenceSurface& original, double spacing, double targetSize,
                          double junctionSpacing, const std::vector<Point3>& hardPoints,
                          const RemeshSettings& settings, bool optimize = true,
                          bool followShortPieces = false) {
  extract::NarrowSheetSettings narrow;
  narrow.spacing = spacing;
  narrow.tolerance = kNarrowChordShare * targetSize;
  narrow.maxChord = kNarrowChordWidths * std::max(sheetWidth(sheet), spacing);
  narrow.sagittaShare = kChordSagittaShare;
  narrow.followShortPieces = followShortPieces;
  narrow.criteria = settings.optimizeSettings.quality;
  QuadMesh mesh = extract::meshNarrowSheet(
      sheet, surface, original,
      sheetJunctionNodes(sheet, extractJunctionSpacing(settings, junctionSpacing)), narrow);
  const std::size_t placed = snapHardPoints(mesh, hardPoints, spacing) +
                             insertHardPoints(mesh, hardPoints, narrow.tolerance);
  if (placed < hardPoints.size())
    throw extract::NarrowSheetRefusal(std::to_string(hardPoints.size() - placed) + " of its " +
                                      std::to_string(hardPoints.size()) +
                                      " hard points inside it (nodes other keywords use) find no "
                                      "node inside its mesh");
  if (optimize && settings.optimize) {
    OptimizeSettings optimizeSettings = settings.optimizeSettings;
    optimizeSettings.quality.targetSize = spacing;
    // The other criteria, the distance and the edits' scale stay at the spacing; a minimum
    // length in model units stays as it is.
    if (!optimizeSettings.quality.minLengthAbsolute)
      optimizeSettings.quality.minLengthFactor *= boundaryMeshSize(mesh, spacing) / spacing;
    if (optimizeSettings.splitFailingShare > 0.0) optimizeSettings.splitFailingShare = 1.0;
    optimizeQuadMesh(mesh, original, optimizeSettings);
  }
  return mesh;
}

/// The sheet with a boundary loop along each junction curve that runs wholly inside it (off its
/// boundary loops: a stiffener standing on a line inside a panel), there and back: a slit whose
/// two lips the boundary strip meets with the curve's nodes, welded into one after extraction.
Sheet withSlits(const Sheet& sheet) {
  std::vector<char> onLoop(sheet.points.size(), 0);
  for (const Polyline& loop : sheet.boundaryLoops)
    for (const PointIndex p : loop.points) onLoop[p] = 1;
  Sheet result = sheet;
  for (const Polyline& curve : sheet.junctionCurves) {
    if (curve.closed || curve.points.size() < 2 ||
        std::any_of(curve.points.begin(), curve.points.end(),
                    [&](PointIndex p) { return onLoop[p] != 0; }))
      continue;
    Polyline slit;
    slit.closed = true;
    slit.points = curve.points;
    slit.points.insert(slit.points.end(), curve.points.rbegin() + 1, curve.points.rend() - 1);
    result.boundaryLoops.push_back(std::move(slit));
  }
  return result;
}

/// The mesh of `voxelised` (a sheet, or it withSlits) through a volume of the given voxel size,
/// extracted, with the hard points inside the sheet snapped to, and optimised on `original`.
QuadMesh meshVolumeOf(const Sheet& voxelised, const ReferenceSurface& original, double voxel,
                      const RemeshSettings& settings, double junctionSpacing,
                      const std::vector<Point3>& hardPoints, RemeshedPart& part,
                      const StageCallback& stage) {
  VolumeSettings volumeSettings = settings.volume;
  volumeSettings.rule = VoxelSizeRule::TargetElementSize;
  volumeSettings.targetElementSize = voxel;
  ExtractSettings extractSettings = settings.extract;
  extractSettings.junctionSpacing = extractJunctionSpacing(settings, junctionSpacing);
  if (stage) stage("volume");
  auto start = std::chrono::steady_clock::now();
  const Volume volume = buildVolume({voxelised}, volumeSettings);
  part.volumeSeconds += since(start);
  if (stage) stage("extract");
  start = std::chrono::steady_clock::now();
  ExtractStats stats;
  QuadMesh mesh = extractQuadMesh(volume, extractSettings, &stats);
  snapHardPoints(mesh, hardPoints, voxel);
  addExtractStats(part.extract, stats);
  part.extractSeconds += since(start);
  if (settings.optimize) {
    if (stage) stage("optimize");
    start = std::chrono::steady_clock::now();
    OptimizeSettings optimizeSettings = settings.optimizeSettings;
    optimizeSettings.quality.targetSize = voxel;
    optimizeQuadMesh(mesh, original, optimizeSettings);
    part.optimizeSeconds += since(start);
  }
  return mesh;
}

/// One sheet's mesh through a volume of the given voxel size (meshVolumeOf). A volume cannot
/// hold a line inside a sheet: where the mesh misses nodes of junction curves wholly inside the
/// sheet, the sheet is meshed again with those curves as slits (withSlits), and that mesh is
/// taken when it has every junction node (else the first stays, and the part's check of its
/// junction nodes refuses it).
QuadMesh meshThroughVolume(const Sheet& sheet, const ReferenceSurface& original, double voxel,
                           const RemeshSettings& settings, double junctionSpacing,
                           const std::vector<Point3>& hardPoints, RemeshedPart& part,
                           const StageCallback& stage) {
  QuadMesh mesh =
      meshVolumeOf(sheet, original, voxel, settings, junctionSpacing, hardPoints, part, stage);
  const Sheet slitted = withSlits(sheet);
  if (slitted.boundaryLoops.size() == sheet.boundaryLoops.size()) return mesh;
  const std::vector<Point3> nodes =
      sheetJunctionNodes(sheet, extractJunctionSpacing(settings, junctionSpacing)).nodes();
  const double tolerance = kJunctionNodeShare * voxel;
  if (missingPoints(mesh, nodes, tolerance) == 0) return mesh;
  try {
    QuadMesh slit =
        meshVolumeOf(slitted, original, voxel, settings, junctionSpacing, hardPoints, part, stage);
    if (missingPoints(slit, nodes, tolerance) == 0) return slit;
  } catch (const SettingError&) {
    throw;
  } catch (const std::runtime_error&) {  // the first mesh stays
  }
  return mesh;
}

/// One sheet's mesh through a volume of voxel `voxel`; where the extraction fails (the sheet too
/// narrow somewhere for the voxel), from its boundary instead when it can be (narrow_sheet.h,
/// nodes `voxel` apart or its rowLength where that is less). `size` is lowered to the
/// size the mesh is judged at. Throws the extraction's error (with the refusal) when neither works.
QuadMesh meshThroughVolumeOrBoundary(const Sheet& sheet, const QuadMesh& surface,
                                     const ReferenceSurface& original, double voxel,
                                     const PartPlan& plan, const RemeshSettings& settings,
                                     double junctionSpacing, const std::vector<Point3>& hardPoints,
                                     RemeshedPart& part, double& size, const StageCallback& stage) {
  try {
    QuadMesh mesh = meshThroughVolume(sheet, original, voxel, settings, junctionSpacing, hardPoints,
                                      part, stage);
    size = std::min(size, voxel);
    return mesh;
  } catch (const SettingError&) {
    throw;
  } catch (const std::runtime_error& error) {
    const double spacing = std::min(voxel, rowLength(sheet, settings));
    try {
      QuadMesh mesh = meshFromBoundary(sheet, surface, original, spacing, plan.targetSize,
                                       junctionSpacing, hardPoints, settings);
      size = std::min(size, boundaryMeshSize(mesh, spacing));
      return mesh;
    } catch (const extract::NarrowSheetRefusal& refusal) {
      throw std::runtime_error(std::string(error.what()) + "; not meshed from its boundary (" +
                               refusal.what() + ")");
    }
  }
}

/// One attempt's mesh: every sheet meshed as its plan says (one sheet's volume alive at a
/// time), then joined at the junctions; the faces folded against their sheet flagged in
/// `folded`; `size` receives the element size to judge it against (the smallest any sheet
/// used: a voxel, or boundaryMeshSize).
QuadMesh meshSheets(const std::vector<Sheet>& sheets, const std::vector<SheetPlan>& plans,
                    const SheetHardPoints& hardPoints, const PartPlan& plan,
                    const RemeshSettings& settings, double junctionSpacing, RemeshedPart& part,
                    std::vector<std::uint8_t>& folded, double& size, const StageCallback& stage) {
  std::vector<QuadMesh> sheetMeshes;
  folded.clear();
  size = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < sheets.size(); ++k) {
    const std::string where = sheets.size() > 1 ? "sheet " + std::to_string(k) + ": " : "";
    const QuadMesh surface = sheetSurface(sheets[k]);
    const ReferenceSurface original(surface);
    try {
      if (plans[k].fromBoundary) {
        sheetMeshes.push_back(plans[k].boundaryMesh);
        size = std::min(size, boundaryMeshSize(sheetMeshes.back(), plans[k].size));
      } else {
        sheetMeshes.push_back(
            meshThroughVolumeOrBoundary(sheets[k], surface, original, plans[k].size, plan, settings,
                                        junctionSpacing, hardPoints[k], part, size, stage));
      }
    } catch (const SettingError&) {
      throw;
    } catch (const std::runtime_error& error) {
      throw std::runtime_error(where + error.what());
    }
    const std::vector<std::uint8_t> sheetFolds =
        foldedAgainstSheet(sheetMeshes.back(), surface, original);
    folded.insert(folded.end(), sheetFolds.begin(), sheetFolds.end());
  }
  QuadMesh mesh = joinAtJunctions(sheetMeshes);
  mesh.part = plan.part;
  return mesh;
}

/// The nodes the junction curves of `sheets` prescribe at `spacing` (as extraction places them),
/// each once: the seams of the part's mesh with its other sheets and parts.
std::vector<Point3> junctionNodePositions(const std::vector<Sheet>& sheets, double spacing) {
  std::vector<Point3> positions;
  for (const Sheet& sheet : sheets) {
    const std::vector<Point3> nodes = sheetJunctionNodes(sheet, spacing).nodes();
    positions.insert(positions.end(), nodes.begin(), nodes.end());
  }
  std::sort(positions.begin(), positions.end());
  positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
  return positions;
}

/// Thrown by an attempt that ends the part's attempts (out of memory, a refused budget).
struct StopAttempts {};

/// The plans of another attempt with sheets meshed from their boundary (meshFromBoundary) again;
/// empty when no sheet can be. With `fromVolumes`, each sheet `plans` meshes through a volume, with
/// nodes one target size apart (or its rowLength where that is less), not optimised (on a wide
/// sheet, such as a wing's skin, the edits move its area and the loads on it more than the rows
/// as made). Else each sheet `plans` meshes from its boundary, at its size, with the nodes of its
/// free stretches following short pieces across (NarrowSheetSettings::followShortPieces: a
/// wedge's junction nodes close toward its wide end, which the first nodes' rows cannot follow).
std::vector<SheetPlan> replannedFromBoundary(const std::vector<Sheet>& sheets,
                                             const SheetHardPoints& hardPoints,
                                             const PartPlan& plan, const RemeshSettings& settings,
                                             double junctionSpacing,
                                             const std::vector<SheetPlan>& plans,
                                             bool fromVolumes) {
  std::vector<SheetPlan> result = plans;
  bool any = false;
  for (std::size_t k = 0; k < sheets.size(); ++k) {
    if (plans[k].fromBoundary == fromVolumes) continue;
    const double spacing =
        fromVolumes ? std::min(plan.targetSize, rowLength(sheets[k], settings)) : plans[k].size;
    try {
      const QuadMesh surface = sheetSurface(sheets[k]);
      const ReferenceSurface original(surface);
      result[k] = {
          true, spacing,
          meshFromBoundary(sheets[k], surface, original, spacing, plan.targetSize, junctionSpacing,
                           hardPoints[k], settings, !fromVolumes, !fromVolumes)};
      any = true;
    } catch (const extract::NarrowSheetRefusal&) {
    }
  }
  if (!any) result.clear();
  return result;
}

/// Per sheet, per junction curve, 1 for a curve inside the part: between its own sheets only
/// (a fold cut, a fin of its own), none of its inner points and not both of its ends a node
/// of another part's shells in `model`. Such a curve's nodes are the part's own concern, and its
/// retries may place them closer.
std::vector<std::vector<std::uint8_t>> curvesInsidePart(const std::vector<Sheet>& sheets,
                                                        const FeModel& model, Id part) {
  std::unordered_set<Id> others;
  for (const Shell& shell : model.shells)
    if (shell.part != part)
      for (int c = 0; c < shell.nodeCount; ++c) others.insert(shell.nodes[std::size_t(c)]);
  std::vector<std::vector<std::uint8_t>> inside(sheets.size());
  for (std::size_t k = 0; k < sheets.size(); ++k)
    for (const Polyline& curve : sheets[k].junctionCurves) {
      auto shared = [&](std::size_t i) {
        return others.count(sheets[k].pointNodeIds[curve.points[i]]) > 0;
      };
      const std::size_t n = curve.points.size();
      bool seam = !curve.closed && n >= 2 && shared(0) && shared(n - 1);
      for (std::size_t i = curve.closed ? 0 : 1; i + (curve.closed ? 0 : 1) < n && !seam; ++i)
        seam = shared(i);
      inside[k].push_back(seam || curve.keepPoints ? 0 : 1);
    }
  return inside;
}

/// Halves the node spacing of the curves `inside` flags (curvesInsidePart; a curve without a
/// spacing of its own has `junctionSpacing`), down to `finest`. Every copy of a curve (one per
/// sheet along it) gets the same value. Returns per sheet whether one of its curves changed.
std::vector<std::uint8_t> halveInsideCurves(std::vector<Sheet>& sheets,
                                            const std::vector<std::vector<std::uint8_t>>& inside,
                                            double junctionSpacing, double finest) {
  std::vector<std::uint8_t> changed(sheets.size(), 0);
  for (std::size_t k = 0; k < sheets.size(); ++k)
    for (std::size_t c = 0; c < sheets[k].junctionCurves.size(); ++c) {
      if (!inside[k][c]) continue;
      Polyline& curve = sheets[k].junctionCurves[c];
      const double now = curve.nodeSpacing > 0.0 ? curve.nodeSpacing : junctionSpacing;
      const double half = std::max(finest, now / 2);
      if (half >= now * (1 - 1e-9)) continue;
      curve.nodeSpacing = half;
      if (curve.nodeCount > 0) curve.nodeCount *= 2;
      changed[k] = 1;
    }
  return changed;
}

/// How a junction curve's nodes are placed: its own spacing and count (Polyline::nodeSpacing,
/// Polyline::nodeCount).
using CurveSampling = std::pair<double, long>;

/// The sampling of every junction curve of `sheets`, sheet by sheet, in order.
std::vector<CurveSampling> junctionCurveSampling(const std::vector<Sheet>& sheets) {
  std::vector<CurveSampling> samplings;
  for (const Sheet& sheet : sheets)
    for (const Polyline& curve : sheet.junctionCurves)
      samplings.emplace_back(curve.nodeSpacing, curve.nodeCount);
  return samplings;
}

/// Gives the junction curves of `sheets` the samplings junctionCurveSampling returned for them.
void setJunctionCurveSampling(std::vector<Sheet>& sheets,
                              const std::vector<CurveSampling>& samplings) {
  std::size_t i = 0;
  for (Sheet& sheet : sheets)
    for (Polyline& curve : sheet.junctionCurves)
      std::tie(curve.nodeSpacing, curve.nodeCount) = samplings[i++];
}

/// The plans of a finer attempt: every sheet at half its size where that stays at `finest` or
/// above, a volume at half the voxel, a boundary-meshed sheet meshed again with nodes half as far
/// apart along its free stretches (as it was where that is refused), and meshed again at its size
/// where `curvesChanged` flags it (halveInsideCurves). False when no sheet got finer. Throws
/// extract::NarrowSheetRefusal when a flagged sheet cannot be meshed from its boundary.
bool halveSheetSizes(std::vector<SheetPlan>& plans, const std::vector<Sheet>& sheets,
                     const SheetHardPoints& hardPoints, const PartPlan& plan,
                     const RemeshSettings& settings, double junctionSpacing, double finest,
                     const std::vector<std::uint8_t>& curvesChanged) {
  bool finer = false;
  for (std::size_t k = 0; k < plans.size(); ++k) {
    SheetPlan& sheetPlan = plans[k];
    const double half = sheetPlan.size / 2;
    const bool halves = half >= finest * (1 - 1e-9);
    if (!halves && !(sheetPlan.fromBoundary && curvesChanged[k])) continue;
    const double size = halves ? half : sheetPlan.size;
    if (sheetPlan.fromBoundary) {
      // A boundary mesh whose curves got closer nodes is made again even at its size, so that
      // the sheets across those curves meet it on the same nodes.
      const QuadMesh surface = sheetSurface(sheets[k]);
      const ReferenceSurface original(surface);
      try {
        sheetPlan.boundaryMesh =
            meshFromBoundary(sheets[k], surface, original, size, plan.targetSize, junctionSpacing,
                             hardPoints[k], settings);
      } catch (const extract::NarrowSheetRefusal&) {
        if (curvesChanged[k]) throw;  // the caller goes back to the curves' previous nodes
        continue;
      }
    }
    sheetPlan.size = size;
    finer = finer || halves;
  }
  return finer;
}

/// The first attempt's plan per sheet: a sheet narrower than settings.narrowFeatureVoxels target
/// sizes is meshed from its boundary when it can be (nodes one target size apart along it, or its
/// rowLength where that is less, so that its elements pass the aspect criterion), else
/// through a volume with a voxel narrowFeatureVoxels times finer than its width (never below the
/// finest voxel); other sheets through a volume at the target size. `note` receives the
/// reductions in words.
std::vector<SheetPlan> planSheets(const std::vector<Sheet>& sheets,
                                  const SheetHardPoints& hardPoints, const PartPlan& plan,
                                  const RemeshSettings& settings, double junctionSpacing,
                                  std::string& note) {
  const double finest = settings.finestVoxelShare * plan.targetSize;
  std::vector<SheetPlan> plans;
  for (std::size_t k = 0; k < sheets.size(); ++k) {
    const double width = sheetWidth(sheets[k]);
    const bool narrow =
        settings.narrowFeatureVoxels > 0 && width < settings.narrowFeatureVoxels * plan.targetSize;
    if (!narrow) {
      plans.push_back({false, plan.targetSize, {}});
      continue;
    }
    const double spacing = sheetNodeSpacing(sheets[k], plan.targetSize, settings);
    try {
      const QuadMesh surface = sheetSurface(sheets[k]);
      const ReferenceSurface original(surface);
      plans.push_back({true, spacing,
                       meshFromBoundary(sheets[k], surface, original, spacing, plan.targetSize,
                                        junctionSpacing, hardPoints[k], settings)});
      if (spacing < plan.targetSize)
        note += std::string(note.empty() ? "" : "; ") + "sheet " + std::to_string(k) + " is " +
                formatNumber(width) + " wide: one row of elements " + formatNumber(spacing) +
                " long across it";
      continue;
    } catch (const extract::NarrowSheetRefusal& refusal) {
      const double voxel = std::max(finest, width / settings.narrowFeatureVoxels);
      plans.push_back({false, voxel, {}});
      note += std::string(note.empty() ? "" : "; ") + "voxel reduced to " + formatNumber(voxel) +
              ": sheet " + std::to_string(k) + " is " + formatNumber(width) +
              " wide, narrower than " + formatNumber(settings.narrowFeatureVoxels) + " voxels of " +
              formatNumber(plan.targetSize) + ", and not meshed from its boundary (" +
              refusal.what() + ")";
    }
  }
  return plans;
}

}  // namespace

double extractJunctionSpacing(const RemeshSettings& settings, double junctionSpacing) {
  return settings.extract.junctionSpacing > 0.0 ? settings.extract.junctionSpacing
                                                : junctionSpacing;
}

extract::JunctionNodes sheetJunctionNodes(const Sheet& sheet, double spacing) {
  std::vector<VolumeCurve> curves;
  for (const Polyline& curve : sheet.junctionCurves) curves.push_back(worldCurve(sheet, curve));
  return extract::JunctionNodes(curves, spacing, 0.2 * spacing, kChordSagittaShare);
}

RemeshedPart remeshPart(const FeModel& model, const PartPlan& plan, const RemeshSettings& settings,
                        const PartSurroundings& surroundings, QuadMesh& mesh,
                        const StageCallback& stage) {
  const double junctionSpacing = surroundings.junctionSpacing;
  RemeshedPart part;
  part.plan = plan;
  part.status = PartStatus::Kept;
  mesh = QuadMesh{};
  std::vector<Sheet> sheets;
  try {
    sheets = buildSheets(model, plan.part, settings.sheets);
    markKeptSeams(sheets, model, surroundings.keptParts);
  } catch (const std::bad_alloc&) {
    part.reason = "out of memory while splitting it into sheets";
    return part;
  } catch (const std::exception& error) {
    part.reason = error.what();
    return part;
  }
  if (sheets.empty()) {
    part.reason = "no shell with an area to remesh";
    return part;
  }
  std::string sizeNote;
  const SheetHardPoints hardPoints = placeHardPoints(sheets, surroundings.hardPoints);
  if (surroundings.seamSpacing) setSeamSpacing(sheets, *surroundings.seamSpacing, junctionSpacing);
  if (surroundings.seamSampling) setSeamSampling(sheets, *surroundings.seamSampling);
  std::vector<Point3> junctionPositions =
      junctionNodePositions(sheets, extractJunctionSpacing(settings, junctionSpacing));
  const std::vector<std::vector<std::uint8_t>> insideCurves =
      curvesInsidePart(sheets, model, plan.part);
  std::vector<Point3> hardPositions;
  for (const Node& node : model.nodes)
    if (surroundings.hardPoints.count(node.id)) hardPositions.push_back(node.xyz);
  std::vector<SheetPlan> plans =
      planSheets(sheets, hardPoints, plan, settings, junctionSpacing, sizeNote);
  const QuadMesh original = quadMeshFromModel(model, plan.part);
  const std::vector<MeshCurve> channels = channelCurves(sheets);
  const double finest = settings.finestVoxelShare * plan.targetSize;
  std::vector<std::string> failures;
  // One attempt with the sheet plans given; true when its mesh is accepted (then in `mesh`).
  const auto attempt = [&](const std::vector<SheetPlan>& attemptPlans, bool first) {
    double size = std::numeric_limits<double>::infinity();
    for (const SheetPlan& sheetPlan : attemptPlans) size = std::min(size, sheetPlan.size);
    ++part.attempts;
    part.extract = ExtractStats{};  // the counts of the attempt that ends the part
    std::string at = "size " + formatNumber(size) + ": ";
    try {
      std::vector<std::uint8_t> folded;
      QuadMesh candidate = meshSheets(sheets, attemptPlans, hardPoints, plan, settings,
                                      junctionSpacing, part, folded, size, stage);
      part.voxelSize = size;
      at = "size " + formatNumber(size) + ": ";
      const auto acceptStart = std::chrono::steady_clock::now();
      part.acceptance = acceptPartMesh(candidate, original, folded, size, plan.targetSize,
                                       settings.optimizeSettings.quality, channels);
      part.acceptSeconds += since(acceptStart);
      const std::size_t missing = missingPoints(candidate, hardPositions);
      if (part.acceptance.accepted && missing > 0) {
        failures.push_back(at + std::to_string(missing) + " of its " +
                           std::to_string(hardPositions.size()) +
                           " hard points (nodes other keywords use) are not nodes of the new mesh");
        return false;
      }
      const std::size_t loose =
          part.acceptance.accepted
              ? missingPoints(candidate, junctionPositions, kJunctionNodeShare * plan.targetSize)
              : 0;
      if (loose > 0) {
        failures.push_back(at + std::to_string(loose) + " of its " +
                           std::to_string(junctionPositions.size()) +
                           " junction nodes (where its sheets meet each other or other parts) are "
                           "not nodes of its mesh");
        return false;
      }
      if (!part.acceptance.accepted) {
        failures.push_back(at + part.acceptance.reason);
        return false;
      }
      part.status = first ? PartStatus::Remeshed : PartStatus::Retried;
      part.reason = sizeNote;
      part.quads = part.acceptance.quads;
      part.trias = part.acceptance.trias;
      mesh = std::move(candidate);
      return true;
    } catch (const std::bad_alloc&) {
      failures.push_back(at + "out of memory");
    } catch (const SettingError& error) {  // the memory budget or the grid's index range
      failures.push_back(at + error.what());
    } catch (const std::exception& error) {
      failures.push_back(at + error.what());
      return false;
    }
    throw StopAttempts{};
  };
  try {
    for (int retry = 0; retry <= settings.retries; ++retry) {
      if (retry > 0) {
        const std::vector<CurveSampling> samplingBefore = junctionCurveSampling(sheets);
        const std::vector<SheetPlan> plansBefore = plans;
        bool finer = false;
        try {
          finer =
              halveSheetSizes(plans, sheets, hardPoints, plan, settings, junctionSpacing, finest,
                              halveInsideCurves(sheets, insideCurves, junctionSpacing, finest));
        } catch (const extract::NarrowSheetRefusal&) {
          // A sheet meshed from its boundary cannot take its curves' closer nodes: all of them
          // keep theirs, and only the sizes are halved.
          setJunctionCurveSampling(sheets, samplingBefore);
          plans = plansBefore;
          finer = halveSheetSizes(plans, sheets, hardPoints, plan, settings, junctionSpacing,
                                  finest, std::vector<std::uint8_t>(sheets.size(), 0));
        }
        if (!finer) break;
        junctionPositions =
            junctionNodePositions(sheets, extractJunctionSpacing(settings, junctionSpacing));
      }
      if (attempt(plans, retry == 0)) return part;
      // The same sizes again with its boundary meshes' nodes following short pieces across.
      const std::vector<SheetPlan> following =
          replannedFromBoundary(sheets, hardPoints, plan, settings, junctionSpacing, plans, false);
      if (!following.empty() && attempt(following, retry == 0)) return part;
    }
    // Last: every volume sheet that can be meshed from its boundary so (a tube, a cup, a box
    // whose volume mesh lost or added a loop).
    std::vector<SheetPlan> fromBoundary =
        replannedFromBoundary(sheets, hardPoints, plan, settings, junctionSpacing, plans, true);
    if (!fromBoundary.empty() && attempt(fromBoundary, false)) {
      part.reason += std::string(part.reason.empty() ? "" : "; ") +
                     "meshed from its sheets' boundaries after " + std::to_string(failures.size()) +
                     " attempts through volumes";
      return part;
    }
  } catch (const StopAttempts&) {
  }
  for (const std::string& failure : failures)
    part.reason += (part.reason.empty() ? "" : "; ") + failure;
  if (!sizeNote.empty()) part.reason += " (" + sizeNote + ")";
  return part;
}

}  // namespace voxremesh::pipeline
