// PolylineIndex: a binary hierarchy over halves of the segment range of a polyline, searched
// nearest box first and pruned by safe box distances (polyline_index.h).
#include "geometry/polyline_index.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "voxremesh/reference_surface.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// Segments per leaf.
constexpr std::uint32_t kLeafSegments = 4;

}  // namespace

PolylineIndex::PolylineIndex(const std::vector<std::array<double, 3>>& points, bool closed)
    : points_(points) {
  if (points_.empty()) return;
  segments_ = closed && points_.size() > 2 ? points_.size() : points_.size() - 1;
  for (const Vec3& q : points_)
    for (const double x : q)
      if (!std::isfinite(x)) return;  // unindexed: every query scans
  if (segments_ == 0) return;
  nodes_.reserve(2 * (segments_ / kLeafSegments) + 2);
  nodes_.emplace_back();
  build(0, static_cast<std::uint32_t>(segments_));
}

std::uint32_t PolylineIndex::build(std::uint32_t begin, std::uint32_t end) {
  // Called with this node already appended (nodes_ may grow: no references kept).
  const auto index = static_cast<std::uint32_t>(nodes_.size() - 1);
  nodes_[index].begin = begin;
  nodes_[index].end = end;
  if (end - begin <= kLeafSegments) {
    Box box;
    for (std::uint32_t i = begin; i < end; ++i) {
      box.add(points_[i]);
      box.add(points_[(i + 1) % points_.size()]);
    }
    nodes_[index].box = safeBox(box);
    return index;
  }
  const std::uint32_t middle = begin + (end - begin) / 2;
  nodes_.emplace_back();
  const std::uint32_t left = build(begin, middle);
  nodes_.emplace_back();
  const std::uint32_t right = build(middle, end);
  Box box = nodes_[left].box;
  box.add(nodes_[right].box);
  nodes_[index].box = box;
  nodes_[index].right = right;
  return index;
}

std::array<double, 3> PolylineIndex::closestPoint(const std::array<double, 3>& p) const {
  if (points_.empty()) throw std::invalid_argument("PolylineIndex::closestPoint: empty polyline");
  // The best so far under (squared distance, rank): the first point has rank 0, segment i rank
  // i + 1, which is the order in which closestPointOnPolyline's scan lets them win.
  Vec3 best = points_[0];
  double best2 = dot(p - best, p - best);
  std::size_t bestRank = 0;
  auto consider = [&](std::size_t i) {
    const Vec3 q = closestPointOnSegment(p, points_[i], points_[(i + 1) % points_.size()]);
    const double d2 = dot(p - q, p - q);
    if (d2 < best2 || (d2 == best2 && i + 1 < bestRank)) {
      best = q;
      best2 = d2;
      bestRank = i + 1;
    }
  };
  if (nodes_.empty()) {
    for (std::size_t i = 0; i < segments_; ++i) consider(i);
    return best;
  }
  // Depth first, nearer child first; a box farther than the best so far holds nothing better (a
  // tie with a lower rank is still looked at: only strictly farther boxes are skipped).
  struct Entry {
    std::uint32_t node;
    double distance2;
  };
  Entry stack[64];
  std::size_t top = 0;
  stack[top++] = {0, boxDistance2(p, nodes_[0].box)};
  while (top > 0) {
    const Entry entry = stack[--top];
    if (entry.distance2 > best2) continue;
    const Node& node = nodes_[entry.node];
    if (node.right == 0) {
      for (std::uint32_t i = node.begin; i < node.end; ++i) consider(i);
      continue;
    }
    const std::uint32_t left = entry.node + 1;
    const double leftD2 = boxDistance2(p, nodes_[left].box);
    const double rightD2 = boxDistance2(p, nodes_[node.right].box);
    if (leftD2 <= rightD2) {
      stack[top++] = {node.right, rightD2};
      stack[top++] = {left, leftD2};
    } else {
      stack[top++] = {left, leftD2};
      stack[top++] = {node.right, rightD2};
    }
  }
  return best;
}

}  // namespace voxremesh
