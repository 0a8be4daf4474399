// The volumes of a part's sheets (volume.h buildSheetVolumes) in one .vdb file (writeVolumes,
// readVolumes): the wheel's three sheet volumes round trip, a one-sheet file keeps the layout of
// writeVolume, files of older versions still read, and readVolume refuses several sheets clearly.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "support/test_support.h"
#include "volume/volume_grids.h"
#include "voxremesh/errors.h"
#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"
#include "voxremesh/volume.h"

namespace voxremesh {
namespace {

namespace fs = std::filesystem;

/// The sheet volumes of a deck's part at the part's default target size.
std::vector<Volume> partSheetVolumes(const FeModel& deck, Id part, const std::string& source) {
  VolumeSettings settings;
  settings.targetElementSize = defaultTargetSize(deck, part);
  return buildSheetVolumes(buildSheets(deck, part), settings, VolumeSource{source});
}

/// The names of the grids in a .vdb file, sorted.
std::vector<std::string> gridNames(const fs::path& path) {
  openvdb::io::File file(path.string());
  file.open();
  std::vector<std::string> names;
  for (auto it = file.beginName(); it != file.endName(); ++it) names.push_back(*it);
  file.close();
  std::sort(names.begin(), names.end());
  return names;
}

void expectSameCurves(const std::vector<VolumeCurve>& a, const std::vector<VolumeCurve>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].closed, b[i].closed);
    EXPECT_EQ(a[i].points, b[i].points);  // bit-identical
  }
}

/// Same active voxel counts, and the same values at every 97th active voxel of `a`'s sdf.
void expectSameGrids(const Volume& a, const Volume& b) {
  const Volume::Impl &x = a.impl(), &y = b.impl();
  EXPECT_EQ(x.sdf->activeVoxelCount(), y.sdf->activeVoxelCount());
  EXPECT_EQ(x.invalid->activeVoxelCount(), y.invalid->activeVoxelCount());
  EXPECT_EQ(x.feature->activeVoxelCount(), y.feature->activeVoxelCount());
  EXPECT_EQ(x.sdf->background(), y.sdf->background());
  const auto values = y.sdf->getConstAccessor();
  std::size_t compared = 0, n = 0;
  for (auto it = x.sdf->cbeginValueOn(); it; ++it, ++n) {
    if (n % 97 != 0) continue;
    EXPECT_EQ(values.getValue(it.getCoord()), *it) << it.getCoord();
    EXPECT_TRUE(values.isValueOn(it.getCoord()));
    ++compared;
  }
  EXPECT_GT(compared, 10u);
}

TEST(SheetVolumes, WheelSheetsRoundTripThroughOneFile) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "wheel.k");
  const FeModel deck = readDeck(path);
  const std::vector<Volume> volumes = partSheetVolumes(deck, 1, "wheel.k");
  ASSERT_EQ(volumes.size(), 3u);  // rim front, rim back, disc
  for (const Volume& volume : volumes) {
    // One voxel size for all sheets, so that they put the same nodes on their junction.
    EXPECT_EQ(volume.info().voxelSize, volumes[0].info().voxelSize);
    EXPECT_EQ(volume.junctionCurves().size(), 1u);
  }
  const fs::path dir = test::scratchDir("sheet-volumes-wheel");
  const fs::path file = dir / "wheel.vdb";
  writeVolumes(volumes, file);
  // Complete or not at all: no temporary file left beside it.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  EXPECT_EQ(gridNames(file),
            (std::vector<std::string>{"feature", "feature.sheet1", "feature.sheet2", "invalid",
                                      "invalid.sheet1", "invalid.sheet2", "sdf", "sdf.sheet1",
                                      "sdf.sheet2"}));

  const std::vector<Volume> back = readVolumes(file);
  ASSERT_EQ(back.size(), volumes.size());
  for (std::size_t k = 0; k < volumes.size(); ++k) {
    SCOPED_TRACE("sheet " + std::to_string(k));
    expectSameGrids(volumes[k], back[k]);
    EXPECT_EQ(back[k].impl().sdf->getName(), "sdf");
    EXPECT_EQ(back[k].info().voxelSize, volumes[k].info().voxelSize);
    EXPECT_EQ(back[k].info().bandWidthVoxels, volumes[k].info().bandWidthVoxels);
    EXPECT_EQ(back[k].info().part, 1);
    EXPECT_EQ(back[k].info().sourceFile, "wheel.k");
    expectSameCurves(back[k].junctionCurves(), volumes[k].junctionCurves());
    expectSameCurves(back[k].boundaryLoops(), volumes[k].boundaryLoops());
    expectSameCurves(back[k].featureLines(), volumes[k].featureLines());
    EXPECT_EQ(back[k].featurePoints(), volumes[k].featurePoints());
  }
  // The junction curves of the three sheets are one curve: the sheets' meshes join.
  const QuadMesh joined = extractPartMesh(back);
  const QuadMesh fresh = extractPartMesh(volumes);
  EXPECT_EQ(joined.points, fresh.points);
  EXPECT_EQ(joined.faces, fresh.faces);

  try {
    readVolume(file);
    FAIL() << "readVolume read a file of three sheets";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file.string());
    EXPECT_TRUE(test::contains(e.what(), "3 sheets")) << e.what();
    EXPECT_TRUE(test::contains(e.what(), "readVolumes")) << e.what();
  }
}

