// Node counts and grading of junction curves across narrow sheets (seam_counts.h).
#include "pipeline/seam_counts.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <map>
#include <optional>
#include <set>

#include "extract/mapped_patch.h"
#include "extract/narrow_sheet.h"
#include "extract/polyline_param.h"
#include "extract/sheet_patches.h"
#include "geometry/vec3.h"
#include "pipeline/remesh_part.h"
#include "pipeline/seam_spacing.h"

namespace voxremesh::pipeline {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// The most passes over all pairs of sides when matching their counts (each pass raises the
/// sides with fewer pieces; pairs tied into a cycle that cannot match stop here).
constexpr int kMatchingPasses = 8;

/// A side of a patch made of whole junction curves, in order: their keys.
using CurveSide = std::vector<NodeEdge>;

/// A junction curve as the ties see it: the pieces its spacing gives it and its length.
struct TiedCurve {
  long pieces = 1;
  double length = 0.0;
};

/// A junction curve facing a side of several whole curves across a patch: the points of it
/// closest to the joints between those curves (its stations, in its order from the point with
/// node ID `firstNode`), and the curves across each stretch between them (one, or with those
/// beyond an end of the curve, which face its end alone).
struct StationTie {
  NodeEdge curve;
  Id firstNode = 0;
  std::vector<std::array<double, 3>> stations;
  std::vector<CurveSide> across;  ///< stations.size() + 1 entries
};

/// A four-sided patch of a narrow sheet, for the aspect limit: its sides in order round the loop
/// (empty: not made of whole curves), and per side the longest rung parallel to it (the largest
/// distance between the two sides next to it, or its own length where that is more: a rib web
/// taller in its middle than at its ends).
struct TiedPatch {
  std::array<CurveSide, 4> sides;
  std::array<double, 4> extent{0.0, 0.0, 0.0, 0.0};
};

/// A three-sided patch of a narrow sheet (a strip running into a tip): its base (the side across
/// from the tip), its two long sides, and the angle the sheet spans at the tip, for the rows that
/// must grow from one piece at the tip to the base's count.
struct TipPatch {
  CurveSide base, left, right;
  double tipDeg = 0.0;
  /// The tip's node ID with the next one's along each side (as SeamSampling::grading keys them).
  std::array<NodeEdge, 2> wedgeSides;
};

/// What one part asks: pairs of sides facing each other across its narrow sheets' four-sided
/// patches, the pieces and length of each curve on such a side, and more.
struct CurveTies {
  std::vector<std::pair<CurveSide, CurveSide>> pairs;
  /// Four-sided patches (TiedPatch).
  std::vector<TiedPatch> patches;
  /// Three-sided patches made of whole curves (TipPatch).
  std::vector<TipPatch> tips;
  std::vector<std::pair<NodeEdge, TiedCurve>> curves;
  /// Curves facing one across a patch whose rungs at their two ends differ in length (a tapering
  /// strip): the curve and the pieces that keep the rows between within the Jacobian ratio.
  std::vector<std::pair<NodeEdge, long>> tapers;
  /// Sharp corners: the corner's node ID and the next one's along a side, wedgeRatio.
  std::vector<std::pair<NodeEdge, double>> graded;
  std::vector<StationTie> stations;
};

/// The edge between two points of a sheet, by point index, lower first.
std::pair<PointIndex, PointIndex> pointEdge(PointIndex a, PointIndex b) {
  return {std::min(a, b), std::max(a, b)};
}

/// The number of pieces the nodes `junctions` places on an open curve cut it into.
long sampledPieces(const Sheet& sheet, const Polyline& curve,
                   const extract::JunctionNodes& junctions) {
  long nodes = 0;
  for (std::size_t i = 0; i < curve.points.size(); ++i) {
    const auto& p = sheet.points[curve.points[i]];
    nodes += junctions.isNodePoint(p) ? 1 : 0;
    if (i + 1 == curve.points.size()) break;
    if (const auto* inside = junctions.edge(p, sheet.points[curve.points[i + 1]]))
      nodes += long(inside->points.size());
  }
  return std::max(1L, nodes - 1);
}

/// The length of a curve of the sheet.
double curveLength(const Sheet& sheet, const Polyline& curve) {
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < curve.points.size(); ++i)
    length += distance(sheet.points[curve.points[i]], sheet.points[curve.points[i + 1]]);
  return length;
}

/// A stretch of a curve facing whole curves across a patch (addStations): its ends (arc lengths
/// along the curve), the curves across it and their length.
struct StationStretch {
  double from = 0.0, to = 0.0;
  CurveSide keys;
  double acrossLength = 0.0;
  bool beyond = false;  ///< it holds curves beyond an end of the curve

