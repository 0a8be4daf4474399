// Narrow sheets meshed from their boundary alone (see narrow_sheet.h).
#include "extract/narrow_sheet.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "extract/mapped_patch.h"
#include "extract/polygon_quads.h"
#include "extract/polyline_param.h"
#include "extract/sheet_patches.h"
#include "geometry/chord_limit.h"
#include "geometry/vec3.h"

namespace voxremesh::extract {

using namespace geom;  // NOLINT: the vector operators

namespace {

/// A node facing one across the sheet is placed only this share of the spacing (or, where the
/// nodes may follow short pieces across, of the pieces next to the node it faces where those are
/// shorter: a wedge's junction nodes close toward its wide end) or more from the nodes before and
/// after it on the loop (so no piece is much shorter than the spacing).
constexpr double kShortestPiece = 0.4;
/// One row across a patch is searched among at most this many boundary nodes (the search costs
/// about the cube of the count where chords are long): a wider sheet is no strip.
constexpr std::size_t kMostRowNodes = 400;
/// Two stretches of the loop face each other when their directions differ by more than 135
/// degrees (the cosine of 45 degrees).
constexpr double kFacingCosine = 0.7071067811865476;

/// The unit direction of the loop's segment holding arc length v.
openvdb::math::Vec3d tangentAt(const PolylineParam& loop, double v) {
  const std::size_t s = loop.segmentAt(std::fmod(v, loop.length()));
  openvdb::math::Vec3d d = loop.point((s + 1) % loop.pointCount()) - loop.point(s);
  return d.length() > 0.0 ? d / d.length() : d;
}

/// A node placed on a loop, which the nodes of stretches facing it line up with: its position, the
/// direction of its loop there and the shorter of the pieces next to it on its loop.
struct FacingSource {
  Vec3 point{};
  openvdb::math::Vec3d tangent;
  double piece = HUGE_VAL;
};

/// The facing sources of the nodes on a closed loop (corners excepted: a strip's tapered end is
/// no row); `nodes` in any order.
std::vector<FacingSource> facingSources(std::vector<LoopNode> nodes, const PolylineParam& loop) {
  std::stable_sort(nodes.begin(), nodes.end(),
                   [](const LoopNode& a, const LoopNode& b) { return a.param < b.param; });
  std::vector<FacingSource> sources;
  const std::size_t n = nodes.size();
  for (std::size_t j = 0; j < n; ++j) {
    if (nodes[j].role == PointRole::Corner) continue;
    const double before = nodes[j].param - nodes[(j + n - 1) % n].param;
    const double after = nodes[(j + 1) % n].param - nodes[j].param;
    const auto wrapped = [&](double gap) { return gap > 0.0 ? gap : gap + loop.length(); };
    sources.push_back({nodes[j].point, tangentAt(loop, nodes[j].param),
                       n > 1 ? std::min(wrapped(before), wrapped(after)) : HUGE_VAL});
  }
  return sources;
}

/// Per source of `sources` within `reach` of the loop where the loop runs against the source's
/// stretch (by more than 135 degrees: the sides of a strip face each other), the arc length in
/// [c0, c1] (c1 may pass the length once) of the loop's closest point to it, with the source's
/// shorter piece; ascending.
std::vector<std::pair<double, double>> facingParams(const PolylineParam& loop, double c0, double c1,
                                                    const std::vector<FacingSource>& sources,
                                                    double reach) {
  const double length = loop.length();
  const std::size_t m = loop.pointCount();
  std::vector<std::pair<double, double>> params;
  for (const FacingSource& source : sources) {
    const openvdb::math::Vec3d p(source.point[0], source.point[1], source.point[2]);
    double best = reach, bestParam = -1.0;
    // The segments overlapping [c0, c1], with their arc lengths unwrapped past c0.
    for (std::size_t step = 0, s = loop.segmentAt(std::fmod(c0, length)); step <= m;
         ++step, s = (s + 1) % m) {
      double v0 = loop.vertexParam(s), v1 = loop.vertexParam(s + 1);
      while (v1 <= c0) v0 += length, v1 += length;
      if (v0 >= c1) break;
      const openvdb::math::Vec3d a = loop.point(s), ab = loop.point((s + 1) % m) - a;
      const double len2 = ab.lengthSqr();
      double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      t = std::clamp(v0 + t * (v1 - v0), c0, c1);
      const double d = (loop.pointAt(t) - p).length();
      if (d < best) best = d, bestParam = t;
    }
    if (bestParam > c0 && bestParam < c1 &&
        tangentAt(loop, bestParam).dot(source.tangent) < -kFacingCosine)
      params.emplace_back(bestParam, source.piece);
  }
  std::sort(params.begin(), params.end());
  return params;
}

/// A closed loop of points with the junction edges on it: arc lengths, and the nodes and gaps of
/// a node list along it.
struct NodeLoop {
  PolylineParam loop;
  double length;
  std::vector<const JunctionEdgeNodes*> junctionEdge;  ///< per segment, or null

