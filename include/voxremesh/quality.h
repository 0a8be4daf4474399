// The quality stage: FE shell element metrics against thresholds, per element and per mesh, and
// the distance between a mesh and the surface it was made from.
//
// Definitions (p0..p3 the corners in order, edges e_i = p_{i+1} - p_i, indices cyclic; a triangle
// has corners p0..p2). Every metric is computed in double precision from the corner positions.
// - Element normal: triangle (p1 - p0) x (p2 - p0); quad (p2 - p0) x (p3 - p1) (the diagonals),
//   the area-weighted average of the four corner normals.
// - Warping angle (quads; 0 for triangles), as Oasys PRIMER: split the quad along diagonal p0-p2
//   into (p0,p1,p2) and (p0,p2,p3) and take the angle between the two triangle normals; do the same
//   along p1-p3 with (p1,p2,p3) and (p1,p3,p0); the warping angle is the larger of the two angles,
//   in degrees (0 for a planar convex quad). A triangle of zero area contributes no normal (0).
// - Aspect ratio: longest edge / shortest edge (infinite when an edge has zero length).
// - Interior angles: the angle at each corner between its two edges, in degrees. For quads they
//   are reflex-corrected: a corner where (e_{i-1} x e_i) points against the element normal is
//   concave and its angle is 360 minus the geometric angle. Min and max over the corners; quads
//   and triangles have separate limits.
// - Skew, in degrees, 0 for a square or an equilateral triangle. Quads: 90 minus the (acute)
//   angle between the two lines joining the midpoints of opposite edges. Triangles (as HyperMesh):
//   at each corner, the angle between the line from the corner to the midpoint of the opposite
//   edge and the line joining the midpoints of the two adjacent edges, folded to 0..90; skew is
//   90 minus the smallest of the three.
// - Jacobian ratio, at the corners as DESIGN.md's table defines it (the default): the quad is
//   mapped bilinearly from [-1, 1]^2, x(xi, eta) = sum N_i(xi, eta) p_i; n is the unit vector of
//   the sum of the corner normals c_i = e_{i-1} x e_i (the plane of the averaged corner normals, on
//   which a warped quad is measured); at corner i, det J is J_i = c_i . n; the ratio is
//   min J_i / max J_i: 1 for a parallelogram, <= 0 for a folded quad, -1 when max J_i <= 0.
//   The option (QualitySettings::jacobianAtGaussPoints) evaluates det J(xi, eta) =
//   (dx/dxi x dx/deta) . n at the 2 x 2 Gauss points xi, eta = +-1/sqrt(3) instead, as HyperMesh
//   does for shells by default (*elementchecksettings jacobian_2d = 0); it is milder: on the
//   bracket input deck 73 of 1,865 elements (3.9 %) fail 0.6 at the Gauss points, 416 (22 %) at the
//   corners. Triangles have a constant Jacobian: 1.
// - Scaled Jacobian (Verdict): quads min_i J_i / (|e_{i-1}| |e_i|) (1 for a rectangle, the sine
//   of the smallest corner angle for a parallelogram); triangles (2 / sqrt 3) x the smallest
//   sin(corner angle) signed by the element normal (1 for an equilateral triangle). 0 when an edge
//   has zero length.
// - Taper (quads; 0 for triangles), as HyperMesh: A_i the signed area of corner triangle
//   (p_{i-1}, p_i, p_{i+1}) measured along the element normal, A the quad area |d1 x d2| / 2;
//   taper = 1 - min A_i / (A / 2). 0 for a parallelogram, 1 when a corner triangle has no area.
// - Minimum element length, the LS-DYNA shell characteristic length of the explicit time step:
//   (1 + b) A / (longest edge), b = 0 for quads (A the quad area above), b = 1 for triangles.
//   Its limit is minLengthFactor itself when the settings give it in model units
//   (minLengthAbsolute), else minLengthFactor x the size the element is judged against: the target
//   size, or, when channel curves are given (assessQuality), the width of the channel the element
//   lies in where that is narrower. A channel is bounded by the curves the mesh must keep (boundary
//   loops, feature lines, junction curves: channelCurves); its width at an element is the
//   diameter of the largest ball that contains the element's centroid and that no curve crosses.
//   A strip 1 mm wide meshed at 5 mm cannot have elements longer than 1 mm across it, so its
//   elements are judged at 1 mm (DESIGN.md: narrow features are kept, with smaller elements,
//   judged against the size actually used there); next to a single curve, or in a corner of a
//   right angle or more, the ball grows past the element and the target size applies. The
//   width is sought only up to twice the element's length (a wider channel cannot excuse it):
//   an element no channel excuses is judged, and reported, at the target size.
// - Sharp corners: where the original surface spans less than the triangle minimum angle between
//   two of those curves at a point (a wing rib's trailing edge, two seams meeting at 15 degrees),
//   every mesh has an element with that angle there. A triangle that fills such a corner (its two
//   edges there run along the corner's two sides) is judged by its other two angles: when both
//   lie within the triangle angle limits, the criteria its corner angle alone decides (minimum
//   angle, aspect, skew, scaled Jacobian) do not count as failing. Its minimum length, distance
//   and fold are judged as any element's. Two elements sharing the corner both fail.
//
// - Degenerate corner (quads): the largest reflex-corrected interior angle above
//   QualitySettings::degenerateCornerDeg (179 degrees): the element normal solvers estimate there
//   vanishes (CalculiX stops on it).
//
// Criteria of an element in its mesh (they need its neighbours or the original surface):
// - Folded: the element's normal points against (more than 120 degrees from) the normals of at
//   least half of its edge neighbours, each neighbour's normal taken in the element's orientation
//   (flipped when the two run along their shared edge in the same direction). foldedFaces below.
//   With an original (assessQuality), a neighbour across an edge along one of the original's
//   feature lines or junction curves (a knife edge of the geometry) does not count as opposite.
// - Distance (only with an original surface): a sample of the element (a corner or a point
//   inside it) lies farther than the distance limit from the original, or a sample of the
//   original farther than the limit has its closest point on the element (the element is where
//   the original is not covered).
//
// Per mesh: the share of triangles among all elements, and the distance between the mesh and an
// original surface in both directions (surfaceDistance, below).
//
// Quality index (as HyperMesh's): per criterion that applies to an element (and is not excused,
// as a sharp corner's triangle is), a penalty from its value and the criterion's thresholds
// (IndexThresholds, with the limit as "fail"): 0 up to good, rising linearly to 0.8 at warn, to
// 1 at the limit and to 10 at worst, and on beyond worst at the slope from the limit to worst
// (indexPenalty). Folded counts 10 for a folded element. The element's index is the weighted sum
// of its penalties, so an element within every limit scores at most the sum of the weights; a
// mesh's index is the mean over its elements.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "voxremesh/quad_mesh.h"

