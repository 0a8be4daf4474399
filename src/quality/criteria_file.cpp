// Quality criteria files (criteria_file.h).
#include "voxremesh/criteria_file.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "io/text_scan.h"
#include "voxremesh/errors.h"

namespace voxremesh {

namespace {

/// The criterion named `name`, or none.
std::optional<Criterion> criterionNamed(std::string_view name) {
  for (int c = 0; c < kCriterionCount; ++c)
    if (name == criterionName(static_cast<Criterion>(c))) return static_cast<Criterion>(c);
  return std::nullopt;
}

/// The words of a line without its comment.
std::vector<std::string_view> words(std::string_view line) {
  line = line.substr(0, line.find('#'));
  std::vector<std::string_view> result;
  std::size_t at = 0;
  while (true) {
    at = line.find_first_not_of(" \t\r", at);
    if (at == std::string_view::npos) return result;
    const std::size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
    result.push_back(line.substr(at, end - at));
    at = end;
  }
}

/// Reads entries of one file, each error naming its source and line.
class CriteriaParser {
 public:
  CriteriaParser(std::string source, QualitySettings& settings)
      : source_(std::move(source)), settings_(settings) {}

  void line(std::string_view text, std::size_t number) {
    number_ = number;
    text_ = std::string(text);
    const std::vector<std::string_view> w = words(text);
    if (w.empty()) return;
    if (!seen_.insert(std::string(w[0])).second) fail("'" + std::string(w[0]) + "' is given twice");
    if (w[0] == "tria_share" || w[0] == "failing_share") {
      if (w.size() != 2) fail(std::string(w[0]) + " takes one share");
      (w[0] == "tria_share" ? settings_.maxTriangleShare : settings_.maxFailingShare) = share(w[1]);
    } else if (w[0] == "jacobian_at") {
      if (w.size() != 2 || (w[1] != "corners" && w[1] != "gauss_points"))
        fail("jacobian_at takes corners or gauss_points");
      settings_.jacobianAtGaussPoints = w[1] == "gauss_points";
    } else if (const auto criterion = criterionNamed(w[0])) {
      metric(*criterion, w);
    } else {
      fail("unknown entry '" + std::string(w[0]) +
           "' (a metric such as warping or min_length, tria_share, failing_share, jacobian_at)");
    }
  }

 private:
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(source_, number_, message, text_);
  }

  double number(std::string_view word) const {
    double value = 0.0;
    if (word.empty() || !io::parseReal(word, value))
      fail("'" + std::string(word) + "' is not a number");
    return value;
  }

  double share(std::string_view word) const {
    const bool percent = !word.empty() && word.back() == '%';
    const double value = number(percent ? word.substr(0, word.size() - 1) : word);
    const double result = percent ? value / 100.0 : value;
    if (!(result >= 0.0 && result <= 1.0))
      fail("a share is within 0 .. 1 (or 0% .. 100%), not " + std::string(word));
    return result;
  }

  /// METRIC IDEAL GOOD WARN FAIL WORST [WEIGHT]
  void metric(Criterion c, const std::vector<std::string_view>& w) {
    const std::string name = criterionName(c);
    if (w.size() != 6 && w.size() != 7)
      fail(name + " takes five values (ideal good warn fail worst) and an optional weight");
    std::array<double, 5> v{};
    const auto absolute = absoluteLengthField(c);
    const bool relativeLine = w[1].back() == 'h';  // words are never empty
    for (std::size_t k = 0; k < 5; ++k) {
      std::string_view word = w[k + 1];
      const bool relative = word.back() == 'h';
      if (relative && !absolute)
        fail(name + " is no length: '" + std::string(word) + "' takes no 'h'");
      if (relative != relativeLine)
        fail(name +
             ": give its five lengths all relative to the target size (as 0.5h) or all "
             "in model units (as 2.5)");
      v[k] = number(relative ? word.substr(0, word.size() - 1) : word);
    }
    const double sign = isMaximumCriterion(c) ? 1.0 : -1.0;
    for (std::size_t k = 1; k < 5; ++k)
      if (sign * v[k] < sign * v[k - 1])
        fail(name + ": the values run from best to worst (" + (sign > 0 ? "growing" : "falling") +
             "), ideal good warn fail worst");
    if (c == Criterion::Folded && v[3] != 0.0) fail("folded's fail value is 0");
    IndexThresholds& t = settings_.index[std::size_t(c)];
    t = {v[0], v[1], v[2], v[4], w.size() == 7 ? number(w[6]) : 1.0};
    if (!(t.weight >= 0.0)) fail(name + ": a weight is 0 or more");
    if (const auto field = limitField(c)) settings_.*field = v[3];
    if (absolute) settings_.*absolute = !relativeLine;
  }

  std::string source_;
  QualitySettings& settings_;
  std::size_t number_ = 0;
  std::string text_;
  std::set<std::string> seen_;
};

/// A number as the file writes it (the shortest form that reads back exactly).
std::string numberText(double value) {
  std::string text;
  io::appendShortest(text, value);
  return text;
}

}  // namespace

void parseCriteria(std::string_view text, const std::string& source, QualitySettings& settings) {
  QualitySettings result = settings;
  CriteriaParser parser(source, result);
  io::LineCursor cursor(text);
  while (cursor.next()) parser.line(cursor.line(), cursor.lineNumber());
  try {
    checkQualitySettings(result);
  } catch (const SettingError& error) {
    throw InputError(source, 0, error.what());
  }
  settings = result;
}

void readCriteriaFile(const std::string& path, QualitySettings& settings) {
  const std::string text = io::loadFile(path);
  io::requireText(text, path);
  parseCriteria(text, path, settings);
}

std::string formatCriteria(const QualitySettings& settings) {
  std::string out =
      "# voxremesh quality criteria (include/voxremesh/criteria_file.h)\n"
      "# metric               ideal      good      warn      fail     worst    weight\n";
  char line[200];
  for (int c = 0; c < kCriterionCount; ++c) {
    const auto criterion = static_cast<Criterion>(c);
    const IndexThresholds& t = settings.index[std::size_t(c)];
    const auto field = limitField(criterion);
    const double values[] = {t.ideal, t.good, t.warn, field ? settings.*field : 0.0, t.worst};
    std::string text = criterionName(criterion);
    text.resize(18, ' ');
    for (const double value : values) {
      const auto absolute = absoluteLengthField(criterion);
      std::string word = numberText(value) + (absolute && !(settings.*absolute) ? "h" : "");
      text += std::string(word.size() < 10 ? 10 - word.size() : 1, ' ') + word;
    }
    std::snprintf(line, sizeof line, "%s%10s\n", text.c_str(), numberText(t.weight).c_str());
    out += line;
  }
  out += "tria_share        " + numberText(settings.maxTriangleShare) + "\n";
  out += "failing_share     " + numberText(settings.maxFailingShare) + "\n";
  out += std::string("jacobian_at       ") +
         (settings.jacobianAtGaussPoints ? "gauss_points" : "corners") + "\n";
  return out;
}

}  // namespace voxremesh
