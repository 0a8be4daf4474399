// Sheets (include/voxremesh/sheets.h): splitting, orientation, boundary loops, feature lines and
// points, junction curves; on synthetic parts whose answers are known by construction and on the
// real decks of ../shared/data.
#include "voxremesh/sheets.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <regex>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "support/test_support.h"
#include "voxremesh/errors.h"
#include "voxremesh/io.h"

using namespace voxremesh;
using test::addNode;
using test::addShell;

namespace {

constexpr double kPi = 3.14159265358979323846;
using Vec3 = std::array<double, 3>;

// ---------------------------------------------------------------------------------------------
// Building models

Id nextShellId(const FeModel& m) {
  Id id = 0;
  for (const Shell& s : m.shells) id = std::max(id, s.id);
  return id + 1;
}

// A structured sheet of nx x ny quads: node (i, j) at place(i, j), node IDs firstNode + j *
// (nx + 1) + i, quads (i, j) -> (i + 1, j) -> (i + 1, j + 1) -> (i, j + 1) unless skip(i, j),
// shell IDs following the model's highest.
template <class Place, class Skip>
void addSheet(FeModel& m, Id part, Id firstNode, int nx, int ny, Place place, Skip skip) {
  auto node = [&](int i, int j) { return firstNode + Id(j) * (nx + 1) + i; };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const Vec3 p = place(i, j);
      addNode(m, node(i, j), p[0], p[1], p[2]);
    }
  Id id = nextShellId(m);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (!skip(i, j))
        addShell(m, id++, part, {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
}

template <class Place>
void addSheet(FeModel& m, Id part, Id firstNode, int nx, int ny, Place place) {
  addSheet(m, part, firstNode, nx, ny, place, [](int, int) { return false; });
}

// A flat nx x ny plate of unit quads in z = 0, normals +z, part 1, node IDs from 1.
FeModel flatPlate(int nx, int ny) {
  FeModel m;
  m.partOrAdd(1, "plate");
  addSheet(m, 1, 1, nx, ny, [](int i, int j) { return Vec3{double(i), double(j), 0.0}; });
  return m;
}

void reverseShell(Shell& s) {
  std::reverse(s.nodes.begin() + 1, s.nodes.begin() + s.nodeCount);
}

// ---------------------------------------------------------------------------------------------
// Checks, independent of the implementation

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

unsigned cornerCount(const Sheet& sheet, std::size_t f) {
  return sheet.faces[f][3] == kNoPoint ? 3u : 4u;
}

// Newell normal of face f (exact for planar faces, robust for warped ones).
Vec3 faceNormal(const Sheet& sheet, std::size_t f) {
  Vec3 n{0, 0, 0};
  const unsigned m = cornerCount(sheet, f);
  for (unsigned k = 0; k < m; ++k) {
    const Vec3 c =
        cross(sheet.points[sheet.faces[f][k]], sheet.points[sheet.faces[f][(k + 1) % m]]);
    for (int a = 0; a < 3; ++a) n[a] += c[a];
  }
  return n;
}

// The vector area of a closed polyline (its normal times its area).
Vec3 vectorArea(const Sheet& sheet, const Polyline& loop) {
  Vec3 area{0, 0, 0};
  const std::size_t n = loop.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 c = cross(sheet.points[loop.points[i]], sheet.points[loop.points[(i + 1) % n]]);
    for (int a = 0; a < 3; ++a) area[a] += 0.5 * c[a];
  }
  return area;
}

using EdgeKey = std::pair<PointIndex, PointIndex>;
EdgeKey key(PointIndex a, PointIndex b) {
  return {std::min(a, b), std::max(a, b)};
}

// The directed uses of each edge of a sheet: (face, runs from lower to higher point).
std::map<EdgeKey, std::vector<std::pair<std::size_t, bool>>> edgeUses(const Sheet& sheet) {
  std::map<EdgeKey, std::vector<std::pair<std::size_t, bool>>> uses;
  for (std::size_t f = 0; f < sheet.faces.size(); ++f) {
    const unsigned m = cornerCount(sheet, f);
    for (unsigned k = 0; k < m; ++k) {
      const PointIndex a = sheet.faces[f][k], b = sheet.faces[f][(k + 1) % m];
      uses[key(a, b)].emplace_back(f, a < b);
    }
  }
  return uses;
}

std::size_t polylineEdges(const std::vector<Polyline>& lines) {
  std::size_t n = 0;
  for (const Polyline& line : lines) n += line.closed ? line.points.size() : line.points.size() - 1;
  return n;
}

// The distinct corners of a shell as sheets.h defines them (neighbouring repeats dropped), or
// empty for a shell without a surface.
std::vector<Id> distinctCorners(const Shell& s) {
  std::vector<Id> c;
  for (unsigned k = 0; k < s.nodeCount; ++k)
    if (c.empty() || c.back() != s.nodes[k]) c.push_back(s.nodes[k]);
  while (c.size() > 1 && c.back() == c.front()) c.pop_back();
  std::set<Id> distinct(c.begin(), c.end());
  if (c.size() < 3 || distinct.size() != c.size()) return {};
  return c;
}

// Everything sheets.h promises of the sheets of `model`, checked with plain maps:
// - each shell with a surface is a face of exactly one sheet, of its part, with the model's
//   corners in the model's order or reversed (keeping the first) as faceFlipped says;
// - points are numbered by first use, positions and node IDs match the model;
// - every edge has one face or two running along it in opposite directions;
// - the boundary loops are closed, cover every boundary edge once, and run with the face on the
//   left (the way the face runs along the edge);
// - polylines run along sheet edges; feature points are ascending and distinct.
void expectValidSheets(const FeModel& model, const std::vector<Sheet>& sheets) {
  std::unordered_map<Id, const Shell*> shellById;
  for (const Shell& s : model.shells) shellById[s.id] = &s;
  std::unordered_map<Id, const Node*> nodeById;
  for (const Node& n : model.nodes) nodeById[n.id] = &n;
  std::map<Id, int> seen;
  for (const Sheet& sheet : sheets) {
    ASSERT_EQ(sheet.points.size(), sheet.pointNodeIds.size());
    ASSERT_EQ(sheet.faces.size(), sheet.faceShellIds.size());
    ASSERT_EQ(sheet.faces.size(), sheet.faceFlipped.size());
    PointIndex nextPoint = 0;
    for (std::size_t f = 0; f < sheet.faces.size(); ++f) {
      const Shell& shell = *shellById.at(sheet.faceShellIds[f]);
      ++seen[shell.id];
      EXPECT_EQ(shell.part, sheet.part);
      std::vector<Id> expected = distinctCorners(shell);
      ASSERT_FALSE(expected.empty()) << "shell " << shell.id << " has no surface";
      if (sheet.faceFlipped[f]) std::reverse(expected.begin() + 1, expected.end());
      const unsigned m = cornerCount(sheet, f);
      ASSERT_EQ(m, expected.size()) << "shell " << shell.id;
      for (unsigned k = 0; k < m; ++k) {
        const PointIndex p = sheet.faces[f][k];
        ASSERT_LT(p, sheet.points.size());
        EXPECT_LE(p, nextPoint) << "points are not numbered by first use";
        if (p == nextPoint) ++nextPoint;
        EXPECT_EQ(sheet.pointNodeIds[p], expected[k]) << "shell " << shell.id;
        EXPECT_EQ(sheet.points[p], nodeById.at(expected[k])->xyz);
      }
    }
    EXPECT_EQ(nextPoint, sheet.points.size()) << "a point no face uses";

    const auto uses = edgeUses(sheet);
    std::set<std::pair<PointIndex, PointIndex>> boundary;  // directed, as the face runs
    for (const auto& [edge, on] : uses) {
      ASSERT_LE(on.size(), 2u) << "non-manifold edge in a sheet of part " << sheet.part;
      if (on.size() == 2) {
        EXPECT_NE(on[0].second, on[1].second)
            << "inconsistent edge between shells " << sheet.faceShellIds[on[0].first] << " and "
            << sheet.faceShellIds[on[1].first];
      } else {
        boundary.insert(on[0].second ? edge : std::make_pair(edge.second, edge.first));
      }
    }
    std::size_t loopEdges = 0;
    for (const Polyline& loop : sheet.boundaryLoops) {
      EXPECT_TRUE(loop.closed);
      for (std::size_t i = 0; i < loop.points.size(); ++i) {
        const auto directed =
            std::make_pair(loop.points[i], loop.points[(i + 1) % loop.points.size()]);
        EXPECT_EQ(boundary.count(directed), 1u)
            << "loop edge " << directed.first << "-" << directed.second
            << " is not a boundary edge run the way its face runs";
        ++loopEdges;
      }
    }
    EXPECT_EQ(loopEdges, boundary.size());
    for (const auto* lines : {&sheet.featureLines, &sheet.junctionCurves})
      for (const Polyline& line : *lines) {
        ASSERT_GE(line.points.size(), 2u);
        const std::size_t n = line.points.size();
        for (std::size_t i = 0; i + 1 < n + (line.closed ? 1 : 0); ++i)
          EXPECT_EQ(uses.count(key(line.points[i], line.points[(i + 1) % n])), 1u)
              << "a polyline leaves the sheet's edges";
      }
    EXPECT_TRUE(std::is_sorted(sheet.featurePoints.begin(), sheet.featurePoints.end()));
    EXPECT_EQ(std::adjacent_find(sheet.featurePoints.begin(), sheet.featurePoints.end()),
              sheet.featurePoints.end());
  }
  for (const Shell& s : model.shells) {
    const int expected = distinctCorners(s).empty() ? 0 : 1;
    EXPECT_EQ(seen[s.id], expected) << "shell " << s.id;
  }
}

// The node IDs of a polyline's points.
std::vector<Id> nodeIds(const Sheet& sheet, const Polyline& line) {
  std::vector<Id> ids;
  for (const PointIndex p : line.points) ids.push_back(sheet.pointNodeIds[p]);
  return ids;
}

// The same as `ids` or reversed.
void expectSameLine(std::vector<Id> actual, const std::vector<Id>& ids) {
  if (!actual.empty() && actual.front() != ids.front()) std::reverse(actual.begin(), actual.end());
  EXPECT_EQ(actual, ids);
}

std::set<Id> featurePointIds(const Sheet& sheet) {
  std::set<Id> ids;
  for (const PointIndex p : sheet.featurePoints) ids.insert(sheet.pointNodeIds[p]);
  return ids;
}

// ---------------------------------------------------------------------------------------------
// Parts with known answers

// A plate of 6 x 4 unit quads in z = 0 and a flange of 6 x 3 bent up along y = 4 by `angle`
// degrees; node (i, j) has ID 1 + 7 j + i, j = 4 is the bend.
FeModel bentFlange(double angleDeg) {
  FeModel m;
  m.partOrAdd(1, "flange");
  const double a = angleDeg * kPi / 180.0;
  addSheet(m, 1, 1, 6, 7, [&](int i, int j) {
    if (j <= 4) return Vec3{double(i), double(j), 0.0};
    return Vec3{double(i), 4.0 + (j - 4) * std::cos(a), (j - 4) * std::sin(a)};
  });
  return m;
}

Id flangeNode(int i, int j) {
  return 1 + 7 * j + i;
}

// A strip of n x bands quads around a circle of radius 5 with a half twist: node rows r = 0 ..
// bands across the strip, node (r, i) has ID 1 + r n + i; shell b n + i + 1 joins rows b and b + 1
// between i and i + 1. Past the twist, row r continues as row bands - r.
FeModel moebius(int n, int bands = 1) {
  FeModel m;
  m.partOrAdd(1, "moebius");
  auto node = [&](int r, int i) { return Id(1 + r * n + i); };
  for (int r = 0; r <= bands; ++r)
    for (int i = 0; i < n; ++i) {
      const double t = 2 * kPi * i / n, w = -1.0 + 2.0 * r / bands;
      const double radius = 5.0 + w * std::cos(t / 2);
      addNode(m, node(r, i), radius * std::cos(t), radius * std::sin(t), w * std::sin(t / 2));
    }
  for (int b = 0; b < bands; ++b) {
    for (int i = 0; i + 1 < n; ++i)
      addShell(m, b * n + i + 1, 1,
               {node(b, i), node(b, i + 1), node(b + 1, i + 1), node(b + 1, i)});
    addShell(m, b * n + n, 1,
             {node(b, n - 1), node(bands - b, 0), node(bands - b - 1, 0), node(b + 1, n - 1)});
  }
  return m;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Orientation

TEST(Sheets, FlatPlateWithRandomFlipsIsOneConsistentSheetKeepingTheMajority) {
  FeModel m = flatPlate(12, 8);
  std::mt19937 random(7);
  std::set<Id> flipped;
  for (Shell& s : m.shells)
    if (s.id == 1 || random() % 10 < 3) {  // the first face (the walk's seed) is in the minority
      reverseShell(s);
      flipped.insert(s.id);
    }
  ASSERT_GT(flipped.size(), 10u);
  ASSERT_LT(2 * flipped.size(), m.shells.size());
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  const Sheet& sheet = sheets[0];
  EXPECT_EQ(sheet.part, 1);
  EXPECT_EQ(sheet.faces.size(), 96u);
  EXPECT_EQ(sheet.points.size(), 13u * 9u);
  for (std::size_t f = 0; f < sheet.faces.size(); ++f) {
    EXPECT_EQ(sheet.faceFlipped[f], flipped.count(sheet.faceShellIds[f]) == 1);
    EXPECT_GT(faceNormal(sheet, f)[2], 0.0) << "the majority's +z orientation is kept";
  }
  EXPECT_TRUE(sheet.featureLines.empty());
  EXPECT_TRUE(sheet.junctionCurves.empty());
  ASSERT_EQ(sheet.boundaryLoops.size(), 1u);
  EXPECT_EQ(sheet.boundaryLoops[0].points.size(), 2u * (12 + 8));
  EXPECT_EQ(featurePointIds(sheet), (std::set<Id>{1, 13, 105, 117}));  // the four corners
}

TEST(Sheets, MajorityOfFlippedFacesDecidesTheOrientation) {
  FeModel m = flatPlate(5, 4);
  std::set<Id> kept;  // shells left as they were: the minority, the first face among them
  for (Shell& s : m.shells) {
    if (s.id % 4 == 1) {
      kept.insert(s.id);
      continue;
    }
    reverseShell(s);
  }
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  for (std::size_t f = 0; f < sheets[0].faces.size(); ++f) {
    EXPECT_EQ(sheets[0].faceFlipped[f], kept.count(sheets[0].faceShellIds[f]) == 1);
    EXPECT_LT(faceNormal(sheets[0], f)[2], 0.0);
  }
}

TEST(Sheets, TieKeepsTheFirstFacesOrientation) {
  FeModel m = flatPlate(2, 2);
  // Shells 1 and 4 face -z, 2 and 3 +z: a tie; shell 1 is the first face.
  reverseShell(m.shells[0]);
  reverseShell(m.shells[3]);
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  EXPECT_EQ(sheets[0].faceFlipped, (std::vector<bool>{false, true, true, false}));
  for (std::size_t f = 0; f < 4; ++f) EXPECT_LT(faceNormal(sheets[0], f)[2], 0.0);
  // Corners of a flipped face: reversed from the same first corner (shell 2 is 2-3-6-5).
  EXPECT_EQ(sheets[0].pointNodeIds[sheets[0].faces[1][0]], 2);
  EXPECT_EQ(sheets[0].pointNodeIds[sheets[0].faces[1][1]], 5);
  EXPECT_EQ(sheets[0].pointNodeIds[sheets[0].faces[1][2]], 6);
  EXPECT_EQ(sheets[0].pointNodeIds[sheets[0].faces[1][3]], 3);
}

TEST(Sheets, MoebiusStripIsReportedNamingTheShell) {
  const FeModel m = moebius(12);
  try {
    buildSheets(m, 1);
    FAIL() << "a Moebius strip was oriented";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(error.file(), "");
    EXPECT_EQ(error.line(), 0u);
    EXPECT_NE(message.find("part 1 (moebius)"), std::string::npos) << message;
    EXPECT_NE(message.find("Moebius"), std::string::npos) << message;
    std::smatch match;
    ASSERT_TRUE(std::regex_search(message, match,
                                  std::regex("shell (\\d+) would have to be flipped both ways; "
                                             "the conflict closes at the edge between nodes "
                                             "(\\d+) and (\\d+), shared with shell (\\d+)")))
        << message;
    // The named shells exist, differ, and both have the named edge.
    const Id shell = std::stoll(match[1]), a = std::stoll(match[2]), b = std::stoll(match[3]),
             other = std::stoll(match[4]);
    EXPECT_NE(shell, other);
    for (const Id id : {shell, other}) {
      ASSERT_TRUE(id >= 1 && id <= 12) << message;
      const Shell& s = m.shells[std::size_t(id - 1)];
      EXPECT_NE(std::find(s.nodes.begin(), s.nodes.end(), a), s.nodes.end()) << message;
      EXPECT_NE(std::find(s.nodes.begin(), s.nodes.end(), b), s.nodes.end()) << message;
    }
  }
  EXPECT_THROW(buildAllSheets(m), InputError);
}

TEST(Sheets, OrientableStripAroundACircleIsOneSheet) {
  // The same strip without the twist: orientable, two boundary loops.
  FeModel m;
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPi * i / n;
    addNode(m, 1 + i, 4 * std::cos(t), 4 * std::sin(t), 0.0);
    addNode(m, 1 + n + i, 6 * std::cos(t), 6 * std::sin(t), 0.0);
  }
  for (int i = 0; i < n; ++i)
    addShell(m, i + 1, 3, {1 + i, 1 + (i + 1) % n, 1 + n + (i + 1) % n, 1 + n + i});
  reverseShell(m.shells[5]);
  const std::vector<Sheet> sheets = buildSheets(m, 3);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  ASSERT_EQ(sheets[0].boundaryLoops.size(), 2u);
  // Normals -z (the shells run clockwise seen from +z): seen from the normal the outer loop runs
  // counter-clockwise, the inner one (a hole) clockwise.
  const Vec3 normal = faceNormal(sheets[0], 0);
  EXPECT_LT(normal[2], 0.0);
  std::vector<double> areas;
  for (const Polyline& loop : sheets[0].boundaryLoops)
    areas.push_back(dot(vectorArea(sheets[0], loop), normal) / std::sqrt(dot(normal, normal)));
  std::sort(areas.begin(), areas.end());
  EXPECT_LT(areas[0], 0.0);  // the hole, radius 4
  EXPECT_GT(areas[1], 0.0);  // the outer contour, radius 6
  EXPECT_GT(areas[1], -areas[0]);
}

// ---------------------------------------------------------------------------------------------
// Splitting

TEST(Sheets, TJunctionGivesThreeSheetsSharingAJunctionCurve) {
  // Three plates on the edge line y = z = 0, x = 0..4 (nodes 1..5 in each plate's numbering).
  FeModel m;
  m.partOrAdd(1, "tee");
  addSheet(m, 1, 1, 4, 2, [](int i, int j) { return Vec3{double(i), double(j), 0.0}; });
  // The other two reuse the line's nodes 1..5; their own nodes are numbered from 101 and 201.
  auto plate = [&](Id firstNode, Vec3 direction) {
    for (int j = 1; j <= 2; ++j)
      for (int i = 0; i <= 4; ++i)
        addNode(m, firstNode + (j - 1) * 5 + i, i + j * direction[0], j * direction[1],
                j * direction[2]);
    auto node = [&](int i, int j) { return j == 0 ? Id(1 + i) : firstNode + (j - 1) * 5 + i; };
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 4; ++i)
        addShell(m, nextShellId(m), 1,
                 {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
  };
  plate(101, {0.0, -1.0, 0.0});
  plate(201, {0.0, 0.0, 1.0});
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 3u);
  expectValidSheets(m, sheets);
  for (const Sheet& sheet : sheets) {
    EXPECT_EQ(sheet.faces.size(), 8u);
    EXPECT_EQ(sheet.points.size(), 15u);
    ASSERT_EQ(sheet.junctionCurves.size(), 1u);
    EXPECT_FALSE(sheet.junctionCurves[0].closed);
    expectSameLine(nodeIds(sheet, sheet.junctionCurves[0]), {1, 2, 3, 4, 5});
    ASSERT_EQ(sheet.boundaryLoops.size(), 1u);  // the junction is on each sheet's boundary
    EXPECT_EQ(sheet.boundaryLoops[0].points.size(), 12u);
  }
}

TEST(Sheets, APlateIsCutAlongAFinOfItsOwnOnToItsFarEdge) {
  // A 6 x 4 plate with a fin standing on y = 2 from x = 0 to 3: the fin's line ends inside the
  // plate, so it is extended along y = 2 to x = 6 and the plate's halves are two sheets, each
  // with the whole line (the fin's nodes and the extension's) on its junction curves.
  FeModel m;
  m.partOrAdd(1, "plate and fin");
  addSheet(m, 1, 1, 6, 4, [](int i, int j) { return Vec3{double(i), double(j), 0.0}; });
  auto plateNode = [](int i, int j) { return Id(1 + 7 * j + i); };
  for (int j = 1; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) addNode(m, 100 + 4 * j + i, i, 2.0, j);
  auto finNode = [&](int i, int j) { return j == 0 ? plateNode(i, 2) : Id(100 + 4 * j + i); };
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i)
      addShell(m, nextShellId(m), 1,
               {finNode(i, j), finNode(i + 1, j), finNode(i + 1, j + 1), finNode(i, j + 1)});
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 3u);
  expectValidSheets(m, sheets);
  std::vector<Id> line;
  for (int i = 0; i <= 6; ++i) line.push_back(plateNode(i, 2));
  std::size_t halves = 0;
  for (const Sheet& sheet : sheets) {
    if (sheet.faces.size() == 6u) continue;  // the fin
    EXPECT_EQ(sheet.faces.size(), 12u);
    ++halves;
    std::set<Id> onCurves;
    for (const Polyline& curve : sheet.junctionCurves)
      for (const Id id : nodeIds(sheet, curve)) onCurves.insert(id);
    EXPECT_EQ(onCurves, std::set<Id>(line.begin(), line.end()));
    EXPECT_TRUE(sheet.featureLines.empty());
  }
  EXPECT_EQ(halves, 2u);
}

