// bench_remesh: the whole-deck remesh on a generated deck of about a million shells.
//
// The deck is the shipped sample part (--part, default tools/samples/hat_rail.k relative to the
// working folder: run it from the source root; 3562 shells, 5 mm) copied into
// a grid of parts, each copy its own part with its own nodes, until the deck holds at least
// --elements shells (default 1,000,000). It is written to a .k file and then timed like
// `voxremesh remesh deck.k -o out.k`: read, remesh (per part: sheets + volume, extraction; parts
// in parallel), assembly, write. Prints the total time, the time per stage (the volume and
// extraction times are summed over the parts, i.e. CPU-side work, next to the wall time of the
// parallel remesh), the element counts and the peak resident memory.
//
// usage: bench_remesh [--elements N] [--threads N] [--size H] [--keep DIR] [--part FILE]
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"

using namespace voxremesh;

namespace {

double seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

FeModel replicate(const FeModel& part, std::size_t copies) {
  FeModel deck;
  Id maxNode = 0, maxShell = 0;
  for (const Node& node : part.nodes) maxNode = std::max(maxNode, node.id);
  for (const Shell& shell : part.shells) maxShell = std::max(maxShell, shell.id);
  deck.nodes.reserve(part.nodes.size() * copies);
  deck.shells.reserve(part.shells.size() * copies);
  for (std::size_t c = 0; c < copies; ++c) {
    const double dx = 500.0 * static_cast<double>(c % 20), dy = 250.0 * static_cast<double>(c / 20);
    const Id nodeOffset = static_cast<Id>(c) * maxNode, shellOffset = static_cast<Id>(c) * maxShell;
    for (const Node& node : part.nodes)
      deck.nodes.push_back(
          Node{node.id + nodeOffset, {node.xyz[0] + dx, node.xyz[1] + dy, node.xyz[2]}});
    for (Shell shell : part.shells) {
      shell.id += shellOffset;
      shell.part = static_cast<Id>(c + 1);
      for (int k = 0; k < shell.nodeCount; ++k)
        shell.nodes[static_cast<std::size_t>(k)] += nodeOffset;
      shell.type = 0;
      shell.extras = -1;
      deck.shells.push_back(shell);
    }
    deck.partOrAdd(static_cast<Id>(c + 1), "rail " + std::to_string(c + 1));
  }
  return deck;
}

long peakMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t elements = 1000000;
  RemeshSettings settings;
  std::filesystem::path keep;
  std::filesystem::path source = "tools/samples/hat_rail.k";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--elements"))
      elements = std::strtoull(argv[i + 1], nullptr, 10);
    else if (!std::strcmp(argv[i], "--threads"))
      settings.threads = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--size"))
      settings.targetSize = std::atof(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--keep"))
      keep = argv[i + 1];
    else {
      std::fprintf(stderr,
                   "usage: bench_remesh [--elements N] [--threads N] [--size H] [--keep DIR] "
                   "[--part FILE]\n");
      return 2;
    }
  }
  const std::filesystem::path dir =
      keep.empty() ? std::filesystem::temp_directory_path() / "voxremesh-bench-remesh" : keep;
  std::filesystem::create_directories(dir);
  const FeModel part = readDeck(source);
  const std::size_t copies = (elements + part.shells.size() - 1) / part.shells.size();
  writeDeck(replicate(part, copies), dir / "deck.k");

  const auto total = std::chrono::steady_clock::now();
  auto stage = std::chrono::steady_clock::now();
  FeModel deck = readDeck(dir / "deck.k");
  const double readSeconds = seconds(stage);
  const std::size_t before = deck.shells.size();
  stage = std::chrono::steady_clock::now();
  const RemeshReport report = remeshDeck(deck, settings);
  const double remeshSeconds = seconds(stage);
  stage = std::chrono::steady_clock::now();
  writeDeck(deck, dir / "out.k");
  const double writeSeconds = seconds(stage);
  const double totalSeconds = seconds(total);
  double volume = 0, extract = 0;
  for (const RemeshedPart& p : report.parts) {
    volume += p.volumeSeconds;
    extract += p.extractSeconds;
  }
  std::printf("deck: %zu parts, %zu shells -> %zu shells\n", report.parts.size(), before,
              deck.shells.size());
  std::printf(
      "total %.2f s: read %.2f s, remesh %.2f s (wall; summed over parts: sheets+volume "
      "%.2f s, extract %.2f s; assembly %.2f s), write %.2f s\n",
      totalSeconds, readSeconds, remeshSeconds, volume, extract, report.assemblySeconds,
      writeSeconds);
  std::printf("peak memory %ld MB\n", peakMegabytes());
  if (keep.empty()) std::filesystem::remove_all(dir);
  return 0;
}
