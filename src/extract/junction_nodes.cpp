// Junction curve nodes (see junction_nodes.h).
#include "extract/junction_nodes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>

#include "extract/polyline_param.h"
#include "geometry/chord_limit.h"

namespace voxremesh::extract {

namespace {

double distance(const Point3& a, const Point3& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

/// The curve's points in the canonical direction (see junction_nodes.h).
std::vector<Point3> canonicalPoints(const VolumeCurve& curve) {
  std::vector<Point3> points = curve.points;
  if (points.size() < 2) return points;
  if (!curve.closed) {
    if (points.back() < points.front()) std::reverse(points.begin(), points.end());
    return points;
  }
  const auto smallest = std::min_element(points.begin(), points.end());
  std::rotate(points.begin(), smallest, points.end());
  if (points.back() < points[1]) std::reverse(points.begin() + 1, points.end());
  return points;
}

/// True when the curve turns at point i by more than kJunctionCornerDeg.
bool turns(const std::vector<Point3>& points, std::size_t previous, std::size_t i,
           std::size_t next) {
  double in[3], out[3], inLength = 0.0, outLength = 0.0, dot = 0.0;
  for (int c = 0; c < 3; ++c) {
    in[c] = points[i][std::size_t(c)] - points[previous][std::size_t(c)];
    out[c] = points[next][std::size_t(c)] - points[i][std::size_t(c)];
    inLength += in[c] * in[c];
    outLength += out[c] * out[c];
    dot += in[c] * out[c];
  }
  if (inLength == 0.0 || outLength == 0.0) return false;
  const double cosine = std::clamp(dot / std::sqrt(inLength * outLength), -1.0, 1.0);
  return std::acos(cosine) * 180.0 / M_PI > kJunctionCornerDeg;
}

/// A node of a curve: at arc length `param`, and at curve point `point` when it is one.
struct CurveNode {
  double param = 0.0;
  std::size_t point = SIZE_MAX;
};

/// A node this share of its segment's length from a curve point (or closer) is that point: even
/// pieces that end on a point but for the rounding of their arc lengths.
constexpr double kOnPointShare = 1e-9;
/// Segments of a curve within this factor of the spacing (either way) are kept as they are.
constexpr double kKeptSpacingFactor = 1.5;

/// Walks a polyline (closed: point n is point 0 again) by arc length.
struct Walk {
  const std::vector<Point3>& points;
  bool closed;
  std::vector<double> arc;  ///< arc length at each point, plus the closing point when closed

  Walk(const std::vector<Point3>& curvePoints, bool isClosed)
      : points(curvePoints), closed(isClosed) {
    const std::size_t n = points.size();
    arc.assign(1, 0.0);
    for (std::size_t i = 1; i < n + (closed ? 1 : 0); ++i)
      arc.push_back(arc.back() + distance(points[i - 1], points[i % n]));
  }
  const Point3& at(std::size_t i) const { return points[i % points.size()]; }
  /// The segment holding arc length s and the fraction along it (closed: s may run one
  /// length past the end).
  std::pair<std::size_t, double> locate(double s) const {
    if (closed && s >= arc.back()) s -= arc.back();
    const std::size_t segment =
        std::min<std::size_t>(
            std::size_t(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin()),
            arc.size() - 1) -
        1;
    const double length = arc[segment + 1] - arc[segment];
    return {segment, length > 0.0 ? (s - arc[segment]) / length : 0.0};
  }
  Point3 position(const CurveNode& node) const {
    if (node.point != SIZE_MAX) return at(node.point);
    const auto [segment, t] = locate(node.param);
    const Point3 &a = at(segment), &b = at(segment + 1);
    return {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t};
  }
};

/// Adds the curve points strictly between nodes x and y that lie farther than `tolerance` (or
/// `sagittaShare` x the chord's length, where positive and less) from the chord between them,
/// farthest first and recursively.
void addFarPoints(const Walk& walk, const CurveNode& x, const CurveNode& y, double tolerance,
                  double sagittaShare, std::vector<CurveNode>& out) {
  const Point3 a = walk.position(x), b = walk.position(y);
  double worst = geom::chordLimit(tolerance, sagittaShare, distance(a, b));
  double worstParam = 0.0;
  std::size_t worstPoint = SIZE_MAX;
  const std::size_t n = walk.points.size();
  for (std::size_t k = 0; k < (walk.closed ? 2 * n : n); ++k) {
    const std::size_t i = k % n;
    const double v = walk.arc[i] + (k >= n ? walk.arc.back() : 0.0);
    if (v <= x.param || v >= y.param) continue;
    const Point3& p = walk.at(i);
    double ab[3], ap[3], len2 = 0.0, dot = 0.0;
    for (int c = 0; c < 3; ++c) {
      ab[c] = b[std::size_t(c)] - a[std::size_t(c)];
      ap[c] = p[std::size_t(c)] - a[std::size_t(c)];
      len2 += ab[c] * ab[c];
      dot += ab[c] * ap[c];
    }
    const double t = len2 > 0.0 ? std::clamp(dot / len2, 0.0, 1.0) : 0.0;
    const Point3 foot{a[0] + ab[0] * t, a[1] + ab[1] * t, a[2] + ab[2] * t};
    const double d = distance(foot, p);
    if (d > worst) worst = d, worstPoint = i, worstParam = v;
  }
  if (worstPoint == SIZE_MAX) return;
  const CurveNode middle{worstParam, worstPoint};
  addFarPoints(walk, x, middle, tolerance, sagittaShare, out);
  out.push_back(middle);
  addFarPoints(walk, middle, y, tolerance, sagittaShare, out);
}

/// True when every segment of the curve is within kKeptSpacingFactor of `spacing`: its points
/// are then nodes as good as an even sampling's, whose pieces (round(L / spacing) of them) lie
/// within the same factor.
bool segmentsFitSpacing(const Walk& walk, double spacing) {
  for (std::size_t i = 0; i + 1 < walk.arc.size(); ++i) {
    const double length = walk.arc[i + 1] - walk.arc[i];
    if (length < spacing / kKeptSpacingFactor || length > spacing * kKeptSpacingFactor)
      return false;
  }
  return true;
}

/// The pieces of each span between anchors when an open curve is cut into `count` pieces in all:
/// at least one per span, the rest by the spans' lengths (largest remainders first, then the
/// earlier span).
std::vector<long> spanPieces(const std::vector<double>& lengths, long count) {
  const long spans = long(lengths.size());
  std::vector<long> pieces(lengths.size(), 1);
  double total = 0.0;
  for (double length : lengths) total += length;
  long left = count - spans;
  if (left <= 0 || !(total > 0.0)) return pieces;
  std::vector<std::pair<double, std::size_t>> remainders;
  for (std::size_t k = 0; k < lengths.size(); ++k) {
    const double share = double(left) * lengths[k] / total;
    pieces[k] += long(std::floor(share));
    remainders.emplace_back(share - std::floor(share), k);
  }
  for (long given : pieces) left -= given - 1;
  std::stable_sort(remainders.begin(), remainders.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t r = 0; left > 0 && r < remainders.size(); ++r, --left)
    ++pieces[remainders[r].second];
  return pieces;
}

/// Relative lengths of the `pieces` pieces of a span whose ends may shrink toward graded points
/// (junction_nodes.h): from a graded end the first piece is 1, and each next node lies at most
/// `ratio` times as far from that end as the node before it (pieces of at most 1); other pieces
/// are 1. A ratio of 1 or less leaves its end even.
std::vector<double> gradedPieces(long pieces, double startRatio, double endRatio) {
  std::vector<double> weights(std::size_t(pieces), 1.0);
  const auto shrink = [&](double ratio, bool fromEnd) {
    if (!(ratio > 1.0)) return;
    double reach = 1.0;  // how far the last node lies from the graded end
    for (long j = 1; j < pieces; ++j) {
      const double next = std::min(reach * ratio, reach + 1.0);
      double& weight = weights[std::size_t(fromEnd ? pieces - 1 - j : j)];
      weight = std::min(weight, next - reach);
      reach = next;
    }
  };
  shrink(startRatio, false);
  shrink(endRatio, true);
  return weights;
}

/// Appends to `nodes` the `pieces` - 1 nodes inside the span of `length` from param `from`, cut as
/// gradedPieces(pieces, startRatio, endRatio) cuts it (at no curve point).
void appendSpanNodes(double from, double length, long pieces, double startRatio, double endRatio,
                     std::vector<CurveNode>& nodes) {
  const std::vector<double> weights = gradedPieces(pieces, startRatio, endRatio);
  double total = 0.0, reached = 0.0;
  for (double weight : weights) total += weight;
  for (long j = 1; j < pieces; ++j) {
    reached += weights[std::size_t(j - 1)];
    nodes.push_back({from + length * reached / total});
  }
}

/// The nodes of an open curve with stations (VolumeCurve::stations): its anchors (`anchors`,
/// curve points, ascending) and the stations cut it into spans; the spans of one stretch (between
/// two stations, or a station and an end) share that stretch's pieces by their lengths
/// (spanPieces), graded toward graded anchor points as sampleCurve grades. Empty when the
/// stations do not fit the curve (not strictly inside it, in order and apart, or a stretch with
/// fewer pieces than spans).
std::vector<CurveNode> sampleWithStations(const Walk& walk, const std::vector<std::size_t>& anchors,
                                          const std::vector<Point3>& stations,
                                          const std::vector<long>& stationPieces,
                                          const std::vector<double>& grading) {
  const double length = walk.arc.back(), apart = 1e-6 * length;
  const PolylineParam line(walk.points, false);
  std::vector<double> cuts;  // station params
  for (const Point3& station : stations) {
    double away = 0.0;
    cuts.push_back(line.closestParam({station[0], station[1], station[2]}, away));
  }
  if (stationPieces.size() != cuts.size() + 1) return {};
  for (std::size_t k = 0; k < cuts.size(); ++k)
    if (cuts[k] < apart || cuts[k] > length - apart || (k > 0 && cuts[k] - cuts[k - 1] < apart))
      return {};
  // The anchors, stations among them where no anchor point is as close.
  std::vector<CurveNode> ends;
  for (const std::size_t i : anchors) ends.push_back({walk.arc[i], i});
  for (const double cut : cuts)
    if (std::none_of(ends.begin(), ends.end(),
                     [&](const CurveNode& node) { return std::abs(node.param - cut) < apart; }))
      ends.push_back({cut});
  std::sort(ends.begin(), ends.end(),
            [](const CurveNode& a, const CurveNode& b) { return a.param < b.param; });
  const auto stretchOf = [&](double from) {
    return std::size_t(std::upper_bound(cuts.begin(), cuts.end(), from + apart) - cuts.begin());
  };
  std::vector<std::vector<double>> lengths(stationPieces.size());
  for (std::size_t k = 0; k + 1 < ends.size(); ++k)
    lengths[stretchOf(ends[k].param)].push_back(ends[k + 1].param - ends[k].param);
  std::vector<std::vector<long>> pieces(stationPieces.size());
  for (std::size_t g = 0; g < lengths.size(); ++g) {
    if (lengths[g].empty() || stationPieces[g] < long(lengths[g].size())) return {};
    pieces[g] = spanPieces(lengths[g], stationPieces[g]);
  }
  const auto ratioAt = [&](const CurveNode& node) {
    return node.point == SIZE_MAX ? 0.0 : grading[node.point];
  };
  std::vector<CurveNode> nodes;
  std::vector<std::size_t> used(pieces.size(), 0);
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    const std::size_t g = stretchOf(ends[k].param);
    nodes.push_back(ends[k]);
    appendSpanNodes(ends[k].param, ends[k + 1].param - ends[k].param, pieces[g][used[g]++],
                    ratioAt(ends[k]), ratioAt(ends[k + 1]), nodes);
  }
  nodes.push_back(ends.back());
  return nodes;
}

/// The nodes of one curve in canonical order (closed: the first is not repeated).
/// A curve that keeps its points (VolumeCurve::keepPoints), or, when not graded, whose points are
/// already spaced as the sampling would space them (segmentsFitSpacing), has every point as a
/// node and no other. An open curve with a count of its own (`count` > 0) has every point as a
/// node when it has that many segments and is not graded, else that many pieces in all, spread
/// over its spans between anchors by their lengths, with no far points added (the count must
/// hold). `grading`: per curve point, the ratio of the pieces shrinking toward it where it ends a
/// span (gradedPieces), else 0. An open curve with stations that fit it is cut as
/// sampleWithStations cuts it.
std::vector<CurveNode> sampleCurve(const Walk& walk, bool keepPoints, long count, double spacing,
                                   double tolerance, double sagittaShare,
                                   const std::vector<double>& grading,
                                   const std::vector<Point3>& stations,
                                   const std::vector<long>& stationPieces) {
  const std::size_t n = walk.points.size();
  if (walk.closed) count = 0;
  const bool ownCount = count > 0;
  const bool graded =
      std::any_of(grading.begin(), grading.end(), [](double ratio) { return ratio > 1.0; });
  if (keepPoints ||
      (!graded && (ownCount ? long(n) - 1 == count : segmentsFitSpacing(walk, spacing)))) {
    std::vector<CurveNode> nodes;
    for (std::size_t i = 0; i < n; ++i) nodes.push_back({walk.arc[i], i});
    return nodes;
  }
  std::vector<std::size_t> anchors;
  for (std::size_t i = 0; i < n; ++i) {
    const bool end = !walk.closed && (i == 0 || i + 1 == n);
    if (end || ((walk.closed || (i > 0 && i + 1 < n)) &&
                turns(walk.points, (i + n - 1) % n, i, (i + 1) % n)))
      anchors.push_back(i);
  }
  if (!walk.closed && !keepPoints && !stations.empty()) {
    std::vector<CurveNode> nodes =
        sampleWithStations(walk, anchors, stations, stationPieces, grading);
    if (!nodes.empty()) return nodes;
  }
  if (anchors.empty()) anchors.push_back(0);
  if (walk.closed) anchors.push_back(anchors.front() + n);  // back to the first anchor
  std::vector<long> ownPieces;
  if (ownCount) {
    std::vector<double> lengths;
    for (std::size_t k = 0; k + 1 < anchors.size(); ++k)
      lengths.push_back(walk.arc[anchors[k + 1]] - walk.arc[anchors[k]]);
    ownPieces = spanPieces(lengths, count);
  }
  std::vector<CurveNode> nodes;
  for (std::size_t k = 0; k + 1 < anchors.size(); ++k) {
    const double from = walk.arc[anchors[k] % n] + (anchors[k] >= n ? walk.arc.back() : 0.0);
    const double to = anchors[k + 1] >= n && walk.closed
                          ? walk.arc[anchors[k + 1] - n] + walk.arc.back()
                          : walk.arc[anchors[k + 1]];
    const double length = to - from;
    long pieces = ownCount ? ownPieces[k] : std::max(1L, std::lround(length / spacing));
    if (walk.closed && anchors.size() == 2) pieces = std::max(3L, pieces);
    std::vector<CurveNode> span{{from, anchors[k] % n}};
    appendSpanNodes(from, length, pieces, grading[anchors[k] % n], grading[anchors[k + 1] % n],
                    span);
    span.push_back({to, anchors[k + 1] % n});
    for (std::size_t j = 0; j + 1 < span.size(); ++j) {
      nodes.push_back(span[j]);
      // Parameters beyond the closing point wrap around for the far-point search.
      if (!ownCount) addFarPoints(walk, span[j], span[j + 1], tolerance, sagittaShare, nodes);
    }
    if (!walk.closed && k + 2 == anchors.size()) nodes.push_back(span.back());
  }
  return nodes;
}

}  // namespace

JunctionNodes::JunctionNodes(const std::vector<VolumeCurve>& curves, double spacing,
                             double tolerance, double sagittaShare) {
  add(curves, spacing, tolerance, sagittaShare);
}

void JunctionNodes::add(const std::vector<VolumeCurve>& curves, double spacing, double tolerance,
                        double sagittaShare) {
  if (!(spacing > 0.0) || !std::isfinite(spacing) || !(tolerance > 0.0) ||
      !std::isfinite(tolerance))
    throw std::invalid_argument("junction nodes: spacing and tolerance must be positive");
  for (const VolumeCurve& curve : curves) {
    if (curve.points.size() < 2) continue;
    const std::vector<Point3> points = canonicalPoints(curve);
    const Walk walk(points, curve.closed);
    // A curve with a spacing of its own keeps the tolerance's share of it.
    const double own =
        curve.nodeSpacing > 0.0 && std::isfinite(curve.nodeSpacing) ? curve.nodeSpacing : spacing;
    std::vector<double> grading(points.size(), 0.0);
    for (const auto& [point, ratio] : curve.grading) {
      const auto at = std::find(points.begin(), points.end(), point);
      if (at != points.end()) grading[std::size_t(at - points.begin())] = ratio;
    }
    // Stations and their pieces in the canonical direction.
    std::vector<Point3> stations = curve.stations;
    std::vector<long> stationPieces = curve.stationPieces;
    if (!curve.closed && points.front() != curve.points.front()) {
      std::reverse(stations.begin(), stations.end());
      std::reverse(stationPieces.begin(), stationPieces.end());
    }
    const std::vector<CurveNode> nodes =
        sampleCurve(walk, curve.keepPoints, curve.nodeCount, own, tolerance * own / spacing,
                    sagittaShare, grading, stations, stationPieces);
    const std::size_t segments = walk.arc.size() - 1;
    std::vector<JunctionEdgeNodes> perEdge(segments);
    for (std::size_t s = 0; s < segments; ++s) perEdge[s].from = walk.at(s);
    for (const CurveNode& node : nodes) {
      if (node.point != SIZE_MAX) {
        nodePoints_.push_back(walk.at(node.point));
        continue;
      }
      auto [segment, t] = walk.locate(node.param);
      // On a curve point after all (an even piece ending there but for rounding).
      if (t <= kOnPointShare || t >= 1.0 - kOnPointShare) {
        nodePoints_.push_back(walk.at(t < 0.5 ? segment : segment + 1));
        continue;
      }
      perEdge[segment].along.push_back(t);
      perEdge[segment].points.push_back(walk.position(node));
    }
    for (std::size_t s = 0; s < segments; ++s) {
      const Point3 &a = walk.at(s), &b = walk.at(s + 1);
      edges_.emplace(std::make_pair(std::min(a, b), std::max(a, b)), std::move(perEdge[s]));
    }
  }
  std::sort(nodePoints_.begin(), nodePoints_.end());
  nodePoints_.erase(std::unique(nodePoints_.begin(), nodePoints_.end()), nodePoints_.end());
}

const JunctionEdgeNodes* JunctionNodes::edge(const Point3& a, const Point3& b) const {
  const auto it = edges_.find(std::make_pair(std::min(a, b), std::max(a, b)));
  return it == edges_.end() ? nullptr : &it->second;
}

std::vector<Point3> JunctionNodes::nodes() const {
  std::vector<Point3> all = nodePoints_;
  for (const auto& [key, edge] : edges_)
    all.insert(all.end(), edge.points.begin(), edge.points.end());
  return all;
}

bool JunctionNodes::isNodePoint(const Point3& p) const {
  return std::binary_search(nodePoints_.begin(), nodePoints_.end(), p);
}

}  // namespace voxremesh::extract
