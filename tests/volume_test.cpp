// The volume stage (include/voxremesh/volume.h) on analytic sheets: a flat square with a square
// hole, a cylinder patch and a bent flange with a sharp 90 degree edge.
#include "voxremesh/volume.h"

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <tbb/global_control.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "support/test_support.h"
#include "volume/volume_grids.h"
#include "voxremesh/errors.h"

namespace {

using voxremesh::Sheet;
using voxremesh::Volume;
using voxremesh::VolumeSettings;
using voxremesh::VoxelSizeRule;
using P3 = std::array<double, 3>;

P3 sub(const P3& a, const P3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
P3 add(const P3& a, const P3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
P3 scale(const P3& a, double s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
double dot3(const P3& a, const P3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
P3 cross3(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm3(const P3& a) {
  return std::sqrt(dot3(a, a));
}

/// A sheet of nu x nv quads on the parameter grid (i, j) -> map(i, j); quads run
/// (i,j) (i+1,j) (i+1,j+1) (i,j+1), so the normal is d map/di x d map/dj. Cells where skip(i, j)
/// is true are left out.
Sheet gridSheet(int nu, int nv, const std::function<P3(int, int)>& map,
                const std::function<bool(int, int)>& skip = {}) {
  Sheet sheet;
  sheet.part = 7;
  auto index = [&](int i, int j) { return voxremesh::PointIndex(j * (nu + 1) + i); };
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) sheet.points.push_back(map(i, j));
  }
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      if (skip && skip(i, j)) continue;
      sheet.faces.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)});
    }
  }
  return sheet;
}

VolumeSettings explicitSize(double h) {
  VolumeSettings settings;
  settings.rule = VoxelSizeRule::Explicit;
  settings.voxelSize = h;
  return settings;
}

