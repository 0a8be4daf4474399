// The volume stage: the sheets of one part written into a narrow-band signed-distance grid plus
// two masks (invalid voxels near free boundaries, cells crossed by feature curves), all on one
// uniform transform, and the curves extraction must keep. Grids are OpenVDB grids; this header
// keeps them behind a handle so that users of the stage need no OpenVDB headers (the stages that
// work on the grids include src/volume/volume_grids.h).
//
// Conventions
// - Index space: voxel (i,j,k) is the sample at world position (i,j,k) * voxelSize (the transform
//   is a uniform scale, no offset).
// - sdf: FloatGrid, class level set, background = band * voxelSize. Active voxels are those whose
//   distance to the sheets is below the band; value = s * d, d the exact distance to the closest
//   point of the closest sheet (quads split into triangles 0-1-2 and 0-2-3), s the side of that
//   closest point after orientation (+1 on the side the face normals point to; on an edge or
//   corner shared by several faces, the side of its angle-weighted pseudo-normal). The closest
//   point is searched from OpenVDB meshToVolume's closest polygon of the voxel (and of its six
//   neighbours where an edge or corner comes out closest) by descending to adjacent triangles;
//   meshToVolume's band is dilated by one voxel first, because its outer layer is ragged.
//   Inactive values are +-background, signed by flood fill from the active voxels.
// - invalid: MaskGrid of voxels (samples) whose closest point lies on a free boundary edge or
//   boundary vertex while the distance vector leans more than invalidAngleDeg away from the face
//   normal there (Bidmon et al., Sect. 3). No surface may be extracted from a cell touching one.
// - feature: MaskGrid of CELLS: the value at (i,j,k) stands for the cube [i,i+1]x[j,j+1]x[k,k+1]
//   in index space, the marching-cubes cell whose lowest corner is voxel (i,j,k). A cell is marked
//   when a feature line segment or a feature point touches it (closed cube, so a segment running
//   along a cell face or edge marks every cell sharing it).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "voxremesh/fe_model.h"
#include "voxremesh/sheets.h"

