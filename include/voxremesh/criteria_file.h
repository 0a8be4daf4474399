// Quality criteria files: an engineer's limits for every quality metric, given the way HyperMesh's
// criteria files give them (per metric: ideal, good, warn, fail and worst values and a weight in
// the quality index; quality.h, "Quality index"), for `remesh`, `quality`, chains and batch jobs.
//
// Format: text, one entry per line; '#' starts a comment; blank lines are skipped; entries in any
// order, each at most once; what a file does not name keeps its value (the defaults, or the
// settings it is read into).
//   METRIC IDEAL GOOD WARN FAIL WORST [WEIGHT]
//       METRIC is a criterion's name (criterionName: warping, aspect, quad_min_angle,
//       quad_max_angle, tria_min_angle, tria_max_angle, skew, jacobian_ratio, scaled_jacobian,
//       taper, min_length, degenerate_corner, folded, distance). FAIL is the limit an element
//       fails beyond; the five values run from best to worst (growing for a maximum such as
//       warping, falling for a minimum such as min_length). WEIGHT defaults to 1. Lengths
//       (min_length, distance) are either relative to the target size, written with a trailing
//       'h' (0.5h: half the size; min_length then scales down in channels narrower than the
//       size, quality.h), or in model units (2.5: the same limit for every part and element);
//       the five values of a line are all one or all the other. folded's FAIL is 0 (no folded
//       element passes).
//   tria_share SHARE        the largest share of triangles (0..1, or a percentage as 5%)
//   failing_share SHARE     the largest share of elements failing a criterion
//   jacobian_at corners|gauss_points   where the Jacobian ratio is evaluated
// share/criteria/default.txt holds the defaults (DESIGN.md's table).
#pragma once

#include <string>
#include <string_view>

#include "voxremesh/quality.h"

namespace voxremesh {

/// Reads a criteria file (see the top of the file) into `settings`: what the file names replaces
/// the settings' values, the rest stays.
/// Throws InputError naming the file and line for a malformed line, an unknown or repeated entry,
/// values out of order, a line mixing relative and absolute lengths, 'h' on a value that is no
/// length, or settings checkQualitySettings refuses (no line:
/// 0), and when the file cannot be read; `settings` is unchanged then.
void readCriteriaFile(const std::string& path, QualitySettings& settings);

/// Parses criteria text as readCriteriaFile does, naming `source` in its errors.
void parseCriteria(std::string_view text, const std::string& source, QualitySettings& settings);

/// The criteria file text of `settings`: every metric with its five values and weight, the shares
/// and where the Jacobian ratio is evaluated. parseCriteria of it gives the same settings.
std::string formatCriteria(const QualitySettings& settings);

}  // namespace voxremesh
