// Reading and writing FE decks and surface meshes in every supported format.
//
// The format is chosen by the file extension unless given explicitly:
//   LS-DYNA keyword .k .key .dyn | Nastran bulk data .bdf .nas .dat | Abaqus .inp
//   OBJ .obj | OFF .off | STL .stl (ASCII or binary) | PLY .ply | VTK XML unstructured grid .vtu
// (.vtu is written only). Writing goes to a temporary file in the target folder that is renamed
// over the target when complete, so a failed write never leaves a half-written file.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "voxremesh/fe_model.h"

namespace voxremesh {

/// Messages about input that was accepted but deserves attention (duplicate nodes, content a
/// target format cannot hold, ...), in the order they were found.
using Warnings = std::vector<std::string>;

/// Options for readDeck.
struct ReadOptions {
  std::optional<DeckFormat> format;  ///< overrides the extension
};

/// Options for writeDeck.
struct WriteOptions {
  std::optional<DeckFormat> format;  ///< overrides the extension
  bool binary = true;                ///< STL and PLY: binary (true) or ASCII (false)
};

/// A named per-element or per-node value array for the .vtu writer.
struct FieldData {
  std::string name;
  std::vector<double> values;  ///< one per shell (cell data) or one per node (point data)
};

/// Returns the format that the extension of `path` names (case-insensitive).
/// Throws SettingError naming the extension when it is not a known one.
DeckFormat formatFromPath(const std::filesystem::path& path);

/// Parses a format name as a user writes it ("k", "lsdyna", "bdf", "nastran", "inp", "obj", ...).
/// Throws SettingError listing the accepted names when `name` is none of them.
DeckFormat formatFromName(const std::string& name);

/// Reads a deck or mesh file into an FeModel.
/// @param path     the file; includes are resolved relative to the including file
/// @param options  format override
/// @param warnings receives non-fatal findings when not null
/// Throws InputError (file, line, card) for unreadable, malformed or inconsistent input:
/// malformed numbers, truncated cards, elements naming missing nodes, duplicate IDs, unknown
/// element types, missing includes, empty files, binary files given as text.
FeModel readDeck(const std::filesystem::path& path, const ReadOptions& options = {},
                 Warnings* warnings = nullptr);

/// Writes a model in the format chosen by the extension or the options. Verbatim blocks are
/// written only when the target format is the model's source format; otherwise a warning says
/// how many blocks the target format cannot hold.
/// Preconditions: every shell names existing nodes.
/// Throws SettingError for a format that cannot be written, std::runtime_error on I/O failure
/// (the target is then left untouched).
void writeDeck(const FeModel& model, const std::filesystem::path& path,
               const WriteOptions& options = {}, Warnings* warnings = nullptr);

/// Writes the model as a VTK XML unstructured grid for ParaView, with "part_id" and "element_id"
/// as cell data plus the given cell and point fields.
/// Preconditions: each cell field has model.shells.size() values, each point field
/// model.nodes.size() values. Throws std::invalid_argument when a field's size is wrong,
/// std::runtime_error on I/O failure (the target is then left untouched).
void writeVtu(const FeModel& model, const std::filesystem::path& path,
              const std::vector<FieldData>& cellData = {},
              const std::vector<FieldData>& pointData = {});

}  // namespace voxremesh
