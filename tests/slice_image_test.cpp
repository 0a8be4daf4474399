// Slice images of a volume (include/voxremesh/slice_image.h): geometry and colours against the
// grids, range and size errors, and the PNG encoding decoded back with zlib.
#include "voxremesh/slice_image.h"

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/png.h"
#include "support/test_support.h"
#include "volume/volume_grids.h"
#include "voxremesh/errors.h"
#include "voxremesh/sheets.h"

namespace fs = std::filesystem;
using voxremesh::Axis;
using voxremesh::Rgb;
using voxremesh::SliceImage;
using voxremesh::SliceStyle;
using voxremesh::Volume;

namespace {

// Off the voxel lattice, so that no sample is equally close to two elements.
constexpr double kX0 = 0.37, kY0 = 0.21, kZ0 = 0.13;

// An L-shaped part 7 of unit quads: a plate x in [0,10], y in [0,6] at z = 0 (normal +z) bent up
// at x = 10 into a wall up to z = 6, all moved by (kX0, kY0, kZ0). The 90 degree bend is a
// feature line; every other edge of the outline is a free boundary.
voxremesh::FeModel lPart() {
  voxremesh::FeModel model;
  model.parts.push_back({7, "L", false});
  auto node = [&](int i, int j, int k) -> voxremesh::Id {
    // Plate nodes (i, j, 0) for i <= 10, wall nodes (10, j, k) for k >= 1.
    return k == 0 ? 1 + j * 11 + i : 1000 + j * 10 + k;
  };
  for (int j = 0; j <= 6; ++j) {
    for (int i = 0; i <= 10; ++i) model.nodes.push_back({node(i, j, 0), {kX0 + i, kY0 + j, kZ0}});
    for (int k = 1; k <= 6; ++k)
      model.nodes.push_back({node(10, j, k), {kX0 + 10, kY0 + j, kZ0 + k}});
  }
  voxremesh::Id id = 1;
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 10; ++i)
      model.shells.push_back(
          {id++, 7, {node(i, j, 0), node(i + 1, j, 0), node(i + 1, j + 1, 0), node(i, j + 1, 0)}});
    for (int k = 0; k < 6; ++k)  // runs along the shared edge opposite to the plate
      model.shells.push_back(
          {id++,
           7,
           {node(10, j + 1, k), node(10, j, k), node(10, j, k + 1), node(10, j + 1, k + 1)}});
  }
  return model;
}

const Volume& lVolume() {
  static const Volume volume = [] {
    voxremesh::VolumeSettings settings;
    settings.rule = voxremesh::VoxelSizeRule::Explicit;
    settings.voxelSize = 1.0;
    return voxremesh::buildVolume(voxremesh::buildSheets(lPart(), 7), settings);
  }();
  return volume;
}

openvdb::Coord voxelOf(const SliceImage& image, int u, int v) {
  openvdb::Coord ijk;
  ijk[int(image.axis)] = image.sliceIndex;
  ijk[int(image.uAxis)] = u;
  ijk[int(image.vAxis)] = v;
  return ijk;
}

/// The centre pixel of the block of the voxel at index (i, j, k); the slice must contain it.
Rgb centreOf(const SliceImage& image, const openvdb::Coord& ijk) {
  EXPECT_EQ(ijk[int(image.axis)], image.sliceIndex);
  const auto origin = image.blockOrigin(ijk[int(image.uAxis)], ijk[int(image.vAxis)]);
  return image.pixel(origin[0] + image.pixelsPerVoxel / 2, origin[1] + image.pixelsPerVoxel / 2);
}

std::string text(const Rgb& c) {
  return "(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")";
}

// What each voxel block and each cell corner of a slice shows, counted while checking it
// against the grids.
struct Seen {
  int invalid = 0, negative = 0, positive = 0, inactive = 0, features = 0, plainCorners = 0;
};

