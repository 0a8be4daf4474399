// `voxremesh quality` run as a subprocess: on the real bracket deck (whose own quality the shared
// data README gives), JSON, the .vtu output, limit overrides and bad input.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "json/json.h"
#include "support/test_support.h"
#include "voxremesh/quality.h"

namespace fs = std::filesystem;
using voxremesh::json::parseJson;
using voxremesh::test::CliRun;
using voxremesh::test::quoted;
using voxremesh::test::readText;
using voxremesh::test::runCliSplit;
using voxremesh::test::scratchDir;
using voxremesh::test::writeText;

namespace {

/// The criteria entry named `metric` of a quality JSON report.
const voxremesh::json::Json& criterion(const voxremesh::json::Json& report,
                                       const std::string& metric) {
  for (const auto& item : report["criteria"].items)
    if (item["metric"].text == metric) return item;
  throw std::runtime_error("no criterion " + metric);
}

/// The values of the cell data array `name` of a .vtu file written by the quality command.
std::vector<double> vtuCellArray(const std::string& vtu, const std::string& name) {
  const std::size_t at = vtu.find("Name=\"" + name + "\"");
  if (at == std::string::npos) throw std::runtime_error("no array " + name);
  const std::size_t begin = vtu.find('>', at) + 1, end = vtu.find("</DataArray>", begin);
  std::istringstream values(vtu.substr(begin, end - begin));
  std::vector<double> result;
  for (double x; values >> x;) result.push_back(x);
  return result;
}

TEST(CliQuality, BracketMatchesThePublishedInputQuality) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "bracket.k");
  const fs::path dir = scratchDir("cli_quality_bracket");
  const CliRun r =
      runCliSplit("quality " + quoted(deck) + " --json --vtu " + quoted(dir / "q.vtu"));
  // A quarter of the input's elements fail a criterion: the report says FAIL, the exit code 3.
  ASSERT_EQ(r.exitCode, 3) << r.err;
  const auto report = parseJson(r.out);
  EXPECT_FALSE(report["pass"].boolean);
  EXPECT_EQ(report["elements"].number, 1865.0);
  EXPECT_EQ(report["trias"].number, 54.0);
  EXPECT_NEAR(report["target_size"].number, 4.46, 0.01);  // the median edge (shared README)
  // shared/data/README.md: 4.6 % warped over 15 degrees (85 of the 1865 elements, both
  // diagonals) and 5.1 % failing at least one of warping, angles, aspect and scaled Jacobian.
  EXPECT_EQ(criterion(report, "warping")["failing"].number, 85.0);
  EXPECT_NEAR(criterion(report, "warping")["share"].number, 0.046, 0.0005);
  using voxremesh::Criterion;
  std::uint32_t readmeCriteria = 0;
  for (const Criterion c : {Criterion::Warping, Criterion::AspectRatio, Criterion::QuadMinAngle,
                            Criterion::QuadMaxAngle, Criterion::TriaMinAngle,
                            Criterion::TriaMaxAngle, Criterion::ScaledJacobian})
    readmeCriteria |= 1u << static_cast<int>(c);
  const std::vector<double> mask = vtuCellArray(readText(dir / "q.vtu"), "fail_mask");
  ASSERT_EQ(mask.size(), 1865u);
  std::size_t failing = 0;
  for (const double m : mask) failing += (static_cast<std::uint32_t>(m) & readmeCriteria) ? 1 : 0;
  EXPECT_NEAR(double(failing) / 1865.0, 0.051, 0.0005);
  // With all our criteria the corner Jacobian ratio (DESIGN.md: corners, stricter than
  // HyperMesh's Gauss points) fails most: 22 % alone, 25 % in all.
  EXPECT_NEAR(criterion(report, "jacobian_ratio")["share"].number, 0.223, 0.001);
  EXPECT_NEAR(report["failing_any_share"].number, 0.2515, 0.001);
  EXPECT_TRUE(report["distance"].type == voxremesh::json::Json::Type::Null);
}

TEST(CliQuality, TableAndVtuWithDistance) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "bracket.k");
  const fs::path dir = scratchDir("cli_quality_vtu");
  const CliRun r = runCliSplit("quality " + quoted(deck) + " --original " + quoted(deck) +
                               " --vtu " + quoted(dir / "q.vtu"));
  ASSERT_EQ(r.exitCode, 3) << r.err;  // the input itself fails (a quarter of its elements)
  EXPECT_NE(r.out.find("result: FAIL"), std::string::npos) << r.out;
  for (const char* row :
       {"warping", "aspect", "quad_min_angle", "taper", "min_length", "degenerate_corner", "folded",
        "distance", "any criterion", "tria share", "distance max"})
    EXPECT_NE(r.out.find(row), std::string::npos) << row;
  const std::string vtu = readText(dir / "q.vtu");
  for (const char* name :
       {"\"warping_deg\"", "\"jacobian_ratio\"", "\"scaled_jacobian\"", "\"min_length\"",
        "\"fail_mask\"", "\"pass\"", "\"distance\"", "NumberOfCells=\"1865\""})
    EXPECT_NE(vtu.find(name), std::string::npos) << name;
  // The quality index per element: 0 for an element within every "good" threshold, at least 1
  // for one failing a criterion.
  const std::vector<double> index = vtuCellArray(vtu, "quality_index");
  const std::vector<double> pass = vtuCellArray(vtu, "pass");
  ASSERT_EQ(index.size(), 1865u);
  ASSERT_EQ(pass.size(), 1865u);
  for (std::size_t f = 0; f < index.size(); ++f) {
    if (pass[f] == 0.0) {
      EXPECT_GE(index[f], 1.0) << f;
    }
  }
  EXPECT_NE(r.out.find("quality index: mean"), std::string::npos) << r.out;
}