  /// The shorter of its length and that across it over the longer (1: alike).
  double closeness() const {
    const double along = to - from;
    return std::min(along, acrossLength) / std::max(along, acrossLength);
  }
  /// This stretch and the next one, `next`, as one.
  StationStretch joined(const StationStretch& next) const {
    StationStretch both = *this;
    both.to = next.to;
    both.keys.insert(both.keys.end(), next.keys.begin(), next.keys.end());
    both.acrossLength += next.acrossLength;
    both.beyond = beyond || next.beyond;
    return both;
  }
};

/// The stretches of a curve (`line`, its points) facing the whole curves `across` of the sheet
/// (in order along the side across) one by one: each between the closest points of a curve's
/// ends, a curve whose closest points are all one end of the curve (beyond that end) with the
/// stretch next to it. None when they do not face it one by one in order (a gap, an overlap, a
/// curve facing a point inside).
std::vector<StationStretch> stretchesFacing(const Sheet& sheet, const extract::PolylineParam& line,
                                            const std::vector<std::size_t>& across) {
  const auto paramOf = [&](const std::array<double, 3>& p) {
    double away = 0.0;
    return line.closestParam({p[0], p[1], p[2]}, away);
  };
  // Per curve across: the params of its two ends on `single`, ordered.
  std::vector<std::pair<double, double>> spans;
  for (const std::size_t c : across) {
    const Polyline& curve = sheet.junctionCurves[c];
    const double a = paramOf(sheet.points[curve.points.front()]);
    const double b = paramOf(sheet.points[curve.points.back()]);
    spans.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::vector<std::size_t> order(across.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return spans[a].first < spans[b].first; });
  const double apart = 1e-6 * line.length();
  std::vector<StationStretch> stretches;
  StationStretch beforeStart;  // curves beyond the start, for the first stretch
  for (const std::size_t k : order) {
    const auto& [from, to] = spans[k];
    const Polyline& curve = sheet.junctionCurves[across[k]];
    StationStretch* stretch = nullptr;
    if (to - from < apart) {
      if (to < apart && stretches.empty())
        stretch = &beforeStart;
      else if (from > line.length() - apart && !stretches.empty())
        stretch = &stretches.back();
      else
        return {};  // a curve across facing one point inside
      stretch->beyond = true;
    } else {
      if (!stretches.empty() && std::abs(from - stretches.back().to) > apart)
        return {};  // a gap or an overlap
      stretches.push_back(stretches.empty() ? beforeStart : StationStretch{});
      stretch = &stretches.back();
      stretch->from = from;
      stretch->to = to;
    }
    stretch->keys.push_back(curveKey(sheet, curve));
    stretch->acrossLength += curveLength(sheet, curve);
  }
  return stretches;
}

/// Joins each stretch holding curves beyond an end whose closeness is under `bound` with the
/// neighbour that brings it closer, worst first, until none is or one stretch is left.
void spreadBeyondEnds(std::vector<StationStretch>& stretches, double bound) {
  while (stretches.size() >= 2) {
    std::size_t worst = stretches.size();
    for (std::size_t k = 0; k < stretches.size(); ++k)
      if (stretches[k].beyond && stretches[k].closeness() < bound &&
          (worst == stretches.size() || stretches[k].closeness() < stretches[worst].closeness()))
        worst = k;
    if (worst == stretches.size()) return;
    std::size_t first = worst == 0 ? 0 : worst - 1;  // joined with the next one
    if (worst > 0 && worst + 1 < stretches.size() &&
        stretches[worst].joined(stretches[worst + 1]).closeness() >
            stretches[worst - 1].joined(stretches[worst]).closeness())
      first = worst;
    stretches[first] = stretches[first].joined(stretches[first + 1]);
    stretches.erase(stretches.begin() + std::ptrdiff_t(first + 1));
  }
}

/// Adds to `ties` the stations of curve `single` facing the whole curves `across` (in order along
/// the side across, two or more): the points of `single` closest to the joints between them. A
/// curve across lying beyond an end of `single` (its closest points all that end: the side across
/// runs on past the patch's corner there) joins the stretch next to it; where that stretch's
/// length and that of the curves across it then differ by more than the square root of
/// minJacobianRatio (the rows' trapezoids halfway between a rectangle and the limit, as
/// taperPieces keeps them), it joins the neighbour that brings them closer, and so on, so that
/// those curves' pieces spread. None when the curves across do not face its stretches one by one
/// in order, or one stretch is left.
void addStations(const Sheet& sheet, const Polyline& single, const std::vector<std::size_t>& across,
                 const QualitySettings& criteria, CurveTies& ties) {
  std::vector<std::array<double, 3>> points;
  for (const PointIndex p : single.points) points.push_back(sheet.points[p]);
  const extract::PolylineParam line(points, false);
  std::vector<StationStretch> stretches = stretchesFacing(sheet, line, across);
  spreadBeyondEnds(stretches, std::sqrt(criteria.minJacobianRatio));
  if (stretches.size() < 2) return;
  StationTie tie{curveKey(sheet, single), sheet.pointNodeIds[single.points.front()], {}, {}};
  for (std::size_t k = 0; k < stretches.size(); ++k) {
    if (k > 0)
      tie.stations.push_back(
          extract::toArray(line.pointAt(0.5 * (stretches[k - 1].to + stretches[k].from))));
    tie.across.push_back(stretches[k].keys);
  }
  ties.stations.push_back(std::move(tie));
}

