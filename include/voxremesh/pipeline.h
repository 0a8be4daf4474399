// The remeshing pipeline as the engineer runs it (`voxremesh remesh`, batch jobs, the chain's
// actions): which parts, at which target size, and the stages composed per part.
//
// remeshDeck composes, per selected part (parts in parallel with TBB, each stage parallel inside;
// the result does not depend on the thread count):
//   buildSheets -> buildVolume          (one sheet's volume at a time; sheets.h, volume.h)
//   -> extractQuadMesh                  (extract.h)
//   -> optimisation                     (optimize.h)
//   -> acceptance, retried at a finer voxel or the part kept (RemeshedPart, PartAcceptance)
// and then replacePartMeshes (deck_assembly.h) puts the accepted meshes back into the deck in the
// order of planRemesh. Each sheet of a part is voxelised, extracted and optimised on its own (a
// sheet narrower than RemeshSettings::narrowFeatureVoxels target sizes is meshed from its boundary
// instead, src/extract/narrow_sheet.h, and then optimised alike); the sheets' meshes are then
// joined at their junction nodes (joinAtJunctions). partVolumes builds all sheet volumes of a part
// at once, for the tools that inspect them.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "voxremesh/deck_assembly.h"
#include "voxremesh/extract.h"
#include "voxremesh/optimize.h"

#include "voxremesh/fe_model.h"
#include "voxremesh/sheets.h"
#include "voxremesh/volume.h"

