// One volume per sheet of a part, all at one voxel size (volume.h buildSheetVolumes).
#include <stdexcept>
#include <string>

#include "voxremesh/errors.h"
#include "voxremesh/volume.h"

namespace voxremesh {

std::vector<Volume> buildSheetVolumes(const std::vector<Sheet>& sheets,
                                      const VolumeSettings& settings, const VolumeSource& source) {
  if (sheets.empty()) throw std::invalid_argument("no sheets to voxelize");
  checkVolumeSettings(settings);
  // One voxel size for all sheets: junction nodes are spaced by the voxel size, so sheets that
  // meet must share it to share their nodes.
  VolumeSettings common = settings;
  common.rule = VoxelSizeRule::Explicit;
  common.voxelSize = chooseVoxelSize(sheets, settings);
  std::vector<Volume> volumes;
  volumes.reserve(sheets.size());
  for (const Sheet& sheet : sheets) volumes.push_back(buildVolume({sheet}, common, source));
  return volumes;
}

const Volume& sheetVolume(const std::vector<Volume>& volumes, long long sheet,
                          const std::string& what) {
  if (volumes.empty()) throw SettingError(what + ": there are no sheet volumes");
  if (sheet < 0 || static_cast<unsigned long long>(sheet) >= volumes.size())
    throw SettingError(what + " must be a sheet of the volume, 0.." +
                       std::to_string(volumes.size() - 1) + " (got " + std::to_string(sheet) + ")");
  return volumes[static_cast<std::size_t>(sheet)];
}

}  // namespace voxremesh
