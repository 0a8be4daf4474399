// bench_io: reads and writes a generated deck of about one million shell elements in every deck
// format and prints the time of each direction, the file size and the peak memory.
//
// usage: bench_io [--elements N] [--dir FOLDER]
//
// The deck is a 10-part grid of quads with a few triangles, sparse IDs and two-line
// *ELEMENT_SHELL_THICKNESS cards, so that the readers take their real paths. There is no OpenVDB
// counterpart for deck I/O; the stages that have one (voxelisation, extraction) have their own
// benchmarks.
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "voxremesh/fe_model.h"
#include "voxremesh/io.h"

namespace {

using voxremesh::bench::secondsSince;

/// Peak resident memory of this process so far, in MiB.
double peakMemoryMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

voxremesh::FeModel makeGridDeck(std::size_t elements) {
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(elements))));
  voxremesh::FeModel model;
  model.sourceFormat = voxremesh::DeckFormat::LsDyna;
  model.nodes.reserve((side + 1) * (side + 1));
  for (std::size_t i = 0; i <= side; ++i)
    for (std::size_t j = 0; j <= side; ++j) {
      const double x = 1.7 * static_cast<double>(i), y = 1.3 * static_cast<double>(j);
      model.nodes.push_back({static_cast<voxremesh::Id>(100000 + 3 * (i * (side + 1) + j)),
                             {x, y, 0.01 * std::sin(0.1 * x) * std::cos(0.07 * y)}});
    }
  const std::uint8_t thick = model.internShellType("_THICKNESS");
  model.shells.reserve(elements);
  for (std::size_t i = 0; i < side && model.shells.size() < elements; ++i)
    for (std::size_t j = 0; j < side && model.shells.size() < elements; ++j) {
      auto id = [&](std::size_t a, std::size_t b) { return model.nodes[a * (side + 1) + b].id; };
      voxremesh::Shell shell;
      shell.id = static_cast<voxremesh::Id>(5000000 + model.shells.size());
      shell.part = static_cast<voxremesh::Id>(1 + (i * 10) / side);
      shell.nodes = {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      if (j % 97 == 0) shell.nodeCount = 3;  // a few triangles
      if (i % 50 == 0) {                     // a few elements with their own thickness
        shell.type = thick;
        shell.extras = static_cast<std::int32_t>(model.shellExtras.size());
        model.shellExtras.push_back({{1.2, 1.2, 1.25, 1.25}, 0.0, false, 0.0});
      }
      model.shells.push_back(shell);
    }
  for (voxremesh::Id p = 1; p <= 10; ++p) model.parts.push_back({p, "part " + std::to_string(p)});
  return model;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t elements = 1000000;
  std::filesystem::path dir = std::filesystem::temp_directory_path() / "voxremesh-bench-io";
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--elements" && a + 1 < argc) {
      elements = std::stoul(argv[++a]);
    } else if (arg == "--dir" && a + 1 < argc) {
      dir = argv[++a];
    } else {
      std::fprintf(stderr, "usage: bench_io [--elements N] [--dir FOLDER]\n");
      return 2;
    }
  }
  try {
    std::filesystem::create_directories(dir);
    const voxremesh::FeModel model = makeGridDeck(elements);
    std::printf("deck: %zu nodes, %zu shells, %zu parts (peak memory %.0f MiB)\n",
                model.nodes.size(), model.shells.size(), model.parts.size(), peakMemoryMiB());
    std::printf("%-10s %10s %10s %10s %12s %14s\n", "format", "write s", "read s", "MiB",
                "shells back", "peak mem MiB");
    for (const char* extension : {"k", "bdf", "inp", "obj", "ply", "stl", "off"}) {
      const std::filesystem::path file = dir / (std::string("bench.") + extension);
      voxremesh::Warnings warnings;
      auto start = std::chrono::steady_clock::now();
      voxremesh::writeDeck(model, file, {}, &warnings);
      const double writeSeconds = secondsSince(start);
      start = std::chrono::steady_clock::now();
      const voxremesh::FeModel back = voxremesh::readDeck(file, {}, &warnings);
      const double readSeconds = secondsSince(start);
      const double mib = static_cast<double>(std::filesystem::file_size(file)) / (1024.0 * 1024.0);
      std::printf("%-10s %10.2f %10.2f %10.1f %12zu %14.0f\n", extension, writeSeconds, readSeconds,
                  mib, back.shells.size(), peakMemoryMiB());
      std::filesystem::remove(file);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_io: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
