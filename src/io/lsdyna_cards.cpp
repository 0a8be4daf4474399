#include "io/lsdyna_cards.h"

#include "io/text_scan.h"

namespace voxremesh::io::lsdyna {

namespace {

using K = FieldKind;

/// Builds a layout whose fields all have one width.
Layout uniform(std::size_t count, std::uint8_t width, std::array<FieldKind, kMaxFields> kinds,
               std::array<const char*, kMaxFields> names) {
  Layout result;
  result.count = count;
  for (std::size_t i = 0; i < count; ++i) result.widths[i] = width;
  result.kinds = kinds;
  result.names = names;
  return result;
}

Layout withWidths(Layout base, std::array<std::uint8_t, kMaxFields> widths) {
  base.widths = widths;
  return base;
}

constexpr std::array<const char*, kMaxFields> kNodeNames{
    "node ID", "x coordinate", "y coordinate", "z coordinate", "TC", "RC"};
constexpr std::array<FieldKind, kMaxFields> kNodeKinds{K::Int,  K::Real, K::Real,
                                                       K::Real, K::Int,  K::Int};
constexpr std::array<const char*, kMaxFields> kShellNames{
    "element ID", "part ID", "node N1", "node N2", "node N3",
    "node N4",    "node N5", "node N6", "node N7", "node N8"};
constexpr std::array<FieldKind, kMaxFields> kShellKinds{K::Int, K::Int, K::Int, K::Int, K::Int,
                                                        K::Int, K::Int, K::Int, K::Int, K::Int};
constexpr std::array<const char*, kMaxFields> kThicknessNames{
    "thickness THIC1", "thickness THIC2", "thickness THIC3", "thickness THIC4", "BETA/MCID"};
constexpr std::array<FieldKind, kMaxFields> kThicknessKinds{K::Real, K::Real, K::Real, K::Real,
                                                            K::Real};
constexpr std::array<const char*, kMaxFields> kPartNames{"part ID", "SECID", "MID",    "EOSID",
                                                         "HGID",    "GRAV",  "ADPOPT", "TMID"};
constexpr std::array<FieldKind, kMaxFields> kPartKinds{K::Int,  K::Skip, K::Skip, K::Skip,
                                                       K::Skip, K::Skip, K::Skip, K::Skip};
constexpr std::array<const char*, kMaxFields> kInertiaNames{"XC", "YC",   "ZC",
                                                            "TM", "IRCS", "NODEID"};
constexpr std::array<FieldKind, kMaxFields> kInertiaKinds{K::Skip, K::Skip, K::Skip,
                                                          K::Skip, K::Int,  K::Skip};

struct Layouts {
  // [card][format]
  std::array<std::array<Layout, 3>, 6> table;
  Layouts() {
    const Layout node = uniform(6, 0, kNodeKinds, kNodeNames);
    table[0] = {withWidths(node, {8, 16, 16, 16, 8, 8}), withWidths(node, {10, 16, 16, 16, 10, 10}),
                withWidths(node, {20, 20, 20, 20, 20, 20})};
    table[1] = {uniform(10, 8, kShellKinds, kShellNames), uniform(10, 10, kShellKinds, kShellNames),
                uniform(10, 20, kShellKinds, kShellNames)};
    table[2] = {uniform(5, 16, kThicknessKinds, kThicknessNames),
                uniform(5, 16, kThicknessKinds, kThicknessNames),
                uniform(5, 20, kThicknessKinds, kThicknessNames)};
    const std::array<FieldKind, kMaxFields> offsetKind{K::Real};
    const std::array<const char*, kMaxFields> offsetName{"OFFSET"};
    table[3] = {uniform(1, 16, offsetKind, offsetName), uniform(1, 16, offsetKind, offsetName),
                uniform(1, 20, offsetKind, offsetName)};
    table[4] = {uniform(8, 10, kPartKinds, kPartNames), uniform(8, 10, kPartKinds, kPartNames),
                uniform(8, 20, kPartKinds, kPartNames)};
    table[5] = {uniform(6, 10, kInertiaKinds, kInertiaNames),
                uniform(6, 10, kInertiaKinds, kInertiaNames),
                uniform(6, 20, kInertiaKinds, kInertiaNames)};
  }
};

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

std::optional<CardFormat> suffixFormat(char c) {
  switch (c) {
    case '+':
      return CardFormat::Long;
    case '%':
      return CardFormat::I10;
    case '-':
      return CardFormat::Standard;
    default:
      return std::nullopt;
  }
}

/// Parses the fields of a split card; returns the first bad index or -1.
int parseFields(const std::string_view* fields, const Layout& layout, CardValues& values) {
  for (std::size_t i = 0; i < layout.count; ++i) {
    switch (layout.kinds[i]) {
      case FieldKind::Int:
        if (!parseInt(fields[i], values.ints[i])) return static_cast<int>(i);
        break;
      case FieldKind::Real:
        if (!parseReal(fields[i], values.reals[i])) return static_cast<int>(i);
        break;
      case FieldKind::Skip:
        break;
    }
  }
  return -1;
}

/// The value of option `name` ("LONG", "I10") in a *KEYWORD line, upper case, or 0.
char optionValue(const std::string& upper, std::string_view name) {
  std::size_t at = 0;
  while ((at = upper.find(name, at)) != std::string::npos) {
    const bool startsToken = at == 0 || isBlank(upper[at - 1]);
    std::size_t i = at + name.size();
    at = i;
    if (!startsToken) continue;
    while (i < upper.size() && isBlank(upper[i])) ++i;
    if (i >= upper.size() || upper[i] != '=') continue;
    ++i;
    while (i < upper.size() && isBlank(upper[i])) ++i;
    if (i < upper.size()) return upper[i];
  }
  return 0;
}

}  // namespace

const Layout& layout(Card card, CardFormat format) {
  static const Layouts layouts;
  return layouts.table[static_cast<std::size_t>(card)][static_cast<std::size_t>(format)];
}

KeywordLine parseKeywordLine(std::string_view line) {
  KeywordLine result;
  std::size_t end = 0;
  while (end < line.size() && !isBlank(line[end])) ++end;
  result.tokenEnd = end;
  std::string_view token = line.substr(0, end);
  if (token.size() > 1) {
    if (auto format = suffixFormat(token.back())) {
      result.suffix = format;
      token.remove_suffix(1);
    }
  }
  if (!result.suffix) {
    std::size_t next = end;
    while (next < line.size() && isBlank(line[next])) ++next;
    if (next < line.size() && (next + 1 == line.size() || isBlank(line[next + 1])))
      result.suffix = suffixFormat(line[next]);
  }
  result.name = toUpper(token);
  return result;
}

std::optional<CardFormat> keywordLineFormat(std::string_view line) {
  const std::string upper = toUpper(line);
  const char longValue = optionValue(upper, "LONG");
  if (longValue == 'Y') return CardFormat::Long;
  if (optionValue(upper, "I10") == 'Y') return CardFormat::I10;
  if (longValue == 'S' || longValue == 'K') return CardFormat::Standard;
  return std::nullopt;
}

const char* suffixText(CardFormat format) {
  switch (format) {
    case CardFormat::Long:
      return " +";
    case CardFormat::I10:
      return " %";
    case CardFormat::Standard:
      break;
  }
  return " -";
}

std::optional<ShellOptions> parseShellOptions(std::string_view suffix, std::string& error) {
  ShellOptions options;
  while (!suffix.empty()) {
    if (suffix.front() != '_') {
      error = "malformed *ELEMENT_SHELL option '" + std::string(suffix) + "'";
      return std::nullopt;
    }
    suffix.remove_prefix(1);
    const std::size_t end = suffix.find('_');
    const std::string_view option = suffix.substr(0, end);
    suffix = end == std::string_view::npos ? std::string_view() : suffix.substr(end);
    bool* flag = nullptr;
    if (option == "THICKNESS") flag = &options.thickness;
    if (option == "BETA") flag = &options.beta;
    if (option == "MCID") flag = &options.mcid;
    if (option == "OFFSET") flag = &options.offset;
    if (!flag) {
      error = "*ELEMENT_SHELL option _" + std::string(option) +
              " is not supported (voxremesh reads *ELEMENT_SHELL with the options _THICKNESS, "
              "_BETA, _MCID and _OFFSET)";
      return std::nullopt;
    }
    if (*flag) {
      error = "*ELEMENT_SHELL option _" + std::string(option) + " is given twice";
      return std::nullopt;
    }
    *flag = true;
  }
  if (options.beta && options.mcid) {
    error = "*ELEMENT_SHELL options _BETA and _MCID exclude each other";
    return std::nullopt;
  }
  return options;
}

std::string shellSuffix(const ShellOptions& options) {
  std::string suffix;
  if (options.thickness && !options.beta && !options.mcid) suffix += "_THICKNESS";
  if (options.beta) suffix += "_BETA";
  if (options.mcid) suffix += "_MCID";
  if (options.offset) suffix += "_OFFSET";
  return suffix;
}

std::size_t splitAtCommas(std::string_view line, std::string_view* fields, std::size_t max) {
  std::size_t count = 0;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string_view piece = line.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    if (count < max) fields[count] = trim(piece);
    ++count;
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return count;
}

std::size_t splitAtBlanks(std::string_view line, std::string_view* fields, std::size_t max) {
  std::size_t count = 0;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isBlank(line[i])) ++i;
    if (i >= line.size()) break;
    const std::size_t start = i;
    while (i < line.size() && !isBlank(line[i])) ++i;
    if (count < max) fields[count] = line.substr(start, i - start);
    ++count;
  }
  return count;
}