TEST(Sheets, TwistedStripClosingAtAFinIsCutThere) {
  // A Moebius strip two quads wide whose closing edges (nodes 1, 13, 25) also carry a fin: those
  // edges are non-manifold, the strip is an orientable band whose ends meet there the wrong way
  // round, so it is cut along them: each of the three nodes gets a point per side, and the faces
  // on one side of the cut share their point at node 13.
  FeModel m = moebius(12, 2);
  addNode(m, 100, 4.0, 0.0, 3.0);
  addNode(m, 101, 5.0, 0.0, 3.0);
  addNode(m, 102, 6.0, 0.0, 3.0);
  addShell(m, 50, 1, {1, 13, 101, 100});
  addShell(m, 51, 1, {13, 25, 102, 101});
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 2u);
  expectValidSheets(m, sheets);
  const Sheet& strip = sheets[0];
  EXPECT_EQ(strip.faces.size(), 24u);
  EXPECT_EQ(strip.points.size(), 36u + 3u);
  for (const Id v : {1, 13, 25})
    EXPECT_EQ(std::count(strip.pointNodeIds.begin(), strip.pointNodeIds.end(), v), 2) << v;
  ASSERT_EQ(strip.boundaryLoops.size(), 1u);
  EXPECT_EQ(strip.boundaryLoops[0].points.size(), 2u * 12u + 4u);  // + both sides of the cut
  ASSERT_EQ(strip.junctionCurves.size(), 2u);                      // each side of the cut
  for (const Polyline& line : strip.junctionCurves)
    expectSameLine(nodeIds(strip, line), {1, 13, 25});
  EXPECT_EQ(sheets[1].faceShellIds, (std::vector<Id>{50, 51}));
  ASSERT_EQ(sheets[1].junctionCurves.size(), 1u);
  expectSameLine(nodeIds(sheets[1], sheets[1].junctionCurves[0]), {1, 13, 25});
  // Without the fin the same strip is not orientable.
  EXPECT_THROW(buildSheets(moebius(12, 2), 1), InputError);
}

