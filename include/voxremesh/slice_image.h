// Pictures of a volume: one axis-aligned slice of the grids rendered into an RGB image, and a
// small PNG writer, so that an engineer can look at the narrow band, the invalid voxels and the
// feature cells of a part without a VDB viewer (`voxremesh slice`).
//
// Image geometry
// - The slice is the plane of voxels whose index along `axis` is round(at / voxelSize); the image
//   covers the index-space bounding box of the active voxels of all three grids in the other two
//   axes (u, v): X slices show u = y to the right and v = z up, Y slices u = x and v = z, Z slices
//   u = x and v = y.
// - Each voxel is a square block of `pixelsPerVoxel` pixels centred on its sample; rows run from
//   the highest v (top row) down to the lowest.
// Colours (SliceStyle defaults)
// - Active voxels of the sdf grid: a diverging map of the signed distance, blue for negative,
//   white at zero, red for positive, saturated at the band width (the grid's background value).
// - Inactive voxels: grey.
// - Invalid voxels: their whole block in yellow, drawn over the distance.
// - Feature cells that meet the slice plane (those of the layers on both sides of it): a black
//   square marker of half a voxel (at least one pixel) centred on the cell centre, the corner
//   shared by the blocks of the cell's four voxels in the plane, drawn last (at one pixel per
//   voxel it covers the pixel of the cell's lower right voxel).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "voxremesh/volume.h"

namespace voxremesh {

/// A coordinate axis.
enum class Axis { X = 0, Y = 1, Z = 2 };

/// Returns "x", "y" or "z".
const char* axisName(Axis axis);

/// Parses "x", "y" or "z" (also upper case). Throws SettingError naming the text otherwise.
Axis axisFromName(const std::string& name);

/// An 8-bit RGB colour.
struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  /// Component-wise equality.
  friend bool operator==(const Rgb& lhs, const Rgb& rhs) {
    return lhs.r == rhs.r && lhs.g == rhs.g && lhs.b == rhs.b;
  }
  /// Component-wise inequality.
  friend bool operator!=(const Rgb& lhs, const Rgb& rhs) { return !(lhs == rhs); }
};

/// How a slice is drawn. Every field has a documented default.
struct SliceStyle {
  /// Edge length of a voxel's block in pixels, in [1, 64]; 0 (the default) picks the largest
  /// scale in [2, 16] for which the longer image side stays within 1200 pixels (2 when even
  /// that is larger).
  int pixelsPerVoxel = 0;
  /// Refuse images with more pixels than this (a 100-megapixel image is 300 MB of RGB).
  std::uint64_t maxPixels = 100'000'000;
  Rgb negative{33, 102, 172};   ///< distance -band and below (ColorBrewer RdBu end)
  Rgb zero{255, 255, 255};      ///< distance 0
  Rgb positive{178, 24, 43};    ///< distance +band and above (ColorBrewer RdBu end)
  Rgb inactive{128, 128, 128};  ///< voxels outside the narrow band
  Rgb invalid{255, 210, 0};     ///< invalid voxels (whole block)
  Rgb feature{0, 0, 0};         ///< feature cell markers
};

/// A rendered slice: RGB pixels plus where they came from.
struct SliceImage {
  int width = 0, height = 0;         ///< in pixels
  std::vector<std::uint8_t> pixels;  ///< width x height x 3 bytes, rows top to bottom
  Axis axis = Axis::Z;               ///< the axis the slice is normal to
  int sliceIndex = 0;                ///< index of the slice plane along `axis`
  double sliceWorld = 0.0;           ///< world coordinate of the slice plane (sliceIndex x voxel)
  double voxelSize = 0.0;
  int pixelsPerVoxel = 1;
  /// The in-plane axes: u to the right, v up (see the header comment).
  Axis uAxis = Axis::X, vAxis = Axis::Y;
  /// Index range of the image along u and v (inclusive): voxel (uMin, vMax) is the top left block.
  int uMin = 0, uMax = -1, vMin = 0, vMax = -1;

  /// The colour of pixel (x, y), x to the right, y down from the top row.
  /// Precondition: 0 <= x < width, 0 <= y < height.
  Rgb pixel(int x, int y) const;

  /// The top left pixel (x, y) of the block of in-plane voxel (u, v).
  /// Precondition: uMin <= u <= uMax, vMin <= v <= vMax.
  std::array<int, 2> blockOrigin(int u, int v) const;
};

/// The world-coordinate range [first, second] along `axis` in which renderSlice accepts `at`: the
/// index-space bounding box of the active voxels of the three grids, times the voxel size.
/// Throws std::invalid_argument for an empty volume or one without any active voxel.
std::array<double, 2> sliceRange(const Volume& volume, Axis axis);

/// Colour of a signed distance in the diverging map of `style`: linear from `zero` at 0 to
/// `negative` at -saturation and `positive` at +saturation, constant beyond; NaN gives `zero`.
/// Precondition: saturation > 0.
Rgb distanceColour(double distance, double saturation, const SliceStyle& style);

/// Renders the slice of `volume` normal to `axis` through world coordinate `at` (see the header
/// comment for geometry and colours).
/// @param volume  a built or read volume
/// @param axis    the axis the slice is normal to
/// @param at      world coordinate along axis, within sliceRange or up to half a voxel beyond
///                it; the nearest voxel layer is drawn
/// @param style   scale and colours
/// Throws std::invalid_argument for an empty volume or one without any active voxel;
/// SettingError when `at` is not finite or lies outside that range (the message names
/// sliceRange), when pixelsPerVoxel is outside [0, 64], or when the image would exceed
/// maxPixels or 2^31 - 1 pixels a side (the message names the size and a scale that fits).
SliceImage renderSlice(const Volume& volume, Axis axis, double at, const SliceStyle& style = {});

/// Encodes an image as a PNG file's bytes: 8-bit RGB, not interlaced, zlib-compressed rows with
/// the "Up" filter, and tEXt chunks "Software" (voxremesh and its version) and "Comment" (the
/// slice axis, coordinate, voxel size and the index range shown).
/// Throws std::invalid_argument when the image is empty or its pixel count does not match
/// width x height; std::runtime_error when zlib fails.
std::string encodePng(const SliceImage& image);

/// Writes encodePng(image) to `path`: to a temporary file beside it, renamed over it when
/// complete, so the file appears complete or not at all.
/// Throws as encodePng; std::runtime_error naming the path when it cannot be written (the
/// target is then left as it was).
void writePng(const SliceImage& image, const std::filesystem::path& path);

}  // namespace voxremesh
