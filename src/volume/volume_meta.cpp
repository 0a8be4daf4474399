// The voxremesh metadata of a .vdb file (volume_meta.h).
//
// Keys (each followed by the sheet suffix; also on every sdf grid, without suffix and curves):
//   voxremesh_version (string), voxremesh_voxel_size (double), voxremesh_band_voxels (double),
//   voxremesh_invalid_angle_deg (double), voxremesh_tie_tolerance_voxels (double),
//   voxremesh_source_file (string), voxremesh_part_id (int64),
//   voxremesh_feature_lines, voxremesh_boundary_loops, voxremesh_junction_curves (string: one
//   curve per line, "closed|open x y z x y z ..."; "closed-kept|open-kept" for a junction curve
//   whose points all stay nodes), voxremesh_feature_points (string: one "x y z" per line).
#include "volume/volume_meta.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "voxremesh/errors.h"

namespace voxremesh::volume {

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
    if (curve.keepPoints) out += "-kept";
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
                                      const std::string& key) {
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
      skip = std::string::npos;
    }
    if (skip != std::string::npos && line.compare(skip, 5, "-kept") == 0)
      curve.keepPoints = true, skip += 5;
    if (skip == std::string::npos) {
      throw InputError(file, 0, "metadata " + key + " holds a malformed curve");
    }
    if (!parsePoints(line.data() + skip, line.data() + line.size(), curve.points)) {
      throw InputError(file, 0, "metadata " + key + " holds a malformed curve");
    }
    curves.push_back(std::move(curve));
  }
  return curves;
}

std::vector<std::array<double, 3>> decodePoints(const std::string& text, const std::string& file,
                                                const std::string& key) {
  std::vector<std::array<double, 3>> points;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t stop = text.find('\n', start);
    if (stop == std::string::npos) stop = text.size();
    if (!parsePoints(text.data() + start, text.data() + stop, points)) {
      throw InputError(file, 0, "metadata " + key + " is malformed");
    }
    start = stop + 1;
  }
  return points;
}

template <typename MetaT, typename T>
void readMeta(const openvdb::MetaMap& meta, const std::string& key, T& value) {
  if (auto m = meta.getMetadata<MetaT>(key)) value = m->value();
}

/// The text under `key`, "" when missing.
std::string readText(const openvdb::MetaMap& meta, const std::string& key) {
  std::string text;
  readMeta<openvdb::StringMetadata>(meta, key, text);
  return text;
}

}  // namespace

std::string sheetSuffix(std::size_t sheet) {
  return sheet == 0 ? std::string() : ".sheet" + std::to_string(sheet);
}

void addInfoMeta(openvdb::MetaMap& meta, const VolumeInfo& info, const std::string& suffix) {
  meta.insertMeta(kMetaVersion + suffix, openvdb::StringMetadata(info.toolVersion));
  meta.insertMeta(kMetaVoxelSize + suffix, openvdb::DoubleMetadata(info.voxelSize));
  meta.insertMeta(kMetaBand + suffix, openvdb::DoubleMetadata(info.bandWidthVoxels));
  meta.insertMeta(kMetaAngle + suffix, openvdb::DoubleMetadata(info.invalidAngleDeg));
  meta.insertMeta(kMetaTolerance + suffix, openvdb::DoubleMetadata(info.tieToleranceVoxels));
  meta.insertMeta(kMetaSource + suffix, openvdb::StringMetadata(info.sourceFile));
  meta.insertMeta(kMetaPart + suffix, openvdb::Int64Metadata(info.part));
}

void addCurveMeta(openvdb::MetaMap& meta, const Volume::Impl& volume, const std::string& suffix) {
  meta.insertMeta(kMetaFeatureLines + suffix,
                  openvdb::StringMetadata(encodeCurves(volume.featureLines)));
  meta.insertMeta(kMetaBoundaryLoops + suffix,
                  openvdb::StringMetadata(encodeCurves(volume.boundaryLoops)));
  meta.insertMeta(kMetaFeaturePoints + suffix,
                  openvdb::StringMetadata(encodePoints(volume.featurePoints)));
  meta.insertMeta(kMetaJunctionCurves + suffix,
                  openvdb::StringMetadata(encodeCurves(volume.junctionCurves)));
}

void readVolumeMeta(const openvdb::MetaMap& meta, const std::string& suffix,
                    const std::string& file, Volume::Impl& volume) {
  VolumeInfo& info = volume.info;
  readMeta<openvdb::StringMetadata>(meta, kMetaVersion + suffix, info.toolVersion);
  readMeta<openvdb::DoubleMetadata>(meta, kMetaBand + suffix, info.bandWidthVoxels);
  readMeta<openvdb::DoubleMetadata>(meta, kMetaAngle + suffix, info.invalidAngleDeg);
  readMeta<openvdb::DoubleMetadata>(meta, kMetaTolerance + suffix, info.tieToleranceVoxels);
  readMeta<openvdb::StringMetadata>(meta, kMetaSource + suffix, info.sourceFile);
  std::int64_t part = 0;
  readMeta<openvdb::Int64Metadata>(meta, kMetaPart + suffix, part);
  info.part = part;
  for (auto [key, curves] : {std::pair{kMetaFeatureLines, &volume.featureLines},
                             std::pair{kMetaBoundaryLoops, &volume.boundaryLoops},
                             std::pair{kMetaJunctionCurves, &volume.junctionCurves}}) {
    const std::string full = key + suffix;
    *curves = decodeCurves(readText(meta, full), file, full);
  }
  const std::string points = kMetaFeaturePoints + suffix;
  volume.featurePoints = decodePoints(readText(meta, points), file, points);
}

}  // namespace voxremesh::volume
