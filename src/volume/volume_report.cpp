// The inspection report of a Volume: per grid class, value type, counts, memory, bounds and value
// range, rendered as text or JSON.
#include <openvdb/openvdb.h>
#include <openvdb/tools/Count.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "json/json.h"
#include "volume/volume_grids.h"
#include "voxremesh/volume.h"

namespace voxremesh {

namespace {

template <typename GridT>
GridReport reportGrid(const GridT& grid) {
  GridReport r;
  r.name = grid.getName();
  r.gridClass = openvdb::GridBase::gridClassToString(grid.getGridClass());
  // OpenVDB names the value type of mask grids "bool"; they hold no values, only topology.
  r.valueType = std::is_same_v<GridT, openvdb::MaskGrid> ? "mask" : grid.valueType();
  r.activeVoxels = grid.activeVoxelCount();
  r.leafNodes = grid.tree().leafCount();
  r.memoryBytes = grid.memUsage();
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  r.emptyBounds = box.empty();
  if (!r.emptyBounds) {
    const openvdb::Vec3d lo = grid.indexToWorld(box.min()), hi = grid.indexToWorld(box.max());
    for (int k = 0; k < 3; ++k) {
      r.indexMin[k] = box.min()[k];
      r.indexMax[k] = box.max()[k];
      r.worldMin[k] = lo[k];
      r.worldMax[k] = hi[k];
    }
  }
  return r;
}

std::string jsonString(const std::string& s) {
  return json::quote(s);
}

std::string jsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

template <typename T>
std::string triple(const std::array<T, 3>& a, const char* format) {
  char text[128];
  std::snprintf(text, sizeof text, format, a[0], a[1], a[2]);
  return text;
}

}  // namespace

VolumeReport inspectVolume(const Volume& volume) {
  if (volume.empty()) throw std::invalid_argument("cannot inspect an empty volume");
  const Volume::Impl& v = volume.impl();
  VolumeReport report;
  report.info = v.info;
  GridReport sdf = reportGrid(*v.sdf);
  if (sdf.activeVoxels > 0) {
    const auto range = openvdb::tools::minMax(v.sdf->tree());
    sdf.hasValueRange = true;
    sdf.minValue = range.min();
    sdf.maxValue = range.max();
  }
  report.grids.push_back(sdf);
  report.grids.push_back(reportGrid(*v.invalid));
  report.grids.push_back(reportGrid(*v.feature));
  report.invalidVoxels = v.invalid->activeVoxelCount();
  report.featureVoxels = v.feature->activeVoxelCount();
  report.featureLines = v.featureLines.size();
  report.featurePoints = v.featurePoints.size();
  report.boundaryLoops = v.boundaryLoops.size();
  report.junctionCurves = v.junctionCurves.size();
  return report;
}

std::string formatVolumeReport(const VolumeReport& report) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line,
                "volume of part %lld  (source %s, voxremesh %s)\n"
                "voxel size %.6g, band %.3g voxels, invalid angle %.3g deg, tie tolerance %.3g "
                "voxels\n",
                static_cast<long long>(report.info.part),
                report.info.sourceFile.empty() ? "-" : report.info.sourceFile.c_str(),
                report.info.toolVersion.empty() ? "?" : report.info.toolVersion.c_str(),
                report.info.voxelSize, report.info.bandWidthVoxels, report.info.invalidAngleDeg,
                report.info.tieToleranceVoxels);
  out += line;
  std::snprintf(line, sizeof line, "%-8s %-10s %-6s %12s %8s %12s\n", "grid", "class", "type",
                "active", "leaves", "memory [B]");
  out += line;
  for (const GridReport& g : report.grids) {
    std::snprintf(line, sizeof line, "%-8s %-10s %-6s %12llu %8llu %12llu\n", g.name.c_str(),
                  g.gridClass.c_str(), g.valueType.c_str(),
                  static_cast<unsigned long long>(g.activeVoxels),
                  static_cast<unsigned long long>(g.leafNodes),
                  static_cast<unsigned long long>(g.memoryBytes));
    out += line;
  }
  for (const GridReport& g : report.grids) {
    if (g.emptyBounds) {
      out += "  " + g.name + ": no active voxels\n";
      continue;
    }
    out += "  " + g.name + ": index " + triple(g.indexMin, "(%d %d %d)") + " .. " +
           triple(g.indexMax, "(%d %d %d)") + ", world " + triple(g.worldMin, "(%.6g %.6g %.6g)") +
           " .. " + triple(g.worldMax, "(%.6g %.6g %.6g)");
    if (g.hasValueRange) {
      std::snprintf(line, sizeof line, ", values %.6g .. %.6g", g.minValue, g.maxValue);
      out += line;
    }
    out += "\n";
  }
  std::snprintf(line, sizeof line,
                "invalid voxels %llu, feature cells %llu, feature lines %zu, feature points %zu, "
                "boundary loops %zu, junction curves %zu\n",
                static_cast<unsigned long long>(report.invalidVoxels),
                static_cast<unsigned long long>(report.featureVoxels), report.featureLines,
                report.featurePoints, report.boundaryLoops, report.junctionCurves);
  out += line;
  return out;
}

