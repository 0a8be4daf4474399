// ReferenceSurface: a bounding-volume hierarchy over the triangles of a mesh with exact
// closest-point queries, and closest points on segments and polylines.
#include "voxremesh/reference_surface.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/safe_box.h"
#include "geometry/vec3.h"

namespace voxremesh {

using namespace geom;  // NOLINT: the vector operators

namespace {

constexpr std::uint32_t kLeafSize = 4;

}  // namespace

std::array<double, 3> closestPointOnSegment(const std::array<double, 3>& p,
                                            const std::array<double, 3>& a,
                                            const std::array<double, 3>& b) {
  const Vec3 ab = b - a;
  const double length2 = dot(ab, ab);
  if (!(length2 > 0.0)) return a;
  const double t = std::clamp(dot(p - a, ab) / length2, 0.0, 1.0);
  return a + ab * t;
}

std::array<double, 3> closestPointOnTriangle(const std::array<double, 3>& p,
                                             const std::array<double, 3>& a,
                                             const std::array<double, 3>& b,
                                             const std::array<double, 3>& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double sum = va + vb + vc;
  if (!(sum > 0.0) || !std::isfinite(sum)) {
    const Vec3 e[3] = {closestPointOnSegment(p, a, b), closestPointOnSegment(p, b, c),
                       closestPointOnSegment(p, c, a)};
    int best = 0;
    for (int k = 1; k < 3; ++k)
      if (dot(p - e[k], p - e[k]) < dot(p - e[best], p - e[best])) best = k;
    return e[best];
  }
  return a + ab * (vb / sum) + ac * (vc / sum);
}

std::array<double, 3> closestPointOnPolyline(const std::vector<std::array<double, 3>>& points,
                                             bool closed, const std::array<double, 3>& p) {
  if (points.empty()) throw std::invalid_argument("closestPointOnPolyline: empty polyline");
  Vec3 best = points[0];
  double bestD2 = dot(p - best, p - best);
  const std::size_t segments = closed && points.size() > 2 ? points.size() : points.size() - 1;
  for (std::size_t i = 0; i < segments; ++i) {
    const Vec3 q = closestPointOnSegment(p, points[i], points[(i + 1) % points.size()]);
    const double d2 = dot(p - q, p - q);
    if (d2 < bestD2) best = q, bestD2 = d2;
  }
  return best;
}

ReferenceSurface::ReferenceSurface(const QuadMesh& mesh) : points_(mesh.points) {
  for (const auto& point : points_)
    for (double x : point)
      if (!std::isfinite(x))
        throw std::invalid_argument("reference surface: a point has a non-finite coordinate");
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    faceTriStart_.push_back(static_cast<std::uint32_t>(tris_.size()));
    const auto& face = mesh.faces[f];
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k)
      if (face[static_cast<std::size_t>(k)] >= points_.size())
        throw std::invalid_argument("reference surface: face " + std::to_string(f) +
                                    " names a missing point");
    tris_.push_back({face[0], face[1], face[2]});
    triFace_.push_back(static_cast<std::uint32_t>(f));
    if (n == 4) {
      tris_.push_back({face[0], face[2], face[3]});
      triFace_.push_back(static_cast<std::uint32_t>(f));
    }
  }
  faceTriStart_.push_back(static_cast<std::uint32_t>(tris_.size()));
  if (tris_.empty()) return;
  std::vector<Vec3> centroids(tris_.size());
  for (std::size_t t = 0; t < tris_.size(); ++t)
    centroids[t] =
        (points_[tris_[t][0]] + points_[tris_[t][1]] + points_[tris_[t][2]]) * (1.0 / 3.0);
  order_.resize(tris_.size());
  for (std::uint32_t t = 0; t < order_.size(); ++t) order_[t] = t;
  leafTris_.resize(tris_.size());
  leafSlot_.resize(tris_.size());
  leafNode_.resize(tris_.size());
  // A leaf holds 2 .. kLeafSize triangles (one when there is only one): at most one node per
  // triangle, and one more.
  nodes_.reserve(tris_.size() + 1);
  nodes_.emplace_back();
  build(0, static_cast<std::uint32_t>(order_.size()), centroids);
  parent_.assign(nodes_.size(), 0);
  for (std::uint32_t n = 0; n < nodes_.size(); ++n)
    if (nodes_[n].count == 0) parent_[nodes_[n].first] = parent_[nodes_[n].right] = n;
}

