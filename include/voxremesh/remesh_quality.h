// The quality of remeshed output as users look at it: the per-element values of a quality report
// as .vtu cell data (ParaView), and per remeshed part the summary of `voxremesh remesh` and of
// batch jobs (elements before and after, elements failing a criterion, distance to the original).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "voxremesh/fe_model.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/quality.h"
#include "voxremesh/sheets.h"

namespace voxremesh {

/// The shells of one part (of all parts for part 0) with just the nodes they use, in order of
/// first use, so that node i of the result is point i of quadMeshFromModel(result). Shell types
/// and extra cards are dropped (the result is for measuring and .vtu output, not for decks).
/// @param deckName  the deck as messages name it
/// Throws std::runtime_error naming deckName when there are no such shells or a shell names a
/// node the model does not define.
FeModel partShells(const FeModel& model, Id part, const std::string& deckName);

/// The curves bounding the channels (quality.h) of one part of a deck, or of all its parts when
/// `part` is 0: channelCurves of the sheets buildSheets finds with `sheets` (seams with the
/// deck's other parts included). Empty when the shells cannot be split into sheets (a part that
/// is not orientable); every element is then judged against the target size.
std::vector<MeshCurve> deckChannelCurves(const FeModel& deck, Id part,
                                         const SheetSettings& sheets = {});

/// The cell data of a quality report for writeVtu, one value per element in report order:
/// every metric under its quality.h name (warping_deg, aspect_ratio, min_angle_deg,
/// max_angle_deg, skew_deg, jacobian_ratio, jacobian_ratio_gauss, scaled_jacobian, taper,
/// min_length), judged_size (the size the minimum length is judged against: the target size or
/// a narrower channel's width), fail_mask (bit c set when Criterion c fails), pass (1 or 0) and
/// quality_index (quality.h, "Quality index").
/// Values that are not finite become +-1e30, which ParaView can read.
std::vector<FieldData> qualityCellFields(const QualityReport& report);

/// The quality of one remeshed part.
struct PartQuality {
  Id part = 0;
  std::size_t elementsBefore = 0;  ///< shells of the part in the original deck
  std::size_t elementsAfter = 0;   ///< shells of the part in the remeshed deck
  /// The report of the remeshed shells against the part's original shells, with
  /// settings.targetSize the part's target size (per-element values, point distances).
  QualityReport report;
  std::size_t failing() const { return report.failingAny; }  ///< elements failing a criterion
  double failingShare() const { return report.failingAnyShare; }
  /// The two-sided distance between the remeshed and the original shells.
  double maxDistance() const { return report.distance ? report.distance->max() : 0.0; }
};

/// Assesses every part of a remesh against the deck it was remeshed from.
/// @param original  the deck before remeshDeck
/// @param remeshed  the deck after remeshDeck
/// @param remesh    what remeshDeck returned: its parts and their target sizes
/// @param settings  the limits (quality.h defaults); targetSize is replaced per part by the
///                  size the part was remeshed at (RemeshedPart::voxelSize), distanceSize by
///                  its target size
/// @param sheets    the feature angles the remesh used: each part's channels (quality.h) are
///                  the curves of its original sheets built with them
/// @return one entry per remeshed or retried part of remesh.parts (kept parts are left out), in
///         that order
/// Throws SettingError for bad settings; std::runtime_error naming the deck when a part has no
/// shells in one of the decks or a shell names an undefined node.
std::vector<PartQuality> assessRemeshedParts(const FeModel& original, const FeModel& remeshed,
                                             const RemeshReport& remesh,
                                             const QualitySettings& settings = {},
                                             const SheetSettings& sheets = {});

/// Writes the remeshed parts' shells to a .vtu file with the quality of every element as cell
/// data (qualityCellFields) and, as point data "distance", each node's distance to its part's
/// original shells (a node shared by two remeshed parts gets the larger of its two distances).
/// @param remeshed  the deck after remeshDeck
/// @param parts     assessRemeshedParts(..., remeshed, ...)
/// Throws std::runtime_error as partShells and when the file cannot be written (atomically: no
/// half-written file is left).
void writeRemeshQualityVtu(const FeModel& remeshed, const std::vector<PartQuality>& parts,
                           const std::filesystem::path& path);

}  // namespace voxremesh