TEST(CliQuality, LimitOverridesChangeTheCounts) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "bracket.k");
  // At the Gauss points 73 of the bracket's quads have a Jacobian ratio under 0.6, at the corners
  // 416.
  const CliRun gauss =
      runCliSplit("quality " + quoted(deck) + " --json --jacobian-at-gauss-points");
  ASSERT_EQ(gauss.exitCode, 3) << gauss.err;
  EXPECT_EQ(criterion(parseJson(gauss.out), "jacobian_ratio")["failing"].number, 73.0);
  EXPECT_EQ(parseJson(gauss.out)["jacobian_at"].text, "gauss_points");
  const CliRun loose = runCliSplit("quality " + quoted(deck) + " --json --warping 90");
  ASSERT_EQ(loose.exitCode, 3) << loose.err;
  EXPECT_EQ(criterion(parseJson(loose.out), "warping")["failing"].number, 0.0);
  EXPECT_EQ(criterion(parseJson(loose.out), "warping")["limit"].number, 90.0);
}

TEST(CliQuality, ACriteriaFileSetsTheLimitsAndFlagsOverrideIt) {
  VOXREMESH_REQUIRE_SHARED_DECK(deck, "bracket.k");
  const fs::path dir = scratchDir("cli_quality_criteria");
  writeText(dir / "oem.txt", "# an OEM's stricter warping\nwarping 0 2 4 8 20 2\n");
  const CliRun strict =
      runCliSplit("quality " + quoted(deck) + " --json --criteria " + quoted(dir / "oem.txt"));
  ASSERT_EQ(strict.exitCode, 3) << strict.err;
  EXPECT_EQ(criterion(parseJson(strict.out), "warping")["limit"].number, 8.0);
  const CliRun plain = runCliSplit("quality " + quoted(deck) + " --json");
  EXPECT_GT(criterion(parseJson(strict.out), "warping")["failing"].number,
            criterion(parseJson(plain.out), "warping")["failing"].number);
  // The index weighs the warping penalties twice and counts them from 2 degrees on.
  EXPECT_GT(parseJson(strict.out)["quality_index"].number,
            parseJson(plain.out)["quality_index"].number);
  const CliRun overridden = runCliSplit("quality " + quoted(deck) + " --json --criteria " +
                                        quoted(dir / "oem.txt") + " --warping 30");
  EXPECT_EQ(criterion(parseJson(overridden.out), "warping")["limit"].number, 30.0);
  // The criteria in effect, as a file that reads back to them.
  const CliRun printed =
      runCliSplit("quality --print-criteria --criteria " + quoted(dir / "oem.txt"));
  ASSERT_EQ(printed.exitCode, 0) << printed.err;
  EXPECT_NE(printed.out.find("warping                    0         2         4         8"),
            std::string::npos)
      << printed.out;
  writeText(dir / "printed.txt", printed.out);
  const CliRun again =
      runCliSplit("quality --print-criteria --criteria " + quoted(dir / "printed.txt"));
  EXPECT_EQ(again.out, printed.out);
  // A bad file: exit 1, its line named, nothing written.
  writeText(dir / "bad.txt", "warping 0 2 4 8 20\nskew 0 10 30\n");
  const CliRun bad = runCliSplit("quality " + quoted(deck) + " --criteria " +
                                 quoted(dir / "bad.txt") + " --vtu " + quoted(dir / "q.vtu"));
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("bad.txt:2"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "q.vtu"));
}

TEST(CliQuality, BadInputAndSettingsFailWithoutOutput) {
  const fs::path dir = scratchDir("cli_quality_bad");
  writeText(dir / "bad.k",
            "*KEYWORD\n*NODE\n       1  1.2.3e+x4             0.0             0.0\n*END\n");
  const CliRun bad =
      runCliSplit("quality " + quoted(dir / "bad.k") + " --vtu " + quoted(dir / "o.vtu"));
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("bad.k:3"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "o.vtu"));

  writeText(dir / "ok.k",
            "*KEYWORD\n*NODE\n       1             0.0             0.0             0.0\n"
            "       2             1.0             0.0             0.0\n"
            "       3             1.0             1.0             0.0\n"
            "       4             0.0             1.0             0.0\n"
            "*ELEMENT_SHELL\n       1       1       1       2       3       4\n*END\n");
  const CliRun ok = runCliSplit("quality " + quoted(dir / "ok.k") + " --json");
  ASSERT_EQ(ok.exitCode, 0) << ok.err;
  EXPECT_TRUE(parseJson(ok.out)["pass"].boolean);
  for (const char* option : {"--warping -1", "--taper nan", "--size -3", "--aspect abc"}) {
    const CliRun r = runCliSplit("quality " + quoted(dir / "ok.k") + " " + option + " --vtu " +
                                 quoted(dir / "o.vtu"));
    EXPECT_EQ(r.exitCode, 2) << option;  // a malformed command line
    EXPECT_NE(r.err.find("usage: voxremesh quality"), std::string::npos) << option << r.err;
    EXPECT_FALSE(fs::exists(dir / "o.vtu")) << option;
  }
  EXPECT_EQ(runCliSplit("quality " + quoted(dir / "ok.k") + " --bogus").exitCode, 2);
  EXPECT_EQ(runCliSplit("quality").exitCode, 2);
  const CliRun missing = runCliSplit("quality " + quoted(dir / "ok.k") + " --part 7");
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.err.find("no shells of part 7"), std::string::npos) << missing.err;
}

}  // namespace