Seen checkAgainstGrids(const SliceImage& image, const SliceStyle& style) {
  const Volume::Impl& v = lVolume().impl();
  const openvdb::CoordBBox box = v.sdf->evalActiveVoxelBoundingBox();
  const int ua = int(image.uAxis), va = int(image.vAxis);
  EXPECT_EQ(image.uMin, box.min()[ua]);
  EXPECT_EQ(image.uMax, box.max()[ua]);
  EXPECT_EQ(image.vMin, box.min()[va]);
  EXPECT_EQ(image.vMax, box.max()[va]);
  const int s = image.pixelsPerVoxel;
  EXPECT_EQ(image.width, (image.uMax - image.uMin + 1) * s);
  EXPECT_EQ(image.height, (image.vMax - image.vMin + 1) * s);
  EXPECT_EQ(image.pixels.size(), std::size_t(image.width) * std::size_t(image.height) * 3);

  Seen seen;
  const double band = double(v.sdf->background());
  for (int vi = image.vMin; vi <= image.vMax; ++vi) {
    for (int ui = image.uMin; ui <= image.uMax; ++ui) {
      const openvdb::Coord ijk = voxelOf(image, ui, vi);
      float value = 0.0f;
      const bool active = v.sdf->tree().probeValue(ijk, value);
      Rgb expected = style.inactive;
      if (v.invalid->tree().isValueOn(ijk)) {
        expected = style.invalid, ++seen.invalid;
      } else if (active) {
        expected = voxremesh::distanceColour(value, band, style);
        ++(value < 0.0f ? seen.negative : seen.positive);
      } else {
        ++seen.inactive;
      }
      EXPECT_EQ(centreOf(image, ijk), expected) << "voxel " << ijk;
    }
  }
  // Cell (u, v) of layer sliceIndex or sliceIndex - 1: marker at the corner its blocks share.
  for (int vi = image.vMin - 1; vi <= image.vMax; ++vi) {
    for (int ui = image.uMin - 1; ui <= image.uMax; ++ui) {
      openvdb::Coord cell = voxelOf(image, ui, vi);
      bool feature = v.feature->tree().isValueOn(cell);
      cell[int(image.axis)] -= 1;
      feature = feature || v.feature->tree().isValueOn(cell);
      const int x = (ui - image.uMin + 1) * s, y = (image.vMax - vi) * s;
      if (x >= image.width || y >= image.height) {
        EXPECT_FALSE(feature) << "a feature cell beyond the image at " << cell;
        continue;
      }
      const Rgb corner = image.pixel(x, y);
      if (feature) {
        ++seen.features;
        EXPECT_EQ(corner, style.feature) << "feature cell " << cell;
      } else {
        ++seen.plainCorners;
        EXPECT_NE(corner, style.feature) << "cell " << cell;
      }
    }
  }
  return seen;
}

}  // namespace

TEST(SliceImage, AxisNames) {
  EXPECT_EQ(voxremesh::axisFromName("x"), Axis::X);
  EXPECT_EQ(voxremesh::axisFromName("Y"), Axis::Y);
  EXPECT_EQ(voxremesh::axisFromName("z"), Axis::Z);
  EXPECT_STREQ(voxremesh::axisName(Axis::Y), "y");
  EXPECT_THROW(voxremesh::axisFromName("w"), voxremesh::SettingError);
  EXPECT_THROW(voxremesh::axisFromName(""), voxremesh::SettingError);
}

TEST(SliceImage, DivergingColourMap) {
  const SliceStyle style;
  EXPECT_EQ(voxremesh::distanceColour(0.0, 3.0, style), style.zero);
  EXPECT_EQ(voxremesh::distanceColour(-3.0, 3.0, style), style.negative);
  EXPECT_EQ(voxremesh::distanceColour(-7.0, 3.0, style), style.negative);
  EXPECT_EQ(voxremesh::distanceColour(3.0, 3.0, style), style.positive);
  EXPECT_EQ(voxremesh::distanceColour(1e9, 3.0, style), style.positive);
  // Half way: the mean of white and the end colour, rounded.
  const Rgb halfPositive = voxremesh::distanceColour(1.5, 3.0, style);
  EXPECT_EQ(halfPositive, (Rgb{217, 140, 149})) << text(halfPositive);
  const Rgb halfNegative = voxremesh::distanceColour(-1.5, 3.0, style);
  EXPECT_EQ(halfNegative, (Rgb{144, 179, 214})) << text(halfNegative);
  // The distinct colours of the legend are distinct indeed.
  const std::vector<Rgb> legend{style.negative, style.zero,    style.positive,
                                style.inactive, style.invalid, style.feature};
  for (std::size_t a = 0; a < legend.size(); ++a)
    for (std::size_t b = a + 1; b < legend.size(); ++b) EXPECT_NE(legend[a], legend[b]);
}