std::uint32_t ReferenceSurface::build(std::uint32_t begin, std::uint32_t end,
                                      const std::vector<std::array<double, 3>>& centroids) {
  // Called with this node already appended to nodes_ (nodes_ may grow: no references kept).
  const std::uint32_t index = static_cast<std::uint32_t>(nodes_.size() - 1);
  Box centroidBox;
  for (std::uint32_t i = begin; i < end; ++i) centroidBox.add(centroids[order_[i]]);
  const Vec3& clo = centroidBox.lo;
  const Vec3& chi = centroidBox.hi;
  if (end - begin <= kLeafSize) {
    // The triangles in leaf order with grown boxes (safeBox), the leaf's box holding them.
    Box leafBox;
    for (std::uint32_t i = begin; i < end; ++i) {
      LeafTriangle& t = leafTris_[i];
      t.triangle = order_[i];
      leafSlot_[t.triangle] = i;
      leafNode_[t.triangle] = index;
      fitLeafTriangle(t);
      leafBox.add(Box{t.lo, t.hi});
    }
    nodes_[index].lo = leafBox.lo;
    nodes_[index].hi = leafBox.hi;
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
  const std::uint32_t middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](std::uint32_t a, std::uint32_t b) {
                     const double ca = centroids[a][axis], cb = centroids[b][axis];
                     return ca < cb || (ca == cb && a < b);
                   });
  nodes_.emplace_back();
  const std::uint32_t left = build(begin, middle, centroids);
  nodes_.emplace_back();
  const std::uint32_t right = build(middle, end, centroids);
  Box box{nodes_[left].lo, nodes_[left].hi};
  box.add(Box{nodes_[right].lo, nodes_[right].hi});
  nodes_[index].lo = box.lo;
  nodes_[index].hi = box.hi;
  nodes_[index].first = left;
  nodes_[index].count = 0;
  nodes_[index].right = right;
  return index;
}

void ReferenceSurface::fitLeafTriangle(LeafTriangle& t) const {
  Box box;
  for (std::size_t k = 0; k < 3; ++k) {
    t.corners[k] = points_[tris_[t.triangle][k]];
    box.add(t.corners[k]);
  }
  box = safeBox(box);
  t.lo = box.lo;
  t.hi = box.hi;
}

void ReferenceSurface::movePoints(const std::vector<std::array<double, 3>>& points) {
  if (points.size() != points_.size())
    throw std::invalid_argument("reference surface: " + std::to_string(points.size()) +
                                " moved points for " + std::to_string(points_.size()));
  for (const auto& point : points)
    for (double x : point)
      if (!std::isfinite(x))
        throw std::invalid_argument("reference surface: a point has a non-finite coordinate");
  points_ = points;
  for (LeafTriangle& t : leafTris_) fitLeafTriangle(t);
  // Children come after their parent in nodes_: from the last node back, each box is fitted
  // after those it holds, as build fits them.
  for (std::size_t n = nodes_.size(); n-- > 0;) {
    Node& node = nodes_[n];
    Box box;
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
        box.add(Box{leafTris_[i].lo, leafTris_[i].hi});
    } else {
      box = Box{nodes_[node.first].lo, nodes_[node.first].hi};
      box.add(Box{nodes_[node.right].lo, nodes_[node.right].hi});
    }
    node.lo = box.lo;
    node.hi = box.hi;
  }
}

SurfaceHit ReferenceSurface::closestPoint(const std::array<double, 3>& p) const {
  return closestPoint(p, std::numeric_limits<std::uint32_t>::max());
}