TEST(Sheets, SheetsTouchingAtOneNodeAreSeparate) {
  // Two squares touching at node 3 only.
  FeModel m;
  m.partOrAdd(1);
  addNode(m, 1, 0, 0);
  addNode(m, 2, 1, 0);
  addNode(m, 3, 1, 1);
  addNode(m, 4, 0, 1);
  addNode(m, 5, 2, 1);
  addNode(m, 6, 2, 2);
  addNode(m, 7, 1, 2);
  addShell(m, 1, 1, {1, 2, 3, 4});
  addShell(m, 2, 1, {3, 5, 6, 7});
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 2u);
  expectValidSheets(m, sheets);
  for (const Sheet& sheet : sheets) EXPECT_EQ(sheet.boundaryLoops.size(), 1u);
}

TEST(Sheets, HolesTouchingAtACornerAreOneLoopThroughTheNodeTwice) {
  // A 4 x 4 plate without cells (2, 1) and (1, 2): node (2, 2) (ID 13) joins two fans of faces
  // that only touch there. The node is not split; the boundary passes it once per fan.
  FeModel m;
  m.partOrAdd(1);
  addSheet(
      m, 1, 1, 4, 4,
      [](int i, int j) {
        return Vec3{double(i), double(j), 0.0};
      },
      [](int i, int j) { return (i == 2 && j == 1) || (i == 1 && j == 2); });
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  EXPECT_EQ(sheets[0].points.size(), 25u);
  ASSERT_EQ(sheets[0].boundaryLoops.size(), 2u);
  std::vector<std::size_t> sizes;
  for (const Polyline& loop : sheets[0].boundaryLoops) {
    sizes.push_back(loop.points.size());
    const std::vector<Id> ids = nodeIds(sheets[0], loop);
    if (loop.points.size() == 8u) {
      EXPECT_EQ(std::count(ids.begin(), ids.end(), 13), 2);
    }
    EXPECT_LT(vectorArea(sheets[0], loop)[2] * (loop.points.size() == 8u ? 1 : -1), 0.0);
  }
  std::sort(sizes.begin(), sizes.end());
  EXPECT_EQ(sizes, (std::vector<std::size_t>{8u, 16u}));
}