/// A side of a patch, from one corner of its loop to the next, made of whole junction curves.
struct PatchSide {
  CurveSide keys;                   ///< the curves' keys, in loop order
  std::vector<std::size_t> curves;  ///< the curves' indices in the sheet, in loop order
  /// The curves' ends in loop order: the side's first corner, the joints where one curve gives way
  /// to the next, its last corner (curves.size() + 1 points).
  std::vector<Vec3> ends;
  double length = 0.0;  ///< along the loop
};

/// The side of the loop from corner point `from` to corner point `to` (loop indices), or nothing
/// when a stretch of it is no junction curve (a free stretch adapts by itself) or it ends inside
/// a curve.
std::optional<PatchSide> patchSide(
    const Sheet& sheet, const std::vector<PointIndex>& loop, std::size_t from, std::size_t to,
    const std::map<std::pair<PointIndex, PointIndex>, std::size_t>& curveOfEdge) {
  PatchSide side;
  std::vector<std::size_t> segments;  // per curve of the side, the loop edges along it
  for (std::size_t i = from; i != to; i = (i + 1) % loop.size()) {
    const PointIndex a = loop[i], b = loop[(i + 1) % loop.size()];
    const auto it = curveOfEdge.find(pointEdge(a, b));
    if (it == curveOfEdge.end()) return std::nullopt;
    if (side.curves.empty() || side.curves.back() != it->second) {
      side.ends.push_back(sheet.points[a]);
      side.curves.push_back(it->second);
      segments.push_back(0);
    }
    ++segments.back();
    side.length += distance(sheet.points[a], sheet.points[b]);
  }
  if (side.curves.empty()) return std::nullopt;
  side.ends.push_back(sheet.points[loop[to]]);
  for (std::size_t c = 0; c < side.curves.size(); ++c) {
    const Polyline& curve = sheet.junctionCurves[side.curves[c]];
    if (segments[c] + 1 != curve.points.size()) return std::nullopt;
    side.keys.push_back(curveKey(sheet, curve));
  }
  return side;
}

/// True when sides `a` and `b`, facing each other across a patch (so running in opposite
/// directions round its loop), are made of as many curves whose joints face each other: each
/// joint of one is the nearest to its counterpart among the other's joints, both ways (so too
/// two single curves).
bool jointsFace(const PatchSide& a, const PatchSide& b) {
  const std::size_t ends = a.ends.size();
  if (b.ends.size() != ends) return false;
  // The joint before end `i` of one side nearest to `p` (the sides' corners excepted).
  const auto nearest = [ends](const Vec3& p, const std::vector<Vec3>& among) {
    std::size_t best = 1;
    for (std::size_t j = 2; j + 1 < ends; ++j)
      if (distance(p, among[j]) < distance(p, among[best])) best = j;
    return best;
  };
  for (std::size_t i = 1; i + 1 < ends; ++i) {
    const std::size_t across = ends - 1 - i;
    if (nearest(a.ends[i], b.ends) != across || nearest(b.ends[across], a.ends) != i) return false;
  }
  return true;
}

/// The pieces a curve needs between two rungs across a strip, `shorter` and `longer` long, so that
/// the rows' rungs between, growing evenly, keep each trapezoid's parallel sides (its Jacobian
/// ratio at the corners) within the square root of minJacobianRatio: halfway (geometrically)
/// between a rectangle and the limit, as wedgeRatio keeps a wedge's; and no more than keep its
/// pieces at least the longer rung over the aspect limit. 1 where the rungs are that close, or
/// where one is a point (a tip, which wedge grading or a triangle takes).
long taperPieces(double shorter, double longer, double curveLength,
                 const QualitySettings& criteria) {
  if (!(shorter > 1e-9 * longer)) return 1;
  const double ratio = std::sqrt(criteria.minJacobianRatio);
  const double needed = (longer - shorter) * ratio / (shorter * (1.0 - ratio));
  const double most = curveLength * criteria.maxAspectRatio / longer;
  return std::max(1L, long(std::min(std::ceil(needed - 1e-9), std::floor(most))));
}