TEST(SliceImage, YSliceShowsTheSectionAsTheGridsHoldIt) {
  SliceStyle style;
  style.pixelsPerVoxel = 8;
  const SliceImage image = voxremesh::renderSlice(lVolume(), Axis::Y, 3.2, style);
  EXPECT_EQ(image.sliceIndex, 3);
  EXPECT_DOUBLE_EQ(image.sliceWorld, 3.0);
  EXPECT_EQ(image.uAxis, Axis::X);
  EXPECT_EQ(image.vAxis, Axis::Z);
  const Seen seen = checkAgainstGrids(image, style);
  // The section has everything: both sides of the sheet, the band's edge, the invalid voxels
  // beyond the free edges and the bend's feature line piercing the plane.
  EXPECT_GT(seen.invalid, 0);
  EXPECT_GT(seen.negative, 0);
  EXPECT_GT(seen.positive, 0);
  EXPECT_GT(seen.inactive, 0);
  EXPECT_GT(seen.features, 0);
  EXPECT_GT(seen.plainCorners, 0);

  // Voxels whose colour follows from the geometry alone (plate at z = 0.13, normal +z, free edge
  // at x = 0.37, band 3 voxels).
  EXPECT_EQ(centreOf(image, {-2, 3, 0}), style.invalid);  // beyond the free edge, in its plane
  EXPECT_EQ(centreOf(image, {5, 3, 2}), voxremesh::distanceColour(1.87, 3.0, style));
  EXPECT_EQ(centreOf(image, {5, 3, -1}), voxremesh::distanceColour(-1.13, 3.0, style));
  EXPECT_EQ(centreOf(image, {5, 3, 5}), style.inactive);  // 4.87 above the plate
  // The bend (10.37, 0.13) pierces cell x 10..11, z 0..1: its marker is at the shared corner of
  // the blocks of voxels x = 10, 11 and z = 0, 1.
  const auto corner = image.blockOrigin(11, 0);
  EXPECT_EQ(image.pixel(corner[0], corner[1]), style.feature);
  // Top left block is voxel (uMin, vMax): the highest z is the top row.
  EXPECT_EQ(image.blockOrigin(image.uMin, image.vMax), (std::array<int, 2>{0, 0}));
  EXPECT_EQ(image.blockOrigin(image.uMax, image.vMin),
            (std::array<int, 2>{image.width - 8, image.height - 8}));
}

TEST(SliceImage, XAndZSlicesMatchTheGrids) {
  SliceStyle style;
  style.pixelsPerVoxel = 3;
  const SliceImage x = voxremesh::renderSlice(lVolume(), Axis::X, 10.1, style);
  EXPECT_EQ(x.uAxis, Axis::Y);
  EXPECT_EQ(x.vAxis, Axis::Z);
  EXPECT_EQ(x.sliceIndex, 10);
  const Seen inWall = checkAgainstGrids(x, style);
  EXPECT_GT(inWall.invalid, 0);   // above the wall's free top edge
  EXPECT_GT(inWall.features, 0);  // the bend runs along y through this layer

  style.pixelsPerVoxel = 2;  // markers of one pixel, beside the blocks' centre pixels
  const SliceImage z = voxremesh::renderSlice(lVolume(), Axis::Z, -0.4, style);
  EXPECT_EQ(z.uAxis, Axis::X);
  EXPECT_EQ(z.vAxis, Axis::Y);
  EXPECT_EQ(z.sliceIndex, 0);
  const Seen underPlate = checkAgainstGrids(z, style);
  EXPECT_GT(underPlate.invalid, 0);
  EXPECT_GT(underPlate.negative, 0);

  // The bend at z = 0.13 lies in the cells of layer z = 0, whose top faces are in the plane
  // z = 1; likewise at x = 10.37 in the cells of layer x = 10, which meet the plane x = 11.
  const SliceImage above = voxremesh::renderSlice(lVolume(), Axis::Z, 1.0, style);
  EXPECT_EQ(above.sliceIndex, 1);
  EXPECT_GT(checkAgainstGrids(above, style).features, 0);
  const SliceImage beside = voxremesh::renderSlice(lVolume(), Axis::X, 11.0, style);
  EXPECT_EQ(beside.sliceIndex, 11);
  EXPECT_GT(checkAgainstGrids(beside, style).features, 0);
  // Two layers away neither touches the bend's cells.
  EXPECT_EQ(
      checkAgainstGrids(voxremesh::renderSlice(lVolume(), Axis::X, 12.0, style), style).features,
      0);
}