  NodeLoop(const std::vector<Vec3>& points, const JunctionNodes& junctions)
      : loop(points, true), length(loop.length()), junctionEdge(points.size(), nullptr) {
    for (std::size_t s = 0; s < points.size(); ++s)
      junctionEdge[s] = junctions.edge(points[s], points[(s + 1) % points.size()]);
  }
  /// The arc length where the gap after nodes[j] ends (past the length for the last).
  double gapEnd(const std::vector<LoopNode>& nodes, std::size_t j) const {
    return j + 1 < nodes.size() ? nodes[j + 1].param : nodes[0].param + length;
  }
  /// True when nodes may go into the gap after nodes[j]: it does not run along a junction curve
  /// (between two of its nodes, or a node and a corner of the sheet on it), whose nodes are the
  /// curve's on every side.
  bool free(const std::vector<LoopNode>& nodes, std::size_t j) const {
    const double middle = std::fmod(0.5 * (nodes[j].param + gapEnd(nodes, j)), length);
    return junctionEdge[loop.segmentAt(middle)] == nullptr;
  }
  /// A Boundary node at arc length v (wrapped into the loop).
  LoopNode nodeAt(double v) const {
    v = std::fmod(v, length);
    return LoopNode{v, toArray(loop.pointAt(v)), PointRole::Boundary};
  }
};

bool byParam(const LoopNode& a, const LoopNode& b) {
  return a.param < b.param;
}

/// The nodes the loop prescribes, ascending: the junction curves' nodes on its junction edges
/// (with the ends of each junction stretch) and its corners; a junction node wins over a corner
/// at the same place.
std::vector<LoopNode> anchorNodes(const NodeLoop& walk, const std::vector<Vec3>& points,
                                  const std::vector<char>& corner, const JunctionNodes& junctions) {
  const std::size_t m = points.size();
  std::vector<LoopNode> anchors;
  for (std::size_t s = 0; s < m; ++s) {
    const JunctionEdgeNodes* edge = walk.junctionEdge[s];
    if (edge == nullptr) continue;
    const double s0 = walk.loop.vertexParam(s), s1 = walk.loop.vertexParam(s + 1);
    const bool forward = edge->from == points[s];
    for (std::size_t j = 0; j < edge->along.size(); ++j) {
      const double t = forward ? edge->along[j] : 1.0 - edge->along[j];
      anchors.push_back({s0 + t * (s1 - s0), edge->points[j], PointRole::Junction});
    }
    for (const std::size_t end : {s, s + 1}) {  // a stretch's ends and the curve's own nodes
      const std::size_t other = end == s ? (s + m - 1) % m : (s + 1) % m;
      if (junctions.isNodePoint(points[end % m]) || walk.junctionEdge[other] == nullptr)
        anchors.push_back({std::fmod(walk.loop.vertexParam(end), walk.length), points[end % m],
                           PointRole::Junction});
    }
  }
  for (std::size_t i = 0; i < m; ++i)
    if (corner[i]) anchors.push_back({walk.loop.vertexParam(i), points[i], PointRole::Corner});
  std::stable_sort(anchors.begin(), anchors.end(), [](const LoopNode& a, const LoopNode& b) {
    return a.param < b.param ||
           (a.param == b.param && a.role == PointRole::Junction && b.role != PointRole::Junction);
  });
  anchors.erase(std::unique(anchors.begin(), anchors.end(),
                            [&](const LoopNode& a, const LoopNode& b) {
                              return b.param - a.param <= 1e-12 * walk.length;
                            }),
                anchors.end());
  if (anchors.empty()) anchors.push_back({0.0, points[0], PointRole::Boundary});
  return anchors;
}

/// The anchors plus nodes in their free gaps, in loop order: first the points facing nodes
/// already placed across the sheet (so that rows run straight across; corners excepted; with
/// `followShortPieces` also as close to other nodes as the pieces next to the node faced are
/// short, see kShortestPiece), then even pieces about `spacing` long between; ascending.
std::vector<LoopNode> fillFreeGaps(const NodeLoop& walk, const std::vector<LoopNode>& anchors,
                                   double spacing, double reach,
                                   const std::vector<FacingSource>& across,
                                   bool followShortPieces) {
  std::vector<LoopNode> nodes = anchors;
  for (std::size_t j = 0; j < anchors.size(); ++j) {
    if (!walk.free(anchors, j)) continue;
    const double c0 = anchors[j].param, c1 = walk.gapEnd(anchors, j);
    std::vector<FacingSource> placed = across;
    for (const FacingSource& source : facingSources(nodes, walk.loop)) placed.push_back(source);
    std::vector<double> breaks{c0};
    for (const auto& [v, piece] : facingParams(walk.loop, c0, c1, placed, reach)) {
      const double shortest =
          kShortestPiece * (followShortPieces ? std::min(spacing, piece) : spacing);
      if (v - breaks.back() >= shortest && c1 - v >= shortest) breaks.push_back(v);
    }
    breaks.push_back(c1);
    for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
      if (b > 0) nodes.push_back(walk.nodeAt(breaks[b]));
      const long pieces = std::max(1L, std::lround((breaks[b + 1] - breaks[b]) / spacing));
      for (long q = 1; q < pieces; ++q)
        nodes.push_back(
            walk.nodeAt(breaks[b] + (breaks[b + 1] - breaks[b]) * double(q) / double(pieces)));
    }
  }
  std::stable_sort(nodes.begin(), nodes.end(), byParam);
  return nodes;
}

/// Adds the loop points farther than `tolerance` (or `sagittaShare` x the chord's length, where
/// that is less) from the chords of free gaps, then one node in the longest free gap when the
/// count is odd (quads need an even count); keeps the order.
void addFarPointsAndEvenCount(const NodeLoop& walk, std::vector<LoopNode>& nodes, double tolerance,
                              double sagittaShare) {
  std::vector<double> far;
  for (std::size_t j = 0; j < nodes.size(); ++j)
    if (walk.free(nodes, j))
      addFarVertices(walk.loop, nodes[j].param, walk.gapEnd(nodes, j), tolerance, far,
                     sagittaShare);
  for (const double v : far) nodes.push_back(walk.nodeAt(v));
  std::stable_sort(nodes.begin(), nodes.end(), byParam);
  if (nodes.size() % 2 == 0) return;
  std::size_t widest = nodes.size();
  for (std::size_t j = 0; j < nodes.size(); ++j)
    if (walk.free(nodes, j) &&
        (widest == nodes.size() ||
         walk.gapEnd(nodes, j) - nodes[j].param > walk.gapEnd(nodes, widest) - nodes[widest].param))
      widest = j;
  if (widest == nodes.size()) return;
  nodes.push_back(walk.nodeAt(0.5 * (nodes[widest].param + walk.gapEnd(nodes, widest))));
  std::stable_sort(nodes.begin(), nodes.end(), byParam);
}

/// The nodes on the loop (see narrow_sheet.h), ascending arc length; free stretches also line up
/// with the nodes of `across` (those of another loop of the patch).
std::vector<LoopNode> loopNodes(const std::vector<Vec3>& points, const std::vector<char>& corner,
                                const JunctionNodes& junctions, const NarrowSheetSettings& settings,
                                const std::vector<FacingSource>& across) {
  const NodeLoop walk(points, junctions);
  std::vector<LoopNode> nodes =
      fillFreeGaps(walk, anchorNodes(walk, points, corner, junctions), settings.spacing,
                   settings.maxChord, across, settings.followShortPieces);
  addFarPointsAndEvenCount(walk, nodes, settings.tolerance, settings.sagittaShare);
  for (std::size_t j = 0; j < nodes.size(); ++j) nodes[j].fixedAfter = !walk.free(nodes, j);
  return nodes;
}

/// True when points sampled along the chord a-b, at most a quarter of `spacing` apart, all lie
/// within `tolerance`, and within `sagittaShare` x its length where that is positive, of the
/// surface.
bool chordOnSurface(const Vec3& a, const Vec3& b, const ReferenceSurface& reference, double spacing,
                    double tolerance, double sagittaShare) {
  tolerance = geom::chordLimit(tolerance, sagittaShare, distance(a, b));
  const long samples = std::max(4L, long(std::ceil(distance(a, b) / (0.25 * spacing))));
  for (long q = 1; q < samples; ++q)
    if (reference.closestPoint(a + (b - a) * (double(q) / double(samples))).distance > tolerance)
      return false;
  return true;
}

/// The surface normal of the face of `surface` closest to p.
Vec3 normalAt(const QuadMesh& surface, const ReferenceSurface& reference, const Vec3& p) {
  const auto& face = surface.faces[reference.closestPoint(p).face];
  const bool triangle = cornerCount(face) == 3;
  return elementNormal(surface.points[face[0]], surface.points[face[1]], surface.points[face[2]],
                       surface.points[face[triangle ? 2 : 3]], triangle);
}

/// Appends to `mesh` one row of faces across a boundary polygon (polygonQuads): its corners
/// `polygon`, corner k being mesh point pointOf[k] (a point may be two corners: a ring's bridge).
/// Throws NarrowSheetRefusal when the polygon has more than kMostRowNodes corners or no mesh of
/// them stays within the tolerance of the surface.
void addRowFaces(QuadMesh& mesh, const std::vector<Vec3>& polygon,
                 const std::vector<std::uint32_t>& pointOf, const QuadMesh& surface,
                 const ReferenceSurface& reference, const NarrowSheetSettings& settings) {
  if (polygon.size() > kMostRowNodes)
    throw NarrowSheetRefusal("its boundary has " + std::to_string(polygon.size()) +
                             " nodes, more than one row across it takes (" +
                             std::to_string(kMostRowNodes) + ")");
  std::vector<Vec3> normals;
  for (const Vec3& p : polygon) normals.push_back(normalAt(surface, reference, p));
  const std::vector<PolygonFace> faces = polygonQuads(
      polygon, normals, settings.maxChord,
      [&](std::size_t i, std::size_t j) {
        return pointOf[i] != pointOf[j] &&
               chordOnSurface(polygon[i], polygon[j], reference, settings.spacing,
                              settings.tolerance, settings.sagittaShare);
      },
      settings.criteria);
  if (faces.empty())
    throw NarrowSheetRefusal("no row of faces across it between its " +
                             std::to_string(mesh.points.size()) + " boundary nodes stays on it");
  for (const PolygonFace& face : faces)
    mesh.faces.push_back({pointOf[face[0]], pointOf[face[1]], pointOf[face[2]],
                          face[3] == UINT32_MAX ? kNoCorner : pointOf[face[3]]});
}

/// The mesh of a grid over a patch (mapped_patch.h) bounded by `loopPoints`.
QuadMesh gridMesh(const MappedPatch& grid, const std::vector<Vec3>& loopPoints) {
  QuadMesh mesh;
  mesh.curves.push_back({loopPoints, true, PointRole::Boundary});
  for (const LoopNode& node : grid.loop) {
    mesh.points.push_back(node.point);
    mesh.constraints.push_back({node.role, 0});
  }
  for (const Vec3& p : grid.inner) {
    mesh.points.push_back(p);
    mesh.constraints.push_back({});
  }
  for (const auto& quad : grid.quads) mesh.faces.push_back({quad[0], quad[1], quad[2], quad[3]});
  return mesh;
}

/// The faces of `mesh` failing one of the criteria (elementFailures) but the minimum length, which
/// the caller judges against the size it used (as polygonQuads does).
std::size_t failingFaces(const QuadMesh& mesh, const QualitySettings& criteria) {
  const std::vector<ElementQuality> qualities = elementQualities(mesh);
  const std::uint32_t lengthBit = 1u << static_cast<int>(Criterion::MinLength);
  std::size_t failing = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    failing +=
        (elementFailures(qualities[f], cornerCount(mesh.faces[f]), criteria) & ~lengthBit) != 0;
  return failing;
}

/// The mesh of one patch from the nodes of its loop (see narrow_sheet.h): a grid where the patch
/// is four-sided (mapped_patch.h); else one row across its boundary polygon (polygon_quads.h),
/// or two grids of an L-shaped patch (lShapedPatch) or grids round its centre (midpointPatch)
/// where no larger share of their elements fails a criterion than of the row's.
QuadMesh meshLoop(const std::vector<Vec3>& loopPoints, const std::vector<char>& corner,
                  const QuadMesh& surface, const ReferenceSurface& reference,
                  const JunctionNodes& junctions, const NarrowSheetSettings& settings) {
  const std::vector<LoopNode> nodes = loopNodes(loopPoints, corner, junctions, settings, {});
  const auto surfaceNormal = [&](const Vec3& p) { return normalAt(surface, reference, p); };
  if (const auto grid = mappedPatch(PolylineParam(loopPoints, true), nodes, reference,
                                    surfaceNormal, settings.tolerance, settings.sagittaShare))
    return gridMesh(*grid, loopPoints);
  auto grids =
      lShapedPatch(nodes, reference, surfaceNormal, settings.tolerance, settings.sagittaShare);
  if (!grids)
    grids =
        midpointPatch(nodes, reference, surfaceNormal, settings.tolerance, settings.sagittaShare);
  QuadMesh mesh;
  mesh.curves.push_back({loopPoints, true, PointRole::Boundary});
  std::vector<Vec3> polygon;
  std::vector<std::uint32_t> pointOf;
  for (const LoopNode& node : nodes) {
    pointOf.push_back(std::uint32_t(mesh.points.size()));
    polygon.push_back(node.point);
    mesh.points.push_back(node.point);
    mesh.constraints.push_back({node.role, 0});
  }
  try {
    addRowFaces(mesh, polygon, pointOf, surface, reference, settings);
  } catch (const NarrowSheetRefusal&) {
    if (!grids) throw;
    return gridMesh(*grids, loopPoints);
  }
  if (grids) {
    QuadMesh gridded = gridMesh(*grids, loopPoints);
    if (failingFaces(gridded, settings.criteria) * mesh.faces.size() <=
        failingFaces(mesh, settings.criteria) * gridded.faces.size())
      return gridded;
  }
  return mesh;
}

/// The nodes the junctions prescribe inside a rung (its points from one loop to the other): its
/// inner points that are nodes and the nodes inside its edges, in its order.
std::vector<Vec3> rungNodes(const std::vector<Vec3>& rung, const JunctionNodes& junctions) {
  std::vector<Vec3> nodes;
  for (std::size_t i = 0; i + 1 < rung.size(); ++i) {
    if (i > 0 && junctions.isNodePoint(rung[i])) nodes.push_back(rung[i]);
    const JunctionEdgeNodes* edge = junctions.edge(rung[i], rung[i + 1]);
    if (edge == nullptr) continue;
    if (edge->from == rung[i])
      nodes.insert(nodes.end(), edge->points.begin(), edge->points.end());
    else
      nodes.insert(nodes.end(), edge->points.rbegin(), edge->points.rend());
  }
  return nodes;
}

/// The index of the node of `nodes` at p exactly, or nodes.size().
std::size_t nodeAt(const std::vector<LoopNode>& nodes, const Vec3& p) {
  for (std::size_t k = 0; k < nodes.size(); ++k)
    if (nodes[k].point == p) return k;
  return nodes.size();
}

/// The mesh of a ring patch (two loops, a band or a tube): the nodes of both loops, the second's
/// lined up with the first's; rows swept from one loop to the other where they fit
/// (mapped_patch.h, mappedRing) and no rung crosses it, else both joined by a bridge into one
/// polygon (each loop run once, the bridge there and back), which polygonQuads meshes; the
/// bridge's two visits are one line of edges again afterwards. The bridge is the rung (its points
/// from a corner of the first loop to one of the second, with the junction nodes inside it), or
/// without one the shortest chord between the loops' nodes that lies on the surface.
QuadMesh meshRing(const std::array<std::vector<Vec3>, 2>& loops,
                  const std::array<std::vector<char>, 2>& corners, const std::vector<Vec3>& rung,
                  const QuadMesh& surface, const ReferenceSurface& reference,
                  const JunctionNodes& junctions, const NarrowSheetSettings& settings) {
  const std::vector<LoopNode> first = loopNodes(loops[0], corners[0], junctions, settings, {});
  const std::vector<FacingSource> across = facingSources(first, PolylineParam(loops[0], true));
  const std::vector<LoopNode> second = loopNodes(loops[1], corners[1], junctions, settings, across);
  const auto surfaceNormal = [&](const Vec3& p) { return normalAt(surface, reference, p); };
  if (const auto rows =
          !rung.empty() ? std::nullopt
                        : mappedRing({PolylineParam(loops[0], true), PolylineParam(loops[1], true)},
                                     {first, second}, settings.spacing, reference, surfaceNormal,
                                     settings.tolerance, settings.sagittaShare)) {
    QuadMesh mesh;
    for (std::uint32_t l = 0; l < 2; ++l) {
      mesh.curves.push_back({loops[l], true, PointRole::Boundary});
      for (const LoopNode& node : rows->loops[l]) {
        mesh.points.push_back(node.point);
        mesh.constraints.push_back({node.role, l});
      }
    }
    for (const Vec3& p : rows->inner) {
      mesh.points.push_back(p);
      mesh.constraints.push_back({});
    }
    for (const auto& quad : rows->quads) mesh.faces.push_back({quad[0], quad[1], quad[2], quad[3]});
    return mesh;
  }
  std::size_t a0 = first.size(), b0 = second.size();
  if (!rung.empty()) {
    a0 = nodeAt(first, rung.front());
    b0 = nodeAt(second, rung.back());
    if (a0 == first.size() || b0 == second.size())
      throw NarrowSheetRefusal("the ends of a rung across it are no nodes of its loops");
  }
  // Else the bridge: the closest pair of nodes whose chord lies on the surface.
  double shortest = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < first.size() && rung.empty(); ++a)
    for (std::size_t b = 0; b < second.size(); ++b) {
      const double d = distance(first[a].point, second[b].point);
      if (d < shortest &&
          chordOnSurface(first[a].point, second[b].point, reference, settings.spacing,
                         settings.tolerance, settings.sagittaShare))
        shortest = d, a0 = a, b0 = b;
    }
  if (a0 == first.size())
    throw NarrowSheetRefusal("no bridge between its two boundary loops stays on it");
  QuadMesh mesh;
  mesh.curves.push_back({loops[0], true, PointRole::Boundary});
  mesh.curves.push_back({loops[1], true, PointRole::Boundary});
  // Polygon: the first loop from a0 round to a0 again, then the second from b0 round to b0.
  std::vector<std::uint32_t> pointOf;  // polygon corner -> mesh point
  std::vector<Vec3> polygon;
  auto add = [&](const std::vector<LoopNode>& nodes, std::size_t start, std::uint32_t curve) {
    const std::uint32_t base = std::uint32_t(mesh.points.size());
    for (const LoopNode& node : nodes) {
      mesh.points.push_back(node.point);
      mesh.constraints.push_back({node.role, curve});
    }
    for (std::size_t k = 0; k <= nodes.size(); ++k) {
      const std::size_t i = (start + k) % nodes.size();
      pointOf.push_back(base + std::uint32_t(i));
      polygon.push_back(nodes[i].point);
    }
  };
  // The rung's inner nodes, fixed, visited on the way to the second loop and back.
  const std::uint32_t rungBase = std::uint32_t(mesh.points.size());
  const std::vector<Vec3> inner = rungNodes(rung, junctions);
  for (const Vec3& p : inner) {
    mesh.points.push_back(p);
    mesh.constraints.push_back({PointRole::Corner, 0});
  }
  add(first, a0, 0);
  for (std::size_t k = 0; k < inner.size(); ++k) {
    pointOf.push_back(rungBase + std::uint32_t(k));
    polygon.push_back(inner[k]);
  }
  add(second, b0, 1);
  for (std::size_t k = inner.size(); k-- > 0;) {
    pointOf.push_back(rungBase + std::uint32_t(k));
    polygon.push_back(inner[k]);
  }
  addRowFaces(mesh, polygon, pointOf, surface, reference, settings);
  return mesh;
}