/// Adds to `ties` what two sides facing each other across a patch ask: where their joints face
/// each other (jointsFace), each curve of one and the curve facing it get the same count, so
/// that the rows between them run straight across; else the two sides get the same total, and a
/// side of one curve facing several gets stations facing their joints (addStations).
void tieFacingSides(const Sheet& sheet, const PatchSide& a, const PatchSide& b,
                    const QualitySettings& criteria, CurveTies& ties) {
  if (jointsFace(a, b)) {
    const std::size_t count = a.keys.size();
    for (std::size_t c = 0; c < count; ++c) {
      const std::size_t across = count - 1 - c;
      ties.pairs.emplace_back(CurveSide{a.keys[c]}, CurveSide{b.keys[across]});
      const double first = distance(a.ends[c], b.ends[across + 1]);
      const double last = distance(a.ends[c + 1], b.ends[across]);
      const double along = std::min(distance(a.ends[c], a.ends[c + 1]),
                                    distance(b.ends[across], b.ends[across + 1]));
      const long pieces =
          taperPieces(std::min(first, last), std::max(first, last), along, criteria);
      if (pieces > 1) ties.tapers.emplace_back(a.keys[c], pieces);
    }
    return;
  }
  ties.pairs.emplace_back(a.keys, b.keys);
  if (a.curves.size() == 1 && b.curves.size() > 1)
    addStations(sheet, sheet.junctionCurves[a.curves[0]], b.curves, criteria, ties);
  if (b.curves.size() == 1 && a.curves.size() > 1)
    addStations(sheet, sheet.junctionCurves[b.curves[0]], a.curves, criteria, ties);
}

/// The largest distance of a point of polyline `a` from polyline `b`, or of `b` from `a`.
double widestApart(const std::vector<std::array<double, 3>>& a,
                   const std::vector<std::array<double, 3>>& b) {
  double widest = 0.0;
  for (const auto* from : {&a, &b}) {
    const auto& to = from == &a ? b : a;
    if (to.size() < 2) continue;
    const extract::PolylineParam line(to, false);
    for (const auto& p : *from) {
      double away = 0.0;
      line.closestParam({p[0], p[1], p[2]}, away);
      widest = std::max(widest, away);
    }
  }
  return widest;
}

/// Adds to `ties` the station of curve `single`, a side of an L-shaped patch across from the two
/// curves `first` and `second` (one of them along an arm's end): the point of it closest to the
/// patch's reflex corner `corner`, where the cut from that corner meets it (lShapedPatch), each
/// stretch to get the count of the curve across it.
void addReflexStation(const Sheet& sheet, const Polyline& single, const Vec3& corner,
                      const Polyline& first, const Polyline& second, CurveTies& ties) {
  std::vector<std::array<double, 3>> points;
  for (const PointIndex p : single.points) points.push_back(sheet.points[p]);
  const extract::PolylineParam line(points, false);
  const auto paramOf = [&](const Vec3& p) {
    double away = 0.0;
    return line.closestParam({p[0], p[1], p[2]}, away);
  };
  const auto middle = [&](const Polyline& curve) {
    return paramOf(sheet.points[curve.points[curve.points.size() / 2]]);
  };
  const double station = paramOf(corner);
  const double apart = 1e-6 * line.length();
  if (station < apart || station > line.length() - apart) return;
  const bool firstBefore = middle(first) < middle(second);
  StationTie tie{curveKey(sheet, single),
                 sheet.pointNodeIds[single.points.front()],
                 {extract::toArray(line.pointAt(station))},
                 {CurveSide{curveKey(sheet, firstBefore ? first : second)},
                  CurveSide{curveKey(sheet, firstBefore ? second : first)}}};
  ties.stations.push_back(std::move(tie));
}

/// Adds to `ties` what an L-shaped patch (six corners, `corners` of `loop`, one of them reflex)
/// asks where its sides are whole junction curves: along each direction, the two sides running
/// one way get as many pieces together as the side across from them, and where that side is one
/// curve and the two are one curve each, a station where the cut from the reflex corner meets it
/// (addReflexStation), so that the patch cut there is two grids (lShapedPatch, mapped_patch.h).
void tieLShapedPatch(const Sheet& sheet, const std::vector<PointIndex>& loop,
                     const std::vector<std::size_t>& corners,
                     const std::vector<std::optional<PatchSide>>& sides, CurveTies& ties) {
  std::vector<std::array<double, 3>> loopPoints;
  for (const PointIndex p : loop) loopPoints.push_back(sheet.points[p]);
  const std::vector<std::size_t> reflex = extract::reflexCorners(loopPoints);
  if (reflex.size() != 1) return;
  const std::size_t r =
      std::size_t(std::find(corners.begin(), corners.end(), reflex[0]) - corners.begin());
  const auto side = [&](std::size_t k) -> const std::optional<PatchSide>& {
    return sides[(r + k) % 6];
  };
  // Side k leaves corner k after the reflex one: sides 0 and 4 face side 2, sides 1 and 5 side 3.
  for (const std::array<std::size_t, 3>& tie :
       {std::array<std::size_t, 3>{0, 4, 2}, std::array<std::size_t, 3>{1, 5, 3}}) {
    const auto &a = side(tie[0]), &b = side(tie[1]), &across = side(tie[2]);
    if (!a || !b || !across) continue;
    CurveSide together = a->keys;
    together.insert(together.end(), b->keys.begin(), b->keys.end());
    ties.pairs.emplace_back(std::move(together), across->keys);
    if (across->curves.size() == 1 && a->curves.size() == 1 && b->curves.size() == 1)
      addReflexStation(sheet, sheet.junctionCurves[across->curves[0]], loopPoints[reflex[0]],
                       sheet.junctionCurves[a->curves[0]], sheet.junctionCurves[b->curves[0]],
                       ties);
  }
}

