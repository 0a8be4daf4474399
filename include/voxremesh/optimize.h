// The optimisation stage: turns an extracted quad-dominant mesh into one that passes the FE
// quality criteria (Bidmon et al., Sect. 5), one function per step (src/optimize/, a file each)
// and a driver running them in order.
//
// Constraints (quad_mesh.h) hold in every step: Corner and Junction points never move (a Junction
// point is on a curve shared with another sheet or part, whose mesh uses the same nodes: moving
// or removing it would break the conforming seam); Feature and Boundary points move only along
// mesh.curves[constraint.curve] (each new position is the closest point of that curve); Free
// points move on the surface (relaxation projects them on the original; warping removal takes
// them off it by at most its maxMove). Topology steps never merge a Corner or Junction point into
// another point (other points may merge into them; they keep their place), and merge a Feature or
// Boundary point only into a point of the same curve or into a Corner or Junction point.
// Every step is deterministic: the result does not depend on the number of TBB threads.
//
// Preconditions of every step (std::invalid_argument otherwise): coordinates are finite; every
// face names existing points; constraints is empty or has one entry per point, and every
// Feature/Boundary/Junction constraint names an existing curve with points. The mesh is expected to
// be manifold (each edge in one or two faces, consistently oriented), as extraction produces it;
// the steps keep it so.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>

#include "voxremesh/quad_mesh.h"
#include "voxremesh/quality.h"
#include "voxremesh/reference_surface.h"

