// LS-DYNA keyword format details shared by the reader and the writer: the field widths of the
// cards voxremesh reads and writes in each of the three card formats, keyword-line parsing, the
// *ELEMENT_SHELL options and the splitting of a data line into fields.
//
// Card formats (Ansys LS-DYNA; layouts as the keyword manual and Oasys PRIMER's format notes give):
//   standard  fields as the manual defines them per card (*NODE I8,3E16,2I8; *ELEMENT_SHELL 10I8;
//             *PART 8I10; the shell thickness card 5E16)
//   I10       "*KEYWORD I10=Y" or a '%' suffix on a keyword: fields narrower than 10 become 10
//   long      "*KEYWORD LONG=Y" or a '+' suffix on a keyword: fields narrower than 20 become 20
//   A '-' suffix selects the standard format for one keyword; LONG=S and LONG=K read standard
//   input.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace voxremesh::io::lsdyna {

/// The width class of a keyword's data fields.
enum class CardFormat : std::uint8_t { Standard, I10, Long };

/// What a field holds; Skip fields are split but not parsed.
enum class FieldKind : std::uint8_t { Int, Real, Skip };

/// The most fields any card voxremesh parses has (*ELEMENT_SHELL card 1).
constexpr std::size_t kMaxFields = 10;

/// The fields of one card: their widths in the fixed format, kinds and names for messages.
struct Layout {
  std::size_t count = 0;
  std::array<std::uint8_t, kMaxFields> widths{};
  std::array<FieldKind, kMaxFields> kinds{};
  std::array<const char*, kMaxFields> names{};
};

/// The cards voxremesh reads or writes.
enum class Card : std::uint8_t {
  Node,            ///< *NODE: nid x y z tc rc
  Shell,           ///< *ELEMENT_SHELL card 1: eid pid n1..n8
  ShellThickness,  ///< *ELEMENT_SHELL_THICKNESS/_BETA/_MCID card 2: thic1..thic4 beta-or-mcid
  ShellOffset,     ///< *ELEMENT_SHELL_OFFSET card: offset
  Part,            ///< *PART card 2: pid secid mid eosid hgid grav adpopt tmid (only pid parsed)
  PartInertia,     ///< *PART_INERTIA card 3: xc yc zc tm ircs nodeid (only ircs parsed)
};

/// Returns the layout of `card` in `format`.
const Layout& layout(Card card, CardFormat format);

/// A keyword line taken apart: "*ELEMENT_SHELL_THICKNESS %" -> name "*ELEMENT_SHELL_THICKNESS",
/// suffix I10.
struct KeywordLine {
  std::string name;                  ///< upper case, without a format suffix
  std::optional<CardFormat> suffix;  ///< '+' long, '%' I10, '-' standard
  std::size_t tokenEnd = 0;          ///< offset just past the keyword token in the line
};

/// True for a keyword line (first column '*').
inline bool isKeywordLine(std::string_view line) {
  return !line.empty() && line.front() == '*';
}

/// True for a comment line (first column '$').
inline bool isCommentLine(std::string_view line) {
  return !line.empty() && line.front() == '$';
}

/// Parses a keyword line. The format suffix may be attached to the keyword ("*NODE%") or be the
/// next blank-separated token ("*NODE %"). Precondition: isKeywordLine(line).
KeywordLine parseKeywordLine(std::string_view line);

/// The card format a *KEYWORD line selects with LONG=Y (long), LONG=S or LONG=K (standard) or
/// I10=Y (I10); nullopt when the line has no such option. Case-insensitive, blanks around '='.
std::optional<CardFormat> keywordLineFormat(std::string_view line);

/// The suffix text that selects `format` for one keyword: " +", " %" or " -".
const char* suffixText(CardFormat format);

/// The options of an *ELEMENT_SHELL keyword that voxremesh reads.
struct ShellOptions {
  bool thickness = false;
  bool beta = false;
  bool mcid = false;
  bool offset = false;
  /// True when each element has the thickness card (card 2).
  bool hasThicknessCard() const { return thickness || beta || mcid; }
};

/// Parses the option suffix of an *ELEMENT_SHELL keyword ("" or e.g. "_THICKNESS_OFFSET", upper
/// case, options in any order). Returns nullopt and sets `error` to a message naming the option
/// when an option is not supported (8-node, composite, DOF, ... shells) or options conflict.
std::optional<ShellOptions> parseShellOptions(std::string_view suffix, std::string& error);

/// The canonical suffix for options: "_THICKNESS", "_BETA", "_MCID", "_OFFSET", "_BETA_OFFSET", ...
std::string shellSuffix(const ShellOptions& options);

/// Splits a free-format data line at commas into at most `max` fields (blanks around each field
/// removed). Returns the number of fields found, which may exceed `max` (the rest are dropped).
std::size_t splitAtCommas(std::string_view line, std::string_view* fields, std::size_t max);

/// Splits a line at blanks (spaces, tabs) into at most `max` fields. Returns the number of
/// fields found, which may exceed `max` (the rest are dropped).
std::size_t splitAtBlanks(std::string_view line, std::string_view* fields, std::size_t max);

/// Splits a line into the fixed columns of `layout` (fields past the end of the line are empty).
void splitFixed(std::string_view line, const Layout& layout, std::string_view* fields);

/// The values of one parsed card, indexed by field.
struct CardValues {
  std::array<std::int64_t, kMaxFields> ints{};
  std::array<double, kMaxFields> reals{};
};

/// Parses a data line by `layout`: free format when it contains a comma (an empty field is 0),
/// else fixed columns, and when a fixed column does not parse (a column cut through a number, a
/// blank-separated line) the blank-separated fields instead.
/// Returns the index of the first field that does not parse (then `bad` is its text, from the
/// fixed-column reading), or -1 when all parse.
int parseCard(std::string_view line, const Layout& layout, CardValues& values,
              std::string_view& bad);

/// Number of characters `value` takes in decimal (with its sign).
int decimalWidth(std::int64_t value);

}  // namespace voxremesh::io::lsdyna
