// Reading and writing a Volume as one .vdb file: grids sdf, invalid, feature plus metadata.
//
// File-level metadata (also copied onto the sdf grid, except the curves):
//   voxremesh_version (string), voxremesh_voxel_size (double), voxremesh_band_voxels (double),
//   voxremesh_invalid_angle_deg (double), voxremesh_tie_tolerance_voxels (double),
//   voxremesh_source_file (string), voxremesh_part_id (int64),
//   voxremesh_feature_lines, voxremesh_boundary_loops (string: one curve per line,
//   "closed|open x y z x y z ..."), voxremesh_feature_points (string: one "x y z" per line).
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <system_error>

#include "volume/volume_grids.h"
#include "voxremesh/errors.h"
#include "voxremesh/volume.h"

namespace voxremesh {

namespace {

constexpr const char* kMetaVersion = "voxremesh_version";
constexpr const char* kMetaVoxelSize = "voxremesh_voxel_size";
constexpr const char* kMetaBand = "voxremesh_band_voxels";
constexpr const char* kMetaAngle = "voxremesh_invalid_angle_deg";
constexpr const char* kMetaTolerance = "voxremesh_tie_tolerance_voxels";
constexpr const char* kMetaSource = "voxremesh_source_file";
constexpr const char* kMetaPart = "voxremesh_part_id";
constexpr const char* kMetaFeatureLines = "voxremesh_feature_lines";
constexpr const char* kMetaBoundaryLoops = "voxremesh_boundary_loops";
constexpr const char* kMetaFeaturePoints = "voxremesh_feature_points";
constexpr const char* kMetaJunctionCurves = "voxremesh_junction_curves";

void appendPoint(std::string& out, const std::array<double, 3>& p) {
  char text[96];
  std::snprintf(text, sizeof text, " %.17g %.17g %.17g", p[0], p[1], p[2]);
  out += text;
}

std::string encodeCurves(const std::vector<VolumeCurve>& curves) {
  std::string out;
  for (const VolumeCurve& curve : curves) {
    out += curve.closed ? "closed" : "open";
    for (const auto& p : curve.points) appendPoint(out, p);
    out += '\n';
  }
  return out;
}

std::string encodePoints(const std::vector<std::array<double, 3>>& points) {
  std::string out;
  for (const auto& p : points) {
    appendPoint(out, p);
    out += '\n';
  }
  return out;
}

/// Parses the coordinates of one line; returns false on a malformed number.
bool parsePoints(const char* begin, const char* end, std::vector<std::array<double, 3>>& points) {
  std::array<double, 3> p{};
  int k = 0;
  const char* s = begin;
  while (true) {
    while (s < end && (*s == ' ' || *s == '\t')) ++s;
    if (s >= end) break;
    char* next = nullptr;
    const double value = std::strtod(s, &next);
    if (next == s || next > end) return false;
    p[k++] = value;
    if (k == 3) points.push_back(p), k = 0;
    s = next;
  }
  return k == 0;
}

std::vector<VolumeCurve> decodeCurves(const std::string& text, const std::string& file,
                                      const char* key) {
  std::vector<VolumeCurve> curves;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t stop = text.find('\n', start);
    if (stop == std::string::npos) stop = text.size();
    const std::string line = text.substr(start, stop - start);
    start = stop + 1;
    if (line.empty()) continue;
    VolumeCurve curve;
    std::size_t skip = 0;
    if (line.rfind("closed", 0) == 0) {
      curve.closed = true, skip = 6;
    } else if (line.rfind("open", 0) == 0) {
      skip = 4;
    } else {
      throw InputError(file, 0, std::string("metadata ") + key + " holds a malformed curve");
    }
    if (!parsePoints(line.data() + skip, line.data() + line.size(), curve.points)) {
      throw InputError(file, 0, std::string("metadata ") + key + " holds a malformed curve");
    }
    curves.push_back(std::move(curve));
  }
  return curves;
}

void addInfo(openvdb::MetaMap& meta, const VolumeInfo& info) {
  meta.insertMeta(kMetaVersion, openvdb::StringMetadata(info.toolVersion));
  meta.insertMeta(kMetaVoxelSize, openvdb::DoubleMetadata(info.voxelSize));
  meta.insertMeta(kMetaBand, openvdb::DoubleMetadata(info.bandWidthVoxels));
  meta.insertMeta(kMetaAngle, openvdb::DoubleMetadata(info.invalidAngleDeg));
  meta.insertMeta(kMetaTolerance, openvdb::DoubleMetadata(info.tieToleranceVoxels));
  meta.insertMeta(kMetaSource, openvdb::StringMetadata(info.sourceFile));
  meta.insertMeta(kMetaPart, openvdb::Int64Metadata(info.part));
}

template <typename MetaT, typename T>
void readMeta(const openvdb::MetaMap& meta, const char* key, T& value) {
  if (auto m = meta.getMetadata<MetaT>(key)) value = m->value();
}

template <typename GridT>
typename GridT::Ptr readTypedGrid(openvdb::io::File& file, const char* name,
                                  const std::string& path, const char* expected) {
  if (!file.hasGrid(name)) {
    std::string found;
    for (auto it = file.beginName(); it != file.endName(); ++it) {
      found += (found.empty() ? "" : ", ") + *it;
    }
    throw InputError(
        path, 0,
        std::string("no grid named '") + name +
            "': a voxremesh volume has grids sdf, invalid and feature; this file has " +
            (found.empty() ? std::string("none") : found));
  }
  openvdb::GridBase::Ptr base = file.readGrid(name);
  typename GridT::Ptr grid = openvdb::gridPtrCast<GridT>(base);
  if (!grid) {
    throw InputError(path, 0,
                     std::string("grid '") + name + "' holds " + base->valueType() +
                         " values, expected " + expected);
  }
  return grid;
}

/// Reads a mask grid written as a BoolGrid (marked voxels active) or as a MaskGrid.
openvdb::MaskGrid::Ptr readMaskGrid(openvdb::io::File& file, const char* name,
                                    const std::string& path) {
  if (file.hasGrid(name) && file.readGridMetadata(name)->isType<openvdb::BoolGrid>()) {
    const openvdb::BoolGrid::Ptr bools = readTypedGrid<openvdb::BoolGrid>(file, name, path, "bool");
    openvdb::MaskGrid::Ptr mask = openvdb::MaskGrid::create(openvdb::MaskTree::Ptr(
        new openvdb::MaskTree(bools->tree(), false, openvdb::TopologyCopy())));
    mask->setName(bools->getName());
    mask->setTransform(bools->transformPtr());
    return mask;
  }
  return readTypedGrid<openvdb::MaskGrid>(file, name, path, "bool or mask");
}

}  // namespace

