// Reading and writing the volumes of a part's sheets as one .vdb file (volume.h writeVolumes):
// per sheet the grids sdf, invalid, feature (names suffixed by the sheet, volume_meta.h
// sheetSuffix) plus file metadata (volume_meta.cpp lists the keys); a one-sheet file is the
// layout writeVolume has always written.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <unistd.h>

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "volume/vdb_layout.h"
#include "volume/volume_grids.h"
#include "volume/volume_meta.h"
#include "voxremesh/errors.h"
#include "voxremesh/volume.h"

namespace voxremesh {

namespace {

constexpr const char* kMetaSheet = "voxremesh_sheet";
constexpr const char* kMetaSheetCount = "voxremesh_sheet_count";

using VolumeRefs = std::vector<std::reference_wrapper<const Volume>>;

/// The grids of one sheet as written: copies sharing the trees, named with the sheet's suffix.
void addSheetGrids(const Volume::Impl& v, std::size_t sheet, const std::string& creator,
                   openvdb::GridPtrVec& grids) {
  const std::string suffix = volume::sheetSuffix(sheet);
  const openvdb::Int64Metadata sheetMeta(static_cast<std::int64_t>(sheet));
  // Copies share the tree but have their own name and metadata.
  openvdb::FloatGrid::Ptr sdf = openvdb::gridPtrCast<openvdb::FloatGrid>(v.sdf->copyGrid());
  sdf->setName(volume::kSdfGridName + suffix);
  sdf->setCreator(creator);
  volume::addInfoMeta(*sdf, v.info, "");
  sdf->insertMeta(kMetaSheet, sheetMeta);
  grids.push_back(sdf);
  // The masks are written as bool grids (active = marked, value true): Python's pyopenvdb and
  // other readers know BoolGrid but not MaskGrid. The reader turns them back into masks.
  for (const openvdb::MaskGrid::Ptr& mask : {v.invalid, v.feature}) {
    openvdb::BoolGrid::Ptr copy = openvdb::BoolGrid::create(openvdb::BoolTree::Ptr(
        new openvdb::BoolTree(mask->tree(), false, true, openvdb::TopologyCopy())));
    copy->setName(mask->getName() + suffix);
    copy->setTransform(mask->transformPtr());
    copy->setCreator(creator);
    copy->insertMeta(kMetaSheet, sheetMeta);
    grids.push_back(copy);
  }
}

/// Writes the sheets' grids and metadata to a temporary file beside `path`, then renames it.
void writeSheets(const VolumeRefs& volumes, const std::filesystem::path& path) {
  if (volumes.empty()) throw std::invalid_argument("cannot write a file of no volumes");
  for (const Volume& volume : volumes)
    if (volume.empty()) throw std::invalid_argument("cannot write an empty volume");
  volume::initializeOpenVdb();
  const std::string creator = std::string("voxremesh ") + VOXREMESH_VERSION;
  openvdb::GridPtrVec grids;
  openvdb::MetaMap fileMeta;
  for (std::size_t k = 0; k < volumes.size(); ++k) {
    const Volume::Impl& v = volumes[k].get().impl();
    addSheetGrids(v, k, creator, grids);
    volume::addInfoMeta(fileMeta, v.info, volume::sheetSuffix(k));
    volume::addCurveMeta(fileMeta, v, volume::sheetSuffix(k));
  }
  fileMeta.insertMeta(kMetaSheetCount,
                      openvdb::Int64Metadata(static_cast<std::int64_t>(volumes.size())));

  std::filesystem::path temporary = path;
  temporary += ".tmp." + std::to_string(::getpid());
  try {
    openvdb::io::File file(temporary.string());
    file.write(grids, fileMeta);
    file.close();
  } catch (const openvdb::Exception& e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write " + path.string() + ": " + e.what());
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw std::runtime_error("cannot write " + path.string() + ": " + error.message());
  }
}

template <typename GridT>
typename GridT::Ptr readTypedGrid(openvdb::io::File& file, const std::string& name,
                                  const std::string& path, const char* expected) {
  if (!file.hasGrid(name)) {
    std::string found;
    for (auto it = file.beginName(); it != file.endName(); ++it) {
      found += (found.empty() ? "" : ", ") + *it;
    }
    throw InputError(
        path, 0,
        "no grid named '" + name +
            "': a voxremesh volume has grids sdf, invalid and feature; this file has " +
            (found.empty() ? std::string("none") : found));
  }
  openvdb::GridBase::Ptr base = file.readGrid(name);
  typename GridT::Ptr grid = openvdb::gridPtrCast<GridT>(base);
  if (!grid) {
    throw InputError(
        path, 0,
        "grid '" + name + "' holds " + base->valueType() + " values, expected " + expected);
  }
  return grid;
}

/// Reads a mask grid written as a BoolGrid (marked voxels active) or as a MaskGrid.
openvdb::MaskGrid::Ptr readMaskGrid(openvdb::io::File& file, const std::string& name,
                                    const std::string& path) {
  if (file.hasGrid(name) && file.readGridMetadata(name)->isType<openvdb::BoolGrid>()) {
    const openvdb::BoolGrid::Ptr bools = readTypedGrid<openvdb::BoolGrid>(file, name, path, "bool");
    openvdb::MaskGrid::Ptr mask = openvdb::MaskGrid::create(openvdb::MaskTree::Ptr(
        new openvdb::MaskTree(bools->tree(), false, openvdb::TopologyCopy())));
    mask->setTransform(bools->transformPtr());
    return mask;
  }
  return readTypedGrid<openvdb::MaskGrid>(file, name, path, "bool or mask");
}

/// Opens a .vdb file for reading. Throws InputError naming it when it is missing or unreadable.
void openFile(openvdb::io::File& file, const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw InputError(path.string(), 0, "no such file");
  }
  volume::checkVdbLayout(path);
  try {
    file.open(/*delayLoad=*/false);
  } catch (const openvdb::Exception& e) {
    // OpenVDB's message may quote a name read from the file: at most its start.
    throw InputError(path.string(), 0,
                     "not a readable .vdb file (" + std::string(e.what()).substr(0, 200) + ")");
  }
}

/// The number of sheet volumes the open file holds (1 without the count: older files).
/// Throws InputError for a count below 1.
std::size_t sheetCount(const openvdb::MetaMap& meta, const std::string& name) {
  std::int64_t count = 1;
  if (auto m = meta.getMetadata<openvdb::Int64Metadata>(kMetaSheetCount)) count = m->value();
  if (count < 1)
    throw InputError(name, 0, std::string("metadata ") + kMetaSheetCount + " must be at least 1");
  return static_cast<std::size_t>(count);
}

/// Reads the grids and metadata of sheet `sheet` of the open file; in memory the grids have
/// the plain names sdf, invalid and feature, as buildVolume makes them.
Volume readSheet(openvdb::io::File& file, const openvdb::MetaMap& meta, std::size_t sheet,
                 const std::string& name) {
  const std::string suffix = volume::sheetSuffix(sheet);
  Volume result;
  Volume::Impl& v = result.impl();
  try {
    v.sdf = readTypedGrid<openvdb::FloatGrid>(file, volume::kSdfGridName + suffix, name, "float");
    v.invalid = readMaskGrid(file, volume::kInvalidGridName + suffix, name);
    v.feature = readMaskGrid(file, volume::kFeatureGridName + suffix, name);
  } catch (const openvdb::Exception& e) {
    throw InputError(name, 0,
                     "cannot read the grids (" + std::string(e.what()).substr(0, 200) + ")");
  }
  v.sdf->setName(volume::kSdfGridName);
  v.invalid->setName(volume::kInvalidGridName);
  v.feature->setName(volume::kFeatureGridName);
  const openvdb::math::Transform& t = v.sdf->transform();
  if (!t.hasUniformScale() || !(t == v.invalid->transform()) || !(t == v.feature->transform())) {
    throw InputError(name, 0,
                     "the grids sdf" + suffix + ", invalid" + suffix + " and feature" + suffix +
                         " must share one uniform transform");
  }
  v.transform = v.sdf->transformPtr();
  v.invalid->setTransform(v.transform);
  v.feature->setTransform(v.transform);
  v.info.voxelSize = t.voxelSize()[0];
  v.info.bandWidthVoxels = double(v.sdf->background()) / v.info.voxelSize;
  volume::readVolumeMeta(meta, suffix, name, v);
  return result;
}

/// Reads every sheet of a .vdb file. With `oneSheet`, a file of several sheets is refused with
/// an InputError that names readVolumes.
std::vector<Volume> readSheets(const std::filesystem::path& path, bool oneSheet) {
  volume::initializeOpenVdb();
  const std::string name = path.string();
  openvdb::io::File file(name);
  openFile(file, path);
  const openvdb::MetaMap::Ptr meta = file.getMetadata();
  const std::size_t count = sheetCount(*meta, name);
  if (oneSheet && count > 1)
    throw InputError(name, 0,
                     "holds the volumes of " + std::to_string(count) +
                         " sheets; read it with readVolumes (the voxremesh commands and the "
                         "chain's -read do)");
  std::vector<Volume> volumes;
  volumes.reserve(count);
  for (std::size_t k = 0; k < count; ++k) volumes.push_back(readSheet(file, *meta, k, name));
  file.close();
  return volumes;
}

}  // namespace

void writeVolume(const Volume& volume, const std::filesystem::path& path) {
  writeSheets({std::cref(volume)}, path);
}

void writeVolumes(const std::vector<Volume>& volumes, const std::filesystem::path& path) {
  writeSheets(VolumeRefs(volumes.begin(), volumes.end()), path);
}

Volume readVolume(const std::filesystem::path& path) {
  return std::move(readSheets(path, /*oneSheet=*/true).front());
}

std::vector<Volume> readVolumes(const std::filesystem::path& path) {
  return readSheets(path, /*oneSheet=*/false);
}

}  // namespace voxremesh