std::string volumeReportJson(const VolumeReport& report) {
  std::string out = "{";
  out += "\"part\":" + std::to_string(report.info.part);
  out += ",\"source_file\":" + jsonString(report.info.sourceFile);
  out += ",\"tool_version\":" + jsonString(report.info.toolVersion);
  out += ",\"voxel_size\":" + jsonNumber(report.info.voxelSize);
  out += ",\"band_voxels\":" + jsonNumber(report.info.bandWidthVoxels);
  out += ",\"invalid_angle_deg\":" + jsonNumber(report.info.invalidAngleDeg);
  out += ",\"tie_tolerance_voxels\":" + jsonNumber(report.info.tieToleranceVoxels);
  out += ",\"grids\":[";
  for (std::size_t i = 0; i < report.grids.size(); ++i) {
    const GridReport& g = report.grids[i];
    out += i ? ",{" : "{";
    out += "\"name\":" + jsonString(g.name);
    out += ",\"class\":" + jsonString(g.gridClass);
    out += ",\"value_type\":" + jsonString(g.valueType);
    out += ",\"active_voxels\":" + std::to_string(g.activeVoxels);
    out += ",\"leaf_nodes\":" + std::to_string(g.leafNodes);
    out += ",\"memory_bytes\":" + std::to_string(g.memoryBytes);
    if (!g.emptyBounds) {
      out += ",\"index_bbox\":[" + triple(g.indexMin, "[%d,%d,%d]") + "," +
             triple(g.indexMax, "[%d,%d,%d]") + "]";
      out += ",\"world_bbox\":[[" + jsonNumber(g.worldMin[0]) + "," + jsonNumber(g.worldMin[1]) +
             "," + jsonNumber(g.worldMin[2]) + "],[" + jsonNumber(g.worldMax[0]) + "," +
             jsonNumber(g.worldMax[1]) + "," + jsonNumber(g.worldMax[2]) + "]]";
    } else {
      out += ",\"index_bbox\":null,\"world_bbox\":null";
    }
    if (g.hasValueRange) {
      out += ",\"value_range\":[" + jsonNumber(g.minValue) + "," + jsonNumber(g.maxValue) + "]";
    } else {
      out += ",\"value_range\":null";
    }
    out += "}";
  }
  out += "]";
  out += ",\"invalid_voxels\":" + std::to_string(report.invalidVoxels);
  out += ",\"feature_cells\":" + std::to_string(report.featureVoxels);
  out += ",\"feature_lines\":" + std::to_string(report.featureLines);
  out += ",\"feature_points\":" + std::to_string(report.featurePoints);
  out += ",\"boundary_loops\":" + std::to_string(report.boundaryLoops);
  out += ",\"junction_curves\":" + std::to_string(report.junctionCurves);
  out += "}";
  return out;
}

std::vector<VolumeReport> inspectVolumes(const std::vector<Volume>& volumes) {
  std::vector<VolumeReport> reports;
  reports.reserve(volumes.size());
  for (const Volume& volume : volumes) reports.push_back(inspectVolume(volume));
  return reports;
}

std::string formatVolumeReports(const std::vector<VolumeReport>& reports) {
  if (reports.size() == 1) return formatVolumeReport(reports.front());
  std::string out;
  for (std::size_t k = 0; k < reports.size(); ++k) {
    out += (k ? "\nsheet " : "sheet ") + std::to_string(k) + " of " +
           std::to_string(reports.size()) + "\n" + formatVolumeReport(reports[k]);
  }
  return out;
}

std::string volumeReportsJson(const std::vector<VolumeReport>& reports) {
  if (reports.size() == 1) return volumeReportJson(reports.front());
  std::string out = "{\"sheet_count\":" + std::to_string(reports.size()) + ",\"sheets\":[";
  for (std::size_t k = 0; k < reports.size(); ++k)
    out += (k ? "," : "") + volumeReportJson(reports[k]);
  return out + "]}";
}

}  // namespace voxremesh
