// Fast, allocation-free scanning of deck text: whole-file loading, line iteration with line
// numbers, and number parsing that accepts the forms FE solvers write (Fortran D exponents,
// Nastran's implicit exponents like 1.-3, leading '+', surrounding blanks).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace voxremesh::io {

/// Reads a whole file into memory.
/// Throws InputError(file, 0) when it is not a regular file (a folder, device or pipe), or cannot
/// be opened or read.
std::string loadFile(const std::filesystem::path& path);

/// Throws InputError naming the line of the first NUL byte if `content` is not text (a binary
/// file given where a text deck is expected), and InputError "empty file" if it has no
/// non-blank character.
void requireText(std::string_view content, const std::filesystem::path& path);

/// Iterates over the lines of a text; a line excludes its terminator ("\n" or "\r\n").
class LineCursor {
 public:
  explicit LineCursor(std::string_view text) : text_(text) {}

  /// Moves to the next line; returns false at the end of the text.
  bool next();
  /// The current line without its terminator.
  std::string_view line() const { return line_; }
  /// The current line including its terminator, exactly as in the text.
  std::string_view rawLine() const { return text_.substr(begin_, end_ - begin_); }
  /// 1-based number of the current line.
  std::size_t lineNumber() const { return number_; }
  /// Offset of the current line's first byte in the text.
  std::size_t begin() const { return begin_; }
  /// Offset just past the current line's terminator.
  std::size_t end() const { return end_; }
  /// Goes back so that the current line is returned again by the next call to next().
  void pushBack();

 private:
  std::string_view text_;
  std::string_view line_;
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  std::size_t number_ = 0;
  bool pushedBack_ = false;
};

/// Removes leading and trailing blanks (space, tab, CR).
std::string_view trim(std::string_view s);

/// Returns `line.substr(start, width)` clipped to the line (empty past its end).
std::string_view field(std::string_view line, std::size_t start, std::size_t width);

/// Parses an integer field; surrounding blanks allowed. An empty field yields `fallback`.
/// Returns false when the field is not an integer (or does not fit).
bool parseInt(std::string_view text, std::int64_t& out, std::int64_t fallback = 0);

/// Parses a real field in any form solvers write: 1.5, -2e3, 1.5D+3, 1.-3, +.5, 7. Surrounding
/// blanks allowed. An empty field yields `fallback`. Returns false when the field is not a finite
/// number (NaN and infinities, which no solver accepts, are refused).
bool parseReal(std::string_view text, double& out, double fallback = 0.0);

/// Case-insensitive comparison of ASCII strings.
bool iequals(std::string_view a, std::string_view b);

/// Case-insensitive prefix test for ASCII strings.
bool istartsWith(std::string_view s, std::string_view prefix);

/// Returns an upper-case copy of an ASCII string.
std::string toUpper(std::string_view s);

/// Appends the shortest decimal text that reads back as exactly `value` (std::to_chars).
void appendShortest(std::string& out, double value);

/// Appends `value` right-aligned in exactly `width` characters, using the most significant digits
/// that fit (fixed notation when it fits, else scientific). Throws std::range_error if even the
/// shortest scientific form does not fit.
void appendRealFixedWidth(std::string& out, double value, int width);

/// Appends an integer right-aligned in `width` characters (wider when it does not fit).
void appendIntRight(std::string& out, std::int64_t value, int width);

}  // namespace voxremesh::io