namespace voxremesh {

struct Sheet;

/// The criteria of the per-element summary, in report order.
enum class Criterion : std::uint8_t {
  Warping,
  AspectRatio,
  QuadMinAngle,
  QuadMaxAngle,
  TriaMinAngle,
  TriaMaxAngle,
  Skew,
  JacobianRatio,
  ScaledJacobian,
  Taper,
  MinLength,
  DegenerateCorner,
  Folded,    ///< needs the element's neighbours (foldedFaces)
  Distance,  ///< needs the original surface
};
/// The criteria elementFailures decides from an element's own corners (Warping ..
/// DegenerateCorner).
constexpr int kElementCriterionCount = 12;
/// All criteria; Folded and Distance are decided by assessQuality from the whole mesh.
constexpr int kCriterionCount = 14;

/// The quality index's thresholds of one criterion besides its limit (QualitySettings): the value
/// where it is ideal, where it is still good, where it warns and where it is worst, and its
/// weight in the index (see "Quality index" at the top of the file). Ordered: for a maximum
/// (warping) ideal <= good <= warn <= worst, for a minimum the other way; a limit outside warn ..
/// worst moves them to it.
/// Lengths are factors as the limit's (minimum length: of the size the element is judged at;
/// distance: of the distance size).
struct IndexThresholds {
  double ideal = 0.0, good = 0.0, warn = 0.0, worst = 0.0;
  double weight = 1.0;
};

/// The default index thresholds, per Criterion (the limits are QualitySettings' defaults).
inline constexpr std::array<IndexThresholds, kCriterionCount> kDefaultIndexThresholds{{
    {0.0, 5.0, 10.0, 30.0, 1.0},       // warping
    {1.0, 2.0, 4.0, 10.0, 1.0},        // aspect
    {90.0, 75.0, 60.0, 20.0, 1.0},     // quad_min_angle
    {90.0, 105.0, 120.0, 160.0, 1.0},  // quad_max_angle
    {60.0, 50.0, 40.0, 15.0, 1.0},     // tria_min_angle
    {60.0, 75.0, 100.0, 150.0, 1.0},   // tria_max_angle
    {0.0, 10.0, 30.0, 60.0, 1.0},      // skew
    {1.0, 0.9, 0.7, 0.3, 1.0},         // jacobian_ratio
    {1.0, 0.8, 0.5, 0.1, 1.0},         // scaled_jacobian
    {0.0, 0.2, 0.5, 0.9, 1.0},         // taper
    {1.0, 0.8, 0.6, 0.2, 1.0},         // min_length (x the judged size)
    {90.0, 120.0, 170.0, 180.0, 1.0},  // degenerate_corner
    {0.0, 0.0, 0.0, 1.0, 1.0},         // folded (1 when folded; its limit is 0)
    {0.0, 0.05, 0.15, 1.0, 1.0},       // distance (x the distance size)
}};

/// Thresholds of the quality criteria. Defaults as DESIGN.md's table. A metric fails when it is
/// beyond its limit (strictly greater than a maximum, strictly less than a minimum).
struct QualitySettings {
  double maxWarpingDeg = 15.0;     ///< warping angle of quads
  double maxAspectRatio = 5.0;     ///< longest / shortest edge
  double minQuadAngleDeg = 45.0;   ///< smallest interior angle of quads
  double maxQuadAngleDeg = 135.0;  ///< largest interior angle of quads
  double minTriaAngleDeg = 30.0;   ///< smallest interior angle of triangles
  double maxTriaAngleDeg = 120.0;  ///< largest interior angle of triangles
  double maxSkewDeg = 40.0;        ///< skew
  double minJacobianRatio = 0.6;   ///< Jacobian ratio
  /// The Jacobian ratio criterion looks at the 2 x 2 Gauss points (HyperMesh's default) instead
  /// of the corners (DESIGN.md's definition, the default; see the top of the file).
  bool jacobianAtGaussPoints = false;
  /// Scaled Jacobian (not in DESIGN.md's table): 0.3, the lower end of Verdict's acceptable range
  /// for quads and triangles.
  double minScaledJacobian = 0.3;
  double maxTaper = 0.6;         ///< taper of quads
  double minLengthFactor = 0.5;  ///< minimum element length limit = this x targetSize
  /// minLengthFactor and min_length's index thresholds are lengths in model units, not multiples
  /// of the size an element is judged against: the limit is the same for every element, narrow
  /// channels included (a criteria file's length without 'h').
  bool minLengthAbsolute = false;
  /// The target element size the length and distance limits scale with, in model units; 0 (the
  /// default) means the median edge length of the assessed mesh.
  double targetSize = 0.0;
  double maxTriangleShare = 0.05;   ///< triangles / all elements
  double maxDistanceFactor = 0.25;  ///< two-sided max distance limit = this x distanceSize
  /// maxDistanceFactor and distance's index thresholds are lengths in model units, not multiples
  /// of distanceSize (a criteria file's length without 'h').
  bool distanceAbsolute = false;
  /// The size the distance limit scales with; 0 (the default) means targetSize. A part remeshed
  /// at a finer voxel than asked keeps the distance limit of the size asked.
  double distanceSize = 0.0;
  /// A quad corner above this angle (reflex-corrected) is degenerate (DegenerateCorner).
  double degenerateCornerDeg = 179.0;
  /// A mesh passes when at most this share of its elements fails a criterion (and no element is
  /// folded or has a degenerate corner, the triangle share and the distance are within limits).
  double maxFailingShare = 0.05;
  /// Per Criterion, the quality index's thresholds besides the limit (IndexThresholds).
  std::array<IndexThresholds, kCriterionCount> index = kDefaultIndexThresholds;
};

/// Checks that every field of the settings is finite and in its meaningful range (angles within
/// 0..180 with min <= max, ratios and factors >= 0, shares within 0..1, targetSize >= 0), and
/// that each criterion's index thresholds are ordered and their weight >= 0.
/// Throws SettingError naming the field and its value.
void checkQualitySettings(const QualitySettings& settings);

/// The quality index's penalty of one value of a criterion (see "Quality index" at the top of
/// the file): 0 up to `t.good`, then linear through 0.8 at `t.warn`, 1 at `limit` and 10 at
/// `t.worst`, and on beyond at that last slope; equal thresholds make a step, and a limit outside
/// warn .. worst moves them to it. `isMaximum` says which way is worse (a maximum criterion grows
/// worse with the value). NaN gives 10.
/// Precondition: the thresholds are ordered (checkQualitySettings).
double indexPenalty(double value, const IndexThresholds& t, double limit, bool isMaximum);

/// The metrics of one element (definitions at the top of the file).
struct ElementQuality {
  double warpingDeg = 0.0;
  double aspectRatio = 1.0;
  double minAngleDeg = 0.0;
  double maxAngleDeg = 0.0;
  double skewDeg = 0.0;
  double jacobianRatio = 1.0;       ///< at the corners
  double jacobianRatioGauss = 1.0;  ///< at the 2 x 2 Gauss points
  double scaledJacobian = 1.0;
  double taper = 0.0;
  double minLength = 0.0;
};

/// The metrics of one element with the given corners (3 for a triangle, 4 for a quad).
/// Precondition: corners is 3 or 4 (std::invalid_argument otherwise).
ElementQuality elementQuality(const std::array<std::array<double, 3>, 4>& p, int corners);

/// The metrics of every face of a mesh, in face order (computed in parallel, deterministic).
/// Precondition: every face names existing points (std::invalid_argument otherwise).
std::vector<ElementQuality> elementQualities(const QuadMesh& mesh);

/// The median length of the distinct edges of a mesh (0 without edges).
double medianEdgeLength(const QuadMesh& mesh);

/// A short name of a criterion ("warping", "aspect", "quad_min_angle", ...), also the JSON key
/// and the .vtu array name of its metric.
const char* criterionName(Criterion criterion);

/// True when a larger value of the criterion is worse (its limit is a maximum).
bool isMaximumCriterion(Criterion criterion);

/// The field of QualitySettings that holds a criterion's limit (a factor of the judged size for
/// the minimum length, of the distance size for the distance); null for folded (none allowed).
double QualitySettings::*limitField(Criterion criterion);

/// For the criteria whose settings are lengths (min_length, distance), the flag that says they are
/// in model units (minLengthAbsolute, distanceAbsolute); null for the others.
bool QualitySettings::*absoluteLengthField(Criterion criterion);

/// What the settings of a length criterion (min_length, distance: limit and index thresholds) are
/// multiples of, for an element judged against `size`: `size`, or 1 where the settings give that
/// criterion's lengths in model units (minLengthAbsolute, distanceAbsolute). 1 for other criteria.
double lengthScale(const QualitySettings& settings, Criterion criterion, double size);

/// The element criteria (the first kElementCriterionCount) an element with these metrics fails
/// under the settings: bit c set when Criterion c applies to the element (quads: all but the
/// triangle angles; triangles: aspect, triangle angles, skew, scaled Jacobian, length) and its
/// value is beyond the limit (NaN fails).
/// Precondition: corners is 3 or 4; settings.targetSize > 0 for the length limit to mean anything.
std::uint32_t elementFailures(const ElementQuality& quality, int corners,
                              const QualitySettings& settings);

/// The summary of one criterion over a mesh.
struct CriterionSummary {
  Criterion criterion = Criterion::Warping;
  double limit = 0.0;
  bool isMaximum = true;    ///< the limit is a maximum (fail above) or a minimum (fail below)
  double worst = 0.0;       ///< the worst value among the elements it applies to (0 when none)
  std::size_t applies = 0;  ///< elements the criterion applies to (quads only for warping, ...)
  std::size_t failing = 0;
  double share = 0.0;  ///< failing / all elements
};

/// The two-sided distance between a mesh and an original surface.
/// Samples: the points of a mesh, the midpoints of its distinct edges and points inside its faces:
/// each face's triangles (quads split along p0-p2) cut into k x k similar triangles, k the
/// smallest count that makes their sides at most the sample spacing (at least 2, at most 64), and
/// the centroid of each taken. Each sample's distance is the exact distance to the other surface.
/// Max and mean are over the samples of one side.
struct SurfaceDistance {
  double maxToOriginal = 0.0;  ///< samples of the mesh -> original
  double meanToOriginal = 0.0;
  double maxFromOriginal = 0.0;  ///< samples of the original -> mesh
  double meanFromOriginal = 0.0;
  std::vector<double> pointDistance;  ///< per mesh point, its distance to the original
  /// Per mesh face: the largest distance of its corners and inner samples to the original, and
  /// of the original's samples whose closest point lies on it.
  std::vector<double> faceDistance;
  /// The two-sided (Hausdorff) distance.
  double max() const { return maxToOriginal > maxFromOriginal ? maxToOriginal : maxFromOriginal; }
};

/// Computes the two-sided distance between `mesh` and `original` (see SurfaceDistance), with
/// queries in parallel; deterministic.
/// @param sampleSpacing  the largest spacing of the samples inside faces; 0: two per triangle side
/// Preconditions: both meshes have faces naming existing points (std::invalid_argument otherwise).
SurfaceDistance surfaceDistance(const QuadMesh& mesh, const QuadMesh& original,
                                double sampleSpacing = 0.0);

/// Per face of the mesh, 1 when it is folded (see "Folded" at the top of the file), else 0.
/// Faces with a zero normal and faces without a neighbour are not folded.
/// @param ridges  null, or curves of the surface the mesh stands for along which it turns
///                sharply (an original's feature lines and junction curves: channelCurves): a
///                neighbour across an edge lying along one of them is not counted as opposite,
///                so that the two sides of a knife edge (a trailing edge, a flange folded back)
///                are no fold. An edge lies along a curve when its ends are within 1e-4 and its
///                midpoint within 0.05 of its length of the same curve.
/// Preconditions: faces name existing points.
std::vector<std::uint8_t> foldedFaces(const QuadMesh& mesh,
                                      const std::vector<MeshCurve>* ridges = nullptr);

/// Connected pieces and boundary loops of a mesh, as the acceptance of a remeshed part compares
/// them with the original part.
struct TopologyCounts {
  std::size_t components = 0;     ///< sets of points joined by face edges (used points only)
  std::size_t boundaryLoops = 0;  ///< sets of points joined by boundary edges (edges of one face);
                                  ///< loops touching at a point count once
};

/// Counts the components and boundary loops of a mesh (see TopologyCounts). Preconditions: faces
/// name existing points.
TopologyCounts topologyCounts(const QuadMesh& mesh);

/// The edges of a mesh that at least `minFaces` and at most `maxFaces` faces share (1 and 1: its
/// boundary; 3 and more: T-junctions, where a fin or a flange stands on a sheet), each as its two
/// point indices, lower first, in ascending order. Preconditions: faces name existing points.
std::vector<std::pair<CornerIndex, CornerIndex>> edgesSharedBy(const QuadMesh& mesh,
                                                               std::size_t minFaces,
                                                               std::size_t maxFaces);

/// The curves that bound the channels of a surface for the minimum-length criterion (see the top of
/// the file): every sheet's boundary loops, feature lines and junction curves, in world
/// coordinates, in sheet order. Preconditions: the sheets' curves name existing points.
std::vector<MeshCurve> channelCurves(const std::vector<Sheet>& sheets);

/// The quality of a whole mesh against the settings.
struct QualityReport {
  QualitySettings settings;  ///< as given, with targetSize resolved
  std::size_t elements = 0;
  std::size_t quads = 0;
  std::size_t triangles = 0;
  std::vector<CriterionSummary> criteria;  ///< one per Criterion, in enum order
  std::size_t failingAny = 0;              ///< elements failing at least one criterion
  double failingAnyShare = 0.0;
  double triangleShare = 0.0;
  std::vector<ElementQuality> elementValues;   ///< per face
  std::vector<std::uint32_t> elementFailures;  ///< per face: bit c set when Criterion c fails
  std::vector<double> qualityIndex;            ///< per face (see "Quality index")
  double meanQualityIndex = 0.0;               ///< over the faces (0 without faces)
  std::optional<SurfaceDistance> distance;     ///< when an original was given
  double distanceLimit = 0.0;  ///< maxDistanceFactor x the distance size (or in model units)
  /// Per face: the size its minimum length is judged against, targetSize or the width of the
  /// narrow channel it lies in (when channel curves were given).
  std::vector<double> judgedSize;
  /// Faces whose minimum length a channel narrower than targetSize excuses (see the top of the
  /// file).
  std::size_t narrowChannelElements = 0;
  /// Triangles filling a corner of the original sharper than the triangle angle limit, judged by
  /// their other two angles (see the top of the file; only with an original and its curves).
  std::size_t sharpCornerElements = 0;