/// The meshes of the patches, joined at their shared nodes.
QuadMesh meshPatches(const Sheet& sheet, const std::vector<SheetPatch>& patches,
                     const QuadMesh& surface, const ReferenceSurface& reference,
                     const JunctionNodes& junctions, const NarrowSheetSettings& settings) {
  const std::set<PointIndex> corners(sheet.featurePoints.begin(), sheet.featurePoints.end());
  std::vector<QuadMesh> patchMeshes;
  for (const SheetPatch& patch : patches) {
    std::array<std::vector<Vec3>, 2> loopPoints;
    std::array<std::vector<char>, 2> corner;
    std::vector<Vec3> rung;
    for (const PointIndex p : patch.rung) rung.push_back(sheet.points[p]);
    for (std::size_t l = 0; l < patch.loops.size(); ++l)
      for (const PointIndex p : patch.loops[l]) {
        loopPoints[l].push_back(sheet.points[p]);
        // A rung's ends are nodes of the loops.
        const bool rungEnd =
            !patch.rung.empty() && (p == patch.rung.front() || p == patch.rung.back());
        corner[l].push_back(corners.count(p) != 0 || rungEnd);
      }
    patchMeshes.push_back(
        patch.loops.size() == 1
            ? meshLoop(loopPoints[0], corner[0], surface, reference, junctions, settings)
            : meshRing(loopPoints, corner, rung, surface, reference, junctions, settings));
    patchMeshes.back().part = sheet.part;
  }
  return joinAtJunctions(patchMeshes);
}