TEST(Sheets, ShellsWithoutSurfaceBelongToNoSheetAndCollapsedQuadsAreTriangles) {
  FeModel m = flatPlate(2, 1);  // nodes 1..6
  addNode(m, 7, 3, 0);
  addShell(m, 10, 1, {3, 7, 7, 6});  // a quad with a repeated corner: triangle 3-7-6
  addShell(m, 11, 1, {1, 2, 2, 1});  // a line
  addShell(m, 12, 1, {1, 2, 1, 4});  // folded onto itself
  addShell(m, 13, 1, {4, 4, 4, 4});  // a point
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  EXPECT_EQ(sheets[0].faceShellIds, (std::vector<Id>{1, 2, 10}));
  EXPECT_EQ(sheets[0].faces[2][3], kNoPoint);
  EXPECT_EQ(sheets[0].points.size(), 7u);
}

// ---------------------------------------------------------------------------------------------
// Boundary loops

TEST(Sheets, PlateWithTwoHolesHasThreeLoopsOrientedByTheNormal) {
  FeModel m;
  m.partOrAdd(1, "holes");
  addSheet(
      m, 1, 1, 10, 6,
      [](int i, int j) {
        return Vec3{double(i), double(j), 0.0};
      },
      [](int i, int j) { return (i == 2 && j == 2) || (i >= 6 && i <= 7 && j == 3); });
  std::mt19937 random(11);
  for (Shell& s : m.shells)
    if (random() % 5 == 0) reverseShell(s);
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  const Sheet& sheet = sheets[0];
  ASSERT_EQ(sheet.boundaryLoops.size(), 3u);
  std::vector<double> areas;
  for (const Polyline& loop : sheet.boundaryLoops) areas.push_back(vectorArea(sheet, loop)[2]);
  std::sort(areas.begin(), areas.end());
  // Normal +z: the outline counter-clockwise (area +60), the holes clockwise (-2 and -1).
  EXPECT_NEAR(areas[0], -2.0, 1e-12);
  EXPECT_NEAR(areas[1], -1.0, 1e-12);
  EXPECT_NEAR(areas[2], 60.0, 1e-12);
  EXPECT_EQ(polylineEdges(sheet.boundaryLoops), 32u + 4u + 6u);
  // The holes' corners are feature points: 4 + 4 + 4 outline corners.
  EXPECT_EQ(sheet.featurePoints.size(), 12u);
}

// ---------------------------------------------------------------------------------------------
// Feature lines and points

TEST(Sheets, SharpBendIsOneFeatureLineWithFeaturePointsAtItsEnds) {
  const FeModel m = bentFlange(90.0);
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  const Sheet& sheet = sheets[0];
  ASSERT_EQ(sheet.featureLines.size(), 1u);
  EXPECT_FALSE(sheet.featureLines[0].closed);
  std::vector<Id> bend;
  for (int i = 0; i <= 6; ++i) bend.push_back(flangeNode(i, 4));
  expectSameLine(nodeIds(sheet, sheet.featureLines[0]), bend);
  // Outline corners and the bend's ends (where the outline also turns by 90 degrees).
  EXPECT_EQ(featurePointIds(sheet),
            (std::set<Id>{flangeNode(0, 0), flangeNode(6, 0), flangeNode(6, 7), flangeNode(0, 7),
                          flangeNode(0, 4), flangeNode(6, 4)}));
  EXPECT_TRUE(sheet.junctionCurves.empty());
}

TEST(Sheets, GentleBendIsNoFeatureAtTheDefaultAngle) {
  const FeModel m = bentFlange(20.0);
  std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  EXPECT_TRUE(sheets[0].featureLines.empty());
  EXPECT_EQ(featurePointIds(sheets[0]),
            (std::set<Id>{flangeNode(0, 0), flangeNode(6, 0), flangeNode(6, 7), flangeNode(0, 7)}));
  // Lower thresholds find the bend and its ends as corners.
  SheetSettings settings;
  settings.featureAngleDeg = 15.0;
  settings.cornerAngleDeg = 15.0;
  sheets = buildSheets(m, 1, settings);
  ASSERT_EQ(sheets[0].featureLines.size(), 1u);
  EXPECT_EQ(sheets[0].featureLines[0].points.size(), 7u);
  EXPECT_EQ(featurePointIds(sheets[0]).size(), 6u);
}

TEST(Sheets, TheTipOfAConeIsAFeaturePointAndAFlatOrCylindricalPointIsNot) {
  // A cone of half angle 30 degrees: its faces' corner angles at the tip add up to 180 degrees,
  // far short of 360 (a cone whose normals turn by the feature angle, 45, across its tip falls
  // 27.4 degrees short), so the tip is a corner the mesh must keep; a cone of 80 degrees (15.5
  // short) and a disk (none) have no such point, nor the points of their rings.
  const FeModel pointed = test::coneModel(12, 4, 30.0);
  std::vector<Sheet> sheets = buildSheets(pointed, 1);
  ASSERT_EQ(sheets.size(), 1u);
  EXPECT_TRUE(sheets[0].featureLines.empty());
  EXPECT_EQ(featurePointIds(sheets[0]).count(1), 1u);
  for (const double blunt : {80.0, 90.0}) {
    sheets = buildSheets(test::coneModel(12, 4, blunt), 1);
    ASSERT_EQ(sheets.size(), 1u);
    EXPECT_EQ(featurePointIds(sheets[0]).count(1), 0u) << blunt;
  }
}