  /// The mesh passes: at most settings.maxFailingShare of its elements fail a criterion, none is
  /// folded or has a degenerate corner, and the triangle share and (if measured) the distance are
  /// within their limits.
  bool passes() const;
  /// Elements failing criterion c.
  std::size_t failing(Criterion c) const { return criteria[static_cast<int>(c)].failing; }
};

/// Assesses a mesh: element metrics, per-criterion summaries (folded elements included), triangle
/// share, and the distance to `original` when it is not null (sampled inside the faces at half
/// the target size at most; elements beyond the limit fail Distance).
/// @param mesh      the mesh; faces name existing points
/// @param settings  thresholds (checked with checkQualitySettings)
/// @param original  the surface the mesh should stay close to, or nullptr
/// @param channels  the curves bounding the surface's channels (channelCurves of the original,
///                  or of the mesh itself), or nullptr: every element's minimum length is then
///                  judged against the target size
/// Throws SettingError for bad settings or when targetSize is 0 and the mesh has no edges;
/// std::invalid_argument when a face names a missing point.
QualityReport assessQuality(const QuadMesh& mesh, const QualitySettings& settings = {},
                            const QuadMesh* original = nullptr,
                            const std::vector<MeshCurve>* channels = nullptr);

/// Renders a report as an aligned text table: per criterion the limit, worst value, failing count
/// and share; then failing-any, the triangle share and the distance.
std::string formatQualityTable(const QualityReport& report);

/// Renders a report (without the per-element arrays) as one JSON object.
std::string qualityReportJson(const QualityReport& report);

}  // namespace voxremesh