/// The feature lines of a sheet in world space.
std::vector<VolumeCurve> featureCurves(const Sheet& sheet) {
  std::vector<VolumeCurve> curves;
  for (const Polyline& line : sheet.featureLines) curves.push_back(worldCurve(sheet, line));
  return curves;
}

}  // namespace

namespace {

/// Pins every node the junction curves of `sheet` prescribe (a curve point that is a node, or a
/// node inside one of its edges) where `mesh` has a point (within 1e-6 of the spacing): a free
/// point there (a grid node on a junction curve across a patch that does not cut it) becomes fixed
/// (role Corner), which optimisation does not move. Throws NarrowSheetRefusal when such a node is
/// no point of the mesh.
void requireJunctionNodes(const Sheet& sheet, const JunctionNodes& junctions, QuadMesh& mesh,
                          double spacing) {
  std::vector<std::pair<Vec3, std::size_t>> points;  // (position, mesh point), sorted
  for (std::size_t p = 0; p < mesh.points.size(); ++p) points.emplace_back(mesh.points[p], p);
  std::sort(points.begin(), points.end());
  mesh.constraints.resize(mesh.points.size());
  const double reach = 1e-6 * spacing;
  const auto present = [&](const Vec3& p) {
    for (auto it = std::lower_bound(
             points.begin(), points.end(),
             std::make_pair(Vec3{p[0] - reach, -HUGE_VAL, -HUGE_VAL}, std::size_t(0)));
         it != points.end() && it->first[0] <= p[0] + reach; ++it)
      if (distance(it->first, p) <= reach) {
        PointConstraint& constraint = mesh.constraints[it->second];
        if (constraint.role == PointRole::Free) constraint.role = PointRole::Corner;
        return true;
      }
    return false;
  };
  for (const Polyline& curve : sheet.junctionCurves) {
    const std::size_t n = curve.points.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& a = sheet.points[curve.points[i]];
      if (junctions.isNodePoint(a) && !present(a))
        throw NarrowSheetRefusal("a junction node is no node of its mesh");
      if (i + 1 == n && !curve.closed) break;
      if (const JunctionEdgeNodes* inside =
              junctions.edge(a, sheet.points[curve.points[(i + 1) % n]]))
        for (const Vec3& p : inside->points)
          if (!present(p)) throw NarrowSheetRefusal("a junction node is no node of its mesh");
    }
  }
}

}  // namespace

