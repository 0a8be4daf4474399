// The voxremesh metadata of a .vdb file (volume_io.cpp): a volume's build parameters, curves and
// feature points as OpenVDB metadata, under keys that carry a per-sheet suffix. Include only from
// .cpp files that need OpenVDB.
#pragma once

#include <openvdb/openvdb.h>

#include <cstddef>
#include <string>

#include "volume/volume_grids.h"

namespace voxremesh::volume {

/// The suffix of sheet `sheet`'s grid names and file metadata keys: "" for sheet 0 (the layout
/// of a one-volume file), ".sheetK" for sheet K > 0.
std::string sheetSuffix(std::size_t sheet);

/// Adds the build parameters of `info` (version, voxel size, band, invalid angle, tie tolerance,
/// source file, part ID) to `meta`, each key followed by `suffix`.
void addInfoMeta(openvdb::MetaMap& meta, const VolumeInfo& info, const std::string& suffix);

/// Adds the feature lines, boundary loops, junction curves and feature points of `volume` to
/// `meta` as text (one curve per line, "closed|open x y z x y z ..."; one "x y z" per feature
/// point), each key followed by `suffix`.
void addCurveMeta(openvdb::MetaMap& meta, const Volume::Impl& volume, const std::string& suffix);

/// Reads what addInfoMeta and addCurveMeta wrote under `suffix` into `volume` (the voxel size
/// stays as the caller set it from the transform; a missing key leaves its field as it is).
/// @param file  the file, for messages
/// Throws InputError naming the file and key when a curve or point list is malformed.
void readVolumeMeta(const openvdb::MetaMap& meta, const std::string& suffix,
                    const std::string& file, Volume::Impl& volume);

}  // namespace voxremesh::volume