/// Calls f(ijk, world position, value, active) for every voxel of the box around the sheets'
/// points grown by the band plus two voxels.
void forEachVoxelNear(const Volume& volume, const std::vector<Sheet>& sheets,
                      const std::function<void(const openvdb::Coord&, const P3&, float, bool)>& f) {
  const auto& impl = volume.impl();
  const double h = volume.info().voxelSize;
  P3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const Sheet& s : sheets) {
    for (const P3& p : s.points) {
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    }
  }
  const double grow = volume.info().bandWidthVoxels + 2.0;
  openvdb::Coord a, b;
  for (int k = 0; k < 3; ++k) {
    a[k] = int(std::floor(lo[k] / h - grow));
    b[k] = int(std::ceil(hi[k] / h + grow));
  }
  auto accessor = impl.sdf->getConstAccessor();
  for (int i = a[0]; i <= b[0]; ++i) {
    for (int j = a[1]; j <= b[1]; ++j) {
      for (int k = a[2]; k <= b[2]; ++k) {
        const openvdb::Coord ijk(i, j, k);
        float value = 0.0f;
        const bool active = accessor.probeValue(ijk, value);
        f(ijk, P3{i * h, j * h, k * h}, value, active);
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Flat square [0,10]^2 with the square hole (4,6)^2, quads of size 1, normal +z, moved off the
// voxel lattice (or on it).

const P3 kPlateOrigin{0.37, 0.21, 0.13};

Sheet plateWithHole(const P3& origin = kPlateOrigin) {
  return gridSheet(
      10, 10,
      [&](int i, int j) {
        return add(origin, P3{double(i), double(j), 0.0});
      },
      [](int i, int j) { return i >= 4 && i < 6 && j >= 4 && j < 6; });
}

/// Distance in the plate's plane from (x, y) (plate coordinates) to the plate region.
double plateDistance2D(double x, double y) {
  const double dx = std::max({0.0, -x, x - 10.0}), dy = std::max({0.0, -y, y - 10.0});
  if (dx > 0.0 || dy > 0.0) return std::hypot(dx, dy);
  if (x > 4.0 && x < 6.0 && y > 4.0 && y < 6.0) {
    return std::min({x - 4.0, 6.0 - x, y - 4.0, 6.0 - y});
  }
  return 0.0;
}

/// Checks the volume of a plate with hole at `origin` (possibly re-meshed) against the analytic
/// distance, sign (+z side positive) and invalid rule.
void checkPlate(const std::vector<Sheet>& sheets, const P3& origin, double h) {
  const Volume volume = voxremesh::buildVolume(sheets, explicitSize(h));
  const auto& impl = volume.impl();
  ASSERT_TRUE(impl.sdf && impl.invalid && impl.feature);
  EXPECT_EQ(impl.sdf->getGridClass(), openvdb::GRID_LEVEL_SET);
  EXPECT_FLOAT_EQ(impl.sdf->background(), float(3.0 * h));
  EXPECT_EQ(impl.sdf->transformPtr(), impl.invalid->transformPtr());
  EXPECT_EQ(impl.sdf->transformPtr(), impl.feature->transformPtr());

  const double band = 3.0 * h;
  auto invalid = impl.invalid->getConstAccessor();
  std::size_t checked = 0, interior = 0, invalidSeen = 0, beyondHole = 0;
  forEachVoxelNear(volume, sheets,
                   [&](const openvdb::Coord& ijk, const P3& p, float value, bool active) {
                     const double x = p[0] - origin[0], y = p[1] - origin[1];
                     const double dz = p[2] - origin[2];
                     const double d2 = plateDistance2D(x, y);
                     const double exact = std::hypot(d2, dz);
                     if (exact < band - 1e-3 * h) {
                       ASSERT_TRUE(active)
                           << "voxel " << ijk << " at distance " << exact << " is not in the band";
                     }
                     if (exact > band + 1e-6) {
                       ASSERT_FALSE(active) << ijk;
                       ASSERT_FALSE(invalid.isValueOn(ijk)) << ijk;
                     }
                     if (!active) return;
                     ++checked;
                     ASSERT_NEAR(std::abs(value), exact, 1e-3 * h) << ijk;
                     ASSERT_EQ(value < 0.0f, dz < 0.0) << ijk << " value " << value;
                     const bool isInvalid = invalid.isValueOn(ijk);
                     if (d2 == 0.0) {
                       ++interior;
                       ASSERT_FALSE(isInvalid) << "voxel " << ijk << " above the inside is invalid";
                       return;
                     }
                     // Closest point on the boundary: invalid where the angle to the normal exceeds
                     // 60 deg
                     // (|dz| / distance < cos 60), with a half degree of slack on either side.
                     const double cosAngle = std::abs(dz) / exact;
                     if (cosAngle < std::cos(60.5 * M_PI / 180.0)) {
                       ASSERT_TRUE(isInvalid) << ijk;
                     } else if (cosAngle > std::cos(59.5 * M_PI / 180.0)) {
                       ASSERT_FALSE(isInvalid) << ijk;
                     }
                     invalidSeen += isInvalid;
                     if (isInvalid && x > 4.0 && x < 6.0 && y > 4.0 && y < 6.0) ++beyondHole;
                   });
  EXPECT_GT(checked, 1000u);
  EXPECT_GT(interior, 500u);
  EXPECT_GT(invalidSeen, 100u);
  EXPECT_GT(beyondHole, 10u) << "voxels in the hole must be invalid";
  EXPECT_EQ(impl.invalid->activeVoxelCount(), invalidSeen);
}

TEST(SignedDistance, PlateWithHoleIsExactSignedAndBoundaryVoxelsAreInvalid) {
  checkPlate({plateWithHole()}, kPlateOrigin, 0.5);
}

TEST(SignedDistance, PlateOnTheLatticeKeepsVoxelsAboveItsEdgesValid) {
  // Plane and boundary lines through voxel centres: voxels straight above a free edge tie
  // between the face and the edge (the face wins, valid), voxels in the plane beyond it are
  // invalid, voxels on the sheet are 0.
  const P3 origin{0.0, 0.0, 0.0};
  checkPlate({plateWithHole(origin)}, origin, 0.5);
}

TEST(SignedDistance, TrianglesAndCollapsedQuadsGiveTheSameDistances) {
  // The same plate with some cells split into two triangles and some given as a quad with a
  // repeated corner (as decks write triangles) plus a triangle.
  Sheet sheet = plateWithHole();
  const std::size_t n = sheet.faces.size();
  for (std::size_t f = 0; f < n; f += 3) {
    const auto q = sheet.faces[f];
    if (f % 2 == 0) {
      sheet.faces[f] = {q[0], q[1], q[2], voxremesh::kNoPoint};
    } else {
      sheet.faces[f] = {q[0], q[1], q[2], q[2]};
    }
    sheet.faces.push_back({q[0], q[2], q[3], voxremesh::kNoPoint});
  }
  checkPlate({sheet}, kPlateOrigin, 0.5);
}

// ---------------------------------------------------------------------------------------------
// Cylinder patch: radius 5 about the y axis, 30..150 degrees, y in [0, 8], 24 x 16 quads, normal
// pointing away from the axis.

const P3 kCylinderOrigin{0.29, 0.11, 0.43};
constexpr double kRadius = 5.0;

P3 cylinderPoint(int i, int j) {
  const double theta = (30.0 + 120.0 * i / 24.0) * M_PI / 180.0;
  return add(kCylinderOrigin, P3{kRadius * std::cos(theta), 0.5 * j, kRadius * std::sin(theta)});
}

Sheet cylinderPatch() {
  // (i, j) -> (theta, y): d/dtheta x d/dy points inwards, so run j first.
  return gridSheet(16, 24, [](int j, int i) { return cylinderPoint(i, j); });
}

/// Closest point of triangle abc to p, computed independently of the library: projection when
/// it falls inside, else the closest of the three edges.
P3 referenceClosest(const P3& p, const P3& a, const P3& b, const P3& c) {
  const P3 n = cross3(sub(b, a), sub(c, a));
  const double nn = dot3(n, n);
  const P3 q = sub(p, scale(n, dot3(sub(p, a), n) / nn));
  const bool inside = dot3(cross3(sub(b, a), sub(q, a)), n) >= 0 &&
                      dot3(cross3(sub(c, b), sub(q, b)), n) >= 0 &&
                      dot3(cross3(sub(a, c), sub(q, c)), n) >= 0;
  if (inside) return q;
  auto onSegment = [&](const P3& s, const P3& e) {
    const P3 d = sub(e, s);
    const double t = std::clamp(dot3(sub(p, s), d) / dot3(d, d), 0.0, 1.0);
    return add(s, scale(d, t));
  };
  P3 best = onSegment(a, b);
  for (const P3& r : {onSegment(b, c), onSegment(c, a)}) {
    if (norm3(sub(p, r)) < norm3(sub(p, best))) best = r;
  }
  return best;
}

TEST(SignedDistance, CylinderPatchMatchesBruteForceDistanceAndOutwardSign) {
  const std::vector<Sheet> sheets{cylinderPatch()};
  const Sheet& s = sheets[0];
  // Check the orientation of the test sheet itself: normals away from the axis.
  {
    const auto& f = s.faces[0];
    const P3 n = cross3(sub(s.points[f[1]], s.points[f[0]]), sub(s.points[f[2]], s.points[f[0]]));
    const P3 radial = sub(s.points[f[0]], kCylinderOrigin);
    ASSERT_GT(n[0] * radial[0] + n[2] * radial[2], 0.0);
  }
  std::vector<std::array<P3, 3>> tris;
  for (const auto& f : s.faces) {
    tris.push_back({s.points[f[0]], s.points[f[1]], s.points[f[2]]});
    tris.push_back({s.points[f[0]], s.points[f[2]], s.points[f[3]]});
  }
  const double h = 0.25;
  const Volume volume = voxremesh::buildVolume(sheets, explicitSize(h));
  const double band = 3.0 * h;
  std::size_t checked = 0, inner = 0, outer = 0;
  forEachVoxelNear(
      volume, sheets, [&](const openvdb::Coord& ijk, const P3& p, float value, bool active) {
        // Cheap pre-filter on the analytic cylinder before the brute force.
        const double r = std::hypot(p[0] - kCylinderOrigin[0], p[2] - kCylinderOrigin[2]);
        if (std::abs(r - kRadius) > band + 1.0 && !active) return;
        double best = std::numeric_limits<double>::infinity();
        P3 closest{}, normal{};
        for (const auto& t : tris) {
          const P3 q = referenceClosest(p, t[0], t[1], t[2]);
          const double d = norm3(sub(p, q));
          if (d < best) best = d, closest = q, normal = cross3(sub(t[1], t[0]), sub(t[2], t[0]));
        }
        if (best < band - 1e-3 * h) {
          ASSERT_TRUE(active) << ijk << " distance " << best;
        }
        if (best > band + 1e-6) {
          ASSERT_FALSE(active) << ijk;
        }
        if (!active) return;
        ++checked;
        ASSERT_NEAR(std::abs(value), best, 1e-3 * h) << ijk;
        // Sign: the side of the closest face; where the closest point is on the sheet's inside
        // (not on its free boundary) this is inside/outside the cylinder.
        const double y = closest[1] - kCylinderOrigin[1];
        const double theta =
            std::atan2(closest[2] - kCylinderOrigin[2], closest[0] - kCylinderOrigin[0]) * 180.0 /
            M_PI;
        const bool onInside =
            y > 1e-6 && y < 8.0 - 1e-6 && theta > 30.0 + 1e-6 && theta < 150.0 - 1e-6;
        const double side = dot3(sub(p, closest), normal) / norm3(normal);
        if (std::abs(side) > 1e-6) {
          ASSERT_EQ(value < 0.0f, side < 0.0) << ijk;
        }
        if (onInside && best > 1e-6) (value > 0.0f ? outer : inner)++;
      });
  EXPECT_GT(checked, 5000u);
  EXPECT_GT(inner, 1000u);
  EXPECT_GT(outer, 1000u);
}

// ---------------------------------------------------------------------------------------------
// Bent flange: a strip of 6 x 4 quads in (u, y) folded at u = 3 by 90 degrees: u <= 3 lies flat
// (normal +z), u >= 3 rises (normal -x). The fold is a feature line.

Sheet bentFlange(const P3& origin, double e) {
  Sheet sheet = gridSheet(6, 4, [&](int i, int j) {
    const double y = e * j;
    return i <= 3 ? add(origin, P3{e * i, y, 0.0}) : add(origin, P3{3 * e, y, e * (i - 3)});
  });
  voxremesh::Polyline fold;
  for (int j = 0; j <= 4; ++j) fold.points.push_back(voxremesh::PointIndex(j * 7 + 3));
  sheet.featureLines.push_back(fold);
  // The fold's ends and the strip's four corners.
  sheet.featurePoints = {3, 4 * 7 + 3, 0, 6, 4 * 7, 4 * 7 + 6};
  return sheet;
}

/// Distance from p to the axis-aligned rectangle lo..hi (one extent zero).
double boxDistance(const P3& p, const P3& lo, const P3& hi) {
  double s = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::max({0.0, lo[k] - p[k], p[k] - hi[k]});
    s += d * d;
  }
  return std::sqrt(s);
}

TEST(SignedDistance, BentFlangeIsExactAndSignedByPseudoNormals) {
  const P3 origin{0.31, 0.17, 0.09};
  const double e = 1.0;
  const std::vector<Sheet> sheets{bentFlange(origin, e)};
  const double h = 0.2;
  const Volume volume = voxremesh::buildVolume(sheets, explicitSize(h));
  const double band = 3.0 * h;
  const P3 foldLo = add(origin, P3{3 * e, 0, 0});
  std::size_t checked = 0, wedge = 0;
  forEachVoxelNear(
      volume, sheets, [&](const openvdb::Coord& ijk, const P3& p, float value, bool active) {
        const double dA = boxDistance(p, origin, add(origin, P3{3 * e, 4 * e, 0}));
        const double dB = boxDistance(p, foldLo, add(origin, P3{3 * e, 4 * e, 3 * e}));
        const double exact = std::min(dA, dB);
        if (exact < band - 1e-3 * h) {
          ASSERT_TRUE(active) << ijk;
        }
        if (exact > band + 1e-6) {
          ASSERT_FALSE(active) << ijk;
        }
        if (!active) return;
        ++checked;
        ASSERT_NEAR(std::abs(value), exact, 1e-3 * h) << ijk;
        // Normals point into the quadrant x < fold, z > fold: positive there, negative elsewhere,
        // including the convex wedge outside the fold (edge pseudo-normal).
        const bool inside = p[0] < foldLo[0] && p[2] > foldLo[2];
        ASSERT_EQ(value > 0.0f, inside) << ijk << " value " << value;
        if (p[0] > foldLo[0] && p[2] < foldLo[2] && p[1] > origin[1] && p[1] < origin[1] + 4 * e) {
          ++wedge;
        }
      });
  EXPECT_GT(checked, 3000u);
  EXPECT_GT(wedge, 50u);
}

// ---------------------------------------------------------------------------------------------
// Feature mask.

/// Distance from p to segment ab.
double segmentDistance(const P3& p, const P3& a, const P3& b) {
  const P3 d = sub(b, a);
  const double t = std::clamp(dot3(sub(p, a), d) / dot3(d, d), 0.0, 1.0);
  return norm3(sub(p, add(a, scale(d, t))));
}

/// Checks that the feature mask holds every cell a dense sampling of the volume's feature
/// segments and points falls into, and no cell whose centre is farther than one voxel diagonal
/// from them.
void expectFeatureMaskCoversCurves(const Volume& volume) {
  const auto& impl = volume.impl();
  const double h = volume.info().voxelSize;
  std::vector<std::array<P3, 2>> segments;
  for (const auto& curve : volume.featureLines()) {
    for (std::size_t i = 0; i + 1 < curve.points.size(); ++i) {
      segments.push_back({curve.points[i], curve.points[i + 1]});
    }
  }
  for (const auto& p : volume.featurePoints()) segments.push_back({p, p});
  ASSERT_FALSE(segments.empty());
  auto mask = impl.feature->getConstAccessor();
  std::size_t samples = 0;
  for (const auto& s : segments) {
    const int n = 20000;
    for (int i = 0; i <= n; ++i) {
      const P3 q = scale(add(s[0], scale(sub(s[1], s[0]), double(i) / n)), 1.0 / h);
      const openvdb::Coord cell(int(std::floor(q[0])), int(std::floor(q[1])),
                                int(std::floor(q[2])));
      ASSERT_TRUE(mask.isValueOn(cell)) << "cell " << cell << " holds a feature sample";
      ++samples;
    }
  }
  EXPECT_GT(samples, 0u);
  const double limit = std::sqrt(3.0) * h;
  std::size_t marked = 0;
  for (auto it = impl.feature->cbeginValueOn(); it; ++it, ++marked) {
    const openvdb::Coord c = it.getCoord();
    const P3 centre{(c.x() + 0.5) * h, (c.y() + 0.5) * h, (c.z() + 0.5) * h};
    double best = std::numeric_limits<double>::infinity();
    for (const auto& s : segments) {
      best = std::min(
          best, s[0] == s[1] ? norm3(sub(centre, s[0])) : segmentDistance(centre, s[0], s[1]));
    }
    ASSERT_LE(best, limit) << "cell " << c << " is marked but far from every feature";
  }
  EXPECT_GT(marked, 0u);
}

TEST(FeatureMask, CoversTheFoldOffTheLattice) {
  const std::vector<Sheet> sheets{bentFlange({0.31, 0.17, 0.09}, 1.0)};
  const Volume volume = voxremesh::buildVolume(sheets, explicitSize(0.2));
  ASSERT_EQ(volume.featureLines().size(), 1u);
  ASSERT_EQ(volume.featurePoints().size(), 6u);
  expectFeatureMaskCoversCurves(volume);
}

TEST(FeatureMask, MarksEveryCellAlongAFoldOnCellEdges) {
  // The fold runs exactly along cell edges (x and z on the lattice): the four cells sharing the
  // edge are all touched and must all be marked.
  const double h = 0.25;
  std::vector<Sheet> sheets{bentFlange({0.0, 0.1, 0.5}, 1.0)};
  sheets[0].featurePoints.clear();
  const Volume volume = voxremesh::buildVolume(sheets, explicitSize(h));
  expectFeatureMaskCoversCurves(volume);
  auto mask = volume.impl().feature->getConstAccessor();
  const int i = 12, k = 2;  // the fold at x = 3 = 12 h, z = 0.5 = 2 h
  for (int j = 1; j < 16; ++j) {
    for (int di = -1; di <= 0; ++di) {
      for (int dk = -1; dk <= 0; ++dk) {
        EXPECT_TRUE(mask.isValueOn(openvdb::Coord(i + di, j, k + dk)))
            << di << " " << j << " " << dk;
      }
    }
  }
}

TEST(FeatureMask, FollowsDiagonalPolylinesExactly) {
  // Generic directions: a staircase diagonal across the cylinder patch as a feature line.
  Sheet sheet = cylinderPatch();
  voxremesh::Polyline diagonal;
  for (int k = 0; k <= 16; ++k) diagonal.points.push_back(voxremesh::PointIndex(k * 17 + k));
  sheet.featureLines.push_back(diagonal);
  const Volume volume = voxremesh::buildVolume({sheet}, explicitSize(0.13));
  expectFeatureMaskCoversCurves(volume);
}

// ---------------------------------------------------------------------------------------------
// Several sheets, determinism.

/// True when both grids have the same topology and bit-identical leaf buffers.
template <typename GridT>
bool sameGrid(const GridT& a, const GridT& b) {
  if (a.tree().leafCount() != b.tree().leafCount()) return false;
  if (a.activeVoxelCount() != b.activeVoxelCount()) return false;
  auto accessor = b.getConstAccessor();
  for (auto it = a.tree().cbeginLeaf(); it; ++it) {
    const auto* other = accessor.probeConstLeaf(it->origin());
    if (!other || it->getValueMask() != other->getValueMask()) return false;
    if constexpr (std::is_same_v<typename GridT::ValueType, float>) {
      if (std::memcmp(it->buffer().data(), other->buffer().data(),
                      sizeof(float) * GridT::TreeType::LeafNodeType::SIZE) != 0) {
        return false;
      }
    }
  }
  return true;
}

TEST(Volume, SameGridsForOneAndTwoThreads) {
  std::vector<Sheet> sheets{cylinderPatch(), plateWithHole(), bentFlange({0.31, 0.17, 0.09}, 1.0)};
  const VolumeSettings settings = explicitSize(0.07);
  Volume one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = voxremesh::buildVolume(sheets, settings);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = voxremesh::buildVolume(sheets, settings);
  }
  ASSERT_GT(one.impl().sdf->activeVoxelCount(), 100000u);
  EXPECT_TRUE(sameGrid(*one.impl().sdf, *two.impl().sdf));
  EXPECT_TRUE(sameGrid(*one.impl().invalid, *two.impl().invalid));
  EXPECT_TRUE(sameGrid(*one.impl().feature, *two.impl().feature));
}

TEST(Volume, SheetsOfOnePartAreUnitedClosestWins) {
  // Two parallel plates 0.4 apart, closer than two bands: between them each voxel takes the
  // closer plate, with the sign of that plate's side.
  Sheet lower = gridSheet(4, 4, [](int i, int j) { return P3{0.13 + i, 0.07 + j, 0.11}; });
  Sheet upper = gridSheet(4, 4, [](int i, int j) { return P3{0.13 + i, 0.07 + j, 0.51}; });
  const double h = 0.1;
  const Volume volume = voxremesh::buildVolume({lower, upper}, explicitSize(h));
  auto accessor = volume.impl().sdf->getConstAccessor();
  std::size_t checked = 0;
  for (int k = -3; k <= 12; ++k) {
    const openvdb::Coord ijk(20, 20, k);
    const double z = k * h;
    const double dLower = std::abs(z - 0.11), dUpper = std::abs(z - 0.51);
    float value = 0;
    if (!accessor.probeValue(ijk, value)) continue;
    ++checked;
    const double expected = dLower <= dUpper ? z - 0.11 : z - 0.51;
    EXPECT_NEAR(value, expected, 1e-5) << k;
  }
  EXPECT_EQ(checked, 10u);  // z in (-0.19, 0.81)
  EXPECT_THROW(
      {
        Sheet other = upper;
        other.part = 8;
        voxremesh::buildVolume({lower, other}, explicitSize(h));
      },
      std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Settings.

TEST(VolumeSettings, VoxelSizeRules) {
  const std::vector<Sheet> sheets{bentFlange({0, 0, 0}, 2.0)};
  VolumeSettings settings;
  settings.rule = VoxelSizeRule::TargetElementSize;
  settings.targetElementSize = 1.5;
  EXPECT_DOUBLE_EQ(voxremesh::chooseVoxelSize(sheets, settings), 1.5);
  settings.targetElementSize = 0.0;  // the mean element edge length; quad diagonals don't count
  EXPECT_DOUBLE_EQ(voxremesh::chooseVoxelSize(sheets, settings), 2.0);
  settings.rule = VoxelSizeRule::MinEdgeLength;
  settings.minEdgeFactor = 0.5;
  EXPECT_DOUBLE_EQ(voxremesh::chooseVoxelSize(sheets, settings), 1.0);
  settings.rule = VoxelSizeRule::Explicit;
  settings.voxelSize = 0.3;
  EXPECT_DOUBLE_EQ(voxremesh::chooseVoxelSize(sheets, settings), 0.3);
}

TEST(VolumeSettings, AbsurdSettingsAreRefused) {
  const std::vector<Sheet> sheets{plateWithHole()};
  auto refused = [&](const VolumeSettings& settings, const std::string& words) {
    try {
      voxremesh::buildVolume(sheets, settings);
    } catch (const voxremesh::SettingError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "not refused: " << words;
  };
  refused(explicitSize(0.0), "voxel size");
  refused(explicitSize(-1.0), "voxel size");
  refused(explicitSize(std::nan("")), "voxel size");
  refused(explicitSize(std::numeric_limits<double>::infinity()), "voxel size");
  VolumeSettings settings = explicitSize(0.5);
  settings.bandWidthVoxels = 0.5;
  refused(settings, "band");
  settings.bandWidthVoxels = std::nan("");
  refused(settings, "band");
  settings = explicitSize(0.5);
  settings.invalidAngleDeg = 120.0;
  refused(settings, "angle");
  settings = explicitSize(0.5);
  settings.rule = VoxelSizeRule::TargetElementSize;
  settings.targetElementSize = -2.0;
  refused(settings, "target element size");
  settings.rule = VoxelSizeRule::MinEdgeLength;
  settings.minEdgeFactor = 0.0;
  refused(settings, "factor");
}

TEST(VolumeSettings, TooManyVoxelsAreRefusedBeforeAllocating) {
  const std::vector<Sheet> sheets{plateWithHole()};  // area 96
  VolumeSettings settings = explicitSize(1e-4);
  settings.memoryLimitBytes = std::uint64_t{4} << 30;
  const voxremesh::VolumeEstimate estimate = voxremesh::estimateVolume(sheets, 1e-4, settings);
  EXPECT_NEAR(estimate.surfaceArea, 96.0, 1e-9);
  EXPECT_NEAR(estimate.activeVoxels, 96.0 / 1e-8 * 7.0, 1.0);
  try {
    voxremesh::buildVolume(sheets, settings);
    FAIL() << "not refused";
  } catch (const voxremesh::SettingError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("6.72e+10 active voxels"), std::string::npos) << message;
    EXPECT_NE(message.find("voxel size of at least"), std::string::npos) << message;
  }
  // The smallest voxel size it proposes does fit.
  VolumeSettings fits = explicitSize(estimate.smallestVoxelSize * 1.01);
  fits.memoryLimitBytes = settings.memoryLimitBytes;
  const voxremesh::VolumeEstimate ok = voxremesh::estimateVolume(sheets, fits.voxelSize, fits);
  EXPECT_LE(ok.peakBytes, double(fits.memoryLimitBytes));
}

// ---------------------------------------------------------------------------------------------
// .vdb files and the report.

TEST(VolumeFile, WritesReadsAndVdbPrintOpensIt) {
  const std::vector<Sheet> sheets{bentFlange({0.31, 0.17, 0.09}, 1.0)};
  const Volume volume =
      voxremesh::buildVolume(sheets, explicitSize(0.2), voxremesh::VolumeSource{"flange.k"});
  const auto dir = voxremesh::test::scratchDir("volume_file");
  const auto path = dir / "part 7.vdb";
  voxremesh::writeVolume(volume, path);
  ASSERT_TRUE(std::filesystem::exists(path));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);

  const Volume back = voxremesh::readVolume(path);
  EXPECT_DOUBLE_EQ(back.info().voxelSize, 0.2);
  EXPECT_DOUBLE_EQ(back.info().bandWidthVoxels, 3.0);
  EXPECT_DOUBLE_EQ(back.info().invalidAngleDeg, 60.0);
  EXPECT_EQ(back.info().sourceFile, "flange.k");
  EXPECT_EQ(back.info().part, 7);
  EXPECT_EQ(back.info().toolVersion, VOXREMESH_VERSION);
  EXPECT_TRUE(sameGrid(*volume.impl().sdf, *back.impl().sdf));
  EXPECT_TRUE(sameGrid(*volume.impl().invalid, *back.impl().invalid));
  EXPECT_TRUE(sameGrid(*volume.impl().feature, *back.impl().feature));
  EXPECT_EQ(back.impl().sdf->transformPtr(), back.impl().feature->transformPtr());
  ASSERT_EQ(back.featureLines().size(), 1u);
  EXPECT_EQ(back.featureLines()[0].points, volume.featureLines()[0].points);
  EXPECT_EQ(back.featurePoints(), volume.featurePoints());
  EXPECT_EQ(back.boundaryLoops().size(), volume.boundaryLoops().size());

  if (!std::filesystem::exists("/usr/bin/vdb_print")) GTEST_SKIP() << "vdb_print not installed";
  const std::string command = "/usr/bin/vdb_print -m '" + path.string() + "' 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  EXPECT_EQ(::pclose(pipe), 0) << output;
  for (const char* word : {"sdf", "invalid", "feature", "voxremesh_voxel_size", "voxremesh_part_id",
                           "voxremesh_version"}) {
    EXPECT_NE(output.find(word), std::string::npos) << word << " missing in:\n" << output;
  }
}

TEST(VolumeFile, FilesWithoutTheGridsAreRefusedClearly) {
  voxremesh::volume::initializeOpenVdb();
  const auto dir = voxremesh::test::scratchDir("volume_bad");
  const auto other = dir / "density.vdb";
  {
    openvdb::FloatGrid::Ptr density = openvdb::FloatGrid::create();
    density->setName("density");
    openvdb::GridPtrVec grids{density};
    openvdb::io::File(other.string()).write(grids);
  }
  try {
    voxremesh::readVolume(other);
    FAIL() << "read a file without sdf";
  } catch (const voxremesh::InputError& e) {
    EXPECT_EQ(e.file(), other.string());
    EXPECT_NE(std::string(e.what()).find("no grid named 'sdf'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("density"), std::string::npos) << e.what();
  }
  const auto text = dir / "text.vdb";
  voxremesh::test::writeText(text, "not a vdb file\n");
  EXPECT_THROW(voxremesh::readVolume(text), voxremesh::InputError);
  EXPECT_THROW(voxremesh::readVolume(dir / "missing.vdb"), voxremesh::InputError);
  EXPECT_THROW(voxremesh::writeVolume(Volume(), dir / "empty.vdb"), std::invalid_argument);
}

TEST(VolumeReport, DescribesEveryGrid) {
  const std::vector<Sheet> sheets{plateWithHole()};
  const Volume volume = voxremesh::buildVolume(sheets, explicitSize(0.5));
  const voxremesh::VolumeReport report = voxremesh::inspectVolume(volume);
  ASSERT_EQ(report.grids.size(), 3u);
  EXPECT_EQ(report.grids[0].name, "sdf");
  EXPECT_EQ(report.grids[0].valueType, "float");
  EXPECT_EQ(report.grids[0].activeVoxels, volume.impl().sdf->activeVoxelCount());
  EXPECT_TRUE(report.grids[0].hasValueRange);
  EXPECT_NEAR(report.grids[0].minValue, -1.5, 0.5);
  EXPECT_LT(report.grids[0].maxValue, 1.5f);
  EXPECT_EQ(report.grids[1].name, "invalid");
  EXPECT_EQ(report.grids[1].valueType, "mask");
  EXPECT_EQ(report.invalidVoxels, volume.impl().invalid->activeVoxelCount());
  EXPECT_GT(report.invalidVoxels, 0u);
  EXPECT_EQ(report.grids[2].name, "feature");
  EXPECT_EQ(report.featureVoxels, 0u);  // the plate has no feature lines
  EXPECT_TRUE(report.grids[2].emptyBounds);
  // The sdf's world box is its index box times the voxel size.
  EXPECT_DOUBLE_EQ(report.grids[0].worldMin[0], report.grids[0].indexMin[0] * 0.5);
  const std::string text = voxremesh::formatVolumeReport(report);
  EXPECT_NE(text.find("sdf"), std::string::npos) << text;
  EXPECT_NE(text.find("level set"), std::string::npos) << text;
  const std::string json = voxremesh::volumeReportJson(report);
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.back(), '}');
  EXPECT_NE(json.find("\"name\":\"invalid\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"active_voxels\":" + std::to_string(report.grids[0].activeVoxels)),
            std::string::npos);
  EXPECT_NE(json.find("\"world_bbox\":null"), std::string::npos) << json;
}

}  // namespace