/// Per point of the sheet, the angle its faces span there (the sum of their corner angles): 360
/// degrees inside a flat sheet, less at a sharp corner of its boundary.
std::vector<double> spannedAngles(const Sheet& sheet) {
  std::vector<double> angle(sheet.points.size(), 0.0);
  for (const auto& face : sheet.faces) {
    const int corners = face[3] == kNoPoint ? 3 : 4;
    for (int c = 0; c < corners; ++c) {
      const auto& at = sheet.points[face[std::size_t(c)]];
      const Vec3 toNext = sheet.points[face[std::size_t((c + 1) % corners)]] - at;
      const Vec3 toPrevious = sheet.points[face[std::size_t((c + corners - 1) % corners)]] - at;
      angle[face[std::size_t(c)]] += angleDeg(toNext, toPrevious);
    }
  }
  return angle;
}

/// Adds to `ties` the sides facing each other across the sheet's one-loop patches where both are
/// made of whole junction curves (tieFacingSides): the opposite sides of a four-sided patch, and
/// the two long sides of a three-sided one (a strip running into a tip: the sides meeting at the
/// corner opposite its shortest side), those of an L (tieLShapedPatch), and the sides of each
/// four-sided patch (CurveTies::patches).
void tieOppositeCurves(const Sheet& sheet, const QualitySettings& criteria, CurveTies& ties) {
  std::map<std::pair<PointIndex, PointIndex>, std::size_t> curveOfEdge;
  for (std::size_t c = 0; c < sheet.junctionCurves.size(); ++c) {
    const Polyline& curve = sheet.junctionCurves[c];
    if (curve.closed) continue;
    for (std::size_t i = 0; i + 1 < curve.points.size(); ++i)
      curveOfEdge[pointEdge(curve.points[i], curve.points[i + 1])] = c;
  }
  std::vector<extract::SheetPatch> patches;
  try {
    patches = extract::sheetPatches(sheet);
  } catch (const extract::NarrowSheetRefusal&) {
    return;
  }
  const std::vector<double> spanned = spannedAngles(sheet);
  for (const extract::SheetPatch& patch : patches) {
    if (patch.loops.size() != 1) continue;
    const std::vector<PointIndex>& loop = patch.loops[0];
    std::vector<std::array<double, 3>> loopPoints;
    for (const PointIndex p : loop) loopPoints.push_back(sheet.points[p]);
    const std::vector<std::size_t> corners = extract::loopCorners(loopPoints);
    const std::size_t count = corners.size();
    if (count != 3 && count != 4 && count != 6) continue;
    std::vector<std::optional<PatchSide>> sides;
    for (std::size_t k = 0; k < count; ++k)
      sides.push_back(patchSide(sheet, loop, corners[k], corners[(k + 1) % count], curveOfEdge));
    if (count == 6) {
      tieLShapedPatch(sheet, loop, corners, sides, ties);
      continue;
    }
    if (count == 3) {
      std::array<double, 3> length{0.0, 0.0, 0.0};
      for (std::size_t k = 0; k < 3; ++k)
        for (std::size_t i = corners[k]; i != corners[(k + 1) % 3]; i = (i + 1) % loop.size())
          length[k] += distance(loopPoints[i], loopPoints[(i + 1) % loop.size()]);
      const std::size_t shortest =
          std::size_t(std::min_element(length.begin(), length.end()) - length.begin());
      const auto& a = sides[(shortest + 1) % 3];
      const auto& b = sides[(shortest + 2) % 3];
      if (a && b && length[shortest] < std::min(a->length, b->length)) {
        tieFacingSides(sheet, *a, *b, criteria, ties);
        const std::size_t tip = corners[(shortest + 2) % 3];
        const auto wedgeSide = [&](std::size_t next) {
          return NodeEdge{sheet.pointNodeIds[loop[tip]], sheet.pointNodeIds[loop[next]]};
        };
        if (sides[shortest])
          ties.tips.push_back({sides[shortest]->keys,
                               a->keys,
                               b->keys,
                               spanned[loop[tip]],
                               {wedgeSide((tip + 1) % loop.size()),
                                wedgeSide((tip + loop.size() - 1) % loop.size())}});
      }
      continue;
    }
    TiedPatch tied;
    std::array<std::vector<std::array<double, 3>>, 4> sidePoints;
    for (std::size_t k = 0; k < 4; ++k) {
      if (sides[k]) tied.sides[k] = sides[k]->keys;
      for (std::size_t i = corners[k];; i = (i + 1) % loop.size()) {
        sidePoints[k].push_back(loopPoints[i]);
        if (i == corners[(k + 1) % 4]) break;
      }
    }
    for (std::size_t k = 0; k < 4; ++k)
      tied.extent[k] = std::max(sides[k] ? sides[k]->length : 0.0,
                                widestApart(sidePoints[(k + 1) % 4], sidePoints[(k + 3) % 4]));
    ties.patches.push_back(std::move(tied));
    for (std::size_t k = 0; k < 2; ++k)
      if (sides[k] && sides[k + 2]) tieFacingSides(sheet, *sides[k], *sides[k + 2], criteria, ties);
  }
}

