// A real FE solver accepts the result (DESIGN.md): CalculiX runs a free-free frequency analysis of
// the original deck and of the remeshed one, both written as Abaqus input by voxremesh itself,
// without errors, finds as many rigid-body modes for both, and (on single parts) natural
// frequencies close to the original's. Skipped where ccx (Debian calculix-ccx) is missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/calculix.h"
#include "support/test_support.h"

namespace fs = std::filesystem;
using voxremesh::test::CcxRun;
using voxremesh::test::Eigenmode;
using voxremesh::test::quoted;

namespace {

constexpr int kModes = 16;

/// A mode is near zero (rigid body) when its frequency is below kNearZero times the largest of
/// the kModes frequencies: independent of units and of the part's size. Measured on these decks:
/// rigid-body modes come out of ccx at 0 to 0.05 Hz (numerical noise; on car5.k, whose first
/// elastic mode is 2.4 Hz, up to 0.9e-3 of the largest frequency, so 1e-3 would not separate
/// reliably), the first elastic mode at 0.07 to 0.5 of the largest. 1e-2 is about an order of
/// magnitude from both; kAmbiguity checks that it stays so.
constexpr double kNearZero = 1e-2;

/// No frequency may lie within this factor of the near-zero threshold (either side): the count
/// would then depend on noise, not on the mesh.
constexpr double kAmbiguity = 3.0;

/// The elastic modes compared on single parts, and the limits of their relative differences.
constexpr std::size_t kElasticCompared = 10;
constexpr double kMeanDifferenceLimit = 0.02;
constexpr double kMaxDifferenceLimit = 0.04;

/// A frequency analysis of one Abaqus deck.
struct Analysis {
  CcxRun run;
  std::string failure;  ///< empty when ccx succeeded
  std::size_t nearZero = 0;
  std::string ambiguous;  ///< the frequencies too close to the threshold, when any
};

/// Writes the analysis deck JOB.inp of `inp` into `dir`, runs ccx on it and counts its modes.
Analysis analyse(const fs::path& dir, const fs::path& inp, const std::string& job) {
  Analysis analysis;
  voxremesh::test::writeText(dir / (job + ".inp"),
                             voxremesh::test::frequencyDeck(voxremesh::test::readText(inp)));
  analysis.run = voxremesh::test::runCcx(dir, job);
  analysis.failure = voxremesh::test::ccxFailure(analysis.run, kModes);
  const std::vector<Eigenmode>& modes = analysis.run.modes;
  analysis.nearZero = voxremesh::test::countNearZeroModes(modes, kNearZero);
  double largest = 0.0;
  for (const Eigenmode& mode : modes) largest = std::max(largest, mode.hertz);
  const double threshold = kNearZero * largest;
  for (const Eigenmode& mode : modes)
    if (mode.hertz > threshold / kAmbiguity && mode.hertz < threshold * kAmbiguity)
      analysis.ambiguous += " mode " + std::to_string(mode.mode) + " " +
                            std::to_string(mode.hertz) + " Hz (threshold " +
                            std::to_string(threshold) + " Hz);";
  std::printf("%s: ccx %.1f s, exit %d, %zu modes, %zu near zero\n", job.c_str(),
              analysis.run.seconds, analysis.run.exitCode, modes.size(), analysis.nearZero);
  return analysis;
}

/// The frequency of row `row` of an analysis, as text ("-" when there is none).
std::string hertzText(const Analysis& analysis, std::size_t row) {
  if (row >= analysis.run.modes.size()) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", analysis.run.modes[row].hertz);
  return buffer;
}

/// Prints both frequency tables side by side, marking the near-zero modes and the relative
/// difference of the elastic modes compared row by row after each deck's near-zero ones.
void printTable(const std::string& deck, const Analysis& original, const Analysis& remeshed) {
  std::printf("%s: frequencies (Hz), rigid = below %g x the largest\n", deck.c_str(), kNearZero);
  std::printf("  mode  original Hz        remeshed Hz        difference %%\n");
  const std::size_t rows = std::max(original.run.modes.size(), remeshed.run.modes.size());
  for (std::size_t row = 0; row < rows; ++row) {
    const bool rigidBefore = row < original.nearZero;
    const bool rigidAfter = row < remeshed.nearZero;
    std::string difference = "-";
    if (!rigidBefore && !rigidAfter && row < original.run.modes.size() &&
        row < remeshed.run.modes.size()) {
      const double before = original.run.modes[row].hertz;
      const double after = remeshed.run.modes[row].hertz;
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%+.2f", 100.0 * (after - before) / before);
      difference = buffer;
    }
    std::printf("  %4zu  %-12s%-7s%-12s%-7s%s\n", row + 1, hertzText(original, row).c_str(),
                rigidBefore ? "rigid" : "", hertzText(remeshed, row).c_str(),
                rigidAfter ? "rigid" : "", difference.c_str());
  }
  std::fflush(stdout);
}

/// The number written just before `words` in `text` (0 when they are not there).
std::size_t countBefore(const std::string& text, const std::string& words) {
  const std::size_t at = text.find(words);
  if (at == std::string::npos) return 0;
  std::size_t begin = at;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(text[begin - 1]))) --begin;
  return begin == at ? 0 : std::stoul(text.substr(begin, at - begin));
}

