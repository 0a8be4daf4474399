// chordError (chord_error.h).
#include "optimize/chord_error.h"

#include <algorithm>

#include "geometry/vec3.h"

namespace voxremesh::opt {

using namespace geom;  // NOLINT: the vector operators

namespace {

using Face = std::array<CornerIndex, 4>;

/// The distances to `original` of points that lie close together: each query starts from the
/// answer before it (the same answers, found faster).
class NearbyDistances {
 public:
  explicit NearbyDistances(const ReferenceSurface& original) : original_(original) {}
  double operator()(const Vec3& p) {
    const SurfaceHit hit = original_.closestPoint(p, hint_);
    hint_ = hit.face;
    return hit.distance;
  }

 private:
  const ReferenceSurface& original_;
  std::uint32_t hint_ = kNoCorner;
};

Vec3 centreOf(const QuadMesh& mesh, const Face& face) {
  const int n = cornerCount(face);
  Vec3 centre{0.0, 0.0, 0.0};
  for (int k = 0; k < n; ++k) centre = centre + mesh.points[face[std::size_t(k)]] * (1.0 / n);
  return centre;
}

Vec3 middleOf(const QuadMesh& mesh, CornerIndex a, CornerIndex b) {
  return (mesh.points[a] + mesh.points[b]) * 0.5;
}

}  // namespace

double chordError(const QuadMesh& mesh, const std::vector<Face>& faces,
                  const ReferenceSurface& original) {
  double largest = 0.0;
  NearbyDistances distanceAt(original);
  for (const auto& face : faces) {
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k)
      largest = std::max(largest, distanceAt(middleOf(mesh, face[std::size_t(k)],
                                                      face[std::size_t((k + 1) % n)])));
    largest = std::max(largest, distanceAt(centreOf(mesh, face)));
  }
  return largest;
}

ChordAroundPoint::ChordAroundPoint(const QuadMesh& mesh, const std::vector<Face>& faces,
                                   CornerIndex v, const ReferenceSurface& original)
    : faces_(faces), original_(original) {
  NearbyDistances distanceAt(original);
  for (const auto& face : faces) {
    const int n = cornerCount(face);
    for (int k = 0; k < n; ++k) {
      const CornerIndex a = face[std::size_t(k)], b = face[std::size_t((k + 1) % n)];
      if (a != v && b != v) {
        fixedLargest_ = std::max(fixedLargest_, distanceAt(middleOf(mesh, a, b)));
        continue;
      }
      const std::array<CornerIndex, 2> edge{std::min(a, b), std::max(a, b)};
      if (std::find(edgesAtPoint_.begin(), edgesAtPoint_.end(), edge) == edgesAtPoint_.end())
        edgesAtPoint_.push_back(edge);
    }
  }
}

double ChordAroundPoint::operator()(const QuadMesh& mesh) const {
  double largest = fixedLargest_;
  NearbyDistances distanceAt(original_);
  for (const auto& edge : edgesAtPoint_)
    largest = std::max(largest, distanceAt(middleOf(mesh, edge[0], edge[1])));
  for (const auto& face : faces_) largest = std::max(largest, distanceAt(centreOf(mesh, face)));
  return largest;
}

}  // namespace voxremesh::opt