namespace voxremesh {

/// VolumeSettings' defaults (volume.h) with the band the extraction reads,
/// kExtractionBandVoxels: the volumes remeshDeck builds serve the extraction only.
inline VolumeSettings remeshVolumeSettings() {
  VolumeSettings settings;
  settings.bandWidthVoxels = kExtractionBandVoxels;
  return settings;
}

/// Settings of remeshing a deck. Every field has a documented default.
struct RemeshSettings {
  /// Target element size in model units; 0 (the default) means one size for the whole deck: the
  /// median edge length of all its shells (deckTargetSize). Negative or non-finite is refused.
  double targetSize = 0.0;
  /// Per-part target sizes that replace targetSize for those parts (only when asked for).
  std::map<Id, double> partSizes;
  /// Finer-voxel retries of a part whose mesh misses the acceptance (each halves the voxel). Two
  /// by default, which reach the finest voxel (finestVoxelShare): each halving quadruples the
  /// part's elements and halves its explicit time step, so no retry goes below that floor.
  int retries = 2;
  /// A sheet narrower than this many target sizes (its width 2 x area / boundary length) is meshed
  /// from its boundary with rows of quads along it (src/extract/narrow_sheet.h); where that
  /// cannot be done, it gets a voxel this much smaller than its width, so that the strip, flange
  /// or hole is kept.
  double narrowFeatureVoxels = 3.0;
  /// The finest voxel any reduction or retry may reach, as a share of the part's target size.
  /// The distance limit stays 0.25 x the target size; element criteria use the voxel reached.
  double finestVoxelShare = 0.25;
  /// The parts to remesh; empty (the default) means every part with shells.
  std::vector<Id> parts;
  /// Feature and corner angles (sheets.h defaults: 45 and 30 degrees).
  SheetSettings sheets;
  /// Band, invalid angle, tie tolerance and memory limit of the volumes (remeshVolumeSettings:
  /// volume.h's defaults with a band of kExtractionBandVoxels, the least refused). The voxel size
  /// rule and size are set per part from the target size.
  VolumeSettings volume = remeshVolumeSettings();
  /// Extraction settings (extract.h defaults).
  ExtractSettings extract;
  /// Quad optimisation after extraction (optimize.h); off leaves the extracted mesh as it is.
  bool optimize = true;
  /// Optimisation settings; the quality target size is set per part to the part's target size.
  OptimizeSettings optimizeSettings;
  /// Threads for the parts and their stages; 0 (the default) means all cores.
  int threads = 0;
};

/// One part as it will be remeshed.
struct PartPlan {
  Id part = 0;
  std::string name;
  std::size_t shells = 0;   ///< shells of the part before remeshing
  double targetSize = 0.0;  ///< the target element size asked for the part
};

/// The IDs of the parts that have shells, ascending.
std::vector<Id> shellPartIds(const FeModel& model);

/// The part an action on one part works on: `requested` when it is not 0 (it must have shells),
/// else the deck's only part with shells.
/// @param deckName  the deck as messages name it
/// @param option    how the user chooses a part, for the message ("--part", "part=")
/// Throws std::runtime_error naming the deck when it has no shells, when `requested` has none
/// (listing the parts with shells), and SettingError when `requested` is 0 and several parts
/// have shells ("DECK has N parts with shells; choose one with OPTION (list)").
Id choosePart(const FeModel& model, Id requested, const std::string& deckName,
              const std::string& option);

/// The median edge length of the part's shells (each side of each shell counted, as
/// reportDeck's edge statistics; the mean of the two middle ones for an even count).
/// Preconditions: the part has shells naming existing nodes. Throws std::invalid_argument when
/// the part has no shells or every side has zero length.
double defaultTargetSize(const FeModel& model, Id part);

/// The median edge length of all shells of the deck (each side of each shell counted), the
/// default target size of every part. Throws std::invalid_argument when the deck has no shells
/// or every side has zero length.
double deckTargetSize(const FeModel& model);

/// The parts remeshDeck will remesh and their target sizes, in ascending part ID.
/// Throws SettingError when a requested part does not exist or has no shells (listing the parts
/// with shells), when the target size is negative or not finite, when threads is negative, or
/// when the volume settings are invalid (checkVolumeSettings); std::invalid_argument as
/// defaultTargetSize.
std::vector<PartPlan> planRemesh(const FeModel& model, const RemeshSettings& settings);

/// One sheet of a part and the volume it was written into.
struct SheetVolume {
  Sheet sheet;
  Volume volume;
};

/// The first two stages for one planned part: its sheets, each written into a volume of its own
/// whose voxel size is the plan's target size (buildSheetVolumes). (Sheets that meet along a
/// junction curve, like the disc and the rim of a wheel at their T-junction, have no common inside
/// and outside, so one signed distance cannot hold them together; extraction then puts the same
/// nodes on the junction curve on every side.) Throws as buildSheets and buildVolume;
/// std::runtime_error when no shell of the part has an area.
std::vector<SheetVolume> partVolumes(const FeModel& model, const PartPlan& plan,
                                     const RemeshSettings& settings);

/// Adds the counts of `add` (one sheet's extraction) to `sum` (the part's).
void addExtractStats(ExtractStats& sum, const ExtractStats& add);

/// The quad mesh of a part from the volumes of its sheets (buildSheetVolumes, readVolumes):
/// extractQuadMesh of each sheet volume, in order, joined at their junction nodes
/// (joinAtJunctions), so that the T-junction between sheets is one conforming mesh.
/// @param volumes   the part's sheet volumes, at least one, all non-empty
/// @param settings  see ExtractSettings
/// @param stats     when not null, receives the counts summed over the sheets
/// @return the joined mesh, its part the first volume's
/// Throws std::invalid_argument when `volumes` is empty or holds an empty volume;
/// std::runtime_error as extractQuadMesh, the message prefixed with "sheet K: " when the part
/// has several sheets.
QuadMesh extractPartMesh(const std::vector<Volume>& volumes, const ExtractSettings& settings = {},
                         ExtractStats* stats = nullptr);

/// The MC33 triangles (extractTriangles) of each sheet volume of a part, concatenated in sheet
/// order (no points merged). Throws std::invalid_argument when `volumes` is empty or holds an
/// empty volume.
QuadMesh extractPartTriangles(const std::vector<Volume>& volumes);

/// How a part ended (DESIGN.md, "What must hold on every real deck").
enum class PartStatus {
  Remeshed,  ///< its new mesh passed the acceptance at the first voxel size
  Retried,   ///< its new mesh passed the acceptance at a finer voxel
  Kept,      ///< its original elements were written back unchanged (reason says why)
};

/// "remeshed", "retried" or "kept".
const char* partStatusName(PartStatus status);

/// The acceptance checks of a part's new mesh against the part's original shells.
struct PartAcceptance {
  bool accepted = false;
  std::string reason;        ///< what failed, empty when accepted
  double size = 0.0;         ///< the element size judged against: the voxel size used
  std::size_t elements = 0;  ///< of the new mesh
  std::size_t quads = 0, trias = 0;
  std::size_t failing = 0;  ///< elements failing a criterion (distance and folds included)
  double failingShare = 0.0;
  double qualityIndex = 0.0;  ///< mean over the elements (quality.h, "Quality index")
  double distance = 0.0;      ///< two-sided, sampled inside the faces
  double distanceLimit = 0.0;
  std::size_t folded = 0;             ///< against neighbours or against the original
  std::size_t degenerateCorners = 0;  ///< quads with a corner of (almost) 180 degrees
  std::size_t componentsBefore = 0, componentsAfter = 0;
  std::size_t loopsBefore = 0, loopsAfter = 0;
  double areaBefore = 0.0, areaAfter = 0.0;  ///< of the part's shells: its mass at one thickness
  /// Length of the original's T-junctions (edges three or more shells share: a fin on a sheet),
  /// and of those the new mesh no longer has (no T-junction edge within the distance limit).
  double junctionLength = 0.0, junctionLengthLost = 0.0;
};

/// What remeshDeck did to one part.
struct RemeshedPart {
  PartPlan plan;
  PartStatus status = PartStatus::Kept;
  std::string reason;                ///< why the part was kept, or why its voxel was reduced
  int attempts = 0;                  ///< meshes built (0 when the part was refused before any)
  double voxelSize = 0.0;            ///< of the accepted mesh (of the last attempt when kept)
  PartAcceptance acceptance;         ///< of the accepted mesh (of the last attempt when kept)
  std::size_t quads = 0, trias = 0;  ///< of the new mesh (0 when kept)
  ExtractStats extract;              ///< of the attempt that ended the part
  /// Wall-clock seconds of the part's stages, all attempts. Parts run side by side, each
  /// isolated (a thread waiting inside one part's parallel loops runs none of another's work):
  /// the times are the part's own (a sum over the parts counts parts that ran at the same time
  /// one after the other).
  double volumeSeconds = 0.0;    ///< sheets and volume
  double extractSeconds = 0.0;   ///< extraction
  double optimizeSeconds = 0.0;  ///< quad optimisation
  double acceptSeconds = 0.0;    ///< acceptance: quality, distance and topology of each mesh
  /// The whole part: sheets, their plans, every attempt and its acceptance, and a second pass
  /// when the part was remeshed again beside kept neighbours (then every time here is the sum).
  double totalSeconds = 0.0;
};

/// What remeshDeck did.
/// The seams of a deck: per pair of parts whose shells share nodes, how many; the edges that
/// three or more shells share (T-junctions); and the nodes that hang on a seam.
struct DeckSeams {
  std::map<std::pair<Id, Id>, std::size_t> sharedNodes;  ///< key: (lower, higher) part ID
  std::size_t tJunctionEdges = 0;
  /// Nodes of a part lying inside an edge of another part it shares nodes with (within 0.005 of
  /// the shorter of the two parts' median edges, not at the edge's ends): one side of the seam
  /// has a node the other lacks. Counted once per node and pair of parts.
  std::size_t hangingNodes = 0;
};

/// Counts the seams of a deck's shells. Deterministic.
DeckSeams deckSeams(const FeModel& deck);

struct RemeshReport {
  std::vector<RemeshedPart> parts;  ///< in plan order
  AssemblyReport assembly;
  DeckSeams seamsBefore;  ///< the deck's seams before the remesh
  DeckSeams seamsAfter;   ///< and after
  double assemblySeconds = 0.0;
  double totalSeconds = 0.0;
  /// Parts with the given status.
  std::size_t count(PartStatus status) const;
  /// More nodes of the output than of the input lie inside an edge of a part they share a seam
  /// with (DeckSeams::hangingNodes): a seam where one side has a node the other lacks.
  bool moreHangingNodes() const { return seamsAfter.hangingNodes > seamsBefore.hangingNodes; }
  /// Every part was remeshed or retried (none kept) and no more nodes hang on seams.
  bool allAccepted() const { return count(PartStatus::Kept) == 0 && !moreHangingNodes(); }
};

/// Progress of remeshDeck: the stage ("volume", "extract", "assemble"), the part (0 for the
/// whole deck) and the share of parts finished so far (0..1). Called from worker threads, one
/// call at a time.
using RemeshProgress = std::function<void(const std::string& stage, Id part, double done)>;

/// Remeshes the planned parts of a deck in place (see the top of the file): parts in parallel
/// within settings.threads, then one assembly of the accepted meshes. A part error never stops
/// the deck: each part ends remeshed, retried at a finer voxel, or kept (its shells unchanged)
/// with the reason. Shells that lie on faces of solid elements stay as they are (remeshing them
/// would detach them); the rest of their part is remeshed around them, sharing their nodes, and
/// a part made of such shells only is kept. The result does not depend on the thread count.
/// @param deck      the deck as readDeck returns it; its accepted parts replaced
/// @param settings  see RemeshSettings
/// @param progress  optional progress callback
/// Throws as planRemesh (bad settings, parts that do not exist).
RemeshReport remeshDeck(FeModel& deck, const RemeshSettings& settings,
                        const RemeshProgress& progress = {});

/// The report as JSON: per part counts, target size and stage times; every node reference
/// remapped (keyword, line, old and new node, part, distance) and every one not remappable.
std::string remeshReportJson(const RemeshReport& report);

/// Writes remeshReportJson(report) to `path` atomically. Throws std::runtime_error naming the
/// path when it cannot be written.
void writeRemeshReport(const RemeshReport& report, const std::filesystem::path& path);

}  // namespace voxremesh