TEST(Sheets, AFlangeFoldedBackIsTwoSheetsMeetingAtTheFold) {
  // Bent by 150 degrees the flange runs back over the plate, 30 degrees apart: a fold. Bent by
  // 110 degrees it is an ordinary sharp bend, held by one volume.
  const FeModel folded = bentFlange(150.0);
  const std::vector<Sheet> sheets = buildSheets(folded, 1);
  ASSERT_EQ(sheets.size(), 2u);
  expectValidSheets(folded, sheets);
  EXPECT_EQ(sheets[0].faces.size(), 24u);  // the plate, 6 x 4
  EXPECT_EQ(sheets[1].faces.size(), 18u);  // the flange, 6 x 3
  std::vector<Id> bend;
  for (int i = 0; i <= 6; ++i) bend.push_back(flangeNode(i, 4));
  for (const Sheet& sheet : sheets) {
    ASSERT_EQ(sheet.junctionCurves.size(), 1u);
    expectSameLine(nodeIds(sheet, sheet.junctionCurves[0]), bend);
    EXPECT_TRUE(sheet.featureLines.empty());
  }
  EXPECT_EQ(findSheetCuts(folded).size(), 6u);
  const FeModel bent = bentFlange(110.0);
  EXPECT_EQ(buildSheets(bent, 1).size(), 1u);
  EXPECT_TRUE(findSheetCuts(bent).empty());
}

namespace {

// A closed wing section extruded along y (4 rows of unit length): 8 nodes round the section,
// from the trailing edge (x = 10, a 30-degree wedge) over the upper side to the rounded leading
// edge (x = 0) and back below; node (k, j) has ID 1 + 8 j + k, k = 0 the trailing edge, k = 4 the
// leading edge.
FeModel wingSection() {
  const std::array<std::array<double, 2>, 8> section{{{10.0, 0.0},
                                                      {7.0, 0.8},
                                                      {4.0, 1.2},
                                                      {1.0, 1.0},
                                                      {0.0, 0.0},
                                                      {1.0, -1.0},
                                                      {4.0, -1.2},
                                                      {7.0, -0.8}}};
  FeModel m;
  m.partOrAdd(1, "skin");
  for (int j = 0; j <= 4; ++j)
    for (int k = 0; k < 8; ++k)
      addNode(m, 1 + 8 * j + k, section[std::size_t(k)][0], double(j), section[std::size_t(k)][1]);
  for (int j = 0; j < 4; ++j)
    for (int k = 0; k < 8; ++k) {
      const Id a = 1 + 8 * j + k, b = 1 + 8 * j + (k + 1) % 8;
      addShell(m, nextShellId(m), 1, {a, b, b + 8, a + 8});
    }
  return m;
}

}  // namespace

TEST(Sheets, AWingSkinIsSplitAtItsTrailingEdgeAndAlongItsLeadingEdge) {
  const FeModel m = wingSection();
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 2u);
  expectValidSheets(m, sheets);
  const std::vector<Id> trailing{1, 9, 17, 25, 33}, leading{5, 13, 21, 29, 37};
  for (const Sheet& sheet : sheets) {
    EXPECT_EQ(sheet.faces.size(), 16u);  // one side of the wing each
    ASSERT_EQ(sheet.junctionCurves.size(), 2u);
    std::vector<std::vector<Id>> curves;
    for (const Polyline& curve : sheet.junctionCurves) {
      std::vector<Id> ids = nodeIds(sheet, curve);
      if (ids.front() > ids.back()) std::reverse(ids.begin(), ids.end());
      curves.push_back(ids);
    }
    std::sort(curves.begin(), curves.end());
    EXPECT_EQ(curves[0], trailing);
    EXPECT_EQ(curves[1], leading);
  }
  // A model holding only some of the skin's shells splits them where the whole skin is split.
  FeModel piece = m;
  piece.shells.resize(12);
  SheetSettings settings;
  settings.sheetCuts = std::make_shared<const std::vector<std::array<Id, 2>>>(findSheetCuts(m));
  std::size_t junctionEdges = 0;
  for (const Sheet& sheet : buildSheets(piece, 1, settings))
    junctionEdges += polylineEdges(sheet.junctionCurves);
  // Row 0 of the trailing and of the leading edge in both sheets, row 1 in the upper one only.
  EXPECT_EQ(junctionEdges, 6u);
}

TEST(Sheets, BendAwayFromTheNormalIsAFeatureToo) {
  // The flange of the sharp bend with every shell reversed: the dihedral angle does not depend
  // on the side the normals point to.
  FeModel m = bentFlange(90.0);
  for (Shell& s : m.shells) reverseShell(s);
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 1u);
  EXPECT_EQ(sheets[0].featureLines.size(), 1u);
  for (const bool flipped : sheets[0].faceFlipped) EXPECT_FALSE(flipped);
}

TEST(Sheets, FeatureLinesStopAtBoundaryPoints) {
  // A triangulated plate (6 x 4 cells, split along (i, j)-(i + 1, j + 1)) bent up by 90 degrees
  // along j = 2, with a notch cut from the top down to the bend at node (3, 2) (ID 18): the bend
  // passes through a boundary point there and is two feature lines.
  FeModel m;
  m.partOrAdd(1, "notched");
  auto node = [](int i, int j) { return Id(1 + 7 * j + i); };
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 6; ++i)
      addNode(m, node(i, j), i, j <= 2 ? j : 2.0, j <= 2 ? 0.0 : j - 2.0);
  Id id = 1;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 6; ++i) {
      const bool notch = i == 3 && j >= 2;
      if (!(notch && j == 3))
        addShell(m, id++, 1, {node(i, j), node(i + 1, j), node(i + 1, j + 1)});
      if (!notch) addShell(m, id++, 1, {node(i, j), node(i + 1, j + 1), node(i, j + 1)});
    }
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  const Sheet& sheet = sheets[0];
  ASSERT_EQ(sheet.featureLines.size(), 2u);
  expectSameLine(nodeIds(sheet, sheet.featureLines[0]),
                 {node(0, 2), node(1, 2), node(2, 2), node(3, 2)});
  expectSameLine(nodeIds(sheet, sheet.featureLines[1]),
                 {node(3, 2), node(4, 2), node(5, 2), node(6, 2)});
  const std::set<Id> points = featurePointIds(sheet);
  for (const Id v : {node(0, 2), node(3, 2), node(6, 2)}) EXPECT_EQ(points.count(v), 1u) << v;
}

TEST(Sheets, FeatureLinesStopAtBranchesAndClosedRidgesAreClosed) {
  // A pyramid roof over a 4 x 4 square: its four ridges meet at the apex (a branch point).
  FeModel m;
  m.partOrAdd(1, "roof");
  addSheet(m, 1, 1, 4, 4, [](int i, int j) {
    return Vec3{double(i), double(j), 2.0 - std::max(std::abs(i - 2), std::abs(j - 2))};
  });
  // Quads across the ridges are split along the diagonals so that ridges are edges.
  FeModel roof;
  roof.partOrAdd(1, "roof");
  roof.nodes = m.nodes;
  for (const Shell& s : m.shells) {
    // Split each quad along the diagonal through the square's centre line.
    const Vec3& p0 = m.nodes[std::size_t(s.nodes[0] - 1)].xyz;
    const bool lowerLeftOrUpperRight = (p0[0] < 2) == (p0[1] < 2);
    if (lowerLeftOrUpperRight) {
      addShell(roof, nextShellId(roof), 1, {s.nodes[0], s.nodes[1], s.nodes[2]});
      addShell(roof, nextShellId(roof), 1, {s.nodes[0], s.nodes[2], s.nodes[3]});
    } else {
      addShell(roof, nextShellId(roof), 1, {s.nodes[0], s.nodes[1], s.nodes[3]});
      addShell(roof, nextShellId(roof), 1, {s.nodes[1], s.nodes[2], s.nodes[3]});
    }
  }
  const std::vector<Sheet> sheets = buildSheets(roof, 1);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(roof, sheets);
  const Sheet& sheet = sheets[0];
  ASSERT_EQ(sheet.featureLines.size(), 4u);  // apex to each corner
  const Id apex = 13;
  for (const Polyline& line : sheet.featureLines) {
    EXPECT_FALSE(line.closed);
    EXPECT_EQ(line.points.size(), 3u);
    const std::vector<Id> ids = nodeIds(sheet, line);
    EXPECT_TRUE(ids.front() == apex || ids.back() == apex);
  }
  EXPECT_EQ(featurePointIds(sheet), (std::set<Id>{1, 5, 21, 25, apex}));
}