SurfaceHit ReferenceSurface::closestPoint(const std::array<double, 3>& p,
                                          std::uint32_t hintFace) const {
  SurfaceHit hit;
  double best2 = std::numeric_limits<double>::infinity();
  std::uint32_t bestTri = std::numeric_limits<std::uint32_t>::max();
  // The best so far under the order (squared distance, triangle index), whatever the visit order;
  // a triangle whose box is farther than the best cannot win (an equal distance still may).
  auto consider = [&](const LeafTriangle& t) {
    if (boxDistance2(p, t.lo, t.hi) > best2) return;
    const Vec3 q = closestPointOnTriangle(p, t.corners[0], t.corners[1], t.corners[2]);
    const double d2 = dot(p - q, p - q);
    if (d2 < best2 || (d2 == best2 && t.triangle < bestTri)) {
      best2 = d2;
      bestTri = t.triangle;
      hit.point = q;
    }
  };
  // Depth first below `root` (at squared box distance root2), the nearer child first, each box
  // distance computed once.
  struct Entry {
    std::uint32_t node;
    double distance2;
  };
  auto search = [&](std::uint32_t root, double root2) {
    Entry stack[128];
    std::size_t top = 0;
    stack[top++] = {root, root2};
    while (top > 0) {
      const Entry entry = stack[--top];
      if (entry.distance2 > best2) continue;
      const Node& node = nodes_[entry.node];
      if (node.count > 0) {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i) consider(leafTris_[i]);
        continue;
      }
      const Node& l = nodes_[node.first];
      const Node& r = nodes_[node.right];
      const double left2 = boxDistance2(p, l.lo, l.hi), right2 = boxDistance2(p, r.lo, r.hi);
      // Push the nearer child last (visited first); a child farther than the best is left out.
      if (left2 <= right2) {
        if (!(right2 > best2)) stack[top++] = {node.right, right2};
        if (!(left2 > best2)) stack[top++] = {node.first, left2};
      } else {
        if (!(left2 > best2)) stack[top++] = {node.first, left2};
        if (!(right2 > best2)) stack[top++] = {node.right, right2};
      }
    }
  };
  if (faceTriStart_.size() > 1 && hintFace < faceTriStart_.size() - 1) {
    // The hint's triangles, the rest of the leaf of its first, then up to the root: at each
    // step the other child's subtree. Every node below the root is searched or pruned once.
    const std::uint32_t first = faceTriStart_[hintFace], end = faceTriStart_[hintFace + 1];
    for (std::uint32_t t = first; t < end; ++t) consider(leafTris_[leafSlot_[t]]);
    std::uint32_t node = leafNode_[first];
    const Node& leaf = nodes_[node];
    for (std::uint32_t i = leaf.first; i < leaf.first + leaf.count; ++i)
      if (leafTris_[i].triangle < first || leafTris_[i].triangle >= end) consider(leafTris_[i]);
    while (node != 0) {
      const std::uint32_t parent = parent_[node];
      const std::uint32_t other =
          nodes_[parent].first == node ? nodes_[parent].right : nodes_[parent].first;
      const double other2 = boxDistance2(p, nodes_[other].lo, nodes_[other].hi);
      if (!(other2 > best2)) search(other, other2);
      node = parent;
    }
  } else {
    search(0, boxDistance2(p, nodes_[0].lo, nodes_[0].hi));
  }
  if (bestTri == std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("ReferenceSurface::closestPoint: the query point is not finite");
  hit.distance = std::sqrt(best2);
  hit.face = triFace_[bestTri];
  return hit;
}

std::vector<std::array<double, 3>> ReferenceSurface::usedPoints() const {
  std::vector<std::uint8_t> used(points_.size(), 0);
  for (const auto& tri : tris_)
    for (const std::uint32_t v : tri) used[v] = 1;
  std::vector<Vec3> result;
  for (std::size_t v = 0; v < points_.size(); ++v)
    if (used[v]) result.push_back(points_[v]);
  return result;
}

std::vector<SurfaceHit> ReferenceSurface::closestPoints(
    const std::vector<std::array<double, 3>>& queries) const {
  std::vector<SurfaceHit> hits(queries.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, queries.size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      // Queries come in runs of near points (a face's samples): each one
                      // starts from the answer before it (the same answers, found faster).
                      std::uint32_t hint = std::numeric_limits<std::uint32_t>::max();
                      for (std::size_t i = r.begin(); i < r.end(); ++i) {
                        hits[i] = closestPoint(queries[i], hint);
                        hint = hits[i].face;
                      }
                    });
  return hits;
}

}  // namespace voxremesh
