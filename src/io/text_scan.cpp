#include "io/text_scan.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "voxremesh/errors.h"

namespace voxremesh::io {

std::string loadFile(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::exists(path, error) && !std::filesystem::is_regular_file(path, error))
    throw InputError(path.string(), 0, "not a regular file (a folder, a device or a pipe)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "cannot open file");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw InputError(path.string(), 0, "cannot read file");
  std::string content(static_cast<std::size_t>(size), '\0');
  in.seekg(0, std::ios::beg);
  if (size > 0 && !in.read(content.data(), size))
    throw InputError(path.string(), 0, "cannot read file");
  return content;
}

void requireText(std::string_view content, const std::filesystem::path& path) {
  const std::size_t nul = content.find('\0');
  if (nul != std::string_view::npos) {
    std::size_t line = 1;
    for (std::size_t i = 0; i < nul; ++i) line += content[i] == '\n';
    throw InputError(path.string(), line, "binary data in a text deck (NUL byte)");
  }
  if (trim(content).find_first_not_of(" \t\r\n") == std::string_view::npos)
    throw InputError(path.string(), 0, "empty file");
}

bool LineCursor::next() {
  if (pushedBack_) {
    pushedBack_ = false;
    return true;
  }
  if (end_ >= text_.size()) return false;
  begin_ = end_;
  const std::size_t newline = text_.find('\n', begin_);
  std::size_t stop = newline == std::string_view::npos ? text_.size() : newline;
  end_ = newline == std::string_view::npos ? text_.size() : newline + 1;
  if (stop > begin_ && text_[stop - 1] == '\r') --stop;
  line_ = text_.substr(begin_, stop - begin_);
  ++number_;
  return true;
}

void LineCursor::pushBack() {
  pushedBack_ = true;
}

std::string_view trim(std::string_view s) {
  std::size_t b = 0;
  std::size_t e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t' || s[b] == '\r')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == '\r')) --e;
  return s.substr(b, e - b);
}

std::string_view field(std::string_view line, std::size_t start, std::size_t width) {
  if (start >= line.size()) return {};
  return line.substr(start, width);
}

bool parseInt(std::string_view text, std::int64_t& out, std::int64_t fallback) {
  text = trim(text);
  if (text.empty()) {
    out = fallback;
    return true;
  }
  if (text.front() == '+') text.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && ptr == text.data() + text.size();
}

bool parseReal(std::string_view text, double& out, double fallback) {
  text = trim(text);
  if (text.empty()) {
    out = fallback;
    return true;
  }
  if (text.front() == '+') text.remove_prefix(1);
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, out);
  if (ec == std::errc() && ptr == end) return std::isfinite(out);  // "nan", "inf": no number
  // Rewrite Fortran and Nastran forms into a plain one: D exponents, implicit exponents.
  char buffer[80];
  if (text.size() + 2 > sizeof buffer) return false;
  std::size_t n = 0;
  bool seenDigit = false;
  bool seenExponent = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (c == 'D' || c == 'd' || c == 'E') c = 'e';
    if (c == 'e') {
      if (seenExponent || !seenDigit) return false;
      seenExponent = true;
    } else if ((c == '+' || c == '-') && i > 0 && !seenExponent) {
      if (!seenDigit) return false;
      buffer[n++] = 'e';  // implicit exponent: 1.-3 means 1.e-3
      seenExponent = true;
    } else if (c >= '0' && c <= '9') {
      seenDigit = true;
    } else if ((c == '+' || c == '-') && n > 0 && buffer[n - 1] == 'e') {
      // the sign of an explicit exponent
    } else if (c != '.' && !(c == '-' && i == 0)) {
      return false;
    }
    buffer[n++] = c;
  }
  const auto rewritten = std::from_chars(buffer, buffer + n, out);
  return rewritten.ec == std::errc() && rewritten.ptr == buffer + n;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i];
    char y = b[i];
    if (x >= 'a' && x <= 'z') x = static_cast<char>(x - 'a' + 'A');
    if (y >= 'a' && y <= 'z') y = static_cast<char>(y - 'a' + 'A');
    if (x != y) return false;
  }
  return true;
}

bool istartsWith(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && iequals(s.substr(0, prefix.size()), prefix);
}

std::string toUpper(std::string_view s) {
  std::string result(s);
  for (char& c : result)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return result;
}

void appendShortest(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

namespace {

/// Writes `value` with `precision` in `format` into buffer; returns the length or 0 on failure.
std::size_t formatReal(char* buffer, std::size_t capacity, double value, std::chars_format format,
                       int precision) {
  const auto result = std::to_chars(buffer, buffer + capacity, value, format, precision);
  return result.ec == std::errc() ? static_cast<std::size_t>(result.ptr - buffer) : 0;
}

void appendRightAligned(std::string& out, const char* text, std::size_t length, int width) {
  if (static_cast<int>(length) < width) out.append(static_cast<std::size_t>(width) - length, ' ');
  out.append(text, length);
}

}  // namespace

void appendRealFixedWidth(std::string& out, double value, int width) {
  // The shortest exact form first: it reads back bit for bit.
  char text[64];
  const auto exact = std::to_chars(text, text + sizeof text, value);
  const std::size_t exactLength = static_cast<std::size_t>(exact.ptr - text);
  if (static_cast<int>(exactLength) <= width) {
    appendRightAligned(out, text, exactLength, width);
    return;
  }
  // Otherwise as many digits as fit. Fixed notation keeps more significant digits than
  // scientific from 0.01 up to the magnitude where no decimal digit would be left; the precision
  // is computed, not searched (one retry when rounding carries into a new digit).
  const int sign = value < 0 ? 1 : 0;
  const double magnitude = std::fabs(value);
  if (std::isfinite(value) && magnitude >= 1e-2 && magnitude < std::pow(10.0, width - sign - 3)) {
    int intDigits = magnitude < 1 ? 1 : static_cast<int>(std::floor(std::log10(magnitude))) + 1;
    for (int attempt = 0; attempt < 2; ++attempt, ++intDigits) {
      const int precision = width - sign - intDigits - 1;
      const std::size_t length =
          formatReal(text, sizeof text, value, std::chars_format::fixed, precision);
      if (length > 0 && static_cast<int>(length) <= width) {
        appendRightAligned(out, text, length, width);
        return;
      }
    }
  }
  const int exponent = magnitude == 0 ? 0 : static_cast<int>(std::floor(std::log10(magnitude)));
  int exponentLength = std::abs(exponent) >= 100 ? 5 : 4;  // "e-05", "e+100"
  for (int attempt = 0; attempt < 2; ++attempt, ++exponentLength) {
    const int precision = width - sign - 2 - exponentLength;
    if (precision < 0) break;
    const std::size_t length =
        formatReal(text, sizeof text, value, std::chars_format::scientific, precision);
    if (length > 0 && static_cast<int>(length) <= width) {
      appendRightAligned(out, text, length, width);
      return;
    }
  }
  throw std::range_error("value " + std::to_string(value) + " does not fit in " +
                         std::to_string(width) + " characters");
}

void appendIntRight(std::string& out, std::int64_t value, int width) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  appendRightAligned(out, buffer, static_cast<std::size_t>(result.ptr - buffer), width);
}

}  // namespace voxremesh::io