TEST(Sheets, CreaseThatNeverStopsIsAClosedFeatureLine) {
  // A cup: a flat ring (radius 1 to 2) and a wall (radius 2, height 2) around it, 16 quads round;
  // the crease at the wall's foot is a closed feature line that turns by 22.5 degrees per point.
  FeModel m;
  m.partOrAdd(1, "cup");
  const int n = 16;
  addSheet(m, 1, 1, n, 3, [&](int i, int j) {
    const double t = 2 * kPi * (i % n) / n;
    const double r = j == 0 ? 1.0 : 2.0, z = j <= 1 ? 0.0 : double(j - 1);
    return Vec3{r * std::cos(t), r * std::sin(t), z};
  });
  // Close the ring: node (n, j) is node (0, j).
  for (Shell& s : m.shells)
    for (Id& v : s.nodes)
      if ((v - 1) % (n + 1) == n) v -= n;
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  ASSERT_EQ(sheets[0].featureLines.size(), 1u);
  EXPECT_TRUE(sheets[0].featureLines[0].closed);
  EXPECT_EQ(sheets[0].featureLines[0].points.size(), std::size_t(n));
  for (const PointIndex p : sheets[0].featureLines[0].points)
    EXPECT_EQ((sheets[0].pointNodeIds[p] - 1) / (n + 1), 1);  // ring j = 1
  EXPECT_EQ(sheets[0].boundaryLoops.size(), 2u);
  EXPECT_TRUE(sheets[0].featurePoints.empty());
}

// ---------------------------------------------------------------------------------------------
// Junctions between parts

TEST(Sheets, PartsSharingARowOfNodesHaveTheSeamAsAJunctionCurve) {
  FeModel m;
  // Part 2 is defined first, so it comes first; part 9 is named only by its shells.
  m.partOrAdd(2, "upper");
  m.partOrAdd(1, "lower");
  m.partOrAdd(5, "no shells");
  addSheet(m, 1, 1, 5, 2, [](int i, int j) { return Vec3{double(i), double(j), 0.0}; });
  // Part 2 continues from row j = 2 of part 1 (nodes 13..18), bent up.
  auto node2 = [](int i, int j) { return j == 0 ? Id(13 + i) : Id(100 + 6 * j + i); };
  for (int j = 1; j <= 2; ++j)
    for (int i = 0; i <= 5; ++i) addNode(m, node2(i, j), i, 2.0, j);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 5; ++i)
      addShell(m, nextShellId(m), 2,
               {node2(i, j), node2(i + 1, j), node2(i + 1, j + 1), node2(i, j + 1)});
  // Part 9 touches part 1 at a single node (1): no curve. Parts 9 and 8 share node 201, a node
  // alone.
  addNode(m, 200, -1, -1);
  addNode(m, 201, 0, -1);
  addShell(m, nextShellId(m), 9, {200, 201, 1});
  // Part 8 touches part 1 at node 2: edge 1-2 of part 1 has both nodes shared, but with different
  // parts, so it is no seam.
  addNode(m, 202, 1, -1);
  addShell(m, nextShellId(m), 8, {201, 202, 2});

  const std::vector<Sheet> sheets = buildAllSheets(m);
  ASSERT_EQ(sheets.size(), 4u);
  expectValidSheets(m, sheets);
  EXPECT_EQ(sheets[0].part, 2);
  EXPECT_EQ(sheets[1].part, 1);
  EXPECT_EQ(sheets[2].part, 8);
  EXPECT_EQ(sheets[3].part, 9);
  for (const Sheet* sheet : {&sheets[0], &sheets[1]}) {
    ASSERT_EQ(sheet->junctionCurves.size(), 1u) << "part " << sheet->part;
    expectSameLine(nodeIds(*sheet, sheet->junctionCurves[0]), {13, 14, 15, 16, 17, 18});
  }
  EXPECT_TRUE(sheets[2].junctionCurves.empty());
  EXPECT_TRUE(sheets[3].junctionCurves.empty());
  // The parts meet at 90 degrees, but each part is flat: no feature lines.
  EXPECT_TRUE(sheets[0].featureLines.empty());
  EXPECT_TRUE(sheets[1].featureLines.empty());
  // buildSheets gives the same per part; a part without shells gives none.
  for (const Sheet& sheet : sheets) {
    const std::vector<Sheet> alone = buildSheets(m, sheet.part);
    ASSERT_EQ(alone.size(), 1u);
    EXPECT_EQ(alone[0].junctionCurves.size(), sheet.junctionCurves.size());
    EXPECT_EQ(alone[0].pointNodeIds, sheet.pointNodeIds);
  }
  EXPECT_TRUE(buildSheets(m, 5).empty());
  EXPECT_TRUE(buildSheets(m, 77).empty());
}

namespace {

// A plate of 8 x 6 unit quads in z = 0 (part 1, node (i, j) ID 1 + 9 j + i) and a web of part 2
// standing on the line y = 3 from x = `from` to x = `to`, sharing the plate's nodes there.
FeModel plateWithWeb(int from, int to) {
  FeModel m;
  m.partOrAdd(1, "plate");
  m.partOrAdd(2, "web");
  addSheet(m, 1, 1, 8, 6, [](int i, int j) { return Vec3{double(i), double(j), 0.0}; });
  for (int i = from; i <= to; ++i) addNode(m, 1001 + i, double(i), 3.0, 1.0);
  for (int i = from; i < to; ++i)
    addShell(m, nextShellId(m), 2,
             {Id(1 + 27 + i), Id(1 + 27 + i + 1), Id(1002 + i), Id(1001 + i)});
  return m;
}

}  // namespace

TEST(Sheets, ASeamThroughAPlateCutsItAndAnEndInsideItIsExtendedToTheEdge) {
  // The web stands on x = 0..5 of the line y = 3: the seam is a cut, and at its end inside the
  // plate (x = 5) it runs on straight to the far edge (x = 8): two sheets, 24 faces each, both
  // with the whole line as a junction curve.
  const FeModel m = plateWithWeb(0, 5);
  expectValidSheets(m, buildAllSheets(m));
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 2u);
  std::vector<Id> line;
  for (int i = 0; i <= 8; ++i) line.push_back(Id(1 + 27 + i));
  for (const Sheet& sheet : sheets) {
    EXPECT_EQ(sheet.faces.size(), 24u);
    std::vector<Id> joined;
    for (const Polyline& curve : sheet.junctionCurves) {
      std::vector<Id> ids = nodeIds(sheet, curve);
      if (ids.front() > ids.back()) std::reverse(ids.begin(), ids.end());
      joined.insert(joined.end(), ids.begin() + (joined.empty() ? 0 : 1), ids.end());
    }
    EXPECT_EQ(joined, line);  // the seam (0..5), then its extension (5..8), one after the other
  }
  // A web wholly inside (x = 2..5) is extended from both ends.
  const FeModel inner = plateWithWeb(2, 5);
  EXPECT_EQ(buildSheets(inner, 1).size(), 2u);
  EXPECT_EQ(findSheetCuts(inner).size(), 8u);
}

