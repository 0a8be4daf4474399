// splitFailingQuads: a quad that fails criteria two triangles would pass becomes those two
// triangles, worst gains first, while the triangle share allows (optimize.h).
#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/edge_polygon.h"
#include "optimize/face_score.h"
#include "optimize/mesh_topology.h"
#include "voxremesh/errors.h"
#include "voxremesh/optimize.h"

namespace voxremesh {

namespace {

using Face = std::array<CornerIndex, 4>;

/// The two triangles of a quad cut along the diagonal from corner k (0 or 1) to corner k + 2;
/// both keep the quad's orientation.
std::array<Face, 2> cutAlong(const Face& quad, int k) {
  const auto at = [&](int i) { return quad[std::size_t((k + i) % 4)]; };
  return {Face{at(0), at(1), at(2), kNoCorner}, Face{at(2), at(3), at(0), kNoCorner}};
}

/// A failing quad and the better of its two cuts.
struct Candidate {
  std::uint32_t face = 0;
  int diagonal = 0;  ///< the cut: from corner 0 or corner 1
  int gain = 0;      ///< criteria the quad fails minus those its triangles fail (> 0)
};

}  // namespace

std::size_t splitFailingQuads(QuadMesh& mesh, const QualitySettings& settings,
                              double maxTriangleShare) {
  if (!(maxTriangleShare >= 0.0 && maxTriangleShare <= 1.0))
    throw SettingError("splitFailingQuads: triangle share " + std::to_string(maxTriangleShare) +
                       " is outside 0 .. 1");
  if (!(settings.targetSize > 0.0))
    throw std::invalid_argument("splitFailingQuads: targetSize must be > 0");
  checkQualitySettings(settings);
  opt::checkMesh(mesh);
  std::optional<opt::Topology> topology;  // built at the first failing quad
  std::size_t triangles = 0;
  std::vector<Candidate> candidates;
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& face = mesh.faces[f];
    if (cornerCount(face) == 3) {
      ++triangles;
      continue;
    }
    const opt::Score quad = opt::faceScore(mesh, face, settings);
    if (quad.failures == 0) continue;
    if (!topology) topology = opt::buildTopology(mesh);
    Candidate best;
    opt::Score bestScore;
    bool found = false;
    for (int k = 0; k < 2; ++k) {
      // A diagonal that is already an edge of other faces would get more than two faces.
      if (topology->edgeFaces(face[std::size_t(k)], face[std::size_t(k + 2)]) > 0) continue;
      // Nor may a triangle fold against the other or a neighbour (a diagonal outside a
      // non-convex quad): a flipped triangle can pass every criterion of its own.
      const std::array<Face, 2> cut = cutAlong(face, k);
      if (!opt::cutKeepsOrientation(mesh, *topology, f, f, cut)) continue;
      opt::Score score;
      for (const Face& triangle : cut) score += opt::faceScore(mesh, triangle, settings);
      if (!found || score.betterThan(bestScore)) {
        found = true;
        bestScore = score;
        best = Candidate{f, k, quad.failures - score.failures};
      }
    }
    if (found && best.gain > 0) candidates.push_back(best);
  }
  // The largest gains first, then in face order; each split adds a face and two triangles.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.gain > b.gain; });
  std::vector<int> cut(mesh.faces.size(), -1);
  std::size_t faces = mesh.faces.size(), split = 0;
  for (const Candidate& c : candidates) {
    if (double(triangles + 2) > maxTriangleShare * double(faces + 1)) break;
    cut[c.face] = c.diagonal;
    triangles += 2;
    ++faces;
    ++split;
  }
  if (split == 0) return 0;
  // The triangles take the quad's place in the face order.
  std::vector<Face> result;
  result.reserve(faces);
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
    if (cut[f] < 0) {
      result.push_back(mesh.faces[f]);
      continue;
    }
    for (const Face& triangle : cutAlong(mesh.faces[f], cut[f])) result.push_back(triangle);
  }
  mesh.faces = std::move(result);
  return split;
}

}  // namespace voxremesh