namespace voxremesh {

/// How the voxel size is chosen (see VolumeSettings).
enum class VoxelSizeRule {
  Explicit,           ///< VolumeSettings::voxelSize as given
  TargetElementSize,  ///< voxel size = target element size (the default route)
  MinEdgeLength,      ///< voxel size = minEdgeFactor x the shortest element edge of the input
};

/// Settings of the volume stage. Every field has a documented default.
struct VolumeSettings {
  VoxelSizeRule rule = VoxelSizeRule::TargetElementSize;
  /// Voxel size in model units for VoxelSizeRule::Explicit. Must be finite and > 0.
  double voxelSize = 0.0;
  /// Target element size of the new mesh for VoxelSizeRule::TargetElementSize; 0 (the default)
  /// means the mean element edge length of the input sheets. Negative or NaN is refused.
  double targetElementSize = 0.0;
  /// Voxel size per shortest edge for VoxelSizeRule::MinEdgeLength, in (0, 100].
  double minEdgeFactor = 1.0;
  /// Narrow band half width in voxels, >= 1 and <= 64: voxels farther than band x voxelSize from
  /// every sheet are inactive.
  double bandWidthVoxels = 3.0;
  /// A voxel whose closest point is on a free boundary is invalid when the angle between its
  /// distance vector and the face normal there exceeds this, in degrees, in [0, 90].
  /// Default 60: a cell beyond the boundary in which the sdf changes sign always has a corner at
  /// an angle of at least atan(2) = 63.4 deg (its far corner is >= 1 voxel out and <= 1/2 voxel
  /// off the plane), so every such cell touches an invalid voxel and the dual mesh stops short of
  /// the free boundary; above the sheet's inside the angle is 0 and nothing is invalid.
  double invalidAngleDeg = 60.0;
  /// Ties between an element interior and its edge or vertex: when the distance vector's part
  /// tangential to the face is at most this many voxels, the closest point counts as the face's
  /// interior (the element wins). In [0, 0.01].
  double tieToleranceVoxels = 1e-4;
  /// Refuse settings whose estimated peak memory exceeds this many bytes; 0 (the default) means
  /// half of the physical memory of this machine or of the address-space limit (ulimit -v),
  /// whichever is lower.
  std::uint64_t memoryLimitBytes = 0;
};

/// Where a volume came from, written into the .vdb metadata.
struct VolumeSource {
  std::string sourceFile;  ///< the deck the sheets were built from (may be empty)
};

/// The parameters a Volume was built with (also read back from a .vdb file).
struct VolumeInfo {
  double voxelSize = 0.0;
  double bandWidthVoxels = 0.0;
  double invalidAngleDeg = 0.0;
  double tieToleranceVoxels = 0.0;
  std::string sourceFile;
  Id part = 0;
  std::string toolVersion;  ///< the voxremesh version that built the grids
};

/// A curve kept for extraction, in world coordinates; closed curves do not repeat their first
/// point.
struct VolumeCurve {
  std::vector<std::array<double, 3>> points;
  bool closed = false;
  bool keepPoints = false;   ///< junction curves: see Polyline::keepPoints (sheets.h)
  double nodeSpacing = 0.0;  ///< junction curves: see Polyline::nodeSpacing (sheets.h)
  long nodeCount = 0;        ///< junction curves: see Polyline::nodeCount (sheets.h)
  /// Junction curves: the points toward which the pieces shrink, with their ratio (see
  /// Polyline::grading, sheets.h).
  std::vector<std::pair<std::array<double, 3>, double>> grading{};
  /// Junction curves: see Polyline::stations and stationPieces (sheets.h), in this curve's order.
  std::vector<std::array<double, 3>> stations{};
  std::vector<long> stationPieces{};
};

/// A curve of a sheet (its boundary loop, feature line or junction curve) in world coordinates,
/// with its sampling (closed, keepPoints, nodeSpacing, nodeCount, grading, stations).
/// Throws std::invalid_argument when the curve refers to a point the sheet does not have.
VolumeCurve worldCurve(const Sheet& sheet, const Polyline& line);

/// The volume of one part: the grids (behind a handle) plus the curves of its sheets.
class Volume {
 public:
  struct Impl;  ///< defined in src/volume/volume_grids.h

  /// An empty volume (no grids); use buildVolume or readVolume to get one with content.
  Volume();
  ~Volume();
  Volume(Volume&&) noexcept;
  Volume& operator=(Volume&&) noexcept;
  /// Deep copy of grids and curves.
  Volume(const Volume& other);
  Volume& operator=(const Volume& other);

  /// True until grids have been built or read.
  bool empty() const;
  /// The build parameters and provenance.
  const VolumeInfo& info() const;
  /// Feature lines of all sheets (world space).
  const std::vector<VolumeCurve>& featureLines() const;
  /// Boundary loops of all sheets (world space), for rebuilding the boundary strip.
  const std::vector<VolumeCurve>& boundaryLoops() const;
  /// Feature points of all sheets (world space).
  const std::vector<std::array<double, 3>>& featurePoints() const;
  /// Junction curves of all sheets (world space): where a sheet met another sheet of its part
  /// or another part. Extraction gives the nodes it puts on them the same positions on every
  /// side (see extract.h), so that the meshes of both sides share nodes there.
  const std::vector<VolumeCurve>& junctionCurves() const;

