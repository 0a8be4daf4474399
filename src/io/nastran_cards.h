// Nastran bulk data entries ("cards") at the level of lines and fields, shared by the reader and
// the writer: the card name of a line, splitting small-field (8 columns), large-field (16 columns)
// and free-field (comma separated) lines into fields, collecting the fields of a card with its
// continuation lines in small-field numbering, and writing reals in Nastran's fixed-width forms.
//
// Field numbering follows the Quick Reference Guide: field 1 holds the name (or, on a continuation
// line, the continuation marker), fields 2-9 hold data, field 10 the continuation marker. A
// large-field line holds half of that (4 data fields of 16 columns), so two large-field lines make
// one small-field line. CardFields numbers the data fields of a whole card from 0: data field k is
// field (k % 8) + 2 of the (k / 8)-th small-field line.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

namespace voxremesh::io::nastran {

/// The name in field 1 of a line that starts a card.
struct CardName {
  std::string_view name;  ///< as written (any case), without the large-field '*'
  bool large = false;     ///< the name is followed by '*': large-field format
};

/// Returns the card name of a line that starts a card: the characters up to the first blank, tab,
/// ',', '*' or '$' (at most 8 for a fixed-format line).
CardName cardName(std::string_view line);

/// True for a line that continues the previous card: its first character is '+', '*', ',', a blank
/// or a tab and it holds more than blanks.
bool isContinuationLine(std::string_view line);

/// True for a comment line ('$' in column 1) or a line of blanks only.
bool isCommentOrBlank(std::string_view line);

/// The fields of one physical line.
struct LineFields {
  std::string_view head;                 ///< field 1 (name or continuation marker), trimmed
  std::array<std::string_view, 8> data;  ///< data fields, trimmed; 4 used on large-field lines
  std::size_t count = 0;                 ///< data fields this line provides: 8 (small) or 4 (large)
  std::string_view marker;               ///< field 10 (continuation marker), trimmed
  bool large = false;                    ///< 16-column (or large free-field) line
  bool free = false;                     ///< comma-separated line
  std::string_view overflow;             ///< first non-blank free field beyond field 10, if any
};

/// Splits one physical line into fields. Text from the first '$' on is a comment and ignored, as
/// are columns past 80 of a fixed-format line. Tabs in a fixed-format line advance to the next
/// multiple of 8 columns; the expanded text is kept in `scratch`, which must outlive the views.
/// @param continuation  the line continues a card: a leading '*' means large field; otherwise
///                      large field is a '*' after the card name
void splitLine(std::string_view line, bool continuation, LineFields& out, std::string& scratch);

/// True when two continuation markers (field 10 of a line and field 1 of the next) belong
/// together: equal apart from a leading '+' or '*', compared case-insensitively, or either blank.
bool markersMatch(std::string_view parentMarker, std::string_view continuationMarker);

/// Collects the data fields of one card over its continuation lines, in small-field numbering,
/// as many as the card has (a SET1 or SPC1 may list hundreds of grids). Reports malformed
/// structure as InputError naming the file and line. Its storage is kept from card to card.
class CardFields {
 public:
  /// Starts a card with its first line.
  /// @param file  the file name for error messages (must outlive this object's use)
  /// Throws InputError for a free-field line with data beyond field 10.
  void start(const std::string* file, std::size_t lineNumber, std::string_view line);

  /// Adds a continuation line.
  /// Throws InputError when its marker does not match field 10 of the previous line, or for a
  /// free-field line with data beyond field 10.
  void addContinuation(std::size_t lineNumber, std::string_view line);

  /// Data field k, trimmed; empty past the fields given.
  std::string_view operator[](std::size_t k) const {
    return k < fields_.size() ? fields_[k] : std::string_view{};
  }
  /// Number of data fields collected (blank ones included).
  std::size_t size() const { return fields_.size(); }
  /// Line number of data field k (of the first line when k is past the fields given).
  std::size_t lineOf(std::size_t k) const {
    return k < fields_.size() ? lineNumbers_[lineOf_[k]] : firstLine();
  }
  /// Text of the line holding data field k (the first line when k is past the fields given).
  std::string_view lineTextOf(std::size_t k) const {
    return k < fields_.size() ? lines_[lineOf_[k]] : lines_[0];
  }
  /// Line number and text of the card's first line.
  std::size_t firstLine() const { return lineNumbers_[0]; }
  std::string_view firstText() const { return lines_[0]; }
  /// Field 10 of the last line: a continuation the card announces.
  std::string_view pendingMarker() const { return lastMarker_; }
  /// True when the last line was the first half of a large-field pair.
  bool endsInHalfLine() const { return fields_.size() % 8 == 4; }

 private:
  /// Appends the data fields of a split line (a small-field line starts a new group of 8).
  void append(const LineFields& fields, std::size_t lineIndex);

  const std::string* file_ = nullptr;
  std::vector<std::string_view> fields_;
  std::vector<std::size_t> lineOf_;  ///< per field, its line's index in lines_
  std::vector<std::string_view> lines_;
  std::vector<std::size_t> lineNumbers_;
  /// Per line, its tab-expanded text (splitLine); a deque, so that the views into earlier lines'
  /// text stay valid while lines are added.
  std::deque<std::string> scratch_;
  std::string_view lastMarker_;
  LineFields split_;
};

/// Writes `value` into `buffer` as a Nastran real of at most `width` characters: always with a
/// decimal point, exponents in the compact form Nastran reads ("1.5-3" for 1.5e-3, "2.+12"), and
/// the most significant digits that fit. Returns the length.
/// Preconditions: 8 <= width <= 32; buffer holds at least 32 characters.
/// Throws std::range_error for NaN or infinity.
std::size_t formatReal(double value, int width, char* buffer);

/// True when formatReal writes `value` in `width` characters without rounding it.
bool fitsExactly(double value, int width);

/// Appends formatReal(value, width) right-aligned in exactly `width` characters.
void appendReal(std::string& out, double value, int width);

}  // namespace voxremesh::io::nastran
