// The node spacing along each seam, from the sheets on both of its sides: a narrow sheet (a
// strip, a flange) meshed with rows along it asks its seams for its row length, and both parts
// of a seam then place the same nodes on it (DESIGN.md, "Connections survive": a seam's spacing
// comes from the parts it joins). Internal to src/pipeline.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "voxremesh/pipeline.h"

namespace voxremesh::pipeline {

/// The longest row length along a narrow sheet whose elements still pass the aspect criterion:
/// an element of a row is the sheet's width (stripWidth) across and one piece of its boundary
/// along, and a boundary cut into even pieces about a spacing long (rounded to whole pieces) has
/// pieces up to 1.5 spacings long; so the aspect limit (settings.optimizeSettings.quality) x the
/// width / 1.5.
double rowLength(const Sheet& sheet, const RemeshSettings& settings);

/// The node spacing a sheet asks of the junction curves along it: `targetSize`, or for a sheet
/// narrower than settings.narrowFeatureVoxels target sizes, its rowLength where that is less: the
/// length of the rows its boundary mesh gets.
double sheetNodeSpacing(const Sheet& sheet, double targetSize, const RemeshSettings& settings);

/// Per node on a junction curve of the planned parts' sheets, the smallest spacing among the
/// sheets through it: a sheet's sheetNodeSpacing at its plan's target size, or its part's junction
/// spacing where that is less (the part places every seam of its at that spacing, so the part on
/// the other side of each must too, also where that part's own junction spacing is larger).
/// @param models          per plan, the part's shells and its neighbours' (as remeshDeck builds
///                        them)
/// @param junctionSpacing per plan, the spacing its junction curves get (PartSurroundings)
/// @param skip            per plan, 1 for parts not remeshed (their seams keep their nodes anyway)
/// A part whose sheets cannot be built adds nothing (its remesh reports why). Deterministic: the
/// result does not depend on the order or thread count.
std::unordered_map<Id, double> seamNodeSpacing(const std::vector<FeModel>& models,
                                               const std::vector<PartPlan>& plans,
                                               const std::vector<double>& junctionSpacing,
                                               const std::vector<std::uint8_t>& skip,
                                               const RemeshSettings& settings);

/// Sets Polyline::nodeSpacing of every junction curve of `sheets` to the smallest spacing
/// `nodeSpacing` gives its inner points' nodes (its ends' when it has none: ends are shared with
/// other curves), when that is below `partSpacing`; curves whose nodes it does not list keep 0.
void setSeamSpacing(std::vector<Sheet>& sheets, const std::unordered_map<Id, double>& nodeSpacing,
                    double partSpacing);

}  // namespace voxremesh::pipeline
