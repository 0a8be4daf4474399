// The remeshing pipeline as the engineer runs it (`voxremesh remesh`, batch jobs, the chain's
// actions): which parts, at which target size, and the stages composed per part.
//
// remeshDeck composes, per selected part (parts in parallel with TBB, each stage parallel inside;
// the result does not depend on the thread count):
//   buildSheets -> buildVolume          (partVolume below; sheets.h, volume.h)
//   -> extractQuadMesh                  (extract.h, issue 4)
//   -> optimisation -> quality report   (optimize.h, quality.h, issue 5)
// and then replacePartMeshes (deck_assembly.h) puts all new meshes back into the deck in the
// order of planRemesh. This header holds the stages that exist: planning and the volumes; the
// declaration of remeshDeck itself is added with the stages it calls, so that nothing here
// links against an unimplemented stage.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "voxremesh/fe_model.h"
#include "voxremesh/sheets.h"
#include "voxremesh/volume.h"

namespace voxremesh {

/// Settings of remeshing a deck. Every field has a documented default.
struct RemeshSettings {
  /// Target element size in model units; 0 (the default) means per part the median element edge
  /// length of the part's shells (defaultTargetSize). Negative or non-finite is refused.
  double targetSize = 0.0;
  /// The parts to remesh; empty (the default) means every part with shells.
  std::vector<Id> parts;
  /// Feature and corner angles (sheets.h defaults: 30 degrees).
  SheetSettings sheets;
  /// Band, invalid angle, tie tolerance and memory limit of the volumes (volume.h defaults). The
  /// voxel size rule and size are set per part from the target size.
  VolumeSettings volume;
  /// Threads for the parts and their stages; 0 (the default) means all cores.
  int threads = 0;
};

/// One part as it will be remeshed.
struct PartPlan {
  Id part = 0;
  std::string name;
  std::size_t shells = 0;   ///< shells of the part before remeshing
  double targetSize = 0.0;  ///< the target element size used for the part
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

/// The parts remeshDeck will remesh and their target sizes, in ascending part ID.
/// Throws SettingError when a requested part does not exist or has no shells (listing the parts
/// with shells), when the target size is negative or not finite, when threads is negative, or
/// when the volume settings are invalid (checkVolumeSettings); std::invalid_argument as
/// defaultTargetSize.
std::vector<PartPlan> planRemesh(const FeModel& model, const RemeshSettings& settings);

/// The first two stages for one planned part: its sheets, written into a volume whose voxel size
/// is the plan's target size.
/// Throws as buildSheets and buildVolume; std::runtime_error when no shell of the part has an
/// area.
Volume partVolume(const FeModel& model, const PartPlan& plan, const RemeshSettings& settings);

}  // namespace voxremesh
