// voxremesh compare: what a deck and its remeshed version carry, and what was lost.
#include <cstdio>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/deck_compare.h"
#include "voxremesh/io.h"

namespace voxremesh::cli {

namespace {

const char* const kUsage = "voxremesh compare IN OUT [--json]";

const char* const kHelp =
    "Compares a deck (IN) with its remeshed version (OUT, same format) and reports what the\n"
    "remesh kept and lost:\n"
    "  - per part: shells and area (mass follows area: the property cards are the same);\n"
    "  - per pair of parts: the nodes they share (seams), and the T-junction edges;\n"
    "  - hard points (nodes other keywords use as points): missing or moved;\n"
    "  - node sets (*SET_NODE, SET1, SPC1, *NSET), matched by keyword and order: members,\n"
    "    repeated members, and the area of the shells all of whose nodes are members;\n"
    "  - per-node data (*INITIAL_VELOCITY_NODE): per part, the shell nodes that carry it;\n"
    "  - the total force of the pressure loads (PLOAD4: pressure x area x normal);\n"
    "  - references in OUT to nodes or shells OUT does not have (dangling).\n"
    "A loss is: a part without shells or whose area changed by more than 1 %, a seam that\n"
    "shares no node any more, a hard point missing or moved, a node set emptied or with more\n"
    "repeated members than before, per-node data that covered a part fully (or at all) and no\n"
    "longer does, a total pressure force changed by more than 1 %, a dangling reference.\n"
    "\n"
    "options:\n"
    "  --json   print the comparison as JSON instead of tables\n"
    "\n"
    "exit code: 0 nothing lost, 3 something lost (listed), 1 error reading a deck.\n";

}  // namespace

int runCompare(const std::vector<std::string>& args) {
  if (wantsHelp(args)) {
    std::printf("usage: %s\n\n%s", kUsage, kHelp);
    return 0;
  }
  const ParsedArgs parsed = parseArgs(args, {{"--json", false}}, 2, 2, kUsage);
  Warnings warnings;
  const FeModel before = readDeck(parsed.positional[0], {}, &warnings);
  const FeModel after = readDeck(parsed.positional[1], {}, &warnings);
  printWarnings(warnings);
  const DeckComparison comparison = compareDecks(before, after);
  if (parsed.has("--json"))
    printOutput(formatComparisonJson(comparison));
  else
    printOutput(parsed.positional[0] + " -> " + parsed.positional[1] + "\n\n" +
                formatComparisonTable(comparison));
  return comparison.losses.empty() ? 0 : kExitShortfall;
}

}  // namespace voxremesh::cli