void splitFixed(std::string_view line, const Layout& layout, std::string_view* fields) {
  std::size_t start = 0;
  for (std::size_t i = 0; i < layout.count; ++i) {
    fields[i] = field(line, start, layout.widths[i]);
    start += layout.widths[i];
  }
}

int parseCard(std::string_view line, const Layout& layout, CardValues& values,
              std::string_view& bad) {
  std::array<std::string_view, kMaxFields> fields{};
  if (line.find(',') != std::string_view::npos) {
    splitAtCommas(line, fields.data(), layout.count);
    const int failed = parseFields(fields.data(), layout, values);
    if (failed >= 0) bad = fields[static_cast<std::size_t>(failed)];
    return failed;
  }
  splitFixed(line, layout, fields.data());
  const int failed = parseFields(fields.data(), layout, values);
  if (failed < 0) return -1;
  std::array<std::string_view, kMaxFields> tokens{};
  const std::size_t count = splitAtBlanks(line, tokens.data(), layout.count);
  if (count <= layout.count && parseFields(tokens.data(), layout, values) < 0) return -1;
  bad = fields[static_cast<std::size_t>(failed)];
  return failed;
}

int decimalWidth(std::int64_t value) {
  int width = value < 0 ? 2 : 1;
  std::uint64_t magnitude =
      value < 0 ? 0 - static_cast<std::uint64_t>(value) : static_cast<std::uint64_t>(value);
  while (magnitude >= 10) {
    magnitude /= 10;
    ++width;
  }
  return width;
}

}  // namespace voxremesh::io::lsdyna
