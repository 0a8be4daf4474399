// rotateFailingEdges: two faces sharing an edge, one of them failing, are cut again along another
// diagonal of the polygon they make together where that scores better (optimize.h).
#include <algorithm>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "geometry/vec3.h"
#include "optimize/edge_polygon.h"
#include "optimize/face_score.h"
#include "optimize/mesh_topology.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

namespace {

using namespace geom;  // NOLINT: the vector operators

using opt::cutKeepsOrientation;
using opt::cutPolygon;
using opt::diagonalEnd;
using opt::Face;
using Edge = std::pair<CornerIndex, CornerIndex>;

Edge edgeKey(CornerIndex a, CornerIndex b) {
  return {std::min(a, b), std::max(a, b)};
}

}  // namespace

std::size_t rotateFailingEdges(QuadMesh& mesh, const QualitySettings& settings, int maxRounds) {
  checkQualitySettings(settings);
  if (!(settings.targetSize > 0.0))
    throw std::invalid_argument("rotateFailingEdges: the target size must be > 0");
  if (maxRounds < 0) throw std::invalid_argument("rotateFailingEdges: negative round count");
  opt::checkMesh(mesh);
  std::size_t rotated = 0;
  for (int round = 0; round < maxRounds; ++round) {
    // The connectivity at the start of the round; faces changed in the round are locked, and
    // the edges it removes or makes are tracked apart.
    const opt::Topology topology = opt::buildTopology(mesh);
    std::vector<std::size_t> faceCount(mesh.points.size());
    for (CornerIndex v = 0; v < mesh.points.size(); ++v) faceCount[v] = topology.faceCount(v);
    std::set<Edge> removed, added;
    auto isEdge = [&](CornerIndex p, CornerIndex q) {
      const Edge key = edgeKey(p, q);
      return added.count(key) || (topology.edgeFaces(p, q) > 0 && !removed.count(key));
    };
    auto isFree = [&](CornerIndex v) { return opt::roleOf(mesh, v) == PointRole::Free; };
    std::vector<std::uint8_t> locked(mesh.faces.size(), 0);
    std::size_t roundRotated = 0;
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
      if (locked[f] || opt::faceScore(mesh, mesh.faces[f], settings).failures == 0) continue;
      const int n = cornerCount(mesh.faces[f]);
      for (int k = 0; k < n && !locked[f]; ++k) {
        const CornerIndex a = mesh.faces[f][std::size_t(k)];
        const CornerIndex b = mesh.faces[f][std::size_t((k + 1) % n)];
        // Edges between two constrained points may run along a curve: they stay.
        if (!isFree(a) && !isFree(b)) continue;
        if (topology.edgeFaces(a, b) != 2) continue;
        std::uint32_t g = f;  // the other face of the edge
        for (const std::uint32_t* h = topology.facesBegin(a); h != topology.facesEnd(a); ++h) {
          const Face& other = mesh.faces[*h];
          if (*h != f && std::find(other.begin(), other.begin() + cornerCount(other), b) !=
                             other.begin() + cornerCount(other))
            g = *h;
        }
        if (g == f || locked[g]) continue;
        // The polygon round both faces, oriented like f (empty when g runs (a, b) the same way
        // or the two faces share another corner).
        const std::vector<CornerIndex> polygon =
            opt::polygonAroundEdge(mesh.faces[f], mesh.faces[g], a, b);
        if (polygon.empty()) continue;
        // Both ends of the edge lose a face: none may be left in fewer than 3 (inside the
        // surface) or 2 (on the boundary), which would be a doublet or a spike.
        if (faceCount[a] < (topology.boundary[a] ? 3u : 4u) ||
            faceCount[b] < (topology.boundary[b] ? 3u : 4u))
          continue;
        opt::Score best = opt::faceScore(mesh, mesh.faces[f], settings);
        best += opt::faceScore(mesh, mesh.faces[g], settings);
        // Every other diagonal (the present one, (a, b), is an edge and skipped): from corner i
        // to i + 3 (4 corners: i + 2), i < 3 (2) as the others repeat them, any i for 5.
        std::size_t chosen = polygon.size();
        for (std::size_t i = 0; i < polygon.size(); ++i) {
          if (polygon.size() != 5 && i >= polygon.size() / 2) continue;
          const std::size_t j = diagonalEnd(polygon.size(), i);
          const CornerIndex p = polygon[i], q = polygon[j];
          if (isEdge(p, q) || (!isFree(p) && !isFree(q))) continue;
          const std::array<Face, 2> faces = cutPolygon(polygon, i);
          if (!cutKeepsOrientation(mesh, topology, f, g, faces)) continue;
          opt::Score score = opt::faceScore(mesh, faces[0], settings);
          score += opt::faceScore(mesh, faces[1], settings);
          if (score.betterThan(best)) best = score, chosen = i;
        }
        if (chosen == polygon.size()) continue;
        const std::array<Face, 2> faces = cutPolygon(polygon, chosen);
        const std::size_t j = diagonalEnd(polygon.size(), chosen);
        removed.insert(edgeKey(a, b));
        added.insert(edgeKey(polygon[chosen], polygon[j]));
        --faceCount[a], --faceCount[b];
        ++faceCount[polygon[chosen]], ++faceCount[polygon[j]];
        mesh.faces[f] = faces[0];
        mesh.faces[g] = faces[1];
        locked[f] = locked[g] = 1;
        ++roundRotated;
      }
    }
    if (roundRotated == 0) break;
    rotated += roundRotated;
  }
  return rotated;
}

}  // namespace voxremesh
