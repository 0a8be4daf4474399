// voxremesh -ACTION ...: vdb_tool-style action chains (action_chain.h).
#include <cstdio>
#include <string>
#include <vector>

#include "cli_common.h"
#include "voxremesh/action_chain.h"

namespace voxremesh::cli {

int runChain(const std::vector<std::string>& args) {
  chain::Chain parsed;
  try {
    parsed = chain::parseChain(args);
  } catch (const SettingError& error) {
    throw UsageError(error.what(),
                     "voxremesh -ACTION [key=value ...] -ACTION ... (voxremesh -help)");
  }
  chain::ChainState state;
  state.print = [](const std::string& text) { printOutput(text); };
  state.warn = [](const std::string& text) { printWarnings({text}); };
  chain::runChain(parsed, state);
  return 0;
}

}  // namespace voxremesh::cli