QuadMesh meshNarrowSheet(const Sheet& sheet, const QuadMesh& surface,
                         const ReferenceSurface& reference, const JunctionNodes& junctions,
                         const NarrowSheetSettings& settings) {
  if (!(settings.spacing > 0.0) || !(settings.tolerance > 0.0) || !(settings.maxChord > 0.0))
    throw std::invalid_argument("meshNarrowSheet: spacing, tolerance and maxChord must be > 0");
  try {
    QuadMesh mesh =
        meshPatches(sheet, sheetPatches(sheet), surface, reference, junctions, settings);
    requireJunctionNodes(sheet, junctions, mesh, settings.spacing);
    return mesh;
  } catch (const NarrowSheetRefusal& refusal) {
    if (sheet.featureLines.empty()) throw;
    // Cut at the feature lines too (walls and cap of a box), with nodes on them shared by the
    // patches on both sides.
    JunctionNodes withFeatures = junctions;
    withFeatures.add(featureCurves(sheet), settings.spacing, 0.2 * settings.spacing,
                     settings.sagittaShare);
    try {
      QuadMesh mesh =
          meshPatches(sheet, sheetPatches(sheet, true), surface, reference, withFeatures, settings);
      requireJunctionNodes(sheet, junctions, mesh, settings.spacing);
      return mesh;
    } catch (const NarrowSheetRefusal& second) {
      throw NarrowSheetRefusal(std::string(refusal.what()) + "; cut at its feature lines too, " +
                               second.what());
    }
  }
}

}  // namespace voxremesh::extract