TEST(SheetVolumes, OneSheetFileHasTheLayoutOfWriteVolume) {
  const FeModel deck = readDeck(test::samplePart());
  const std::vector<Volume> volumes = partSheetVolumes(deck, 100, "hat_rail.k");
  ASSERT_EQ(volumes.size(), 1u);
  const fs::path dir = test::scratchDir("sheet-volumes-rail");
  writeVolumes(volumes, dir / "many.vdb");
  writeVolume(volumes[0], dir / "one.vdb");
  for (const char* name : {"many.vdb", "one.vdb"}) {
    SCOPED_TRACE(name);
    EXPECT_EQ(gridNames(dir / name), (std::vector<std::string>{"feature", "invalid", "sdf"}));
    expectSameGrids(volumes[0], readVolume(dir / name));
    const std::vector<Volume> back = readVolumes(dir / name);
    ASSERT_EQ(back.size(), 1u);
    expectSameGrids(volumes[0], back[0]);
    expectSameCurves(back[0].boundaryLoops(), volumes[0].boundaryLoops());
  }
}

TEST(SheetVolumes, FilesOfOlderVersionsStillRead) {
  // An older writeVolume file: the same grids and keys, without the sheet count and the grids'
  // sheet numbers.
  const FeModel deck = readDeck(test::samplePart());
  const std::vector<Volume> volumes = partSheetVolumes(deck, 100, "hat_rail.k");
  const fs::path dir = test::scratchDir("sheet-volumes-old");
  writeVolume(volumes[0], dir / "new.vdb");
  {
    openvdb::io::File in((dir / "new.vdb").string());
    in.open();
    openvdb::GridPtrVecPtr grids = in.getGrids();
    openvdb::MetaMap::Ptr meta = in.getMetadata();
    in.close();
    ASSERT_TRUE(meta->getMetadata<openvdb::Int64Metadata>("voxremesh_sheet_count"));
    meta->removeMeta("voxremesh_sheet_count");
    for (const openvdb::GridBase::Ptr& grid : *grids) grid->removeMeta("voxremesh_sheet");
    openvdb::io::File((dir / "old.vdb").string()).write(*grids, *meta);
  }
  expectSameGrids(volumes[0], readVolume(dir / "old.vdb"));
  const std::vector<Volume> back = readVolumes(dir / "old.vdb");
  ASSERT_EQ(back.size(), 1u);
  expectSameGrids(volumes[0], back[0]);
  expectSameCurves(back[0].featureLines(), volumes[0].featureLines());
  EXPECT_EQ(back[0].info().part, 100);
}

TEST(SheetVolumes, RefusesNothingToWriteAndSheetsOutOfRange) {
  const fs::path dir = test::scratchDir("sheet-volumes-bad");
  EXPECT_THROW(writeVolumes({}, dir / "none.vdb"), std::invalid_argument);
  std::vector<Volume> empty(2);
  EXPECT_THROW(writeVolumes(empty, dir / "empty.vdb"), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir / "none.vdb"));
  EXPECT_FALSE(fs::exists(dir / "empty.vdb"));
  EXPECT_THROW(buildSheetVolumes({}, VolumeSettings{}), std::invalid_argument);
  EXPECT_EQ(&sheetVolume(empty, 1, "sheet="), &empty[1]);
  EXPECT_THROW(sheetVolume(empty, 2, "sheet="), SettingError);
  EXPECT_THROW(sheetVolume(empty, -1, "sheet="), SettingError);
  EXPECT_THROW(extractPartMesh({}), std::invalid_argument);
}

}  // namespace
}  // namespace voxremesh
