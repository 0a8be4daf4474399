// The actions of the chain (see action_chain.h) and the runner. Adding an action is one entry in
// kActions plus its function; optimize and quality live in chain_mesh_actions.cpp.
#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "chain/chain_stack.h"
#include "io/atomic_file.h"
#include "voxremesh/action_chain.h"
#include "voxremesh/deck_assembly.h"
#include "voxremesh/deck_report.h"
#include "voxremesh/errors.h"
#include "voxremesh/extract.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/sheets.h"
#include "voxremesh/slice_image.h"

namespace voxremesh::chain {

namespace {

using Kind = ChainItem::Kind;
using detail::kindName;
using detail::meshCounts;
using detail::say;
using detail::top;
using detail::topOf;
using detail::warnAll;

bool isVdb(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".vdb";
}

/// ", N sheets" for a volume of several sheets, "" for one.
std::string sheetCount(const std::vector<Volume>& volumes) {
  return volumes.size() > 1 ? ", " + std::to_string(volumes.size()) + " sheets" : "";
}

void runRead(ChainState& state, const ActionCall& call) {
  const std::filesystem::path path = call.text("file");
  ChainItem item;
  item.name = path.string();
  if (isVdb(path)) {
    item.kind = Kind::Volume;
    item.volumes = readVolumes(path);
    say(state, "read " + item.name + ": volume of part " +
                   std::to_string(item.volumes.front().info().part) + sheetCount(item.volumes) +
                   "\n");
  } else {
    ReadOptions options;
    if (call.has("format")) options.format = formatFromName(call.text("format"));
    Warnings warnings;
    item.deck = readDeck(path, options, &warnings);
    warnAll(state, warnings);
    say(state, "read " + item.name + ": " + std::to_string(item.deck.nodes.size()) + " nodes, " +
                   std::to_string(item.deck.shells.size()) + " shells\n");
  }
  state.stack.push_back(std::move(item));
}

void runVoxelize(ChainState& state, const ActionCall& call) {
  const ChainItem& source = topOf(state, Kind::Deck);
  const Id part =
      choosePart(source.deck, call.has("part") ? call.integer("part") : 0, source.name, "part=");
  SheetSettings sheetSettings;
  sheetSettings.featureAngleDeg = call.number("feature");
  VolumeSettings settings;
  settings.bandWidthVoxels = call.number("band");
  settings.invalidAngleDeg = call.number("invalid");
  if (call.has("size") && call.has("voxel"))
    throw SettingError("give either size= or voxel=, not both");
  if (call.has("voxel")) {
    settings.rule = VoxelSizeRule::Explicit;
    settings.voxelSize = call.number("voxel");
  } else {
    settings.rule = VoxelSizeRule::TargetElementSize;
    settings.targetElementSize =
        call.has("size") ? call.number("size") : defaultTargetSize(source.deck, part);
  }
  checkVolumeSettings(settings);
  const std::vector<Sheet> sheets = buildSheets(source.deck, part, sheetSettings);
  if (sheets.empty())
    throw std::runtime_error("part " + std::to_string(part) + " of " + source.name +
                             " has no shell with an area to voxelize");
  ChainItem item;
  item.kind = Kind::Volume;
  item.name = "volume of part " + std::to_string(part) + " of " + source.name;
  item.volumes = buildSheetVolumes(sheets, settings, VolumeSource{source.name});
  item.original = quadMeshFromModel(source.deck, part);
  item.targetSize = item.volumes.front().info().voxelSize;
  char text[160];
  std::snprintf(text, sizeof text, ": voxel size %.6g, %zu sheets\n", item.targetSize,
                sheets.size());
  say(state, "voxelized part " + std::to_string(part) + text);
  state.stack.push_back(std::move(item));
}

void runExtract(ChainState& state, const ActionCall& call) {
  const ChainItem& source = topOf(state, Kind::Volume);
  ChainItem item;
  item.kind = Kind::Mesh;
  ExtractStats stats;
  if (call.flag("triangles")) {
    item.mesh = extractPartTriangles(source.volumes);
    item.name = "MC33 triangles of " + source.name;
  } else {
    ExtractSettings settings;
    settings.rebuildBoundary = call.flag("boundary");
    settings.snapFeatures = call.flag("features");
    item.mesh = extractPartMesh(source.volumes, settings, &stats);
    item.name = "quad mesh of " + source.name;
  }
  item.original = source.original;
  item.targetSize = source.volumes.front().info().voxelSize;
  say(state,
      "extracted part " + std::to_string(item.mesh.part) + ": " + meshCounts(item.mesh) + "\n");
  state.stack.push_back(std::move(item));
}

void runWrite(ChainState& state, const ActionCall& call) {
  const std::filesystem::path path = call.text("file");
  const ChainItem& item = top(state);
  if (item.kind == Kind::Volume) {
    if (!isVdb(path))
      throw SettingError("the top item is a volume: write it to a .vdb file, not " + path.string());
    writeVolumes(item.volumes, path);
    say(state, "wrote " + path.string() + "\n");
    return;
  }
  if (isVdb(path))
    throw SettingError(std::string("the top item is a ") + kindName(item.kind) +
                       ": write it to a deck or mesh format, not .vdb");
  WriteOptions options;
  if (call.has("format")) options.format = formatFromName(call.text("format"));
  Warnings warnings;
  std::string note;
  if (item.kind == Kind::Deck) {
    writeDeck(item.deck, path, options, &warnings);
  } else {
    const ChainItem* host = nullptr;
    for (auto it = state.stack.rbegin(); it != state.stack.rend() && !host; ++it)
      if (it->kind == Kind::Deck && it->deck.findPart(item.mesh.part)) host = &*it;
    if (host) {
      FeModel deck = host->deck;
      const AssemblyReport report = replacePartMeshes(deck, {item.mesh});
      writeDeck(deck, path, options, &warnings);
      note = " (part " + std::to_string(item.mesh.part) + " replaced in " + host->name + ", " +
             std::to_string(report.remaps.size()) + " node references remapped, " +
             std::to_string(report.unmapped.size()) + " not remappable)";
      for (const UnmappedReference& ref : report.unmapped)
        warnings.push_back(ref.keyword + " at " +
                           (ref.blockLine ? "line " + std::to_string(ref.line) + " of its block"
                                          : (ref.file.empty() ? "" : ref.file + " ") + "line " +
                                                std::to_string(ref.line)) +
                           ": node " + std::to_string(ref.node) + " kept: " + ref.reason);
    } else {
      writeDeck(modelFromQuadMesh(item.mesh, item.mesh.part != 0 ? item.mesh.part : 1), path,
                options, &warnings);
    }
  }
  warnAll(state, warnings);
  say(state, "wrote " + path.string() + note + "\n");
}

void runPrint(ChainState& state, const ActionCall&) {
  const ChainItem& item = top(state);
  switch (item.kind) {
    case Kind::Deck:
      say(state, item.name + " (" + formatName(item.deck.sourceFormat) + ")\n\n" +
                     formatReportTable(reportDeck(item.deck)));
      return;
    case Kind::Volume:
      say(state, item.name + "\n\n" + formatVolumeReports(inspectVolumes(item.volumes)));
      return;
    case Kind::Mesh:
      say(state, item.name + ": quad mesh of part " + std::to_string(item.mesh.part) + ", " +
                     meshCounts(item.mesh) + ", " + std::to_string(item.mesh.curves.size()) +
                     " curves\n");
      return;
  }
}

void runSlice(ChainState& state, const ActionCall& call) {
  const ChainItem& item = topOf(state, Kind::Volume);
  SliceStyle style;
  const long long scale = call.integer("scale");
  if (scale < 0 || scale > 64) throw SettingError("scale= must be within 0..64 (0: automatic)");
  style.pixelsPerVoxel = static_cast<int>(scale);
  const Volume& volume = sheetVolume(item.volumes, call.integer("sheet"), "sheet=");
  const SliceImage image =
      renderSlice(volume, axisFromName(call.text("axis")), call.number("at"), style);
  writePng(image, call.text("file"));
  say(state, "wrote " + call.text("file") + ": " + std::to_string(image.width) + " x " +
                 std::to_string(image.height) + " pixels\n");
}

void runSaveChain(ChainState& state, const ActionCall& call) {
  io::writeFileAtomically(call.text("file"), formatChain(state.chain));
  say(state, "wrote " + call.text("file") + "\n");
}

void runNothing(ChainState&, const ActionCall&) {}

const OptionDef kFile{"file", OptionType::Text, "", "the file", true};
const OptionDef kCriteria{"criteria", OptionType::Text, "",
                          "a quality criteria file (include/voxremesh/criteria_file.h) for the "
                          "limits (default: share/criteria/default.txt's)"};
const OptionDef kFormat{"format", OptionType::Text, "",
                        "format name instead of the extension (k, bdf, inp, obj, ...)"};

const std::vector<ActionDef> kActions = {
    {"read",
     "read a deck or mesh (.k .bdf .inp .obj .off .stl .ply) or a volume (.vdb)",
     "file",
     {kFile, kFormat},
     runRead,
     ""},
    {"voxelize",
     "write one part of the top deck into signed-distance volumes, one per sheet",
     "",
     {{"size", OptionType::Number, "", "target element size (default: median edge of the part)"},
      {"voxel", OptionType::Number, "", "voxel size instead of size="},
      {"part", OptionType::Integer, "", "the part (may be left out for a one-part deck)"},
      {"band", OptionType::Number, "3", "narrow band half width in voxels"},
      {"feature", OptionType::Number, "45", "feature angle in degrees"},
      {"invalid", OptionType::Number, "60", "invalid angle at free boundaries in degrees"}},
     runVoxelize,
     ""},
    {"extract",
     "extract the quad mesh of the topmost volume, its sheets joined (extract.h)",
     "",
     {{"boundary", OptionType::Flag, "1", "rebuild the strip up to the boundary loops"},
      {"features", OptionType::Flag, "1", "snap vertices to feature lines and points"},
      {"triangles", OptionType::Flag, "0", "the MC33 triangles instead (inspection)"}},
     runExtract,
     "Each sheet volume is extracted on its own; the sheets' meshes are then joined at the\n"
     "nodes they share on their junction curves (one conforming mesh). triangles=1 gives the\n"
     "sheets' MC33 triangles one after the other, not joined.\n"},
    {"optimize",
     "optimise the topmost quad mesh against the surface it was extracted from (optimize.h)",
     "",
     {{"size", OptionType::Number, "",
       "target element size (default: the voxel size the mesh was extracted at)"},
      {"warping", OptionType::Number, "",
       "warping removal threshold in degrees (default: 0.8 x the criteria's warping limit)"},
      {"iterations", OptionType::Integer, "200", "most warping removal iterations"},
      {"relax", OptionType::Integer, "10", "relaxation iterations (before and after merging)"},
      {"damping", OptionType::Number, "0.5", "relaxation damping, in (0, 0.7]"},
      {"rhombic", OptionType::Flag, "1", "collapse rhombic quads"},
      {"merge", OptionType::Flag, "1", "merge triangle pairs into quads"},
      {"folded", OptionType::Flag, "1", "collapse faces folded along a curve"},
      {"short", OptionType::Number, "0", "collapse edges shorter than this x size (0: none)"},
      {"reconnect", OptionType::Integer, "8",
       "rounds of the reconnection of faces still failing (0: none)"},
      {"fit", OptionType::Integer, "3",
       "passes pulling points towards the places of the original the mesh passes farthest from "
       "(0: none)"},
      {"split", OptionType::Number, "0.03",
       "split quads still failing into two triangles that fail less, while the triangle share "
       "stays at or under this (0: none)"},
      {"original", OptionType::Text, "",
       "a deck holding the original part (default: the part the mesh was made from)"},
      kCriteria},
     detail::runOptimize,
     "The original surface is the part's shells as voxelize saw them; for a mesh of a volume read\n"
     "from a .vdb file, the part from the topmost deck that has it, or from original=FILE.\n"
     "Pushes the optimised mesh (the extracted one stays below it).\n"},
    {"quality",
     "print the FE quality of the topmost quad mesh or deck (quality.h)",
     "",
     {{"part", OptionType::Integer, "", "decks: only this part's shells (default: all)"},
      {"size", OptionType::Number, "",
       "target size of the length and distance limits (default: the mesh's voxel size, else the "
       "median edge)"},
      {"original", OptionType::Text, "",
       "a deck to measure the distance to (default for meshes: the part they were made from)"},
      {"json", OptionType::Text, "", "also write the report as JSON to this file"},
      {"vtu", OptionType::Text, "",
       "also write the elements with their metrics (cell data) and the distance to the original "
       "(point data) to this .vtu file"},
      kCriteria},
     detail::runQuality,
     "Prints the table of voxremesh quality (limits at their defaults, see voxremesh help\n"
     "quality, or criteria=FILE's). With original= the same part (part=, or the mesh's part) is\n"
     "taken from that deck.\n"},
    {"write",
     "write the top item: a deck or mesh by extension, a volume as .vdb",
     "file",
     {kFile, kFormat},
     runWrite,
     "A quad mesh is written into a copy of the topmost deck holding its part (the part's shells\n"
     "replaced, node references remapped), or alone when no deck holds it.\n"},
    {"print",
     "print a report of the top item (deck: mesh report; volume: grids of each sheet)",
     "",
     {},
     runPrint,
     ""},
    {"slice",
     "render a slice of the topmost volume as a PNG image",
     "file",
     {kFile,
      {"axis", OptionType::Text, "", "x, y or z", true},
      {"at", OptionType::Number, "", "world coordinate along the axis", true},
      {"scale", OptionType::Integer, "0", "pixels per voxel, 0 = automatic"},
      {"sheet", OptionType::Integer, "0", "the sheet whose volume to draw (0 = the first)"}},
     runSlice,
     "A volume holds one grid set per sheet of its part (sheets meeting at a T-junction are\n"
     "voxelised apart); sheet= picks one, 0..sheets-1 (-print lists them).\n"},
    {"save-chain",
     "write this whole chain as a config file for -config",
     "file",
     {kFile},
     runSaveChain,
     ""},
    {"config",
     "run the actions of a config file (one action per line)",
     "file",
     {kFile},
     runNothing,
     ""},
    {"help",
     "list the actions, or describe one",
     "action",
     {{"action", OptionType::Text, "", "the action to describe"}},
     runNothing,
     ""},
};

}  // namespace

const std::vector<ActionDef>& actions() {
  return kActions;
}

void runChain(const Chain& chain, ChainState& state) {
  bool help = false;
  for (const ActionCall& call : chain)
    if (call.action->name == "help") {
      say(state, chainHelp(call.text("action")));
      help = true;
    }
  if (help) return;
  state.chain = chain;
  for (const ActionCall& call : chain) {
    const std::string where = "-" + call.action->name + " (" + call.origin + "): ";
    try {
      call.action->run(state, call);
    } catch (const InputError&) {
      throw;
    } catch (const SettingError& error) {
      throw SettingError(where + error.what());
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& error) {
      throw std::runtime_error(where + error.what());
    }
  }
}

}  // namespace voxremesh::chain
