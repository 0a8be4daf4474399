// Format dispatch for readDeck / writeDeck / writeVtu.
#include <algorithm>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/text_scan.h"
#include "voxremesh/errors.h"
#include "voxremesh/io.h"

namespace voxremesh {

namespace {

struct FormatName {
  const char* name;
  DeckFormat format;
};

// Extensions and the names a user may give with --format; the first of each format is canonical.
constexpr FormatName kFormatNames[] = {
    {"k", DeckFormat::LsDyna},      {"key", DeckFormat::LsDyna},      {"dyn", DeckFormat::LsDyna},
    {"lsdyna", DeckFormat::LsDyna}, {"bdf", DeckFormat::Nastran},     {"nas", DeckFormat::Nastran},
    {"dat", DeckFormat::Nastran},   {"nastran", DeckFormat::Nastran}, {"inp", DeckFormat::Abaqus},
    {"abaqus", DeckFormat::Abaqus}, {"obj", DeckFormat::Obj},         {"off", DeckFormat::Off},
    {"stl", DeckFormat::Stl},       {"ply", DeckFormat::Ply},         {"vtu", DeckFormat::Vtu},
};

std::string acceptedNames() {
  std::string list;
  for (const auto& entry : kFormatNames) list += std::string(list.empty() ? "" : ", ") + entry.name;
  return list;
}

/// Throws std::invalid_argument when a shell names a node the model does not have, or a node ID
/// is used twice: every writer relies on both.
void requireConsistentModel(const FeModel& model) {
  const std::unordered_map<Id, std::size_t> index = [&] {
    try {
      return model.nodeIndex();
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(std::string("cannot write the model: ") + e.what());
    }
  }();
  for (const Shell& shell : model.shells)
    for (int k = 0; k < shell.nodeCount; ++k)
      if (!index.count(shell.nodes[k]))
        throw std::invalid_argument("cannot write the model: element " + std::to_string(shell.id) +
                                    " names node " + std::to_string(shell.nodes[k]) +
                                    ", which the model does not have");
}

}  // namespace

DeckFormat formatFromName(const std::string& name) {
  for (const auto& entry : kFormatNames)
    if (io::iequals(name, entry.name)) return entry.format;
  throw SettingError("unknown format '" + name + "' (accepted: " + acceptedNames() + ")");
}

DeckFormat formatFromPath(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  if (!extension.empty()) extension.erase(0, 1);
  for (const auto& entry : kFormatNames)
    if (io::iequals(extension, entry.name) && extension.size() <= 3) return entry.format;
  throw SettingError("cannot tell the format of '" + path.string() + "' from its extension '" +
                     extension +
                     "' (known: .k .key .dyn .bdf .nas .dat .inp .obj .off .stl .ply "
                     ".vtu; give the format explicitly)");
}

FeModel readDeck(const std::filesystem::path& path, const ReadOptions& options,
                 Warnings* warnings) {
  const DeckFormat format = options.format ? *options.format : formatFromPath(path);
  if (!std::filesystem::exists(path)) throw InputError(path.string(), 0, "no such file");
  if (std::filesystem::is_directory(path))
    throw InputError(path.string(), 0, "is a folder, not a file");
  Warnings local;
  Warnings& sink = warnings ? *warnings : local;
  switch (format) {
    case DeckFormat::LsDyna:
      return io::readLsDyna(path, sink);
    case DeckFormat::Nastran:
      return io::readNastran(path, sink);
    case DeckFormat::Abaqus:
      return io::readAbaqus(path, sink);
    case DeckFormat::Obj:
      return io::readObj(path, sink);
    case DeckFormat::Off:
      return io::readOff(path, sink);
    case DeckFormat::Stl:
      return io::readStl(path, sink);
    case DeckFormat::Ply:
      return io::readPly(path, sink);
    case DeckFormat::Vtu:
      break;
  }
  throw SettingError("reading " + std::string(formatName(format)) +
                     " files is not supported (it is an output format)");
}

void writeDeck(const FeModel& model, const std::filesystem::path& path, const WriteOptions& options,
               Warnings* warnings) {
  const DeckFormat format = options.format ? *options.format : formatFromPath(path);
  requireConsistentModel(model);
  Warnings local;
  Warnings& sink = warnings ? *warnings : local;
  if (format != model.sourceFormat) {
    const auto foreign = std::count_if(
        model.blocks.begin(), model.blocks.end(),
        [](const DeckBlock& b) { return b.kind == DeckBlock::Kind::Verbatim && !b.text.empty(); });
    if (foreign > 0)
      sink.push_back(
          std::to_string(foreign) + " block(s) of " + formatName(model.sourceFormat) +
          " content (keywords other than nodes, shells and parts) cannot be written to " +
          formatName(format) + " and are left out of " + path.string());
  }
  std::string out;
  switch (format) {
    case DeckFormat::LsDyna:
      io::writeLsDyna(model, out, sink);
      break;
    case DeckFormat::Nastran:
      io::writeNastran(model, out, sink);
      break;
    case DeckFormat::Abaqus:
      io::writeAbaqus(model, out, sink);
      break;
    case DeckFormat::Obj:
      io::writeObj(model, out, sink);
      break;
    case DeckFormat::Off:
      io::writeOff(model, out, sink);
      break;
    case DeckFormat::Stl:
      io::writeStl(model, out, options.binary, sink);
      break;
    case DeckFormat::Ply:
      io::writePly(model, out, options.binary, sink);
      break;
    case DeckFormat::Vtu:
      io::writeVtuContent(model, out, {}, {});
      break;
  }
  io::writeFileAtomically(path, out);
}

void writeVtu(const FeModel& model, const std::filesystem::path& path,
              const std::vector<FieldData>& cellData, const std::vector<FieldData>& pointData) {
  requireConsistentModel(model);
  std::string out;
  io::writeVtuContent(model, out, cellData, pointData);
  io::writeFileAtomically(path, out);
}

}  // namespace voxremesh