TEST(SliceImage, AutomaticScaleKeepsTheImageReadable) {
  const SliceImage image = voxremesh::renderSlice(lVolume(), Axis::Y, 3.0);
  // 16 x 12 voxels: 1200 / 16 is above the largest automatic scale.
  EXPECT_EQ(image.pixelsPerVoxel, 16);
  checkAgainstGrids(image, SliceStyle{});
}

TEST(SliceImage, CoordinatesOutsideTheVolumeNameTheRange) {
  const std::array<double, 2> range = voxremesh::sliceRange(lVolume(), Axis::Z);
  const openvdb::CoordBBox box = lVolume().impl().sdf->evalActiveVoxelBoundingBox();
  EXPECT_EQ(range[0], box.min()[2] * 1.0);
  EXPECT_EQ(range[1], box.max()[2] * 1.0);
  // Half a voxel of slack on either side picks the outermost layer.
  EXPECT_EQ(voxremesh::renderSlice(lVolume(), Axis::Z, range[1] + 0.4).sliceIndex, box.max()[2]);
  try {
    voxremesh::renderSlice(lVolume(), Axis::Z, range[1] + 0.6);
    FAIL() << "no error";
  } catch (const voxremesh::SettingError& e) {
    const std::string message = e.what();
    const std::string expected =
        std::to_string(box.min()[2]) + " .. " + std::to_string(box.max()[2]);
    EXPECT_NE(message.find("z = "), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
  EXPECT_THROW(voxremesh::renderSlice(lVolume(), Axis::X, -100.0), voxremesh::SettingError);
  EXPECT_THROW(voxremesh::renderSlice(lVolume(), Axis::X, std::nan("")), voxremesh::SettingError);
  EXPECT_THROW(voxremesh::renderSlice(Volume(), Axis::X, 0.0), std::invalid_argument);
  EXPECT_THROW(voxremesh::sliceRange(Volume(), Axis::X), std::invalid_argument);
}

TEST(SliceImage, ImagesBeyondTheLimitAreRefused) {
  SliceStyle style;
  style.pixelsPerVoxel = 65;
  EXPECT_THROW(voxremesh::renderSlice(lVolume(), Axis::Y, 3.0, style), voxremesh::SettingError);
  style.pixelsPerVoxel = -1;
  EXPECT_THROW(voxremesh::renderSlice(lVolume(), Axis::Y, 3.0, style), voxremesh::SettingError);
  // The image box holds 16 x 12 voxels (x -2..13, z -2..9); a limit just below 9 x 9 pixels per
  // voxel.
  const openvdb::CoordBBox box = lVolume().impl().sdf->evalActiveVoxelBoundingBox();
  const std::uint64_t voxels = std::uint64_t(box.dim()[0]) * std::uint64_t(box.dim()[2]);
  EXPECT_EQ(voxels, 16u * 12u);
  style.pixelsPerVoxel = 10;
  style.maxPixels = voxels * 81 - 1;
  try {
    voxremesh::renderSlice(lVolume(), Axis::Y, 3.0, style);
    FAIL() << "no error";
  } catch (const voxremesh::SettingError& e) {
    EXPECT_NE(std::string(e.what()).find("use at most 8 pixels per voxel"), std::string::npos)
        << e.what();
  }
  style.pixelsPerVoxel = 8;
  EXPECT_NO_THROW(voxremesh::renderSlice(lVolume(), Axis::Y, 3.0, style));
}

TEST(SliceImage, PngDecodesToTheSamePixels) {
  SliceStyle style;
  style.pixelsPerVoxel = 5;
  const SliceImage image = voxremesh::renderSlice(lVolume(), Axis::Y, 3.0, style);
  const std::string bytes = voxremesh::encodePng(image);
  const voxremesh::test::DecodedPng png = voxremesh::test::decodePng(bytes);
  EXPECT_EQ(png.width, std::uint32_t(image.width));
  EXPECT_EQ(png.height, std::uint32_t(image.height));
  EXPECT_EQ(png.rgb, image.pixels);
  ASSERT_GE(png.chunkTypes.size(), 5u);
  EXPECT_EQ(png.chunkTypes.front(), "IHDR");
  EXPECT_EQ(png.chunkTypes.back(), "IEND");
  EXPECT_EQ(png.text.at("Software"), std::string("voxremesh ") + VOXREMESH_VERSION);
  EXPECT_NE(png.text.at("Comment").find("slice y = 3 (voxel index 3)"), std::string::npos)
      << png.text.at("Comment");

  // The decoder the tests rely on notices a damaged file.
  std::string damaged = bytes;
  damaged[bytes.size() / 2] = char(damaged[bytes.size() / 2] ^ 0x40);
  EXPECT_THROW(voxremesh::test::decodePng(damaged), std::runtime_error);
  EXPECT_THROW(voxremesh::test::decodePng(bytes.substr(0, bytes.size() - 4)), std::runtime_error);
}

TEST(SliceImage, LargeImagesSpanSeveralDataChunks) {
  // 700 x 600 pixels of noise: about 1.26 MB that zlib cannot shrink, more than one IDAT chunk.
  SliceImage noise;
  noise.width = 700;
  noise.height = 600;
  noise.pixels.resize(std::size_t(noise.width) * noise.height * 3);
  std::uint32_t state = 12345;
  for (std::uint8_t& byte : noise.pixels) {
    state = state * 1664525u + 1013904223u;
    byte = std::uint8_t(state >> 24);
  }
  const voxremesh::test::DecodedPng png = voxremesh::test::decodePng(voxremesh::encodePng(noise));
  EXPECT_EQ(png.rgb, noise.pixels);
  int idat = 0;
  for (const std::string& type : png.chunkTypes) idat += type == "IDAT" ? 1 : 0;
  EXPECT_GE(idat, 2);

  SliceImage wrong = noise;
  wrong.pixels.pop_back();
  EXPECT_THROW(voxremesh::encodePng(wrong), std::invalid_argument);
  EXPECT_THROW(voxremesh::encodePng(SliceImage{}), std::invalid_argument);
}

TEST(SliceImage, WritePngIsAllOrNothing) {
  const fs::path dir = voxremesh::test::scratchDir("slice-png");
  const SliceImage image = voxremesh::renderSlice(lVolume(), Axis::Y, 3.0);
  voxremesh::writePng(image, dir / "slice.png");
  EXPECT_EQ(voxremesh::test::decodePng(voxremesh::test::readText(dir / "slice.png")).rgb,
            image.pixels);

  // A failed write leaves an existing file as it was and nothing beside it.
  voxremesh::test::writeText(dir / "kept.png", "old");
  SliceImage wrong = image;
  wrong.pixels.pop_back();
  EXPECT_THROW(voxremesh::writePng(wrong, dir / "kept.png"), std::invalid_argument);
  EXPECT_EQ(voxremesh::test::readText(dir / "kept.png"), "old");
  EXPECT_THROW(voxremesh::writePng(image, dir / "missing" / "slice.png"), std::runtime_error);
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"kept.png", "slice.png"}));
}