/// Adds to `graded` the points of the sheet's boundary loops where the sheet spans less than a
/// quad's smallest angle (spannedAngles), once per side of the wedge (the loop's next and
/// previous points), with their wedgeRatio.
void gradeSharpCorners(const Sheet& sheet, const QualitySettings& criteria,
                       std::vector<std::pair<NodeEdge, double>>& graded) {
  const std::vector<double> angle = spannedAngles(sheet);
  for (const Polyline& loop : sheet.boundaryLoops) {
    const std::size_t n = loop.points.size();
    for (std::size_t i = 0; i < n; ++i) {
      const double ratio = wedgeRatio(angle[loop.points[i]], criteria);
      if (!(ratio > 0.0)) continue;
      const Id corner = sheet.pointNodeIds[loop.points[i]];
      for (const std::size_t side : {(i + 1) % n, (i + n - 1) % n})
        graded.push_back({{corner, sheet.pointNodeIds[loop.points[side]]}, ratio});
    }
  }
}

/// The ties of one part (see CurveTies); none when its sheets cannot be built.
CurveTies partTies(const FeModel& model, const PartPlan& plan, double junctionSpacing,
                   const std::unordered_map<Id, double>& seamSpacing,
                   const std::unordered_set<Id>& hardPoints, const std::vector<Id>& keptParts,
                   const RemeshSettings& settings) {
  CurveTies ties;
  std::vector<Sheet> sheets;
  try {
    sheets = buildSheets(model, plan.part, settings.sheets);
  } catch (const std::exception&) {
    return ties;  // remeshPart builds them again and reports why they cannot be
  }
  placeHardPoints(sheets, hardPoints);
  setSeamSpacing(sheets, seamSpacing, junctionSpacing);
  markKeptSeams(sheets, model, keptParts);
  const double spacing = extractJunctionSpacing(settings, junctionSpacing);
  for (const Sheet& sheet : sheets) {
    if (!(settings.narrowFeatureVoxels > 0 &&
          sheetWidth(sheet) < settings.narrowFeatureVoxels * plan.targetSize))
      continue;  // a sheet meshed through a volume: no rows to match
    gradeSharpCorners(sheet, settings.optimizeSettings.quality, ties.graded);
    const std::size_t before = ties.pairs.size();
    tieOppositeCurves(sheet, settings.optimizeSettings.quality, ties);
    if (ties.pairs.size() == before) continue;
    const extract::JunctionNodes junctions = sheetJunctionNodes(sheet, spacing);
    for (const Polyline& curve : sheet.junctionCurves) {
      if (curve.closed || curve.points.size() < 2) continue;
      ties.curves.emplace_back(
          curveKey(sheet, curve),
          TiedCurve{sampledPieces(sheet, curve, junctions), curveLength(sheet, curve)});
    }
  }
  return ties;
}

}  // namespace

NodeEdge curveKey(const Sheet& sheet, const Polyline& curve) {
  NodeEdge lowest{0, 0};
  for (std::size_t i = 0; i + 1 < curve.points.size(); ++i) {
    const Id a = sheet.pointNodeIds[curve.points[i]], b = sheet.pointNodeIds[curve.points[i + 1]];
    const NodeEdge edge{std::min(a, b), std::max(a, b)};
    if (i == 0 || edge < lowest) lowest = edge;
  }
  return lowest;
}

