#include "io/nastran_cards.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "io/text_scan.h"
#include "voxremesh/errors.h"

namespace voxremesh::io::nastran {

CardName cardName(std::string_view line) {
  const bool free = line.find(',') != std::string_view::npos;
  std::size_t end = line.find_first_of(" \t,*$");
  if (end == std::string_view::npos) end = line.size();
  if (!free && end > 8) end = 8;
  CardName result;
  result.name = line.substr(0, end);
  result.large = end < line.size() && line[end] == '*';
  return result;
}

bool isContinuationLine(std::string_view line) {
  if (line.empty()) return false;
  const char c = line[0];
  if (c != '+' && c != '*' && c != ',' && c != ' ' && c != '\t') return false;
  return !trim(line).empty();
}

bool isCommentOrBlank(std::string_view line) {
  return (!line.empty() && line[0] == '$') || trim(line).empty();
}

namespace {

/// Expands tabs to the next multiple of 8 columns.
std::string_view expandTabs(std::string_view line, std::string& scratch) {
  scratch.clear();
  for (const char c : line) {
    if (c == '\t') {
      scratch.append(8 - scratch.size() % 8, ' ');
    } else {
      scratch.push_back(c);
    }
  }
  return scratch;
}

void splitFree(std::string_view line, bool continuation, LineFields& out) {
  std::size_t entry = 0;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = line.find(',', begin);
    const std::string_view text = trim(line.substr(
        begin, comma == std::string_view::npos ? std::string_view::npos : comma - begin));
    if (entry == 0) {
      out.head = text;
      out.large = continuation ? (!text.empty() && text.front() == '*')
                               : text.find('*') != std::string_view::npos;
      out.count = out.large ? 4 : 8;
    } else if (entry <= out.count) {
      out.data[entry - 1] = text;
    } else if (entry == out.count + 1) {
      out.marker = text;
    } else if (!text.empty() && out.overflow.empty()) {
      out.overflow = text;
    }
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
    ++entry;
  }
}

void splitFixed(std::string_view line, bool continuation, LineFields& out) {
  out.head = trim(field(line, 0, 8));
  out.large = continuation ? (!out.head.empty() && out.head.front() == '*')
                           : out.head.find('*') != std::string_view::npos;
  if (out.large) {
    out.count = 4;
    for (std::size_t i = 0; i < 4; ++i) out.data[i] = trim(field(line, 8 + 16 * i, 16));
  } else {
    out.count = 8;
    for (std::size_t i = 0; i < 8; ++i) out.data[i] = trim(field(line, 8 + 8 * i, 8));
  }
  out.marker = trim(field(line, 72, 8));
}

std::string_view withoutLeadingFlag(std::string_view marker) {
  if (!marker.empty() && (marker.front() == '+' || marker.front() == '*')) marker.remove_prefix(1);
  return trim(marker);
}

}  // namespace

void splitLine(std::string_view line, bool continuation, LineFields& out, std::string& scratch) {
  out = LineFields{};
  const std::size_t dollar = line.find('$');
  if (dollar != std::string_view::npos) line = line.substr(0, dollar);
  if (line.find(',') != std::string_view::npos) {
    out.free = true;
    splitFree(line, continuation, out);
    return;
  }
  if (line.find('\t') != std::string_view::npos) line = expandTabs(line, scratch);
  splitFixed(line, continuation, out);
}

bool markersMatch(std::string_view parentMarker, std::string_view continuationMarker) {
  const std::string_view a = withoutLeadingFlag(parentMarker);
  const std::string_view b = withoutLeadingFlag(continuationMarker);
  return a.empty() || b.empty() || iequals(a, b);
}

void CardFields::start(const std::string* file, std::size_t lineNumber, std::string_view line) {
  file_ = file;
  fields_.clear();
  lineOf_.clear();
  lines_.assign(1, line);
  lineNumbers_.assign(1, lineNumber);
  if (scratch_.empty()) scratch_.emplace_back();
  splitLine(line, false, split_, scratch_[0]);
  append(split_, 0);
}