void writeVolume(const Volume& volume, const std::filesystem::path& path) {
  if (volume.empty()) throw std::invalid_argument("cannot write an empty volume");
  volume::initializeOpenVdb();
  const Volume::Impl& v = volume.impl();
  const std::string creator = std::string("voxremesh ") + VOXREMESH_VERSION;

  openvdb::GridPtrVec grids;
  // Copies share the tree but have their own metadata.
  openvdb::FloatGrid::Ptr sdf = openvdb::gridPtrCast<openvdb::FloatGrid>(v.sdf->copyGrid());
  sdf->setCreator(creator);
  addInfo(*sdf, v.info);
  grids.push_back(sdf);
  // The masks are written as bool grids (active = marked, value true): Python's pyopenvdb and
  // other readers know BoolGrid but not MaskGrid. readVolume turns them back into masks.
  for (const openvdb::MaskGrid::Ptr& mask : {v.invalid, v.feature}) {
    openvdb::BoolGrid::Ptr copy = openvdb::BoolGrid::create(openvdb::BoolTree::Ptr(
        new openvdb::BoolTree(mask->tree(), false, true, openvdb::TopologyCopy())));
    copy->setName(mask->getName());
    copy->setTransform(mask->transformPtr());
    copy->setCreator(creator);
    grids.push_back(copy);
  }
  openvdb::MetaMap fileMeta;
  addInfo(fileMeta, v.info);
  fileMeta.insertMeta(kMetaFeatureLines, openvdb::StringMetadata(encodeCurves(v.featureLines)));
  fileMeta.insertMeta(kMetaBoundaryLoops, openvdb::StringMetadata(encodeCurves(v.boundaryLoops)));
  fileMeta.insertMeta(kMetaFeaturePoints, openvdb::StringMetadata(encodePoints(v.featurePoints)));
  fileMeta.insertMeta(kMetaJunctionCurves, openvdb::StringMetadata(encodeCurves(v.junctionCurves)));

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

Volume readVolume(const std::filesystem::path& path) {
  volume::initializeOpenVdb();
  const std::string name = path.string();
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw InputError(name, 0, "no such file");
  }
  openvdb::io::File file(name);
  try {
    file.open(/*delayLoad=*/false);
  } catch (const openvdb::Exception& e) {
    throw InputError(name, 0, std::string("not a readable .vdb file (") + e.what() + ")");
  }
  Volume result;
  Volume::Impl& v = result.impl();
  try {
    v.sdf = readTypedGrid<openvdb::FloatGrid>(file, volume::kSdfGridName, name, "float");
    v.invalid = readMaskGrid(file, volume::kInvalidGridName, name);
    v.feature = readMaskGrid(file, volume::kFeatureGridName, name);
  } catch (const openvdb::Exception& e) {
    throw InputError(name, 0, std::string("cannot read the grids (") + e.what() + ")");
  }
  const openvdb::math::Transform& t = v.sdf->transform();
  if (!t.hasUniformScale() || !(t == v.invalid->transform()) || !(t == v.feature->transform())) {
    throw InputError(name, 0,
                     "the grids sdf, invalid and feature must share one uniform "
                     "transform");
  }
  v.transform = v.sdf->transformPtr();
  v.invalid->setTransform(v.transform);
  v.feature->setTransform(v.transform);

  VolumeInfo& info = v.info;
  info.voxelSize = t.voxelSize()[0];
  info.bandWidthVoxels = double(v.sdf->background()) / info.voxelSize;
  const openvdb::MetaMap::Ptr meta = file.getMetadata();
  readMeta<openvdb::StringMetadata>(*meta, kMetaVersion, info.toolVersion);
  readMeta<openvdb::DoubleMetadata>(*meta, kMetaBand, info.bandWidthVoxels);
  readMeta<openvdb::DoubleMetadata>(*meta, kMetaAngle, info.invalidAngleDeg);
  readMeta<openvdb::DoubleMetadata>(*meta, kMetaTolerance, info.tieToleranceVoxels);
  readMeta<openvdb::StringMetadata>(*meta, kMetaSource, info.sourceFile);
  std::int64_t part = 0;
  readMeta<openvdb::Int64Metadata>(*meta, kMetaPart, part);
  info.part = part;
  std::string text;
  readMeta<openvdb::StringMetadata>(*meta, kMetaFeatureLines, text);
  v.featureLines = decodeCurves(text, name, kMetaFeatureLines);
  text.clear();
  readMeta<openvdb::StringMetadata>(*meta, kMetaBoundaryLoops, text);
  v.boundaryLoops = decodeCurves(text, name, kMetaBoundaryLoops);
  text.clear();
  readMeta<openvdb::StringMetadata>(*meta, kMetaJunctionCurves, text);
  v.junctionCurves = decodeCurves(text, name, kMetaJunctionCurves);
  text.clear();
  readMeta<openvdb::StringMetadata>(*meta, kMetaFeaturePoints, text);
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t stop = text.find('\n', start);
    if (stop == std::string::npos) stop = text.size();
    if (!parsePoints(text.data() + start, text.data() + stop, v.featurePoints)) {
      throw InputError(name, 0, std::string("metadata ") + kMetaFeaturePoints + " is malformed");
    }
    start = stop + 1;
  }
  file.close();
  return result;
}

}  // namespace voxremesh