double wedgeRatio(double cornerDeg, const QualitySettings& criteria) {
  if (!(cornerDeg < criteria.minQuadAngleDeg)) return 0.0;
  const double halfTangent = std::tan(0.5 * std::max(cornerDeg, 0.0) * M_PI / 180.0);
  return std::min(1.0 / std::sqrt(criteria.minJacobianRatio),
                  1.0 + std::sqrt(criteria.maxAspectRatio) * 2.0 * halfTangent);
}

SeamSampling seamSampling(const std::vector<FeModel>& models, const std::vector<PartPlan>& plans,
                          const std::vector<double>& junctionSpacing,
                          const std::vector<std::uint8_t>& skip,
                          const std::unordered_map<Id, double>& seamSpacing,
                          const std::vector<std::unordered_set<Id>>& hardPoints,
                          const std::vector<Id>& keptParts, const RemeshSettings& settings) {
  std::vector<CurveTies> perPlan(plans.size());
  tbb::parallel_for(std::size_t(0), plans.size(), [&](std::size_t i) {
    if (!skip[i] && !std::binary_search(keptParts.begin(), keptParts.end(), plans[i].part))
      perPlan[i] = partTies(models[i], plans[i], junctionSpacing[i], seamSpacing, hardPoints[i],
                            keptParts, settings);
  });
  // Every tied curve, with the most pieces any part's sampling gives it.
  std::map<NodeEdge, TiedCurve> curves;
  for (const CurveTies& ties : perPlan)
    for (const auto& [key, curve] : ties.curves) {
      const auto [it, added] = curves.emplace(key, curve);
      if (!added) it->second.pieces = std::max(it->second.pieces, curve.pieces);
    }
  std::map<NodeEdge, long> count;
  for (const auto& [key, curve] : curves) count[key] = curve.pieces;
  const auto known = [&](const CurveSide& side) {
    return std::all_of(side.begin(), side.end(), [&](const NodeEdge& k) { return count.count(k); });
  };
  const auto sum = [&](const CurveSide& side) {
    long total = 0;
    for (const NodeEdge& key : side) total += count.at(key);
    return total;
  };
  const auto length = [&](const CurveSide& side) {
    double total = 0.0;
    for (const NodeEdge& key : side) total += curves.at(key).length;
    return total;
  };
  // Adds `more` pieces to the side's curve with the longest pieces.
  const auto raise = [&](const CurveSide& side, long more) {
    const NodeEdge* longest = &side.front();
    for (const NodeEdge& key : side)
      if (curves.at(key).length / double(count.at(key)) >
          curves.at(*longest).length / double(count.at(*longest)))
        longest = &key;
    count[*longest] += more;
  };
  // Raises the side with fewer pieces to the other's count, on its curve with the longest
  // pieces, pass after pass (counts only grow) until every pair matches or kMatchingPasses.
  const auto matchPairs = [&] {
    for (int pass = 0; pass < kMatchingPasses; ++pass) {
      bool changed = false;
      for (const CurveTies& ties : perPlan)
        for (const auto& [a, b] : ties.pairs) {
          if (!known(a) || !known(b)) continue;
          const long sa = sum(a), sb = sum(b);
          if (sa == sb) continue;
          raise(sa < sb ? a : b, std::abs(sa - sb));
          changed = true;
        }
      if (!changed) break;
    }
  };
  matchPairs();
  // Then each curve along a tapering strip gets as many pieces as keep its rows' trapezoids
  // within the Jacobian ratio (taperPieces), and each side of a four-sided patch whose pieces are
  // longer than the aspect limit times the pieces of a side across it that has two or more (a
  // patch two elements across, where a web stands on the middle of its end; a rib web taller in
  // its middle than its ends are long) as many as that limit asks, by the counts matched so far;
  // the pairs are matched again after each pass of raises, until no side asks for more or
  // kMatchingPasses.
  std::map<NodeEdge, long> tapers;  // per curve, the most pieces any patch asks
  for (const CurveTies& ties : perPlan)
    for (const auto& [key, pieces] : ties.tapers)
      if (count.count(key)) tapers[key] = std::max(tapers[key], pieces);
  bool raised = false;
  for (const auto& [key, pieces] : tapers)
    if (pieces > count.at(key)) {
      raise(CurveSide{key}, pieces - count.at(key));
      raised = true;
    }
  if (raised) matchPairs();
  const QualitySettings& criteria = settings.optimizeSettings.quality;
  const double aspect = criteria.maxAspectRatio;
  // A tip whose base has more pieces than its angle can fan into triangles within the smallest
  // angle grows its rows by one piece each, from a triangle at the tip to the base: its long
  // sides get as many pieces as the base, evenly (each rung's pieces as long as the tip's).
  const auto growsRows = [&](const TipPatch& tip) {
    if (!known(tip.base) || !known(tip.left) || !known(tip.right)) return false;
    const long base = sum(tip.base);
    return base >= 2 && tip.tipDeg < double(base) * criteria.minTriaAngleDeg;
  };
  std::set<const TipPatch*> grownTips;  // those whose sides were raised so
  for (int pass = 0; pass < kMatchingPasses; ++pass) {
    std::vector<std::pair<const CurveSide*, long>> raises;
    for (const CurveTies& ties : perPlan)
      for (const TiedPatch& patch : ties.patches)
        for (std::size_t k = 0; k < 4; ++k) {
          const CurveSide& side = patch.sides[k];
          if (side.empty() || !known(side)) continue;
          double across = HUGE_VAL;
          for (const std::size_t j : {(k + 1) % 4, (k + 3) % 4}) {
            const CurveSide& next = patch.sides[j];
            if (!next.empty() && known(next) && sum(next) > 1)
              across = std::min(across, length(next) / double(sum(next)));
          }
          if (!std::isfinite(across)) continue;
          const long needed = long(std::ceil(patch.extent[k] / (aspect * across) - 1e-9));
          if (needed > sum(side)) raises.emplace_back(&side, needed - sum(side));
        }
    for (const CurveTies& ties : perPlan)
      for (const TipPatch& tip : ties.tips)
        if (growsRows(tip))
          for (const CurveSide* side : {&tip.left, &tip.right})
            if (sum(*side) < sum(tip.base)) {
              raises.emplace_back(side, sum(tip.base) - sum(*side));
              grownTips.insert(&tip);
            }
    if (raises.empty()) break;
    for (const auto& [side, more] : raises) raise(*side, more);
    matchPairs();
  }
  SeamSampling sampling;
  for (const auto& [key, curve] : curves)
    if (count.at(key) > curve.pieces) sampling.counts[key] = count.at(key);
  for (const CurveTies& ties : perPlan)
    for (const auto& [side, ratio] : ties.graded) {
      const auto [it, added] = sampling.grading.emplace(side, ratio);
      if (!added) it->second = std::min(it->second, ratio);
    }
  for (const TipPatch* tip : grownTips)
    for (const NodeEdge& side : tip->wedgeSides) sampling.grading.erase(side);
  // Stations: each stretch gets the count of the curves across it; the first tie of a curve whose
  // counts add up to the curve's own stays.
  for (const CurveTies& ties : perPlan)
    for (const StationTie& tie : ties.stations) {
      SeamStations stations{tie.firstNode, tie.stations, {}};
      long total = 0;
      for (const CurveSide& side : tie.across) {
        if (!known(side)) break;
        stations.pieces.push_back(sum(side));
        total += sum(side);
      }
      if (stations.pieces.size() == tie.across.size() && total == count.at(tie.curve))
        sampling.stations.emplace(tie.curve, std::move(stations));
    }
  return sampling;
}