void CardFields::addContinuation(std::size_t lineNumber, std::string_view line) {
  const std::size_t index = lines_.size();
  lines_.push_back(line);
  lineNumbers_.push_back(lineNumber);
  if (scratch_.size() <= index) scratch_.emplace_back();
  splitLine(line, true, split_, scratch_[index]);
  if (!markersMatch(lastMarker_, split_.head))
    throw InputError(*file_, lineNumber,
                     "continuation marker '" + std::string(split_.head) + "' does not match '" +
                         std::string(lastMarker_) +
                         "' in field 10 of the line before; continuation lines out of order are "
                         "not supported (keep each continuation right after its card)",
                     std::string(line));
  append(split_, index);
}

void CardFields::append(const LineFields& fields, std::size_t lineIndex) {
  if (!fields.overflow.empty())
    throw InputError(*file_, lineNumbers_[lineIndex],
                     "free-field line with data beyond field 10 ('" + std::string(fields.overflow) +
                         "'); put fields after the 9th on a continuation line",
                     std::string(lines_[lineIndex]));
  // A small-field line starts a new group of 8; a large-field line fills half of one.
  const std::size_t target = fields.large ? fields_.size() : (fields_.size() + 7) / 8 * 8;
  fields_.resize(target);
  lineOf_.resize(target, lineIndex);
  for (std::size_t i = 0; i < fields.count; ++i) {
    fields_.push_back(fields.data[i]);
    lineOf_.push_back(lineIndex);
  }
  lastMarker_ = fields.marker;
}