TEST(Sheets, AFinOfThePartItselfEndingInsideAPlateIsExtendedToItsEdges) {
  // The web of x = 2..5 as shells of the plate's own part: its line, a T-junction of the part,
  // ends inside the plate at both ends and is extended to both edges, so that the plate's two
  // sheets carry the line's nodes as the fin does (one sheet around a line ending inside it is
  // meshed without them: the fin's nodes then lie on the plate's faces).
  FeModel m = plateWithWeb(2, 5);
  for (Shell& shell : m.shells) shell.part = 1;
  expectValidSheets(m, buildAllSheets(m));
  const std::vector<Sheet> sheets = buildSheets(m, 1);
  ASSERT_EQ(sheets.size(), 3u);
  std::vector<std::size_t> faces;
  for (const Sheet& sheet : sheets) faces.push_back(sheet.faces.size());
  std::sort(faces.begin(), faces.end());
  EXPECT_EQ(faces, (std::vector<std::size_t>{3, 24, 24}));
}

TEST(Sheets, JunctionCurvesEndWhereTheSeamChangesItsPartner) {
  // Part 1, a 5 x 2 plate; part 2 bends up from nodes 13..15 of its row j = 2, part 3 bends down
  // from nodes 15..18. At node 15 the seam changes partner: part 1's curve must end there, as the
  // curves of parts 2 and 3 do, so that every side samples the same pieces.
  FeModel m;
  addSheet(m, 1, 1, 5, 2, [](int i, int j) { return Vec3{double(i), double(j), 0.0}; });
  auto up = [](int i) { return Id(100 + i); };
  auto down = [](int i) { return Id(200 + i); };
  for (int i = 0; i <= 2; ++i) addNode(m, up(i), i, 2.0, 1.0);
  for (int i = 2; i <= 5; ++i) addNode(m, down(i), i, 2.0, -1.0);
  for (int i = 0; i < 2; ++i)
    addShell(m, nextShellId(m), 2, {Id(13 + i), Id(14 + i), up(i + 1), up(i)});
  for (int i = 2; i < 5; ++i)
    addShell(m, nextShellId(m), 3, {Id(13 + i), Id(14 + i), down(i + 1), down(i)});
  const std::vector<Sheet> plate = buildSheets(m, 1);
  ASSERT_EQ(plate.size(), 1u);
  ASSERT_EQ(plate[0].junctionCurves.size(), 2u);
  expectSameLine(nodeIds(plate[0], plate[0].junctionCurves[0]), {13, 14, 15});
  expectSameLine(nodeIds(plate[0], plate[0].junctionCurves[1]), {15, 16, 17, 18});
  for (const Id part : {2, 3}) {
    const std::vector<Sheet> other = buildSheets(m, part);
    ASSERT_EQ(other.size(), 1u);
    ASSERT_EQ(other[0].junctionCurves.size(), 1u);
    expectSameLine(nodeIds(other[0], other[0].junctionCurves[0]),
                   part == 2 ? std::vector<Id>{13, 14, 15} : std::vector<Id>{15, 16, 17, 18});
  }
}

TEST(Sheets, JunctionCurvesEndWhereASheetAlongTheSeamEnds) {
  // A web (part 2) stands on the whole line y = 3 of an 8 x 6 plate (part 1) whose quads of
  // x >= 5 above the line are cut away: along x = 0..5 the line has the plate on both sides and
  // the web, along x = 5..8 the plate on one side only. Every curve along the line ends at
  // x = 5, where the upper sheet's ends, so that the lower sheet, the upper one and the web
  // sample the same pieces (one curve 0..8 on the lower sheet placed its nodes along 0..5
  // otherwise than the upper sheet's curve 0..5 did).
  FeModel m;
  m.partOrAdd(1, "plate");
  m.partOrAdd(2, "web");
  addSheet(
      m, 1, 1, 8, 6,
      [](int i, int j) {
        return Vec3{double(i), double(j), 0.0};
      },
      [](int i, int j) { return i >= 5 && j >= 3; });
  for (int i = 0; i <= 8; ++i) addNode(m, 1001 + i, double(i), 3.0, 1.0);
  for (int i = 0; i < 8; ++i)
    addShell(m, nextShellId(m), 2, {Id(28 + i), Id(29 + i), Id(1002 + i), Id(1001 + i)});
  const std::vector<Id> stem{28, 29, 30, 31, 32, 33}, rest{33, 34, 35, 36};
  for (const Id part : {1, 2})
    for (const Sheet& sheet : buildSheets(m, part)) {
      std::vector<std::vector<Id>> along;  // the curves on the line y = 3
      for (const Polyline& curve : sheet.junctionCurves) {
        std::vector<Id> ids = nodeIds(sheet, curve);
        if (ids.front() > ids.back()) std::reverse(ids.begin(), ids.end());
        if (ids.front() >= 28 && ids.back() <= 36) along.push_back(ids);
      }
      std::sort(along.begin(), along.end());
      const bool upper = part == 1 && sheet.faces.size() == 15;
      const std::vector<std::vector<Id>> expected =
          upper ? std::vector<std::vector<Id>>{stem} : std::vector<std::vector<Id>>{stem, rest};
      EXPECT_EQ(along, expected) << "part " << part << ", " << sheet.faces.size() << " faces";
    }
}

TEST(Sheets, ASeamIsWhereTheOtherPartRunsAlongNotWhereItTouchesBothEnds) {
  // Part 1, a 5 x 2 plate (node (i, j): 1 + 6 j + i). Part 2 stands on its rows j = 0 and j = 1
  // (two walls, a hat section's flanges on a skin): the plate's edges from row 0 to row 1 have
  // both nodes on part 2 but are none of its edges, and no seam. Part 3 stands on row j = 2 with
  // a node of its own between every two of the plate's: its edges run along the plate's, which
  // are a seam even though no shell of part 3 has them.
  FeModel m;
  addSheet(m, 1, 1, 5, 2, [](int i, int j) { return Vec3{double(i), double(j), 0.0}; });
  const auto plate = [](int i, int j) { return Id(1 + 6 * j + i); };
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= 5; ++i) addNode(m, Id(100 + 10 * j + i), i, j, 1.0);
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i < 5; ++i)
      addShell(m, nextShellId(m), 2,
               {plate(i, j), plate(i + 1, j), Id(101 + 10 * j + i), Id(100 + 10 * j + i)});
  for (int h = 0; h <= 10; ++h) addNode(m, Id(300 + h), 0.5 * h, 2.0, -1.0);
  for (int h = 1; h < 10; h += 2) addNode(m, Id(400 + h), 0.5 * h, 2.0, 0.0);
  const auto row = [&](int h) { return h % 2 == 0 ? plate(h / 2, 2) : Id(400 + h); };
  for (int h = 0; h < 10; ++h)
    addShell(m, nextShellId(m), 3, {row(h + 1), row(h), Id(300 + h), Id(301 + h)});
  std::set<std::pair<Id, Id>> seamEdges;
  for (const Sheet& sheet : buildSheets(m, 1))
    for (const Polyline& curve : sheet.junctionCurves) {
      const std::vector<Id> ids = nodeIds(sheet, curve);
      for (std::size_t k = 0; k + 1 < ids.size(); ++k)
        seamEdges.insert({std::min(ids[k], ids[k + 1]), std::max(ids[k], ids[k + 1])});
    }
  std::set<std::pair<Id, Id>> expected;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i < 5; ++i) expected.insert({plate(i, j), plate(i + 1, j)});
  EXPECT_EQ(seamEdges, expected);
}

// ---------------------------------------------------------------------------------------------
// Settings, determinism, robustness

TEST(Sheets, RejectsAnglesOutsideZeroTo180) {
  const FeModel m = flatPlate(1, 1);
  for (const double bad : {-1.0, 180.5, std::nan("")}) {
    SheetSettings settings;
    settings.featureAngleDeg = bad;
    EXPECT_THROW(buildSheets(m, 1, settings), SettingError);
    settings = {};
    settings.cornerAngleDeg = bad;
    EXPECT_THROW(buildAllSheets(m, settings), SettingError);
  }
}

