// formatQualityTable and qualityReportJson: the quality report as a text table and as JSON.
#include <cmath>
#include <cstdio>
#include <string>

#include "io/text_scan.h"
#include "voxremesh/quality.h"

namespace voxremesh {

namespace {

/// A number with 4 significant digits, "-" when not finite.
std::string real(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

std::string percent(double share) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.2f %%", 100.0 * share);
  return buffer;
}

void appendJsonNumber(std::string& out, double value) {
  if (std::isfinite(value))
    io::appendShortest(out, value);
  else
    out += "null";
}

void appendRow(std::string& out, const std::string& name, const std::string& limit,
               const std::string& worst, const std::string& failing, const std::string& share) {
  char line[256];
  std::snprintf(line, sizeof line, "  %-16s %12s %12s %9s %9s\n", name.c_str(), limit.c_str(),
                worst.c_str(), failing.c_str(), share.c_str());
  out += line;
}

}  // namespace

std::string formatQualityTable(const QualityReport& report) {
  std::string out;
  char line[256];
  std::snprintf(
      line, sizeof line,
      "elements %zu (quads %zu, trias %zu), target size %.4g, Jacobian ratio at the %s\n\n",
      report.elements, report.quads, report.triangles, report.settings.targetSize,
      report.settings.jacobianAtGaussPoints ? "Gauss points" : "corners");
  out += line;
  appendRow(out, "metric", "limit", "worst", "failing", "share");
  out += "  " + std::string(62, '-') + "\n";
  for (const CriterionSummary& c : report.criteria) {
    appendRow(out, criterionName(c.criterion), (c.isMaximum ? "<= " : ">= ") + real(c.limit),
              c.applies ? real(c.worst) : "-", std::to_string(c.failing), percent(c.share));
  }
  out += "  " + std::string(62, '-') + "\n";
  if (report.narrowChannelElements > 0) {
    std::snprintf(line, sizeof line,
                  "  min_length of %zu elements judged against the narrower channel they lie in\n",
                  report.narrowChannelElements);
    out += line;
  }
  if (report.sharpCornerElements > 0) {
    std::snprintf(
        line, sizeof line,
        "  %zu triangles fill corners sharper than %.4g deg: judged by their other angles\n",
        report.sharpCornerElements, report.settings.minTriaAngleDeg);
    out += line;
  }
  appendRow(out, "any criterion", "", "", std::to_string(report.failingAny),
            percent(report.failingAnyShare));
  appendRow(out, "tria share", "<= " + percent(report.settings.maxTriangleShare),
            percent(report.triangleShare), std::to_string(report.triangles),
            report.triangleShare > report.settings.maxTriangleShare ? "FAIL" : "ok");
  if (report.distance) {
    const SurfaceDistance& d = *report.distance;
    appendRow(out, "distance max", "<= " + real(report.distanceLimit), real(d.max()), "",
              d.max() > report.distanceLimit ? "FAIL" : "ok");
    std::snprintf(line, sizeof line,
                  "  distance to original: max %.4g mean %.4g; from original: max %.4g mean %.4g\n",
                  d.maxToOriginal, d.meanToOriginal, d.maxFromOriginal, d.meanFromOriginal);
    out += line;
  }
  std::snprintf(line, sizeof line, "  quality index: mean %.4g per element\n",
                report.meanQualityIndex);
  out += line;
  out += report.passes() ? "\nresult: pass\n" : "\nresult: FAIL\n";
  return out;
}

std::string qualityReportJson(const QualityReport& report) {
  std::string out = "{\"elements\":" + std::to_string(report.elements);
  out += ",\"quads\":" + std::to_string(report.quads);
  out += ",\"trias\":" + std::to_string(report.triangles);
  out += ",\"target_size\":";
  appendJsonNumber(out, report.settings.targetSize);
  out += report.settings.jacobianAtGaussPoints ? ",\"jacobian_at\":\"gauss_points\""
                                               : ",\"jacobian_at\":\"corners\"";
  out += ",\"criteria\":[";
  for (std::size_t i = 0; i < report.criteria.size(); ++i) {
    const CriterionSummary& c = report.criteria[i];
    out += i ? ",{" : "{";
    out += "\"metric\":\"" + std::string(criterionName(c.criterion)) + "\"";
    out += ",\"limit\":";
    appendJsonNumber(out, c.limit);
    out += c.isMaximum ? ",\"limit_is\":\"max\"" : ",\"limit_is\":\"min\"";
    out += ",\"worst\":";
    if (c.applies)
      appendJsonNumber(out, c.worst);
    else
      out += "null";
    out += ",\"applies\":" + std::to_string(c.applies);
    out += ",\"failing\":" + std::to_string(c.failing);
    out += ",\"share\":";
    appendJsonNumber(out, c.share);
    out += "}";
  }
  out += "],\"narrow_channel_elements\":" + std::to_string(report.narrowChannelElements);
  out += ",\"sharp_corner_elements\":" + std::to_string(report.sharpCornerElements);
  out += ",\"failing_any\":" + std::to_string(report.failingAny);
  out += ",\"failing_any_share\":";
  appendJsonNumber(out, report.failingAnyShare);
  out += ",\"tria_share\":";
  appendJsonNumber(out, report.triangleShare);
  out += ",\"tria_share_limit\":";
  appendJsonNumber(out, report.settings.maxTriangleShare);
  out += ",\"quality_index\":";
  appendJsonNumber(out, report.meanQualityIndex);
  out += ",\"distance\":";
  if (report.distance) {
    const SurfaceDistance& d = *report.distance;
    out += "{\"max_to_original\":";
    appendJsonNumber(out, d.maxToOriginal);
    out += ",\"mean_to_original\":";
    appendJsonNumber(out, d.meanToOriginal);
    out += ",\"max_from_original\":";
    appendJsonNumber(out, d.maxFromOriginal);
    out += ",\"mean_from_original\":";
    appendJsonNumber(out, d.meanFromOriginal);
    out += ",\"max\":";
    appendJsonNumber(out, d.max());
    out += ",\"limit\":";
    appendJsonNumber(out, report.distanceLimit);
    out += "}";
  } else {
    out += "null";
  }
  out += report.passes() ? ",\"pass\":true}\n" : ",\"pass\":false}\n";
  return out;
}

}  // namespace voxremesh
