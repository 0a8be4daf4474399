// Abaqus input syntax shared by the reader and the writer (src/io/abaqus_read.cpp,
// abaqus_write.cpp): element type classes, label quoting, the comment that keeps part IDs.
// Header-only, internal to src/io.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace voxremesh::io::abaqus {

/// The comment our writer puts before each element block: `** voxremesh part <id> "<name>"`.
inline constexpr std::string_view kPartComment = "** voxremesh part ";

/// What an *ELEMENT TYPE means to voxremesh.
enum class ElementClass {
  Shell3,       ///< a 3-node surface element (S3R, M3D3, R3D3, ...): read as a triangle
  Shell4,       ///< a 4-node surface element (S4R, M3D4, R3D4, ...): read as a quadrilateral
  HigherShell,  ///< a surface element with midside nodes (S8R, STRI65, M3D8, ...): refused
  Other,        ///< any other Abaqus element (solids, beams, springs, ...): kept verbatim
  Unknown       ///< not an Abaqus element type name
};

/// Classifies an element type name given in upper case.
/// The 3- and 4-node surface types are those of the Abaqus conventional shell, membrane, surface
/// and 3D rigid element libraries; other names are recognised by the prefix of their family.
inline ElementClass classifyElementType(std::string_view type) {
  static constexpr std::string_view kShell3[] = {"S3",   "S3R",  "S3RS",  "STRI3",
                                                 "M3D3", "R3D3", "SFM3D3"};
  static constexpr std::string_view kShell4[] = {"S4",   "S4R",   "S4RS", "S4RSW",  "S4R5",
                                                 "M3D4", "M3D4R", "R3D4", "SFM3D4", "SFM3D4R"};
  static constexpr std::string_view kHigher[] = {"STRI65", "S8R",    "S8R5",   "S9R5",
                                                 "M3D6",   "M3D8",   "M3D8R",  "M3D9",
                                                 "M3D9R",  "SFM3D6", "SFM3D8", "SFM3D8R"};
  for (std::string_view name : kShell3)
    if (type == name) return ElementClass::Shell3;
  for (std::string_view name : kShell4)
    if (type == name) return ElementClass::Shell4;
  for (std::string_view name : kHigher)
    if (type == name) return ElementClass::HigherShell;
  if (type.empty()) return ElementClass::Unknown;
  for (char c : type)
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'))) return ElementClass::Unknown;
  // Element families of the Abaqus element libraries, by the prefix of their names.
  static constexpr std::string_view kFamilies[] = {
      "AC1D",  "AC2D",    "AC3D",    "ACAX",  "ACIN",  "ASI",     "B21",    "B22",   "B23",
      "B31",   "B32",     "B33",     "C3D",   "CAX",   "CCL",     "CGAX",   "CINAX", "CINPE",
      "CINPS", "CIN3D",   "COH2D",   "COH3D", "COHAX", "CONN2D",  "CONN3D", "CPE",   "CPEG",
      "CPS",   "CSS",     "DASHPOT", "DC1D",  "DC2D",  "DC3D",    "DCAX",   "DCC",   "DCOUP",
      "DGAP",  "DRAG",    "DS",      "DSAX",  "EC3D",  "ELBOW",   "EMC",    "F2D",   "F3D",
      "FAX",   "FC3D",    "FRAME",   "GAP",   "GK",    "HEATCAP", "IRS",    "ISL",   "ITS",
      "ITT",   "JOINT",   "KCOUP",   "LAX",   "LS",    "M3D",     "MASS",   "MAX",   "MCL",
      "MGAX",  "PC3D",    "PIPE",    "PSI",   "Q3D",   "R2D",     "R3D",    "RAX",   "RB2D",
      "RB3D",  "ROTARYI", "S3",      "S4",    "S8",    "S9",      "SAX",    "SC6",   "SC8",
      "SFM",   "SPRING",  "STRI",    "T2D",   "T3D",   "TAX",     "U",      "VU",    "WARP"};
  for (std::string_view family : kFamilies)
    if (type.substr(0, family.size()) == family) {
      // User elements are U<number> / VU<number>.
      if ((family == "U" || family == "VU") &&
          (type.size() == family.size() || type[family.size()] < '0' || type[family.size()] > '9'))
        continue;
      return ElementClass::Other;
    }
  return ElementClass::Unknown;
}

/// The type with the other node count in the same element family (S4R <-> S3R, M3D4 <-> M3D3,
/// ...) for writing a triangle of a quadrilateral type or the reverse; empty when there is none.
inline std::string_view counterpartType(std::string_view type) {
  static constexpr std::string_view kPairs[][2] = {
      {"S4R", "S3R"},       {"S4", "S3"},          {"S4RS", "S3RS"},  {"S4RSW", "S3RS"},
      {"S4R5", "S3R"},      {"M3D4", "M3D3"},      {"M3D4R", "M3D3"}, {"R3D4", "R3D3"},
      {"SFM3D4", "SFM3D3"}, {"SFM3D4R", "SFM3D3"}, {"STRI3", "S4R"}};
  for (const auto& pair : kPairs) {
    if (type == pair[0]) return pair[1];
  }
  for (const auto& pair : kPairs) {
    if (type == pair[1]) return pair[0];
  }
  return {};
}

/// True when `label` can be written without quotes: it starts with a letter, has only letters,
/// digits and underscores, and is at most 80 characters long (the Abaqus label rules; other
/// labels must be enclosed in double quotes).
inline bool isPlainLabel(std::string_view label) {
  if (label.empty() || label.size() > 80) return false;
  const char first = label.front();
  if (!((first >= 'A' && first <= 'Z') || (first >= 'a' && first <= 'z'))) return false;
  for (char c : label)
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'))
      return false;
  return true;
}

}  // namespace voxremesh::io::abaqus
