// Rendering one axis-aligned slice of a Volume into an RGB image (include/voxremesh/slice_image.h).
#include "voxremesh/slice_image.h"

#include <openvdb/openvdb.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "volume/volume_grids.h"
#include "voxremesh/errors.h"

namespace voxremesh {

namespace {

/// Largest automatic scale, and the longer image side it aims to stay within.
constexpr int kAutoScaleMax = 16;
constexpr int kAutoScaleMin = 2;
constexpr int kAutoLongSide = 1200;
constexpr int kMaxScale = 64;

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

/// The index-space bounding box of the active voxels of the three grids.
openvdb::CoordBBox activeBounds(const Volume& volume) {
  if (volume.empty()) throw std::invalid_argument("cannot slice an empty volume");
  const Volume::Impl& v = volume.impl();
  openvdb::CoordBBox box = v.sdf->evalActiveVoxelBoundingBox();
  for (const openvdb::MaskGrid::Ptr& mask : {v.invalid, v.feature}) {
    const openvdb::CoordBBox maskBox = mask->evalActiveVoxelBoundingBox();
    if (!maskBox.empty()) box.expand(maskBox);
  }
  if (box.empty()) throw std::invalid_argument("the volume has no active voxels to slice");
  return box;
}

std::uint8_t mix(std::uint8_t from, std::uint8_t to, double t) {
  return static_cast<std::uint8_t>(std::lround(double(from) + (double(to) - double(from)) * t));
}

void fillBlock(SliceImage& image, int x0, int y0, int width, int height, const Rgb& colour) {
  const int x1 = std::min(image.width, x0 + width), y1 = std::min(image.height, y0 + height);
  for (int y = std::max(0, y0); y < y1; ++y) {
    std::uint8_t* row = image.pixels.data() + (std::size_t(y) * std::size_t(image.width)) * 3;
    for (int x = std::max(0, x0); x < x1; ++x) {
      row[3 * x] = colour.r;
      row[3 * x + 1] = colour.g;
      row[3 * x + 2] = colour.b;
    }
  }
}

/// The coordinate of voxel (u, v) in the slice plane `index` along `axis`.
openvdb::Coord voxelAt(const SliceImage& image, int u, int v) {
  openvdb::Coord ijk;
  ijk[int(image.axis)] = image.sliceIndex;
  ijk[int(image.uAxis)] = u;
  ijk[int(image.vAxis)] = v;
  return ijk;
}

}  // namespace

const char* axisName(Axis axis) {
  switch (axis) {
    case Axis::X:
      return "x";
    case Axis::Y:
      return "y";
    case Axis::Z:
      return "z";
  }
  return "?";
}

Axis axisFromName(const std::string& name) {
  if (name == "x" || name == "X") return Axis::X;
  if (name == "y" || name == "Y") return Axis::Y;
  if (name == "z" || name == "Z") return Axis::Z;
  throw SettingError("axis must be x, y or z, not '" + name + "'");
}

Rgb SliceImage::pixel(int x, int y) const {
  const std::size_t at = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
  return {pixels[at], pixels[at + 1], pixels[at + 2]};
}

std::array<int, 2> SliceImage::blockOrigin(int u, int v) const {
  return {(u - uMin) * pixelsPerVoxel, (vMax - v) * pixelsPerVoxel};
}

std::array<double, 2> sliceRange(const Volume& volume, Axis axis) {
  const openvdb::CoordBBox box = activeBounds(volume);
  const double h = volume.info().voxelSize;
  return {box.min()[int(axis)] * h, box.max()[int(axis)] * h};
}

Rgb distanceColour(double distance, double saturation, const SliceStyle& style) {
  const double t = std::isnan(distance) ? 0.0 : std::min(1.0, std::abs(distance) / saturation);
  const Rgb& end = distance < 0.0 ? style.negative : style.positive;
  return {mix(style.zero.r, end.r, t), mix(style.zero.g, end.g, t), mix(style.zero.b, end.b, t)};
}

SliceImage renderSlice(const Volume& volume, Axis axis, double at, const SliceStyle& style) {
  const openvdb::CoordBBox box = activeBounds(volume);
  const Volume::Impl& v = volume.impl();
  const double h = volume.info().voxelSize;

  SliceImage image;
  image.axis = axis;
  image.voxelSize = h;
  image.uAxis = axis == Axis::X ? Axis::Y : Axis::X;
  image.vAxis = axis == Axis::Z ? Axis::Y : Axis::Z;
  const int a = int(axis), ua = int(image.uAxis), va = int(image.vAxis);
  const int first = box.min()[a], last = box.max()[a];
  // Half a voxel of slack on either side: the layer nearest to `at` is drawn.
  if (!std::isfinite(at) || at < (first - 0.5) * h || at > (last + 0.5) * h) {
    throw SettingError(std::string(axisName(axis)) + " = " + number(at) +
                       " is outside the volume: the slice coordinate must lie within " +
                       number(first * h) + " .. " + number(last * h) + " (voxel size " + number(h) +
                       ")");
  }
  image.sliceIndex = std::clamp(int(std::lround(at / h)), first, last);
  image.sliceWorld = image.sliceIndex * h;
  image.uMin = box.min()[ua];
  image.uMax = box.max()[ua];
  image.vMin = box.min()[va];
  image.vMax = box.max()[va];
  const std::uint64_t columns = std::uint64_t(image.uMax - image.uMin + 1);
  const std::uint64_t rows = std::uint64_t(image.vMax - image.vMin + 1);

  if (style.pixelsPerVoxel < 0 || style.pixelsPerVoxel > kMaxScale) {
    throw SettingError("pixels per voxel must be between 1 and " + std::to_string(kMaxScale) +
                       " (got " + std::to_string(style.pixelsPerVoxel) + ")");
  }
  int scale = style.pixelsPerVoxel;
  if (scale == 0) {
    const std::uint64_t longSide = std::max(columns, rows);
    scale = int(std::clamp<std::uint64_t>(kAutoLongSide / longSide, kAutoScaleMin, kAutoScaleMax));
  }
  const std::uint64_t pixelCount = columns * rows * std::uint64_t(scale) * std::uint64_t(scale);
  if (pixelCount > style.maxPixels) {
    const double fits = std::floor(std::sqrt(double(style.maxPixels) / double(columns * rows)));
    throw SettingError("a slice of " + std::to_string(columns) + " x " + std::to_string(rows) +
                       " voxels at " + std::to_string(scale) + " pixels per voxel has " +
                       number(double(pixelCount)) + " pixels, more than the limit of " +
                       number(double(style.maxPixels)) +
                       (fits >= 1.0 ? ": use at most " + number(fits) + " pixels per voxel"
                                    : ": use a coarser voxel size"));
  }
  constexpr std::uint64_t kMaxSide = 0x7fffffff;  // PNG and int limit of a side in pixels
  if (columns * std::uint64_t(scale) > kMaxSide || rows * std::uint64_t(scale) > kMaxSide) {
    throw SettingError("a slice of " + std::to_string(columns) + " x " + std::to_string(rows) +
                       " voxels at " + std::to_string(scale) +
                       " pixels per voxel is wider than 2^31 - 1 pixels");
  }
  image.pixelsPerVoxel = scale;
  image.width = int(columns) * scale;
  image.height = int(rows) * scale;
  image.pixels.assign(std::size_t(pixelCount) * 3, 0);

  // Voxel blocks, in parallel over rows of voxels (each row writes its own pixel rows).
  const double saturation = double(v.sdf->background());
  tbb::parallel_for(tbb::blocked_range<int>(image.vMin, image.vMax + 1),
                    [&](const tbb::blocked_range<int>& range) {
                      auto sdf = v.sdf->getConstAccessor();
                      auto invalid = v.invalid->getConstAccessor();
                      for (int vi = range.begin(); vi < range.end(); ++vi) {
                        for (int ui = image.uMin; ui <= image.uMax; ++ui) {
                          const openvdb::Coord ijk = voxelAt(image, ui, vi);
                          float value = 0.0f;
                          Rgb colour = style.inactive;
                          if (invalid.isValueOn(ijk)) {
                            colour = style.invalid;
                          } else if (sdf.probeValue(ijk, value)) {
                            colour = distanceColour(value, saturation, style);
                          }
                          const std::array<int, 2> origin = image.blockOrigin(ui, vi);
                          fillBlock(image, origin[0], origin[1], scale, scale, colour);
                        }
                      }
                    });

  // Feature cells meeting the plane: the layers sliceIndex - 1 and sliceIndex along the axis.
  // Cell (u, v) spans voxels u..u+1, v..v+1; its centre is the corner its four blocks share.
  const int marker = std::max(1, scale / 2);
  auto feature = v.feature->getConstAccessor();
  for (int vi = image.vMin - 1; vi <= image.vMax; ++vi) {
    for (int ui = image.uMin - 1; ui <= image.uMax; ++ui) {
      openvdb::Coord cell = voxelAt(image, ui, vi);
      bool marked = feature.isValueOn(cell);
      cell[a] -= 1;
      marked = marked || feature.isValueOn(cell);
      if (!marked) continue;
      const int cx = (ui - image.uMin + 1) * scale, cy = (image.vMax - vi) * scale;
      fillBlock(image, cx - marker / 2, cy - marker / 2, marker, marker, style.feature);
    }
  }
  return image;
}

}  // namespace voxremesh
