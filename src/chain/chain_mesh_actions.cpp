// The chain's actions on quad meshes: -optimize (optimize.h) and -quality (quality.h); see
// action_chain.h for the stack and chain_actions.cpp for the action table.
#include <climits>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "chain/chain_stack.h"
#include "io/atomic_file.h"
#include "voxremesh/criteria_file.h"
#include "voxremesh/errors.h"
#include "voxremesh/io.h"
#include "voxremesh/optimize.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"
#include "voxremesh/remesh_quality.h"

namespace voxremesh::chain::detail {

namespace {

using Kind = ChainItem::Kind;

/// The shells of `part` (all shells for 0) of the deck in `path`, as a mesh.
QuadMesh originalFromFile(const ChainState& state, const std::string& path, Id part) {
  Warnings warnings;
  const FeModel deck = readDeck(path, {}, &warnings);
  warnAll(state, warnings);
  return quadMeshFromModel(partShells(deck, part, path));
}

bool hasShellsOf(const FeModel& deck, Id part) {
  for (const Shell& shell : deck.shells)
    if (shell.part == part) return true;
  return false;
}

/// The original surface of a mesh item: the deck of original= when given, else the shells the
/// item was made from, else the part's shells in the topmost deck that has them; nothing when
/// none of these exists.
std::optional<QuadMesh> originalOfMesh(const ChainState& state, const ChainItem& item,
                                       const ActionCall& call) {
  if (call.has("original")) return originalFromFile(state, call.text("original"), item.mesh.part);
  if (!item.original.faces.empty()) return item.original;
  for (auto it = state.stack.rbegin(); it != state.stack.rend(); ++it)
    if (it->kind == Kind::Deck && hasShellsOf(it->deck, item.mesh.part))
      return quadMeshFromModel(it->deck, item.mesh.part);
  return std::nullopt;
}

/// An option that must be a positive size when given.
double positiveSize(const ActionCall& call, const std::string& option, double fallback) {
  if (!call.has(option)) return fallback;
  const double value = call.number(option);
  if (!(value > 0))
    throw SettingError(option + "= must be a positive size, not " + call.text(option));
  return value;
}

/// An Integer option as an int within 0..INT_MAX.
int count(const ActionCall& call, const std::string& option) {
  const long long value = call.integer(option);
  if (value < 0 || value > INT_MAX)
    throw SettingError(option + "= must be a count of 0 or more, not " + call.text(option));
  return static_cast<int>(value);
}

}  // namespace

void runOptimize(ChainState& state, const ActionCall& call) {
  const ChainItem& source = topOf(state, Kind::Mesh);
  OptimizeSettings settings;
  if (call.has("criteria")) readCriteriaFile(call.text("criteria"), settings.quality);
  settings.quality.targetSize = positiveSize(call, "size", source.targetSize);
  if (call.has("warping")) settings.warpingDeg = call.number("warping");
  settings.warpingIterations = count(call, "iterations");
  settings.relaxIterations = count(call, "relax");
  settings.relaxDamping = call.number("damping");
  settings.collapseRhombic = call.flag("rhombic");
  settings.mergeTriangles = call.flag("merge");
  settings.collapseFoldedCurves = call.flag("folded");
  settings.shortEdgeFactor = call.number("short");
  settings.reconnectRounds = count(call, "reconnect");
  settings.fitPasses = count(call, "fit");
  settings.splitFailingShare = call.number("split");
  std::optional<QuadMesh> original = originalOfMesh(state, source, call);
  if (!original)
    throw std::runtime_error("no original surface for part " + std::to_string(source.mesh.part) +
                             " of " + source.name +
                             ": read the deck it was made from, or give original=FILE");
  ChainItem item;
  item.kind = Kind::Mesh;
  item.name = "optimised " + source.name;
  item.mesh = source.mesh;
  item.targetSize = source.targetSize;
  const ReferenceSurface surface(*original);
  item.original = std::move(*original);
  OptimizeStats stats;
  optimizeQuadMesh(item.mesh, surface, settings, &stats);
  say(state, "optimised part " + std::to_string(item.mesh.part) + ": " + meshCounts(item.mesh) +
                 " (" + std::to_string(stats.rhombicCollapsed) + " rhombic quads collapsed, " +
                 std::to_string(stats.trianglesMerged) + " triangle pairs merged, " +
                 std::to_string(stats.reconnected) + " neighbourhoods reconnected, " +
                 std::to_string(stats.farPulls) + " points pulled towards far places, " +
                 std::to_string(stats.failingSplit) + " failing quads split, warped quads " +
                 std::to_string(stats.warping.warpedBefore) + " -> " +
                 std::to_string(stats.warping.warpedAfter) + ")\n");
  state.stack.push_back(std::move(item));
}

void runQuality(ChainState& state, const ActionCall& call) {
  const ChainItem* item = nullptr;
  for (auto it = state.stack.rbegin(); it != state.stack.rend() && !item; ++it)
    if (it->kind == Kind::Mesh || it->kind == Kind::Deck) item = &*it;
  if (!item) throw std::runtime_error("needs a quad mesh or a deck on the stack; read one first");
  QualitySettings settings;
  if (call.has("criteria")) readCriteriaFile(call.text("criteria"), settings);
  settings.targetSize = positiveSize(call, "size", item->kind == Kind::Mesh ? item->targetSize : 0);
  checkQualitySettings(settings);

  FeModel shells;  // the elements as the .vtu shows them; node i is point i of `mesh`
  QuadMesh mesh;
  std::optional<QuadMesh> original;
  std::vector<MeshCurve> channels;
  std::string title = item->name;
  if (item->kind == Kind::Mesh) {
    if (call.has("part"))
      throw SettingError("part= applies to decks; the top quad mesh is part " +
                         std::to_string(item->mesh.part));
    mesh = item->mesh;
    shells = modelFromQuadMesh(mesh, mesh.part != 0 ? mesh.part : 1);
    original = originalOfMesh(state, *item, call);
    channels = mesh.curves;
  } else {
    const Id part = call.has("part") ? call.integer("part") : 0;
    shells = partShells(item->deck, part, item->name);
    mesh = quadMeshFromModel(shells);
    if (part) title += " part " + std::to_string(part);
    if (call.has("original")) original = originalFromFile(state, call.text("original"), part);
    channels = deckChannelCurves(item->deck, part);
  }
  QualityReport report = assessQuality(mesh, settings, original ? &*original : nullptr, &channels);
  if (call.has("json")) io::writeFileAtomically(call.text("json"), qualityReportJson(report));
  if (call.has("vtu")) {
    std::vector<FieldData> pointFields;
    if (report.distance) pointFields.push_back({"distance", report.distance->pointDistance});
    writeVtu(shells, call.text("vtu"), qualityCellFields(report), pointFields);
  }
  say(state, title + "\n" + formatQualityTable(report));
  state.quality = std::move(report);
}

}  // namespace voxremesh::chain::detail