/// What checkModes asks of the remesh besides ccx accepting it and the rigid-body mode count.
enum class Expect {
  AllRemeshed,  ///< every part remeshed (exit 0), elastic frequencies within the limits
  Any,          ///< parts may be kept (exit 3); frequencies compared where every part was remeshed
};

/// Converts and remeshes `deck` to Abaqus input, runs ccx on both and checks the rigid-body mode
/// count and, where every part was remeshed, the first kElasticCompared elastic frequencies
/// (`compareFrequencies`: single parts; an assembly's frequencies depend on its seams).
void checkModes(const fs::path& deck, const std::string& name, bool compareFrequencies,
                Expect expect) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = voxremesh::test::scratchDir("calculix_" + name);
  const fs::path original = dir / "orig.inp";
  const fs::path remeshed = dir / "new.inp";
  const auto convert = voxremesh::test::runCli("convert " + quoted(deck) + " " + quoted(original));
  ASSERT_EQ(convert.exitCode, 0) << convert.output;
  const auto remesh =
      voxremesh::test::runCli("remesh " + quoted(deck) + " -o " + quoted(remeshed) + " --quiet");
  // 0: every part remeshed; 3: some parts kept unchanged. Either way the output is written.
  ASSERT_TRUE(remesh.exitCode == 0 || remesh.exitCode == 3)
      << "voxremesh remesh exited with " << remesh.exitCode << "\n"
      << remesh.output;
  if (expect == Expect::AllRemeshed) {
    ASSERT_EQ(remesh.exitCode, 0) << remesh.output;
  }
  ASSERT_TRUE(fs::exists(remeshed)) << remesh.output;
  // Which parts were remeshed and which kept (kept ones have the original's frequencies).
  std::printf("%s: voxremesh remesh exit %d\n%s", name.c_str(), remesh.exitCode,
              remesh.output.c_str());

  const Analysis before = analyse(dir, original, "orig");
  const Analysis after = analyse(dir, remeshed, "new");
  printTable(name, before, after);
  EXPECT_EQ(before.failure, "") << "ccx on the original deck " << dir / "orig.inp";
  EXPECT_EQ(after.failure, "") << "ccx on the remeshed deck " << dir / "new.inp";
  ASSERT_TRUE(before.failure.empty() && after.failure.empty());
  ASSERT_EQ(before.ambiguous, "") << "original: near-zero threshold ambiguous";
  ASSERT_EQ(after.ambiguous, "") << "remeshed: near-zero threshold ambiguous";

  EXPECT_EQ(after.nearZero, before.nearZero)
      << "rigid-body modes: " << before.nearZero << " in the original, " << after.nearZero
      << " in the remeshed deck (more means parts or seams came apart)";
  // Frequencies are compared where no part was kept, against the original at the size the parts
  // were remeshed at: a shell's frequencies depend on its element size (the bracket's original
  // cut into four falls 6.5 % on average; its remesh at half the size lies within 0.3 % of that).
  // Every part remeshed at the target size: the original; every part retried once at half of it:
  // the original cut into four; otherwise nothing is compared.
  const std::size_t remeshedParts = countBefore(remesh.output, " parts remeshed");
  const std::size_t retriedParts = countBefore(remesh.output, " retried at a finer voxel");
  const std::size_t keptParts = countBefore(remesh.output, " kept;");
  const bool atTargetSize = keptParts == 0 && retriedParts == 0;
  const bool atHalfSize = keptParts == 0 && remeshedParts == 0 && retriedParts > 0;
  Analysis halfSize;
  if (compareFrequencies && atHalfSize) {
    voxremesh::test::writeSubdividedAbaqus(deck, dir / "orig_half.inp");
    halfSize = analyse(dir, dir / "orig_half.inp", "orig_half");
    printTable(name + " (original cut into four)", halfSize, after);
    ASSERT_EQ(halfSize.failure, "") << "ccx on the subdivided original " << dir / "orig_half.inp";
  }
  const Analysis& reference = atHalfSize ? halfSize : before;
  if (compareFrequencies && !atTargetSize && !atHalfSize)
    std::printf("%s: parts were kept; frequencies not compared\n", name.c_str());
  if (compareFrequencies && (atTargetSize || atHalfSize) && after.nearZero == reference.nearZero) {
    ASSERT_GE(reference.run.modes.size(), reference.nearZero + kElasticCompared)
        << "fewer than " << kElasticCompared << " elastic modes among the " << kModes;
    double sum = 0.0, largest = 0.0;
    std::size_t worst = 0;
    for (std::size_t k = 0; k < kElasticCompared; ++k) {
      const std::size_t row = reference.nearZero + k;
      const double hertz = reference.run.modes[row].hertz;
      const double difference = std::abs(after.run.modes[row].hertz - hertz) / hertz;
      sum += difference;
      if (k == 0 || difference > largest) {
        largest = difference;
        worst = row + 1;
      }
    }
    const double mean = sum / kElasticCompared;
    std::printf(
        "%s: first %zu elastic modes differ by %.2f %% on average, %.2f %% at most "
        "(mode %zu)\n",
        name.c_str(), kElasticCompared, 100.0 * mean, 100.0 * largest, worst);
    EXPECT_LE(mean, kMeanDifferenceLimit) << "mean relative difference of the elastic frequencies";
    EXPECT_LE(largest, kMaxDifferenceLimit)
        << "largest relative difference of the elastic frequencies (mode " << worst << ")";
  }
  std::printf("%s: %.1f s in all\n", name.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

class CalculixModes : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!voxremesh::test::ccxAvailable())
      GTEST_SKIP() << "the CalculiX solver ccx is not on PATH (Debian package calculix-ccx, "
                      "installed by tools/install_dependencies.sh); skipping";
  }
};

}  // namespace