void setSeamSampling(std::vector<Sheet>& sheets, const SeamSampling& sampling) {
  for (Sheet& sheet : sheets)
    for (Polyline& curve : sheet.junctionCurves) {
      if (curve.points.size() < 2) continue;
      if (!curve.closed) {
        const auto it = sampling.counts.find(curveKey(sheet, curve));
        if (it != sampling.counts.end()) curve.nodeCount = it->second;
      }
      curve.stations.clear();
      curve.stationPieces.clear();
      if (!curve.closed) {
        const auto it = sampling.stations.find(curveKey(sheet, curve));
        if (it != sampling.stations.end()) {
          curve.stations = it->second.points;
          curve.stationPieces = it->second.pieces;
          if (sheet.pointNodeIds[curve.points.front()] != it->second.firstNode) {
            std::reverse(curve.stations.begin(), curve.stations.end());
            std::reverse(curve.stationPieces.begin(), curve.stationPieces.end());
          }
        }
      }
      curve.grading.clear();
      if (sampling.grading.empty()) continue;
      // A point is graded where the curve runs from it along a graded side of a wedge.
      const std::size_t n = curve.points.size();
      for (std::size_t i = 0; i < n; ++i) {
        double ratio = 0.0;
        for (const long step : {1L, -1L}) {
          const long j = long(i) + step;
          if (!curve.closed && (j < 0 || j >= long(n))) continue;
          const PointIndex next = curve.points[std::size_t((j + long(n)) % long(n))];
          const auto it = sampling.grading.find(
              {sheet.pointNodeIds[curve.points[i]], sheet.pointNodeIds[next]});
          if (it != sampling.grading.end())
            ratio = ratio > 0.0 ? std::min(ratio, it->second) : it->second;
        }
        if (ratio > 0.0) curve.grading.emplace_back(i, ratio);
      }
    }
}

}  // namespace voxremesh::pipeline