namespace {

void expectSameSheets(const std::vector<Sheet>& a, const std::vector<Sheet>& b) {
  ASSERT_EQ(a.size(), b.size());
  auto same = [](const std::vector<Polyline>& x, const std::vector<Polyline>& y) {
    if (x.size() != y.size()) return false;
    for (std::size_t i = 0; i < x.size(); ++i)
      if (x[i].points != y[i].points || x[i].closed != y[i].closed) return false;
    return true;
  };
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].part, b[i].part);
    EXPECT_EQ(a[i].points, b[i].points);
    EXPECT_EQ(a[i].pointNodeIds, b[i].pointNodeIds);
    EXPECT_EQ(a[i].faces, b[i].faces);
    EXPECT_EQ(a[i].faceShellIds, b[i].faceShellIds);
    EXPECT_EQ(a[i].faceFlipped, b[i].faceFlipped);
    EXPECT_TRUE(same(a[i].boundaryLoops, b[i].boundaryLoops));
    EXPECT_TRUE(same(a[i].featureLines, b[i].featureLines));
    EXPECT_EQ(a[i].featurePoints, b[i].featurePoints);
    EXPECT_TRUE(same(a[i].junctionCurves, b[i].junctionCurves));
  }
}

// A random soup of triangles and quads on `nodes` nodes in a few parts.
FeModel randomSoup(std::mt19937& random, int nodes, int shells, int parts) {
  FeModel m;
  for (int v = 1; v <= nodes; ++v)
    addNode(m, v, double(random() % 1000) / 100.0, double(random() % 1000) / 100.0,
            double(random() % 1000) / 100.0);
  for (int s = 1; s <= shells; ++s) {
    const int count = random() % 3 == 0 ? 4 : 3;
    std::vector<Id> corners;
    while (int(corners.size()) < count) {
      const Id v = 1 + Id(random() % unsigned(nodes));
      if (std::find(corners.begin(), corners.end(), v) == corners.end()) corners.push_back(v);
    }
    addShell(m, s, 1 + Id(random() % unsigned(parts)), corners);
  }
  return m;
}

}  // namespace

TEST(Sheets, ResultDoesNotDependOnTheThreadCount) {
  FeModel m;
  for (Id part = 1; part <= 6; ++part) {
    m.partOrAdd(part);
    addSheet(m, part, 1000 * part, 20, 10, [&](int i, int j) {
      return Vec3{double(i), double(j), std::sin(0.3 * i * double(part)) * 3.0};
    });
  }
  std::mt19937 random(3);
  for (Shell& s : m.shells)
    if (random() % 3 == 0) reverseShell(s);
  const std::vector<Sheet> parallel = buildAllSheets(m);
  std::vector<Sheet> serial;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    serial = buildAllSheets(m);
  }
  expectValidSheets(m, parallel);
  expectSameSheets(parallel, serial);
}

TEST(Sheets, RandomSoupsGiveValidSheetsOrTheNonOrientableReport) {
  // Random non-manifold soups exercise joining and cutting at non-manifold edges: every result
  // must keep every shell and be edge-manifold and consistently oriented.
  std::mt19937 random(2024);
  int valid = 0, nonOrientable = 0, withCuts = 0;
  for (int round = 0; round < 3000; ++round) {
    const FeModel m =
        randomSoup(random, 5 + int(random() % 6), 4 + int(random() % 14), 1 + int(random() % 2));
    std::vector<Sheet> sheets;
    try {
      sheets = buildAllSheets(m);
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("would have to be flipped both ways"),
                std::string::npos);
      ++nonOrientable;
      continue;
    }
    ++valid;
    expectValidSheets(m, sheets);
    for (const Sheet& sheet : sheets) {
      std::set<Id> distinct(sheet.pointNodeIds.begin(), sheet.pointNodeIds.end());
      if (distinct.size() != sheet.pointNodeIds.size()) ++withCuts;
    }
    if (::testing::Test::HasFailure()) {
      ADD_FAILURE() << "in round " << round;
      break;
    }
  }
  std::printf("valid %d nonOrientable %d withCuts %d\n", valid, nonOrientable, withCuts);
  EXPECT_GT(valid, 500);
  EXPECT_GT(nonOrientable, 50);
  EXPECT_GT(withCuts, 20);
}

// ---------------------------------------------------------------------------------------------
// Real decks

TEST(SheetsDecks, BracketIsOneManifoldConsistentlyOrientedSheet) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "bracket.k");
  const FeModel m = readDeck(path);
  const std::vector<Sheet> sheets = buildAllSheets(m);
  ASSERT_EQ(sheets.size(), 1u);
  expectValidSheets(m, sheets);
  const Sheet& sheet = sheets[0];
  EXPECT_EQ(sheet.part, 4075);
  EXPECT_EQ(sheet.faces.size(), 1865u);
  EXPECT_EQ(sheet.boundaryLoops.size(), 12u);
  EXPECT_EQ(polylineEdges(sheet.boundaryLoops), 288u);
  EXPECT_EQ(std::count(sheet.faceFlipped.begin(), sheet.faceFlipped.end(), true), 0);
  EXPECT_TRUE(sheet.junctionCurves.empty());
  // A bent sheet-metal bracket has bends and corners.
  EXPECT_FALSE(sheet.featureLines.empty());
  EXPECT_FALSE(sheet.featurePoints.empty());
}

TEST(SheetsDecks, WheelKeepsEveryElementInOneManifoldConsistentSheet) {
  VOXREMESH_REQUIRE_SHARED_DECK(path, "wheel.k");
  const FeModel m = readDeck(path);
  ASSERT_EQ(m.shells.size(), 11553u);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Sheet> sheets = buildAllSheets(m);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("buildAllSheets(wheel.k): %zu sheets in %.3f s\n", sheets.size(), seconds);
  // Every element in exactly one sheet; every sheet edge-manifold and consistently oriented.
  expectValidSheets(m, sheets);
  std::size_t faces = 0, flipped = 0, junctionEdges = 0;
  for (const Sheet& sheet : sheets) {
    faces += sheet.faces.size();
    flipped += std::size_t(std::count(sheet.faceFlipped.begin(), sheet.faceFlipped.end(), true));
    junctionEdges += polylineEdges(sheet.junctionCurves);
  }
  EXPECT_EQ(faces, 11553u);
  // The 812 two-shell edges with flipped normals are resolved by flipping faces.
  EXPECT_GT(flipped, 0u);
  // Each of the 168 T-junction edges has its three shells in three sheets: 3 x 168 junction
  // edges in all.
  EXPECT_EQ(junctionEdges, 3u * 168u);
  EXPECT_GE(sheets.size(), 3u);
}

// ---------------------------------------------------------------------------------------------
// Speed

TEST(SheetsSpeed, MillionElementPartInAFewSeconds) {
  // 1000 x 1000 quads, with a bend (a feature line), 100 holes (boundary loops) and random flips.
  FeModel m;
  m.partOrAdd(1, "big");
  const int n = 1000;
  addSheet(
      m, 1, 1, n, n,
      [&](int i, int j) {
        return Vec3{double(i), double(j), j > n / 2 ? 0.8 * (j - n / 2) : 0.0};
      },
      [](int i, int j) { return i % 100 == 50 && j % 100 == 25; });
  std::mt19937 random(5);
  for (Shell& s : m.shells)
    if (random() % 4 == 0) reverseShell(s);
  const auto start = std::chrono::steady_clock::now();
  SheetSettings settings;
  settings.featureAngleDeg = 30.0;  // the kink turns by atan(0.8) = 38.7 degrees
  const std::vector<Sheet> sheets = buildAllSheets(m, settings);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("buildAllSheets(%zu elements): %.3f s\n", m.shells.size(), seconds);
  ASSERT_EQ(sheets.size(), 1u);
  EXPECT_EQ(sheets[0].faces.size(), std::size_t(n) * n - 100);
  EXPECT_EQ(sheets[0].boundaryLoops.size(), 101u);
  EXPECT_EQ(sheets[0].featureLines.size(), 1u);
  // Loose: a few seconds on a shared machine; quadratic work would take minutes.
  EXPECT_LT(seconds, 15.0);
}