TEST(CalculixDeck, FrequencyDeckAddsMaterialSectionsAndStep) {
  const std::string inp =
      "*HEADING\nx\n*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n"
      "** voxremesh part 7 \"a, b\"\n"
      "*ELEMENT, TYPE=S4R, ELSET=\"a, b\"\n1, 1, 2, 3, 4\n"
      "*Element, type=s3r, elset=PLAIN\n2, 1, 2, 3\n"
      "*ELEMENT, TYPE=S4R, ELSET=\"a, b\"\n3, 1, 2, 3, 4\n";
  EXPECT_EQ(voxremesh::test::shellElsets(inp), (std::vector<std::string>{"\"a, b\"", "PLAIN"}));
  const std::string deck = voxremesh::test::frequencyDeck(inp);
  EXPECT_EQ(deck.find("S4R"), std::string::npos) << deck;
  EXPECT_EQ(deck.find("S3R"), std::string::npos) << deck;
  EXPECT_TRUE(voxremesh::test::contains(deck, "*ELEMENT, TYPE=S4, ELSET=\"a, b\"\n1, 1, 2, 3, 4\n"))
      << deck;
  EXPECT_TRUE(voxremesh::test::contains(deck, "*ELEMENT, TYPE=S3, elset=PLAIN\n")) << deck;
  EXPECT_TRUE(voxremesh::test::contains(deck, "*ELASTIC\n210000, 0.3\n*DENSITY\n7.85e-09\n"))
      << deck;
  EXPECT_TRUE(voxremesh::test::contains(deck,
                                        "*SHELL SECTION, ELSET=\"a, b\", MATERIAL=TEST_STEEL\n1\n"
                                        "*SHELL SECTION, ELSET=PLAIN, MATERIAL=TEST_STEEL\n1\n"
                                        "*STEP\n*FREQUENCY\n16\n*END STEP\n"))
      << deck;
  EXPECT_THROW(voxremesh::test::frequencyDeck(inp + "*STEP\n*STATIC\n*END STEP\n"),
               std::runtime_error);
  EXPECT_THROW(voxremesh::test::frequencyDeck("*NODE\n1, 0, 0, 0\n"), std::runtime_error);
}