namespace voxremesh {

/// What removeWarping did.
struct WarpingResult {
  int iterations = 0;
  std::size_t warpedBefore = 0;  ///< quads above the threshold before
  std::size_t warpedAfter = 0;   ///< quads above the threshold after
};

/// Warping removal (paper Sect. 5.1). Per iteration, for every quad whose warping angle (quality.h)
/// exceeds `maxWarpingDeg`, proposes for each of its corners the projection on the plane through
/// the quad's centroid whose normal is the sum of the four diagonal-split triangle normals; every
/// point then moves to the mean of its proposals, pulled back to at most `maxMove` from where it
/// was before the first iteration (curve points to the closest point of their curve after that,
/// corners stay). Repeats until no quad exceeds the threshold, `maxIterations` is reached, or 10
/// iterations in a row did not lower the number of warped quads.
/// @param mesh           the mesh (preconditions at the top of the file)
/// @param maxWarpingDeg  threshold in degrees, finite and >= 0
/// @param maxIterations  >= 0
/// @param maxMove        the largest displacement of a point, > 0 (infinity: unlimited)
/// Throws std::invalid_argument for a bad threshold, iteration count, displacement or mesh.
WarpingResult removeWarping(QuadMesh& mesh, double maxWarpingDeg, int maxIterations = 200,
                            double maxMove = std::numeric_limits<double>::infinity());

/// Rhombic-quad collapse (paper Sect. 5.2). A rhombic quad is a quad whose four points are Free,
/// not on the mesh boundary, and of odd degree (number of edges at the point), with the two points
/// of one diagonal of lower degree sum than the other and the other two of degree > 3. Its lower
/// diagonal is collapsed: the two points merge at their midpoint (projected on `surface` when not
/// null) and the quad disappears. A collapse is done only where it keeps the mesh manifold and
/// conforming (the two points have no other common neighbour and share no other face); collapses
/// in one round touch disjoint neighbourhoods; rounds repeat until none is left.
/// @return the number of collapsed quads
/// Throws std::invalid_argument for a mesh that breaks the preconditions.
std::size_t collapseRhombicQuads(QuadMesh& mesh, const ReferenceSurface* surface = nullptr);

/// Relaxation: tangential smoothing towards well-shaped elements of the target size. Per
/// iteration (Jacobi: all targets from the previous positions), every face gets its ideal shape:
/// the square (quad) or equilateral triangle with edge `targetSize` (0: of the face's own area)
/// that best fits its corners (centred on its centroid, in its plane, turned to fit in the
/// least-squares sense). A Free point moves `damping` of the way to the mean of the positions its
/// faces' ideal shapes give it, minus the part of the move along its normal, and is then
/// projected on `original` (the closest point of the original surface, not of the previous
/// iterate). A Free point on the mesh boundary moves towards the midpoint of its two boundary
/// neighbours only along the line joining them (the outline does not shrink), and not at all
/// where the boundary turns by more than 30 degrees there; then it is projected on `original`.
/// A curve point with exactly two neighbours on its curve (along boundary edges for Boundary
/// points, else along edges to points of the same curve or to Corners that run along the curve:
/// the edge's midpoint within a tenth of its length of the curve) moves towards their
/// midpoint and then to the closest point of its curve; Corner and Junction points stay.
/// @param original    the surface to stay on, not empty
/// @param iterations  >= 0
/// @param damping     in (0, 0.7]: the Jacobi update oscillates above that
/// @param targetSize  the edge length of the ideal shapes, finite and >= 0 (0: per face, from its
///                    area)
/// Throws std::invalid_argument for an empty surface, bad parameters or a bad mesh.
void relaxMesh(QuadMesh& mesh, const ReferenceSurface& original, int iterations = 10,
               double damping = 0.5, double targetSize = 0.0);

/// What cleanUpMesh removed.
struct CleanupResult {
  std::size_t zeroAreaFaces = 0;   ///< faces removed or reduced by collapsing their shortest edge
  std::size_t shortEdges = 0;      ///< edges shorter than the short-edge threshold collapsed
  std::size_t duplicateFaces = 0;  ///< faces removed for using the same points as another
  std::size_t valence2Points = 0;  ///< Free interior points in exactly two faces (doublets) removed
  std::size_t foldedCurveFaces = 0;  ///< faces folded along a curve (quads -> triangles, slivers)
};

/// What cleanUpMesh looks for.
struct CleanupSettings {
  double zeroArea = 0.0;     ///< faces with at most this area, model units squared, >= 0
  double shortEdge = 0.0;    ///< edges shorter than this, model units, >= 0 (0: none)
  bool foldedCurves = true;  ///< collapse faces folded along a curve (step 3 below)
};

/// Clean-up: (0) duplicate faces: of faces using the same points, a pair running opposite ways
/// (two faces back to back, a fold) is removed, of faces running the same way all but the first;
/// (1) zero-area faces and short edges: a face with area (quality.h's element area) at most
/// settings.zeroArea, or whose shortest edge is shorter than settings.shortEdge, gets its shortest
/// edge collapsed (a quad becomes a triangle, a triangle vanishes) where the merge keeps the mesh
/// manifold and the constraints allow it (see the top of the file); (2) doublets: a Free point
/// that is not on the boundary and lies in exactly two faces is removed and the two faces become
/// one (two quads -> a quad, a quad and a triangle -> a triangle, two triangles -> nothing).
/// Constrained points in doublets are kept; (3) when settings.foldedCurves, faces folded along a
/// curve: three consecutive
/// corners a, b, c on one curve (b a Feature/Boundary point, a and c on its curve or Corners or
/// Junctions) with an interior angle above 150 degrees at b: b merges into the nearer of a and c
/// (a quad becomes a triangle, a triangle vanishes; the constraint rules above apply). Rounds
/// repeat until nothing changes. Unused points are removed at the end (indices of points change;
/// order is kept).
/// Throws std::invalid_argument for a negative or non-finite threshold or a bad mesh.
CleanupResult cleanUpMesh(QuadMesh& mesh, const CleanupSettings& settings);

/// Triangle-pair merging: two triangles sharing an edge become the quad of their four points when
/// that quad passes every element criterion of `settings` (quality.h; the length limit with
/// settings.targetSize, which must be > 0). Pairs are taken best first (smallest largest deviation
/// of a corner angle from 90 degrees; ties by triangle index), each triangle at most once.
/// @return the number of quads made
/// Throws std::invalid_argument for targetSize <= 0 or a bad mesh; SettingError for bad settings.
std::size_t mergeTrianglePairs(QuadMesh& mesh, const QualitySettings& settings);

/// The three searches below (improveFailingElements, fitFarOriginalPoints, reconnectFailingFaces)
/// are one engine: the same loop of rounds over a worklist, independent items in parallel, and
/// one record of tries in vain (an item not tried again while the points it depends on are
/// unchanged); they differ in their kind of item: a point moved, a point pulled towards the
/// original, a neighbourhood reconnected.

/// Moves the points of failing elements by a pattern search: steps of 0.25 x the point's mean
/// edge length, halved down to 0.01 x, in eight directions of the tangent plane (the plane normal
/// to the sum of its faces' normals); Free points are projected on `original` after every step,
/// curve points kept on their curves, Corners and Junction points fixed. A step is taken when the
/// faces around the point then fail fewer criteria (quality.h, under `settings`), or as many with
/// a smaller penalty: the squares of how far each metric lies beyond a soft limit a margin inside
/// its criterion (e.g. 55 .. 125 degrees for quad angles, 0.7 for the Jacobian ratio), and no
/// more of the faces touching those faces are folded than before (foldedFaces, quality.h: a
/// folded face can pass every criterion of its own). Points that share no face are split
/// greedily in index order into classes, each class searched in parallel and the classes one after
/// another; the fold check reads the faces across a point's faces at their positions from before
/// the class, so the result does not depend on the thread count. Repeats up to `sweeps` times over
/// the points of the faces still failing, or until no point moves.
/// @return the number of point moves made
/// Throws std::invalid_argument for an empty surface, negative sweeps, settings.targetSize <= 0
/// or a bad mesh; SettingError for bad settings.
std::size_t improveFailingElements(QuadMesh& mesh, const ReferenceSurface& original,
                                   const QualitySettings& settings, int sweeps = 5);

/// Edge splitting: every edge longer than `maxLength` with at least one Free end (an edge between
/// two constrained points may run along a curve or a junction another mesh shares) and, when
/// `surface` is not null, whose midpoint lies farther than `chordTolerance` from it than its ends
/// do on average (the edge cuts across the curved surface; not farther than a quarter of the
/// edge's length, which is a gap such as a hole, not a bend) gets its midpoint, projected on
/// `surface` when not null, as a new Free point; the faces around split edges are cut by templates
/// in their own orientation: a quad with one split edge into a quad and a triangle (the cut whose
/// worst corner angle is best), with two opposite ones into two quads, with two adjacent ones or
/// more into quads around a new centre point (and a triangle for three); a triangle into two
/// triangles, a quad and a triangle, or three quads. Rounds repeat until no edge is longer or
/// `maxRounds` is reached. Serial and deterministic (new points numbered in the order of the split
/// edges, then of the faces). Where the dual mesh stops far from the original boundary (a narrow
/// lobe around a hole), the boundary strip fans wide and its long faces cut across the curved
/// surface: this brings them back to it.
/// @param mesh       the mesh (preconditions at the top of the file)
/// @param maxLength  finite and > 0
/// @param surface    the original surface (not empty), or null to leave midpoints on their edges
/// @param chordTolerance  finite and >= 0
/// @param maxRounds  >= 0
/// @return the number of edges split
/// Throws std::invalid_argument for a bad length, tolerance, round count, empty surface or bad
/// mesh.
std::size_t splitLongEdges(QuadMesh& mesh, double maxLength, const ReferenceSurface* surface,
                           double chordTolerance = 0.0, int maxRounds = 3);

/// Inverted and flat-cornered quads: a quad with exactly one reflex corner (det J <= 0 there,
/// with quality.h's corner Jacobian: a negative Jacobian ratio, which solvers refuse) or corner
/// of `degenerateCornerDeg` degrees or more (where solvers cannot estimate the shell normal)
/// becomes the two triangles on either side of the diagonal from that corner, which lies inside
/// the quad; both keep the quad's orientation. Quads with more than one such corner are left as
/// they are. Serial, deterministic.
/// @return the number of quads split
/// Throws std::invalid_argument for a bad mesh.
std::size_t splitInvertedQuads(QuadMesh& mesh, double degenerateCornerDeg = 179.0);

/// Folds untangled, or cut out and filled again: the folded faces (quality.h's foldedFaces) and
/// every face sharing a point with them form regions. A region whose outline is one simple loop
/// is first untangled: grown at the reflex corners of its outline (projected on the plane of its
/// unfolded faces' mean normal) for up to three rounds, its Free inner points placed by Tutte's
/// barycentric embedding on that plane (points on curves held) and laid on the original, its
/// faces kept, when that leaves fewer folded faces, no sliver (face_score.h) and the faces within
/// the distance limit of `original` (or as close as they were). Else, where its inner points are
/// all Free and the outline projects as a simple polygon, the region is replaced by triangles
/// filling it (its inner points dropped) within the same distance and without a sliver: a fan from
/// the outline's centroid laid on the original where the outline is star-shaped round it, else ear
/// clipping, triangles too far split at their centroid; then triangle pairs are merged into quads
/// where they pass (mergeTrianglePairs, when settings.targetSize > 0). The fills are kept only when
/// fewer faces are folded afterwards. Deterministic.
/// @return the number of regions untangled or refilled
/// Throws std::invalid_argument for an empty surface or a bad mesh; SettingError for bad
/// settings.
std::size_t refillFoldedRegions(QuadMesh& mesh, const ReferenceSurface& original,
                                const QualitySettings& settings);

/// Points pulled towards the far places of the original: the points of `original` (its
/// usedPoints, the original's nodes) farther from the mesh than a share of the distance limit
/// (settings.maxDistanceFactor x targetSize), farthest first, one per face of the mesh nearest
/// to them, each the start of a compass search (as improveFailingElements') of a Free interior
/// corner of that face, the nearest first. A move is taken when the original points nearest to
/// the corner's faces lie less beyond that share (summed squares), none farther than before
/// where beyond it, the faces fail no more criteria (as face_score counts them) and stray from
/// `original` no more than before or than that share (chordError). Points round a moved one wait
/// for the next pass; passes repeat until none moves or `maxPasses` is reached. The passes run
/// with the share 0.8 (a margin under the limit), then again with 0.2: the chords across bends
/// that make the new mesh softer than the original. The faces of a pass are split greedily, in
/// that order, into classes whose searches do not read the points others move; the searches of a
/// class run in parallel, the classes one after another: deterministic. Faces do not change.
/// @return the number of points moved
/// Throws std::invalid_argument for an empty surface, negative passes, settings.targetSize <= 0
/// or a bad mesh; SettingError for bad settings.
std::size_t fitFarOriginalPoints(QuadMesh& mesh, const ReferenceSurface& original,
                                 const QualitySettings& settings, int maxPasses = 3);

/// The kinds of local edits reconnectFailingFaces tries at a failing face (bits).
enum ReconnectEdit : unsigned {
  kRecutPair = 1u,        ///< the other cuts of the polygon a face makes with a neighbour
  kThreeQuadCorner = 2u,  ///< an inner corner of three quads taken out, their hexagon cut again
  kCollapse = 4u,         ///< a quad's diagonals collapsed; a short or sliver face's edges
  kSplitQuad = 8u,        ///< a quad cut into two triangles while the triangle share allows
};

/// What reconnectFailingFaces does.
struct ReconnectSettings {
  /// Rounds over every failing face, then as many over the faces with a degenerate corner (>= 0).
  int rounds = 3;
  /// Sweeps of pattern searches of each try (>= 0; 0: tries are scored as cut, and the
  /// neighbourhood as it is is not a try).
  int sweeps = 3;
  unsigned edits = kRecutPair | kThreeQuadCorner | kCollapse;  ///< ReconnectEdit bits
  /// kSplitQuad is applied while the triangle share stays at or under this (0 .. 1).
  double maxTriangleShare = 0.0;
};

/// The search engine of the optimisation: local edits round each failing face, each followed by
/// pattern searches of the points round it, kept by one rule. Per round, for each face failing a
/// criterion (quality.h, under `settings`), its neighbourhood (the faces round the points of the
/// faces round its corners) is tried as it is (when reconnect.sweeps > 0) and after each edit of
/// the kinds reconnect.edits names (ReconnectEdit): every other cut of the polygon the face makes
/// with a neighbour across one of its edges (an edge between two constrained points is not
/// removed, a diagonal between two constrained points or along an existing edge not made,
/// neither end of the removed edge left in fewer than 3 faces, 2 on the boundary); the removal of
/// an inner corner that exactly three quads share (their hexagon cut into two quads along each of
/// its diagonals: the corner an uneven count of rows leaves); for a quad the collapse of either
/// diagonal and, for a face failing the minimum length or the triangles' minimum angle or with a
/// degenerate corner, the collapse of each of its edges (under the constraint and manifold rules
/// of the rhombic collapse); a quad's cut into two triangles along either diagonal, while the
/// triangle share stays at or under reconnect.maxTriangleShare. Each try gets one sweep of the
/// pattern search of improveFailingElements (down to steps of a sixteenth of an edge) over the
/// points of the faces round the face's corners; the three that then score best go on to
/// reconnect.sweeps sweeps in all. The rule: only tries whose faces stay as close to the original
/// as half the distance limit (settings.maxDistanceFactor x targetSize; the whole limit round a
/// face with a degenerate corner, which no acceptance allows), or as the neighbourhood's faces
/// were, take part (measured at face centres and edge midpoints), and only those with no more
/// folded faces (foldedFaces, quality.h) than the neighbourhood had: a flipped face can pass every
/// criterion of its own. The one whose neighbourhood then scores best (face_score.h: fewer
/// criteria failed, then the smaller penalty) is kept when it fails fewer criteria than the
/// neighbourhood did. Rounds repeat until none changes or reconnect.rounds is reached, then as
/// many again over the faces with a degenerate corner only. The faces of a round are split
/// greedily, in index order, into classes whose neighbourhoods share no point; the faces of a
/// class are tried in parallel (and the tries of one face too) and their changes applied in face
/// order, the classes one after another, a face whose neighbourhood an earlier class changed
/// waiting for the next round: the result does not depend on the thread count.
/// @return the number of neighbourhoods changed
/// Throws std::invalid_argument for an empty surface, negative rounds or sweeps,
/// settings.targetSize <= 0 or a bad mesh; SettingError for bad settings or a triangle share
/// outside 0 .. 1.
std::size_t reconnectFailingFaces(QuadMesh& mesh, const ReferenceSurface& original,
                                  const QualitySettings& settings,
                                  const ReconnectSettings& reconnect = {});

/// The warping removal's threshold as a share of the warping criterion's limit when
/// OptimizeSettings::warpingDeg is unset (12 degrees for the default 15).
inline constexpr double kWarpingRemovalShare = 0.8;

/// Settings of optimizeQuadMesh.
struct OptimizeSettings {
  /// Quality limits: targetSize (0: the median edge length of the input mesh) scales the
  /// zero-area threshold; the element criteria decide which triangle pairs merge.
  QualitySettings quality;
  /// Warping removal threshold, degrees, in 0 .. 180; unset: kWarpingRemovalShare x the
  /// criterion's limit (quality.maxWarpingDeg), so that the output keeps a margin under it.
  std::optional<double> warpingDeg;
  int warpingIterations = 200;
  /// Relaxation iterations before and after triangle merging, and the damping of each step
  /// (0 < damping <= 0.7, see relaxMesh).
  int relaxIterations = 10;
  double relaxDamping = 0.5;
  bool collapseRhombic = true;
  bool mergeTriangles = true;
  /// Recut pairs of faces round failing faces (edge rotations: the search engine with kRecutPair
  /// alone, no searches, 5 rounds) after the first improveFailingElements pass, and improve again
  /// when any was recut.
  bool rotateEdges = true;
  /// Sweeps of each improveFailingElements pass (before and after warping removal; 0: none): a
  /// point moved in one sweep opens moves for its neighbours in the next.
  int improveSweeps = 3;
  /// Rounds of the search engine (reconnectFailingFaces, every edit but the quad split) after the
  /// last improveFailingElements pass (0: none).
  int reconnectRounds = 8;
  /// Passes of fitFarOriginalPoints after the reconnection (0: none).
  int fitPasses = 3;
  /// Quads still failing are split into two triangles where these fail fewer criteria, while the
  /// triangle share stays at or under this (the search engine with kSplitQuad alone, no searches,
  /// at the end; 0: none).
  double splitFailingShare = 0.03;
  /// A face is of zero area below zeroAreaFactor x targetSize^2.
  double zeroAreaFactor = 1e-4;
  /// Edges longer than splitLengthFactor x targetSize whose midpoint lies farther than
  /// splitChordFactor x targetSize from the original than their ends do are split first
  /// (splitLongEdges; splitLengthFactor 0: none, else >= 1): a long chord across a curved region
  /// leaves the original uncovered, which the distance criterion counts.
  double splitLengthFactor = 1.75;
  double splitChordFactor = 0.01;
  /// Edges shorter than shortEdgeFactor x targetSize are collapsed in the clean-up. Off by default:
  /// each collapse turns two quads into triangles, which the later steps handle better.
  double shortEdgeFactor = 0.0;
  /// Warping removal moves no point farther than warpingMoveFactor x targetSize from where it
  /// started (relaxation left it on the original surface), so the surface stays close.
  double warpingMoveFactor = 0.1;
  /// Collapse faces folded along a curve in the clean-up (CleanupSettings::foldedCurves): fewer
  /// failing elements at the cost of more triangles (most on parts with many feature lines).
  bool collapseFoldedCurves = true;
};

/// What optimizeQuadMesh did and how long each step took (wall-clock seconds).
struct OptimizeStats {
  double splitSeconds = 0.0;
  double cleanupSeconds = 0.0;
  double rhombicSeconds = 0.0;
  double relaxSeconds = 0.0;
  double mergeSeconds = 0.0;
  double improveSeconds = 0.0;
  double rotateSeconds = 0.0;
  double warpingSeconds = 0.0;
  double reconnectSeconds = 0.0;
  double fitSeconds = 0.0;        ///< fitFarOriginalPoints
  double quadSplitSeconds = 0.0;  ///< the engine's quad split and splitInvertedQuads
  double totalSeconds = 0.0;
  std::size_t edgesSplit = 0;
  CleanupResult cleanup;  ///< summed over both clean-up passes
  std::size_t rhombicCollapsed = 0;
  std::size_t trianglesMerged = 0;  ///< quads made from triangle pairs
  std::size_t improvedMoves = 0;    ///< points moved by improveFailingElements
  std::size_t edgesRotated = 0;     ///< pairs of faces recut by the engine's first phase
  std::size_t reconnected = 0;      ///< neighbourhoods changed by reconnectFailingFaces
  std::size_t farPulls = 0;         ///< points pulled towards far original places
  std::size_t failingSplit = 0;     ///< failing quads split into two triangles (the last phase)
  std::size_t invertedSplit = 0;    ///< quads with a reflex corner split into two triangles (last)
  std::size_t foldsRefilled = 0;    ///< fold regions untangled or refilled (both passes)
  WarpingResult warping;
};

/// Runs the steps: edge splitting, clean-up, rhombic collapse, clean-up, relaxation, triangle
/// merging, relaxation, improvement of the failing elements, edge rotation (the search engine
/// recutting pairs of faces, no searches; the improvement again where any was recut), warping
/// removal (OptimizeSettings::warpingDeg), the regions round folded faces refilled
/// (refillFoldedRegions), the improvement once more (it takes only moves that leave fewer criteria
/// failing around a point, warping included), the search engine with every edit but the quad split,
/// points pulled towards the far places of the original (fitFarOriginalPoints), the search engine
/// splitting quads still failing into triangle pairs that fail less (within splitFailingShare), the
/// split of quads still inverted (splitInvertedQuads), and last the regions round faces these
/// passes left folded refilled again.
/// @param mesh      the extracted mesh (preconditions at the top of the file)
/// @param original  the original surface (built from the input shells), not empty
/// @param settings  see OptimizeSettings
/// @param stats     receives counts and per-step timings when not null
/// Throws SettingError for bad settings; std::invalid_argument for a bad mesh or an empty
/// surface.
void optimizeQuadMesh(QuadMesh& mesh, const ReferenceSurface& original,
                      const OptimizeSettings& settings = {}, OptimizeStats* stats = nullptr);

}  // namespace voxremesh