namespace {

/// Rewrites a number as std::to_chars writes it ("1e-05", "0.25", "12") in Nastran's form
/// ("1.-5", ".25", "12."). Returns the length written to `out`.
std::size_t toNastranForm(const char* text, std::size_t length, char* out) {
  const char* exponent = static_cast<const char*>(std::memchr(text, 'e', length));
  const std::size_t mantissaLength = exponent ? static_cast<std::size_t>(exponent - text) : length;
  std::size_t n = 0;
  std::size_t i = 0;
  if (i < mantissaLength && text[i] == '-') out[n++] = text[i++];
  // "0.xxx" -> ".xxx" (but zero itself stays "0.")
  if (mantissaLength - i >= 3 && text[i] == '0' && text[i + 1] == '.') ++i;
  bool hasPoint = false;
  for (; i < mantissaLength; ++i) {
    hasPoint = hasPoint || text[i] == '.';
    out[n++] = text[i];
  }
  if (!hasPoint) out[n++] = '.';
  if (exponent) {
    std::size_t j = 1;  // past 'e'
    const std::size_t rest = length - mantissaLength;
    out[n++] = (j < rest && exponent[j] == '-') ? '-' : '+';
    if (j < rest && (exponent[j] == '-' || exponent[j] == '+')) ++j;
    while (j + 1 < rest && exponent[j] == '0') ++j;
    for (; j < rest; ++j) out[n++] = exponent[j];
  }
  return n;
}

/// Drops zeros at the end of a mantissa ("1.2500" -> "1.25", "3.0-5" -> "3.-5"): they carry no
/// digits. Returns the new length.
std::size_t dropTrailingZeros(char* text, std::size_t length) {
  std::size_t mantissaEnd = length;
  for (std::size_t i = 1; i < length; ++i)
    if (text[i] == '+' || text[i] == '-') {
      mantissaEnd = i;
      break;
    }
  const char* point = static_cast<const char*>(std::memchr(text, '.', mantissaEnd));
  if (!point) return length;
  std::size_t end = mantissaEnd;
  while (end > static_cast<std::size_t>(point - text) + 1 && text[end - 1] == '0') --end;
  if (end == mantissaEnd) return length;
  std::memmove(text + end, text + mantissaEnd, length - mantissaEnd);
  return end + (length - mantissaEnd);
}

/// Significant digits of a number text (leading zeros and exponent digits not counted).
int significantDigits(const char* text, std::size_t length) {
  int digits = 0;
  bool leading = true;
  for (std::size_t i = 0; i < length; ++i) {
    const char c = text[i];
    if (c == '.') continue;
    if ((c == '+' || c == '-') && i > 0) break;  // exponent
    if (c < '0' || c > '9') continue;
    if (leading && c == '0') continue;
    leading = false;
    ++digits;
  }
  return digits;
}

/// The fixed-notation form with the most digits that fits `width`; returns its length or 0.
std::size_t fixedCandidate(double value, int width, char* out) {
  const double magnitude = std::fabs(value);
  const int sign = value < 0 ? 1 : 0;
  const int integerDigits =
      magnitude >= 1.0 ? static_cast<int>(std::floor(std::log10(magnitude))) + 1 : 0;
  char text[400];
  for (int precision = width - sign - integerDigits - 1; precision >= 0; --precision) {
    const auto result =
        std::to_chars(text, text + sizeof text, value, std::chars_format::fixed, precision);
    if (result.ec != std::errc()) return 0;
    const std::size_t length =
        toNastranForm(text, static_cast<std::size_t>(result.ptr - text), out);
    if (static_cast<int>(length) <= width) return dropTrailingZeros(out, length);
  }
  return 0;
}

/// The compact scientific form with the most digits that fits `width`; returns its length or 0.
std::size_t scientificCandidate(double value, int width, char* out) {
  const int sign = value < 0 ? 1 : 0;
  const int exponent =
      value == 0.0 ? 0 : static_cast<int>(std::floor(std::log10(std::fabs(value))));
  const int exponentLength = 1 + (std::abs(exponent) >= 100 ? 3 : std::abs(exponent) >= 10 ? 2 : 1);
  char text[64];
  for (int precision = width - sign - 2 - exponentLength + 1; precision >= 0; --precision) {
    const auto result =
        std::to_chars(text, text + sizeof text, value, std::chars_format::scientific, precision);
    if (result.ec != std::errc()) return 0;
    const std::size_t length =
        toNastranForm(text, static_cast<std::size_t>(result.ptr - text), out);
    if (static_cast<int>(length) <= width) return dropTrailingZeros(out, length);
  }
  return 0;
}

std::size_t shortestForm(double value, char* out) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return toNastranForm(text, static_cast<std::size_t>(result.ptr - text), out);
}

}  // namespace

std::size_t formatReal(double value, int width, char* buffer) {
  if (!std::isfinite(value))
    throw std::range_error("cannot write the non-finite value " + std::to_string(value) +
                           " as a Nastran real");
  const std::size_t exact = shortestForm(value, buffer);
  if (static_cast<int>(exact) <= width) return exact;
  char fixed[64];
  char scientific[64];
  const std::size_t fixedLength = fixedCandidate(value, width, fixed);
  const std::size_t scientificLength = scientificCandidate(value, width, scientific);
  const bool useFixed = fixedLength > 0 && (scientificLength == 0 ||
                                            significantDigits(fixed, fixedLength) >=
                                                significantDigits(scientific, scientificLength));
  if (useFixed) {
    std::memcpy(buffer, fixed, fixedLength);
    return fixedLength;
  }
  if (scientificLength == 0)
    throw std::range_error("value " + std::to_string(value) + " does not fit in " +
                           std::to_string(width) + " characters");
  std::memcpy(buffer, scientific, scientificLength);
  return scientificLength;
}

bool fitsExactly(double value, int width) {
  if (!std::isfinite(value)) return false;
  char buffer[64];
  return static_cast<int>(shortestForm(value, buffer)) <= width;
}

void appendReal(std::string& out, double value, int width) {
  char buffer[64];
  const std::size_t length = formatReal(value, width, buffer);
  if (static_cast<int>(length) < width) out.append(static_cast<std::size_t>(width) - length, ' ');
  out.append(buffer, length);
}

}  // namespace voxremesh::io::nastran