TEST(CalculixDeck, ParsesTheEigenvalueTable) {
  const std::string dat =
      "\n     E I G E N V A L U E   O U T P U T\n\n"
      " MODE NO    EIGENVALUE                       FREQUENCY   \n"
      "                                     REAL PART            IMAGINARY PART\n"
      "                           (RAD/TIME)      (CYCLES/TIME     (RAD/TIME)\n\n"
      "      1  -0.2769450E-02   0.0000000E+00   0.0000000E+00   0.5262557E-01\n"
      "      2   0.9695689E-03   0.3113790E-01   0.4955751E-02   0.0000000E+00\n"
      "      3   0.2281427E+05   0.1510439E+03   0.2403939E+02   0.0000000E+00\n"
      "\n     P A R T I C I P A T I O N   F A C T O R S\n\n"
      "      1  -0.1595775E-04   0.6620703E-05   0.2583695E-01   0.1885941E+01\n";
  const std::vector<Eigenmode> modes = voxremesh::test::parseEigenmodes(dat);
  ASSERT_EQ(modes.size(), 3u);
  EXPECT_EQ(modes[2].mode, 3);
  EXPECT_DOUBLE_EQ(modes[0].eigenvalue, -0.2769450E-02);
  EXPECT_DOUBLE_EQ(modes[0].hertz, 0.0);
  EXPECT_DOUBLE_EQ(modes[2].radians, 0.1510439E+03);
  EXPECT_DOUBLE_EQ(modes[2].hertz, 0.2403939E+02);
  EXPECT_EQ(voxremesh::test::countNearZeroModes(modes, 1e-2), 2u);
  EXPECT_TRUE(voxremesh::test::parseEigenmodes("no table").empty());
}

TEST_F(CalculixModes, SamplePartKeepsRigidModesAndFrequencies) {
  checkModes(voxremesh::test::samplePart(), "hat_rail", true, Expect::AllRemeshed);
}

// The bracket's mesh at its default size still has folded elements (2, near a narrow tongue of
// its outline), so `remesh` retries it at half the size: its frequencies are compared with the
// original's cut into four.
TEST_F(CalculixModes, BracketKeepsRigidModesAndFrequencies) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "bracket.k");
  checkModes(deck, "bracket", true, Expect::Any);
}

// car5.k: five parts joined at seams (shared nodes) and a separate pole (part 6), so two bodies:
// 12 rigid-body modes. Seams that come apart in the remesh show as more rigid-body modes.
TEST_F(CalculixModes, Car5KeepsRigidModes) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "car5.k");
  checkModes(deck, "car5", false, Expect::Any);
}
