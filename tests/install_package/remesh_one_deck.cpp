// Remeshes the deck named on the command line through the installed library and prints, per
// part, its ID and status ("remeshed", "retried" or "kept"), then the number of shells.
#include <cstdio>
#include <exception>

#include "voxremesh/io.h"
#include "voxremesh/pipeline.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: remesh_one_deck DECK\n");
    return 2;
  }
  try {
    voxremesh::FeModel deck = voxremesh::readDeck(argv[1]);
    const voxremesh::RemeshReport report = voxremesh::remeshDeck(deck, {});
    for (const voxremesh::RemeshedPart& part : report.parts)
      std::printf("part %lld %s\n", static_cast<long long>(part.plan.part),
                  voxremesh::partStatusName(part.status));
    std::printf("shells %zu\n", deck.shells.size());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
  return 0;
}
