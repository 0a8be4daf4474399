// The finite-element shell model every stage of voxremesh reads and writes.
//
// A deck is held as geometry (nodes, shell elements, parts) plus everything else of the file kept
// verbatim, in order, so that writing it back in the same format reproduces the untouched content
// byte for byte. IDs are kept exactly as the file gives them (sparse, large, 64-bit).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace voxremesh {

/// Node, element and part identifiers as written in the deck.
using Id = std::int64_t;

/// The file formats voxremesh reads or writes.
enum class DeckFormat { LsDyna, Nastran, Abaqus, Obj, Off, Stl, Ply, Vtu };

/// A node: its ID and coordinates.
struct Node {
  Id id = 0;
  std::array<double, 3> xyz{};
};

/// Fields of a node that carry no geometry but must survive a round trip through its format:
/// LS-DYNA *NODE TC and RC; Nastran GRID CD, PS and SEID. Only nodes with a nonzero field have one.
struct NodeExtras {
  std::int32_t dynaTc = 0;
  std::int32_t dynaRc = 0;
  std::int32_t nastranCd = 0;
  std::int32_t nastranPs = 0;
  std::int32_t nastranSeid = 0;
};

/// Per-element shell data some decks give on the element itself (LS-DYNA *ELEMENT_SHELL_THICKNESS,
/// _BETA, _MCID, _OFFSET; Nastran CQUAD4 THETA/MCID, ZOFFS, T1..T4). Zero thickness means "from
/// the section/property".
struct ShellExtras {
  std::array<double, 4> thickness{};
  double angle = 0.0;  ///< material angle in degrees, or a coordinate system ID if angleIsMcid
  bool angleIsMcid = false;  ///< angle holds a material coordinate system ID
  double offset = 0.0;       ///< reference surface offset
};

/// A shell element: a triangle (nodeCount 3) or a quadrilateral (nodeCount 4).
struct Shell {
  Id id = 0;
  Id part = 0;
  std::array<Id, 4> nodes{};   ///< node IDs; nodes[3] is unused for triangles
  std::uint8_t nodeCount = 4;  ///< 3 or 4
  std::uint8_t type = 0;       ///< index into FeModel::shellTypes (0: the format's default)
  std::int32_t extras = -1;    ///< index into FeModel::shellExtras, or -1 for none
};

/// A part (LS-DYNA *PART, Nastran PSHELL, Abaqus ELSET): its ID and name.
struct Part {
  Id id = 0;
  std::string name;
  bool definedInBlocks = false;  ///< the part's own card is among FeModel::blocks (same format)
};

/// A piece of the deck in file order: text kept verbatim, or the place where the geometry the
/// writer regenerates (nodes, shell elements) stood in the source.
struct DeckBlock {
  enum class Kind { Verbatim, Nodes, Shells };
  Kind kind = Kind::Verbatim;
  std::string text;  ///< for Verbatim: the exact bytes of the source, line endings included
  /// Where the block's first line stood in the source: the file as messages name it and the
  /// 1-based line; line 0 when the reader does not record it (Nastran and Abaqus blocks, which
  /// gather lines of several keywords, and blocks built in memory).
  std::string file{};
  std::size_t line = 0;
};

/// A whole deck: geometry plus the rest of the file, verbatim.
struct FeModel {
  std::vector<Node> nodes;
  std::vector<Shell> shells;
  std::vector<Part> parts;
  std::map<Id, NodeExtras> nodeExtras;  ///< only nodes with a nonzero extra field
  std::vector<ShellExtras> shellExtras;
  /// Element type names of the source format, indexed by Shell::type: "" (the default) first,
  /// then e.g. "_THICKNESS" (LS-DYNA keyword option), "CQUADR" (Nastran), "S4R" (Abaqus).
  std::vector<std::string> shellTypes{""};
  /// The format the verbatim blocks are written in; blocks are only written back to that format.
  DeckFormat sourceFormat = DeckFormat::LsDyna;
  std::vector<DeckBlock> blocks;

  /// Maps node IDs to indices into nodes.
  /// Throws std::runtime_error naming the ID if two nodes share one.
  std::unordered_map<Id, std::size_t> nodeIndex() const;

  /// Returns the part with the given ID, or nullptr.
  const Part* findPart(Id id) const;

  /// Returns the part with the given ID, appending a new one named `name` if there is none.
  Part& partOrAdd(Id id, const std::string& name = {});

  /// Interns an element type name into shellTypes and returns its index.
  /// Throws std::length_error beyond 255 distinct types.
  std::uint8_t internShellType(const std::string& name);
};

/// Returns the printable name of a format ("LS-DYNA keyword", "Nastran bulk data", ...).
const char* formatName(DeckFormat format);

}  // namespace voxremesh
