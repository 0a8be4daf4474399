// MeshCache: the topology and per-face failures kept between the optimisation steps
// (mesh_cache.h).
#include "optimize/mesh_cache.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "optimize/face_score.h"

namespace voxremesh::opt {

const Topology& MeshCache::topology(const QuadMesh& mesh) {
  if (!hasTopology_ || topologyPoints_ != mesh.points.size() || topologyFaces_ != mesh.faces) {
    topology_ = buildTopology(mesh);
    topologyFaces_ = mesh.faces;
    topologyPoints_ = mesh.points.size();
    hasTopology_ = true;
  }
  return topology_;
}

const std::vector<std::uint32_t>& MeshCache::failures(const QuadMesh& mesh) {
  // A face keeps its mask when it has the same corners as the face of the same index then, each
  // at the same position (NaN positions never compare equal: found anew).
  const auto unchanged = [&](std::size_t f) {
    if (f >= failureFaces_.size() || failureFaces_[f] != mesh.faces[f]) return false;
    const auto& face = mesh.faces[f];
    for (int k = 0; k < cornerCount(face); ++k) {
      const CornerIndex v = face[std::size_t(k)];
      if (v >= failurePoints_.size() || failurePoints_[v] != mesh.points[v]) return false;
    }
    return true;
  };
  std::vector<std::uint32_t> changed;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (!unchanged(f)) changed.push_back(std::uint32_t(f));
  failures_.resize(mesh.faces.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, changed.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i < r.end(); ++i) {
                        const auto& face = mesh.faces[changed[i]];
                        failures_[changed[i]] = faceFailures(mesh, face, settings_);
                      }
                    });
  failureFaces_ = mesh.faces;
  failurePoints_ = mesh.points;
  return failures_;
}

}  // namespace voxremesh::opt
