// The per-format readers and writers behind readDeck and writeDeck (one .cpp per format).
// Readers throw InputError naming file, line and card; writers append the file content to `out`.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "voxremesh/fe_model.h"
#include "voxremesh/io.h"

namespace voxremesh::io {

/// The longest chain of include files a deck reader follows (the deck itself counts as the
/// first): each level holds its file's content and the reader's frames, so a deeper chain is
/// refused at the include that would exceed it.
inline constexpr std::size_t kMaxIncludeDepth = 32;

/// The message for an include refused by kMaxIncludeDepth.
inline std::string includeTooDeepMessage(const std::string& name) {
  return "include of '" + name + "' nested deeper than " + std::to_string(kMaxIncludeDepth) +
         " files";
}

/// LS-DYNA keyword deck (src/io/lsdyna_read.cpp, src/io/lsdyna_write.cpp).
FeModel readLsDyna(const std::filesystem::path& path, Warnings& warnings);
void writeLsDyna(const FeModel& model, std::string& out, Warnings& warnings);

/// Nastran bulk data (src/io/nastran_read.cpp, src/io/nastran_write.cpp).
FeModel readNastran(const std::filesystem::path& path, Warnings& warnings);
void writeNastran(const FeModel& model, std::string& out, Warnings& warnings);

/// Abaqus input (src/io/abaqus.cpp).
FeModel readAbaqus(const std::filesystem::path& path, Warnings& warnings);
void writeAbaqus(const FeModel& model, std::string& out, Warnings& warnings);

/// Surface mesh formats (src/io/obj.cpp, off.cpp, stl.cpp, ply.cpp).
FeModel readObj(const std::filesystem::path& path, Warnings& warnings);
void writeObj(const FeModel& model, std::string& out, Warnings& warnings);
FeModel readOff(const std::filesystem::path& path, Warnings& warnings);
void writeOff(const FeModel& model, std::string& out, Warnings& warnings);
FeModel readStl(const std::filesystem::path& path, Warnings& warnings);
void writeStl(const FeModel& model, std::string& out, bool binary, Warnings& warnings);
FeModel readPly(const std::filesystem::path& path, Warnings& warnings);
void writePly(const FeModel& model, std::string& out, bool binary, Warnings& warnings);

/// VTK XML unstructured grid (src/io/vtu.cpp); see voxremesh::writeVtu.
void writeVtuContent(const FeModel& model, std::string& out, const std::vector<FieldData>& cellData,
                     const std::vector<FieldData>& pointData);

}  // namespace voxremesh::io