  /// Internal access for the stages that work on the grids (src/volume/volume_grids.h).
  Impl& impl() { return *impl_; }
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// Returns the voxel size the settings ask for on these sheets.
/// Explicit: settings.voxelSize; TargetElementSize: settings.targetElementSize, or the mean edge
/// length of the sheets when that is 0; MinEdgeLength: minEdgeFactor x the shortest edge (edges
/// shorter than 1e-9 of the sheets' bounding box diagonal are ignored as degenerate).
/// Throws SettingError for a zero, negative, NaN or infinite size or factor, or when the rule
/// needs edges and the sheets have none.
double chooseVoxelSize(const std::vector<Sheet>& sheets, const VolumeSettings& settings);

/// What a volume of these sheets at this voxel size will need, estimated before allocating.
struct VolumeEstimate {
  double surfaceArea = 0.0;        ///< total area of the sheets (model units squared)
  double activeVoxels = 0.0;       ///< area / voxel^2 x (2 band + 1)
  double peakBytes = 0.0;          ///< activeVoxels x bytes per voxel while building
  std::uint64_t memoryLimit = 0;   ///< the limit the estimate is checked against
  double smallestVoxelSize = 0.0;  ///< the smallest voxel size that fits the limit
};

/// Estimates the active voxels and the peak memory of buildVolume for these sheets.
/// Preconditions: voxelSize finite and > 0; settings valid (see checkVolumeSettings).
VolumeEstimate estimateVolume(const std::vector<Sheet>& sheets, double voxelSize,
                              const VolumeSettings& settings);

/// Checks the settings that do not depend on the sheets (band, angle, tolerance, factors).
/// Throws SettingError naming the setting, its value and the allowed range.
void checkVolumeSettings(const VolumeSettings& settings);

/// Writes the sheets of one part into a volume: the signed distance grid, the invalid and
/// feature masks, and the sheets' feature lines, feature points, boundary loops and junction
/// curves. Sheets that meet along junction curves (a T-junction) have no consistent sign where
/// they meet: give each of them a volume of its own (buildSheetVolumes; remeshDeck does).
/// Several sheets are united: per voxel the closest sheet wins (exact ties: the lower sheet
/// index, then the lower face index). The result does not depend on the number of threads.
/// Parameters: sheets - manifold, consistently oriented sheets of ONE part; settings - see
/// VolumeSettings; source - provenance for the metadata.
/// Throws SettingError for invalid settings or when the estimated memory exceeds the limit
/// (the message gives the voxel count and the smallest voxel size that fits);
/// std::invalid_argument when sheets are of different parts, a face refers to a missing point,
/// or a coordinate is not finite.
Volume buildVolume(const std::vector<Sheet>& sheets, const VolumeSettings& settings,
                   const VolumeSource& source = {});

/// Writes each sheet of one part into a volume of its own (buildVolume({sheet}, ...) per sheet, in
/// order), all at ONE voxel size: chooseVoxelSize over all the sheets. The volumes of sheets that
/// meet along junction curves then put the same nodes on those curves (extract.h, "Junctions"),
/// and joinAtJunctions (quad_mesh.h) joins their meshes again.
/// Parameters: sheets - the sheets of ONE part as buildSheets returns them (at least one);
/// settings, source - as buildVolume.
/// Throws std::invalid_argument when `sheets` is empty; otherwise as chooseVoxelSize and
/// buildVolume (the estimated memory is checked per sheet).
std::vector<Volume> buildSheetVolumes(const std::vector<Sheet>& sheets,
                                      const VolumeSettings& settings,
                                      const VolumeSource& source = {});

/// The volume of sheet `sheet` among the sheet volumes of a part (the chain's and the CLI's
/// sheet= / --sheet choice). @param what names the option in the message ("sheet=").
/// Throws SettingError naming the option and the valid range when `sheet` is not in
/// 0..volumes.size()-1.
const Volume& sheetVolume(const std::vector<Volume>& volumes, long long sheet,
                          const std::string& what);

/// Writes the volume to a .vdb file with grids "sdf", "invalid" and "feature" and voxremesh
/// metadata (voxel size, band, thresholds, source file, part ID, tool version, curves). The masks
/// are stored as bool grids (marked voxels active, value true) because pyopenvdb and other
/// readers do not know MaskGrid; readVolume accepts bool or mask grids. The file appears complete
/// or not at all. Throws std::invalid_argument for an empty volume and
/// std::runtime_error naming the path when it cannot be written.
void writeVolume(const Volume& volume, const std::filesystem::path& path);

/// Reads a volume written by writeVolume (or a writeVolumes file of one sheet). Throws InputError
/// naming the file when it cannot be read as a .vdb file, lacks one of the grids sdf (float),
/// invalid and feature (mask), the grids do not share one uniform transform, or the file holds
/// the volumes of several sheets (the message says to read it with readVolumes).
Volume readVolume(const std::filesystem::path& path);

/// Writes the volumes of all sheets of one part (buildSheetVolumes) to one .vdb file.
/// Layout: sheet 0 exactly as writeVolume writes a volume (grids "sdf", "invalid", "feature",
/// the file metadata keys of volume_io.cpp), so that a file of one sheet is a writeVolume file;
/// sheet k > 0 has the grids "sdf.sheetK", "invalid.sheetK", "feature.sheetK" and its file
/// metadata under the same keys with the suffix ".sheetK" (e.g.
/// "voxremesh_junction_curves.sheet2"). Every grid carries the int64 metadata "voxremesh_sheet"
/// = k, and the file the int64 "voxremesh_sheet_count" (a file without it holds one sheet).
/// The file appears complete or not at all.
/// Throws std::invalid_argument when `volumes` is empty or holds an empty volume;
/// std::runtime_error naming the path when it cannot be written.
void writeVolumes(const std::vector<Volume>& volumes, const std::filesystem::path& path);

/// Reads every sheet volume of a file written by writeVolumes or writeVolume (older files: one
/// volume), in sheet order. Throws InputError naming the file as readVolume, naming the sheet
/// whose grids or metadata are missing or malformed.
std::vector<Volume> readVolumes(const std::filesystem::path& path);

/// One grid in a VolumeReport.
struct GridReport {
  std::string name;
  std::string gridClass;  ///< "level set", "unknown", ...
  std::string valueType;  ///< "float", "mask", ...
  std::uint64_t activeVoxels = 0;
  std::uint64_t leafNodes = 0;
  std::uint64_t memoryBytes = 0;
  bool emptyBounds = true;  ///< no active voxels: the bounding boxes below are meaningless
  std::array<std::int32_t, 3> indexMin{}, indexMax{};
  std::array<double, 3> worldMin{}, worldMax{};
  bool hasValueRange = false;             ///< false for masks
  double minValue = 0.0, maxValue = 0.0;  ///< over active voxels
};

/// What `voxremesh inspect` shows about a volume.
struct VolumeReport {
  VolumeInfo info;
  std::vector<GridReport> grids;  ///< sdf, invalid, feature
  std::uint64_t invalidVoxels = 0;
  std::uint64_t featureVoxels = 0;
  std::size_t featureLines = 0;
  std::size_t featurePoints = 0;
  std::size_t boundaryLoops = 0;
  std::size_t junctionCurves = 0;
};

/// Inspects the grids of a volume. Throws std::invalid_argument for an empty volume.
VolumeReport inspectVolume(const Volume& volume);

/// inspectVolume of each volume, in order. Throws std::invalid_argument for an empty volume.
std::vector<VolumeReport> inspectVolumes(const std::vector<Volume>& volumes);

/// Renders a report as an aligned text table.
std::string formatVolumeReport(const VolumeReport& report);

/// Renders a report as one JSON object.
std::string volumeReportJson(const VolumeReport& report);

/// Renders the reports of a part's sheet volumes: for one sheet formatVolumeReport; for several,
/// each table under a "sheet K of N" heading. Precondition: reports not empty.
std::string formatVolumeReports(const std::vector<VolumeReport>& reports);

/// Renders the reports of a part's sheet volumes as JSON: for one sheet volumeReportJson; for
/// several, {"sheet_count": N, "sheets": [one volumeReportJson object per sheet]}.
/// Precondition: reports not empty.
std::string volumeReportsJson(const std::vector<VolumeReport>& reports);

}  // namespace voxremesh
