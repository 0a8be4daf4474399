// voxremesh convert: reads a deck in one format and writes it in another.
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/io.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage = "voxremesh convert IN OUT [--from F] [--to F] [--ascii]";

const char* const kHelp =
    "Reads IN and writes its nodes, shells and parts to OUT. Keywords other than nodes, shells "
    "and\n"
    "parts are written back only when OUT has the format of IN (a warning says what is left out\n"
    "otherwise). OUT is written completely or not at all.\n"
    "\n"
    "options:\n"
    "  --from F   read IN as format F instead of guessing it from the extension\n"
    "  --to F     write OUT as format F instead of guessing it from the extension\n"
    "             (k, lsdyna, bdf, nastran, inp, abaqus, obj, off, stl, ply, vtu)\n"
    "  --ascii    write STL and PLY as text instead of binary\n";

bool hasBinaryForm(DeckFormat format) {
  return format == DeckFormat::Stl || format == DeckFormat::Ply;
}

}  // namespace

int runConvert(const std::vector<std::string>& args) {
  if (wantsHelp(args)) {
    std::printf("usage: %s\n\n%s", kUsage, kHelp);
    return 0;
  }
  const ParsedArgs parsed =
      parseArgs(args, {{"--from", true}, {"--to", true}, {"--ascii", false}}, 2, 2, kUsage);
  const std::string& in = parsed.positional[0];
  const std::string& out = parsed.positional[1];
  refuseOverwritingInput(in, out, "OUT");
  ReadOptions readOptions;
  DeckFormat target{};
  // Decide the formats before reading, so that a bad name fails at once.
  parseOptionValues(kUsage, [&] {
    if (const auto from = parsed.value("--from")) readOptions.format = formatFromName(*from);
    const auto to = parsed.value("--to");
    target = to ? formatFromName(*to) : formatFromPath(out);
  });
  WriteOptions writeOptions;
  writeOptions.format = target;
  writeOptions.binary = !parsed.has("--ascii");

  Warnings readWarnings;
  const FeModel model = readDeck(in, readOptions, &readWarnings);
  printWarnings(readWarnings);
  Warnings writeWarnings;
  if (parsed.has("--ascii") && !hasBinaryForm(target))
    writeWarnings.push_back(std::string("--ascii only affects STL and PLY output; ignored for ") +
                            formatName(target));
  writeDeck(model, out, writeOptions, &writeWarnings);
  printWarnings(writeWarnings);

  std::set<Id> parts;
  for (const Part& part : model.parts) parts.insert(part.id);
  for (const Shell& shell : model.shells) parts.insert(shell.part);
  std::string form;
  if (hasBinaryForm(target)) form = writeOptions.binary ? ", binary" : ", ASCII";
  printOutput("wrote " + out + ": " + std::to_string(model.nodes.size()) + " nodes, " +
              std::to_string(model.shells.size()) + " shells, " + std::to_string(parts.size()) +
              " parts (" + formatName(target) + form + ")\n");
  return 0;
}

}  // namespace voxremesh::cli
