// voxremesh command line: dispatches to one subcommand per file (cli_*.cpp).
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/errors.h"

namespace {

struct Command {
  const char* name;
  const char* summary;
  voxremesh::cli::CommandFunction run;
};

// The subcommands; `voxremesh help NAME` runs NAME with --help.
constexpr Command kCommands[] = {
    {"remesh", "remesh the shell parts of a deck through the volume and write the deck",
     voxremesh::cli::runRemesh},
    {"info", "mesh report per part: counts, sizes, topology checks", voxremesh::cli::runInfo},
    {"convert", "convert between deck and mesh formats", voxremesh::cli::runConvert},
    {"voxelize", "write one part into a .vdb: a narrow-band signed-distance volume per sheet",
     voxremesh::cli::runVoxelize},
    {"inspect", "report the grids of a .vdb volume: counts, bounds, values, settings",
     voxremesh::cli::runInspect},
    {"slice", "render one axis-aligned slice of a .vdb volume as a PNG image",
     voxremesh::cli::runSlice},
    {"extract", "extract the quad mesh (or MC33 triangles) of a .vdb volume",
     voxremesh::cli::runExtract},
    {"batch", "run the jobs of a JSON job file in parallel, with a summary",
     voxremesh::cli::runBatchCommand},
    {"quality", "FE quality criteria of a deck's shells: table, JSON, .vtu",
     voxremesh::cli::runQuality},
    {"compare", "what a remeshed deck kept and lost: areas, seams, hard points, sets, loads",
     voxremesh::cli::runCompare},
};

const char* const kUsage = "voxremesh COMMAND [options]  (see voxremesh --help)";

void printHelp() {
  std::printf(
      "voxremesh %s: remeshing of FE shell models through a volumetric representation\n\n"
      "usage: voxremesh COMMAND [options]\n\ncommands:\n",
      VOXREMESH_VERSION);
  for (const Command& command : kCommands)
    std::printf("  %-10s %s\n", command.name, command.summary);
  std::printf(
      "\n"
      "  voxremesh help COMMAND   the options of a command (also: voxremesh COMMAND --help)\n"
      "  voxremesh --help         this text\n"
      "  voxremesh --version      the version\n"
      "  voxremesh -read IN -voxelize -write OUT.vdb ...   an action chain (voxremesh -help)\n\n"
      "exit codes: 0 success, 1 error (bad input, failed write), 2 malformed command line,\n"
      "3 done but short of the goal (remesh: parts kept unchanged; quality: the mesh fails;\n"
      "compare: something was lost)\n");
}

const Command* findCommand(const std::string& name) {
  for (const Command& command : kCommands)
    if (name == command.name) return &command;
  return nullptr;
}

int usageError(const std::string& message, const std::string& usage) {
  std::fprintf(stderr, "voxremesh: %s\nusage: %s\n", message.c_str(), usage.c_str());
  return 2;
}

int failure(const char* what) {
  std::fprintf(stderr, "voxremesh: error: %s\n", what);
  return 1;
}

int dispatch(const std::vector<std::string>& args) {
  if (args.empty()) return usageError("no command given", kUsage);
  const std::string& name = args[0];
  if (name == "-h" || name == "--help") {
    printHelp();
    return 0;
  }
  // An action chain: a single dash and a letter (-read, -config, -help, ...).
  if (name.size() >= 2 && name[0] == '-' && name[1] != '-' && name != "-h")
    return voxremesh::cli::runChain(args);
  if (name == "--version") {
    std::printf("voxremesh %s\n", VOXREMESH_VERSION);
    return 0;
  }
  if (name == "help") {
    if (args.size() == 1) {
      printHelp();
      return 0;
    }
    const Command* command = findCommand(args[1]);
    if (!command || args.size() > 2)
      return usageError(command ? "help takes one command" : "unknown command '" + args[1] + "'",
                        "voxremesh help COMMAND");
    return command->run({"--help"});
  }
  const Command* command = findCommand(name);
  if (!command) return usageError("unknown command '" + name + "'", kUsage);
  return command->run(std::vector<std::string>(args.begin() + 1, args.end()));
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return dispatch(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const voxremesh::cli::UsageError& error) {
    return usageError(error.what(), error.usage());
  } catch (const std::bad_alloc&) {
    return failure("out of memory");
  } catch (const std::exception& error) {
    return failure(error.what());
  }
}
