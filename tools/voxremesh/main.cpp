// voxremesh command line: dispatches to one subcommand per file (cli_*.cpp).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "voxremesh/errors.h"

namespace {

void printUsage() {
  std::printf(
      "voxremesh %s: remeshing of FE shell models through a volumetric representation\n\n"
      "usage: voxremesh COMMAND [options]\n\n"
      "commands:\n"
      "  info DECK [--json]          mesh report per part: counts, sizes, topology checks\n"
      "  convert IN OUT [--format F] convert between deck and mesh formats\n"
      "  --version                   print the version\n",
      VOXREMESH_VERSION);
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "-h" || args[0] == "--help" || args[0] == "help") {
    printUsage();
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::printf("voxremesh %s\n", VOXREMESH_VERSION);
    return 0;
  }
  std::fprintf(stderr, "voxremesh: unknown command '%s' (see voxremesh --help)\n", args[0].c_str());
  return 2;
}
