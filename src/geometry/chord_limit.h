// The distance a chord may keep from the curve or surface it stands for (DESIGN.md, "Sizing
// resolves the part": a curved edge keeps its length, a curved sheet its area).
#pragma once

#include <algorithm>

namespace voxremesh::geom {

/// How far a chord `length` long may lie from the curve or surface it stands for: `tolerance`,
/// or `sagittaShare` x its length where that share is positive and the product smaller (a
/// sagitta limit: an arc cut by chords of sagitta s and length c is 8/3 (s/c)^2 longer).
inline double chordLimit(double tolerance, double sagittaShare, double length) {
  return sagittaShare > 0.0 ? std::min(tolerance, sagittaShare * length) : tolerance;
}

}  // namespace voxremesh::geom
