// CalculiX (ccx) for the tests: a free-free frequency analysis of a deck written by the Abaqus
// writer, run as a subprocess, and the eigenvalue table of its .dat output.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace voxremesh::test {

/// True when the CalculiX solver `ccx` is on PATH.
bool ccxAvailable();

/// What the analysis deck adds to the writer's geometry. Units mm, tonne, s (N, MPa): steel.
struct FrequencySettings {
  double youngsModulus = 210000.0;  ///< MPa
  double poissonsRatio = 0.3;
  double density = 7.85e-9;  ///< tonne / mm^3
  double thickness = 1.0;    ///< mm, every shell
  int modes = 16;            ///< eigenmodes asked of *FREQUENCY
};

/// The ELSET labels of the *ELEMENT blocks of shells (types S3, S3R, S4, S4R and the other
/// 3-/4-node Abaqus shell types) in Abaqus input text, each once, in the order of first use, as
/// written (with their quotes).
std::vector<std::string> shellElsets(const std::string& inp);

/// A free-free frequency analysis deck made of Abaqus input text as the writer wrote it (nodes,
/// *ELEMENT blocks with ELSET, no step): the text with the reduced-integration shells S4R / S3R
/// written as S4 / S3, then one material, a *SHELL SECTION for every shell ELSET and a step
/// *FREQUENCY. Why S4: ccx expands S4R into C3D8R bricks whose hourglass stiffness is not
/// orthogonal to linear displacement fields on non-parallelogram elements, so on a real mesh its
/// rigid-body rotations come out as modes of tens of Hz; S4 (C3D8I) keeps all six at zero.
/// Throws std::runtime_error when the text has a *STEP already or no shell ELSET.
std::string frequencyDeck(const std::string& inp, const FrequencySettings& settings = {});

/// One row of the eigenvalue table of a ccx .dat file.
struct Eigenmode {
  int mode = 0;
  double eigenvalue = 0.0;  ///< (rad/time)^2; slightly negative for rigid-body modes
  double radians = 0.0;     ///< real part of the frequency, rad/time (0 for a negative eigenvalue)
  double hertz = 0.0;       ///< real part of the frequency, cycles/time
};

/// The rows of the first "E I G E N V A L U E   O U T P U T" table of a ccx .dat file, in the
/// order written (empty when there is none).
std::vector<Eigenmode> parseEigenmodes(const std::string& dat);

/// Result of one ccx run.
struct CcxRun {
  int exitCode = -1;   ///< ccx's, or 124 when the time limit ended it
  std::string output;  ///< stdout and stderr together
  std::string dat;     ///< the JOB.dat file (empty when missing)
  std::vector<Eigenmode> modes;
  double seconds = 0.0;  ///< wall time
};

/// Runs `ccx -i JOB` in `dir` (which holds JOB.inp) with OMP_NUM_THREADS=`threads`, ended after
/// `timeoutSeconds`, and parses its eigenvalue table. One thread by default: no slower than two on
/// these decks on two idle cores, much faster on a busy machine.
CcxRun runCcx(const std::filesystem::path& dir, const std::string& job, int timeoutSeconds = 300,
              int threads = 1);

/// Empty when a frequency run succeeded; else what went wrong: a non-zero exit, "*ERROR" or
/// "nonpositive jacobian" in the output or the .dat file (with the lines that say so), or fewer
/// than `modes` eigenmodes.
std::string ccxFailure(const CcxRun& run, int modes);

/// The number of near-zero (rigid-body) modes: those whose frequency is below `factor` times the
/// largest frequency of the table.
std::size_t countNearZeroModes(const std::vector<Eigenmode>& modes, double factor);

/// Writes `deck`'s shells as Abaqus input with every element cut into four (quads at their edge
/// midpoints and centroid, triangles at their edge midpoints; new nodes and elements numbered
/// above the deck's): the same geometry at half the element size, the reference for a part
/// remeshed at half its target size, since a shell's frequencies depend on its element size.
/// Uses the project's reader and writer. Throws as readDeck and writeDeck.
void writeSubdividedAbaqus(const std::filesystem::path& deck, const std::filesystem::path& out);

}  // namespace voxremesh::test
