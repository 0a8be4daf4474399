// OBJ, OFF, STL and PLY: round trips of a generated two-part model with a non-manifold
// T-junction (three faces on one edge), hand-written files of each variant, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "support/expect_input_error.h"
#include "support/test_support.h"
#include "voxremesh/errors.h"

namespace fs = std::filesystem;
using namespace voxremesh;

namespace {

using voxremesh::test::expectInputError;

constexpr int kNx = 4;
constexpr int kNy = 3;

Id floorNode(int i, int j) {
  return 1000 + 10 * j + i;
}
Id finNode(int i) {
  return 5000 + 3 * i;
}

/// A floor of kNx x kNy cells (quads, some split into two triangles) in part 7 "Floor Panel"
/// and a fin of quads standing on the floor line j = 1 in part 12 "RIB": each floor edge on that
/// line is shared by two floor faces and one fin face (a T-junction, non-manifold).
FeModel makeModel() {
  FeModel model;
  model.sourceFormat = DeckFormat::LsDyna;
  for (int j = 0; j <= kNy; ++j)
    for (int i = 0; i <= kNx; ++i)
      model.nodes.push_back(
          Node{floorNode(i, j), {0.1 * i + 1.0 / 3.0, 0.25 * j - 1e-9 * i, 1e-12 * (i * j) - 0.7}});
  for (int i = 0; i <= kNx; ++i)
    model.nodes.push_back(Node{finNode(i), {0.1 * i + 1.0 / 3.0, 0.25 - 1e-9 * i, 0.5 / 7.0}});
  model.parts.push_back(Part{7, "Floor Panel", false});
  model.parts.push_back(Part{12, "RIB", false});
  Id element = 501;
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i) {
      const Id a = floorNode(i, j), b = floorNode(i + 1, j), c = floorNode(i + 1, j + 1),
               d = floorNode(i, j + 1);
      if ((i + j) % 3 == 0) {
        model.shells.push_back(Shell{element, 7, {a, b, c, 0}, 3});
        element += 2;
        model.shells.push_back(Shell{element, 7, {a, c, d, 0}, 3});
      } else {
        model.shells.push_back(Shell{element, 7, {a, b, c, d}, 4});
      }
      element += 2;
    }
  for (int i = 0; i < kNx; ++i) {
    model.shells.push_back(
        Shell{element, 12, {floorNode(i, 1), floorNode(i + 1, 1), finNode(i + 1), finNode(i)}, 4});
    element += 2;
  }
  return model;
}

std::size_t countTriangles(const FeModel& m) {
  return static_cast<std::size_t>(std::count_if(m.shells.begin(), m.shells.end(),
                                                [](const Shell& s) { return s.nodeCount == 3; }));
}

/// Number of edges used by three or more faces.
std::size_t nonManifoldEdges(const FeModel& model) {
  std::map<std::pair<Id, Id>, int> uses;
  for (const Shell& s : model.shells)
    for (int k = 0; k < s.nodeCount; ++k) {
      Id a = s.nodes[k], b = s.nodes[(k + 1) % s.nodeCount];
      if (a > b) std::swap(a, b);
      ++uses[{a, b}];
    }
  return static_cast<std::size_t>(
      std::count_if(uses.begin(), uses.end(), [](const auto& e) { return e.second >= 3; }));
}

std::map<Id, std::array<double, 3>> coordinates(const FeModel& model) {
  std::map<Id, std::array<double, 3>> xyz;
  for (const Node& n : model.nodes) xyz[n.id] = n.xyz;
  return xyz;
}

/// The corner coordinates of every face, in order (quads split 0-1-2 / 0-2-3 when `split`).
std::vector<std::vector<std::array<double, 3>>> faceCorners(const FeModel& model, bool split) {
  const auto xyz = coordinates(model);
  std::vector<std::vector<std::array<double, 3>>> faces;
  for (const Shell& s : model.shells) {
    if (split && s.nodeCount == 4) {
      faces.push_back({xyz.at(s.nodes[0]), xyz.at(s.nodes[1]), xyz.at(s.nodes[2])});
      faces.push_back({xyz.at(s.nodes[0]), xyz.at(s.nodes[2]), xyz.at(s.nodes[3])});
      continue;
    }
    std::vector<std::array<double, 3>> corners;
    for (int k = 0; k < s.nodeCount; ++k) corners.push_back(xyz.at(s.nodes[k]));
    faces.push_back(corners);
  }
  return faces;
}

/// Faces of `read` match those of `original` corner by corner within `tolerance` (relative).
void expectSameFaces(const FeModel& original, const FeModel& read, bool split, double tolerance) {
  const auto expected = faceCorners(original, split);
  const auto actual = faceCorners(read, false);
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t f = 0; f < expected.size(); ++f) {
    ASSERT_EQ(actual[f].size(), expected[f].size()) << "face " << f;
    for (std::size_t k = 0; k < expected[f].size(); ++k)
      for (int a = 0; a < 3; ++a) {
        if (tolerance == 0)
          EXPECT_EQ(actual[f][k][a], expected[f][k][a]) << "face " << f << " corner " << k;
        else
          EXPECT_NEAR(actual[f][k][a], expected[f][k][a],
                      tolerance * std::max(1.0, std::fabs(expected[f][k][a])))
              << "face " << f << " corner " << k;
      }
  }
}

/// The name of the part of every face, in order.
std::vector<std::string> facePartNames(const FeModel& model) {
  std::vector<std::string> names;
  for (const Shell& s : model.shells) {
    const Part* p = model.findPart(s.part);
    names.push_back(p ? p->name : "?");
  }
  return names;
}

fs::path put(const fs::path& dir, const std::string& name, const std::string& content) {
  const fs::path path = dir / name;
  io::writeFileAtomically(path, content);
  return path;
}

void expectElementIdsOneToM(const FeModel& m) {
  for (std::size_t i = 0; i < m.shells.size(); ++i)
    EXPECT_EQ(m.shells[i].id, static_cast<Id>(i + 1));
  for (std::size_t i = 0; i < m.nodes.size(); ++i) EXPECT_EQ(m.nodes[i].id, static_cast<Id>(i + 1));
}

}  // namespace

TEST(SurfaceModel, HasTheTJunctionTheRoundTripsMustKeep) {
  const FeModel m = makeModel();
  EXPECT_EQ(nonManifoldEdges(m), static_cast<std::size_t>(kNx));
  EXPECT_GT(countTriangles(m), 0u);
}

// ---------------------------------------------------------------------------------------- OBJ

TEST(Obj, RoundTripKeepsEveryFaceCoordinatesExactlyAndPartsWithIds) {
  const FeModel original = makeModel();
  Warnings warnings;
  std::string text;
  io::writeObj(original, text, warnings);
  const fs::path path = put(test::scratchDir("obj_round"), "model.obj", text);
  const FeModel read = io::readObj(path, warnings);
  EXPECT_EQ(read.sourceFormat, DeckFormat::Obj);
  EXPECT_EQ(read.nodes.size(), original.nodes.size());
  EXPECT_EQ(read.shells.size(), original.shells.size());
  EXPECT_EQ(countTriangles(read), countTriangles(original));
  EXPECT_EQ(nonManifoldEdges(read), static_cast<std::size_t>(kNx));
  expectSameFaces(original, read, false, 0.0);
  expectElementIdsOneToM(read);
  for (std::size_t i = 0; i < read.nodes.size(); ++i)
    EXPECT_EQ(read.nodes[i].xyz, original.nodes[i].xyz);
  ASSERT_EQ(read.parts.size(), 2u);
  ASSERT_NE(read.findPart(7), nullptr);
  ASSERT_NE(read.findPart(12), nullptr);
  EXPECT_EQ(read.findPart(7)->name, "Floor Panel");
  EXPECT_EQ(read.findPart(12)->name, "RIB");
  for (std::size_t i = 0; i < read.shells.size(); ++i)
    EXPECT_EQ(read.shells[i].part, original.shells[i].part);
}

TEST(Obj, ReadsIndexFormsRelativeIndicesGroupsAndWarnsAboutLinesAndPoints) {
  const fs::path dir = test::scratchDir("obj_forms");
  const fs::path path = put(dir, "forms.obj",
                            "# a comment\n"
                            "mtllib x.mtl\n"
                            "v 0 0 0\n"
                            "v 1 0 0 1.0\n"
                            "v 1 1 0\n"
                            "v 0 1 0\n"
                            "vt 0 0\nvn 0 0 1\n"
                            "f 1 2 3\n"
                            "g left side\n"
                            "usemtl steel\ns off\n"
                            "f 1/1 3/1 4/1\n"
                            "o other\n"
                            "v 2 0 0\n"
                            "f -4//1 -1//1 -3//1\n"
                            "f 1/1/1 2/1/1 3/1/1 4/1/1\n"
                            "g left side\n"
                            "f 2 5 3\n"
                            "l 1 2\nl 2 3\np 1\n");
  Warnings warnings;
  const FeModel m = io::readObj(path, warnings);
  ASSERT_EQ(m.nodes.size(), 5u);
  ASSERT_EQ(m.shells.size(), 5u);
  EXPECT_EQ(m.nodes[1].xyz, (std::array<double, 3>{1, 0, 0}));
  // f -4 -1 -3 after five vertices: vertices 2, 5, 3.
  EXPECT_EQ(m.shells[2].nodes[0], 2);
  EXPECT_EQ(m.shells[2].nodes[1], 5);
  EXPECT_EQ(m.shells[2].nodes[2], 3);
  EXPECT_EQ(m.shells[3].nodeCount, 4);
  ASSERT_EQ(m.parts.size(), 3u);
  EXPECT_EQ(m.parts[0].name, "default");
  EXPECT_EQ(m.parts[1].name, "left side");
  EXPECT_EQ(m.parts[2].name, "other");
  EXPECT_EQ(m.shells[4].part, m.parts[1].id);  // 'g left side' again: same part
  const auto has = [&](const std::string& fragment) {
    return std::any_of(warnings.begin(), warnings.end(),
                       [&](const std::string& w) { return w.find(fragment) != std::string::npos; });
  };
  EXPECT_TRUE(has("2 line element(s)"));
  EXPECT_TRUE(has("1 point element(s)"));
}

TEST(Obj, BadInputNamesFileAndLine) {
  const fs::path dir = test::scratchDir("obj_bad");
  Warnings w;
  const auto read = [&](const fs::path& p) { return [&w, p] { io::readObj(p, w); }; };
  fs::path p = put(dir, "number.obj", "v 0 0 0\nv 1 0 0\nv 1 1.2.3 0\nf 1 2 3\n");
  expectInputError(read(p), p, 3, "malformed y coordinate '1.2.3'");
  p = put(dir, "missing.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\n\nf 1 2 9\n");
  expectInputError(read(p), p, 5, "names vertex 9, but the file defines only 3 vertices");
  p = put(dir, "polygon.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 2 0\nf 1 2 3 4 5\n");
  expectInputError(read(p), p, 6, "polygon with 5 vertices");
  p = put(dir, "binary.obj", std::string("v 0 0 0\nv 1 0 0\n\0\x01\x02", 19));
  expectInputError(read(p), p, 3, "NUL");
  p = put(dir, "empty.obj", "  \n\n");
  expectInputError(read(p), p, 0, "empty file");
  p = put(dir, "unknown.obj", "v 0 0 0\nbanana 1 2\n");
  expectInputError(read(p), p, 2, "unknown OBJ statement 'banana'");
  p = put(dir, "zero.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 0 1 2\n");
  expectInputError(read(p), p, 4, "vertex index 0");
  p = put(dir, "relative.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf -1 -2 -4\n");
  expectInputError(read(p), p, 4, "reaches before the first vertex");
  p = put(dir, "truncated.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2\n");
  expectInputError(read(p), p, 4, "face with 2 vertices");
  p = put(dir, "nofaces.obj", "v 0 0 0\nv 1 0 0\n");
  expectInputError(read(p), p, 0, "contains no faces");
}

// ---------------------------------------------------------------------------------------- OFF

TEST(Off, RoundTripKeepsEveryFaceAndWarnsThatPartsAreMerged) {
  const FeModel original = makeModel();
  Warnings warnings;
  std::string text;
  io::writeOff(original, text, warnings);
  EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(), [](const std::string& w) {
    return w.find("OFF has no parts") != std::string::npos;
  }));
  const fs::path path = put(test::scratchDir("off_round"), "model.off", text);
  const FeModel read = io::readOff(path, warnings);
  EXPECT_EQ(read.sourceFormat, DeckFormat::Off);
  EXPECT_EQ(read.nodes.size(), original.nodes.size());
  EXPECT_EQ(read.shells.size(), original.shells.size());
  EXPECT_EQ(nonManifoldEdges(read), static_cast<std::size_t>(kNx));
  expectSameFaces(original, read, false, 0.0);
  expectElementIdsOneToM(read);
  ASSERT_EQ(read.parts.size(), 1u);
  EXPECT_EQ(read.parts[0].name, "model");
}

TEST(Off, ReadsVariantsCommentsAndCountsOnTheHeaderLine) {
  const fs::path dir = test::scratchDir("off_variants");
  Warnings w;
  const fs::path p = put(dir, "c.off",
                         "COFF 4 2 0 # counts on the header line\n"
                         "# a comment line\n"
                         "0 0 0 255 0 0 255\n"
                         "1 0 0 255 0 0 255\n\n"
                         "1 1 0 255 0 0 255\n"
                         "0 1 0.5 255 0 0 255\n"
                         "3 0 1 2 1.0 0.0 0.0\n"
                         "4 0 1 2 3\n");
  const FeModel m = io::readOff(p, w);
  ASSERT_EQ(m.nodes.size(), 4u);
  ASSERT_EQ(m.shells.size(), 2u);
  EXPECT_EQ(m.nodes[3].xyz[2], 0.5);
  EXPECT_EQ(m.shells[0].nodeCount, 3);
  EXPECT_EQ(m.shells[1].nodeCount, 4);
  EXPECT_EQ(m.shells[1].nodes[3], 4);
}

TEST(Off, BadInputNamesFileAndLine) {
  const fs::path dir = test::scratchDir("off_bad");
  Warnings w;
  const auto read = [&](const fs::path& p) { return [&w, p] { io::readOff(p, w); }; };
  fs::path p = put(dir, "header.off", "PLY\n3 1 0\n");
  expectInputError(read(p), p, 1, "expected the header 'OFF'");
  p = put(dir, "number.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n1 1 0\n3 0 1 2\n");
  expectInputError(read(p), p, 4, "malformed y coordinate 'x' in vertex 1");
  p = put(dir, "truncated.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n");
  expectInputError(read(p), p, 6, "file ends after 1 of 2 faces");
  p = put(dir, "missing.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 3\n");
  expectInputError(read(p), p, 6, "names vertex 3, but the file has 3 vertices");
  p = put(dir, "polygon.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n5 0 1 2 0 1\n");
  expectInputError(read(p), p, 6, "polygon with 5 vertices");
  p = put(dir, "binary.off", std::string("OFF\n3 1 0\n\0\0\0", 13));
  expectInputError(read(p), p, 3, "NUL");
  p = put(dir, "empty.off", "");
  expectInputError(read(p), p, 0, "empty file");
  p = put(dir, "fourd.off", "4OFF\n3 1 0\n");
  expectInputError(read(p), p, 1, "OFF variant '4OFF' is not supported");
}

// ---------------------------------------------------------------------------------------- STL

TEST(Stl, AsciiRoundTripKeepsSolidsAsPartsAndSplitsQuads) {
  const FeModel original = makeModel();
  Warnings warnings;
  std::string text;
  io::writeStl(original, text, false, warnings);
  const std::size_t quads = original.shells.size() - countTriangles(original);
  EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(), [&](const std::string& w) {
    return w.find(std::to_string(quads) + " quadrilateral(s) written as two triangles") !=
           std::string::npos;
  }));
  const fs::path path = put(test::scratchDir("stl_ascii"), "model.stl", text);
  const FeModel read = io::readStl(path, warnings);
  EXPECT_EQ(read.sourceFormat, DeckFormat::Stl);
  EXPECT_EQ(read.shells.size(), original.shells.size() + quads);
  EXPECT_EQ(read.nodes.size(), original.nodes.size());  // merged back by exact coordinates
  EXPECT_EQ(nonManifoldEdges(read), static_cast<std::size_t>(kNx));
  expectSameFaces(original, read, true, 0.0);
  expectElementIdsOneToM(read);
  ASSERT_EQ(read.parts.size(), 2u);
  EXPECT_EQ(read.parts[0].name, "Floor Panel");
  EXPECT_EQ(read.parts[1].name, "RIB");
  std::vector<std::string> expected;
  for (const Shell& s : original.shells)
    for (int k = 0; k < (s.nodeCount == 4 ? 2 : 1); ++k)
      expected.push_back(s.part == 7 ? "Floor Panel" : "RIB");
  EXPECT_EQ(facePartNames(read), expected);
}

TEST(Stl, BinaryRoundTripKeepsEveryFaceToFloatPrecision) {
  const FeModel original = makeModel();
  Warnings warnings;
  std::string bytes;
  io::writeStl(original, bytes, true, warnings);
  const std::size_t quads = original.shells.size() - countTriangles(original);
  ASSERT_EQ(bytes.size(), 84 + 50 * (original.shells.size() + quads));
  EXPECT_NE(bytes.substr(0, 5), "solid");
  const fs::path path = put(test::scratchDir("stl_binary"), "model.stl", bytes);
  const FeModel read = io::readStl(path, warnings);
  EXPECT_EQ(read.shells.size(), original.shells.size() + quads);
  EXPECT_EQ(read.nodes.size(), original.nodes.size());
  EXPECT_EQ(nonManifoldEdges(read), static_cast<std::size_t>(kNx));
  expectSameFaces(original, read, true, 1e-7);
  ASSERT_EQ(read.parts.size(), 1u);
}

TEST(Stl, BinaryStartingWithSolidIsDetectedBySizeAndVerticesMergeInFirstSeenOrder) {
  std::string bytes = "solid but binary";
  bytes.resize(80, ' ');
  const std::uint32_t count = 2;
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  const float triangles[2][12] = {{0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0},
                                  {0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 0}};
  for (const auto& t : triangles) {
    bytes.append(reinterpret_cast<const char*>(t), sizeof t);
    bytes.append(2, '\0');
  }
  const fs::path path = put(test::scratchDir("stl_solid_binary"), "b.stl", bytes);
  Warnings w;
  const FeModel m = io::readStl(path, w);
  ASSERT_EQ(m.shells.size(), 2u);
  ASSERT_EQ(m.nodes.size(), 4u);
  EXPECT_EQ(m.nodes[0].xyz, (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(m.nodes[1].xyz, (std::array<double, 3>{1, 0, 0}));
  EXPECT_EQ(m.nodes[2].xyz, (std::array<double, 3>{0, 1, 0}));
  EXPECT_EQ(m.nodes[3].xyz, (std::array<double, 3>{1, 1, 0}));
  EXPECT_EQ(m.shells[1].nodes[0], 2);
  EXPECT_EQ(m.shells[1].nodes[1], 4);
  EXPECT_EQ(m.shells[1].nodes[2], 3);
}

TEST(Stl, BadInputNamesFileAndLine) {
  const fs::path dir = test::scratchDir("stl_bad");
  Warnings w;
  const auto read = [&](const fs::path& p) { return [&w, p] { io::readStl(p, w); }; };
  const std::string facet =
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 "
      "0\nendloop\nendfacet\n";
  fs::path p = put(dir, "truncated.stl", "solid a\n" + facet + facet.substr(0, 43));
  expectInputError(read(p), p, 11, "file ends inside a solid");
  p = put(dir, "number.stl",
          "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
          "vertex 1 1e 0\nendloop\nendfacet\nendsolid a\n");
  expectInputError(read(p), p, 6, "malformed y coordinate '1e'");
  p = put(dir, "four.stl",
          "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
          "vertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid a\n");
  expectInputError(read(p), p, 7, "more than three vertices");
  std::string binary(80, ' ');
  const std::uint32_t count = 3;
  binary.append(reinterpret_cast<const char*>(&count), 4);
  binary.append(100, '\0');
  p = put(dir, "short.stl", binary);
  expectInputError(read(p), p, 0, "announces 3 triangles (234 bytes) but the file has 184 bytes");
  expectInputError(read(p), p, 0, "byte offset 184");
  p = put(dir, "empty.stl", "\n");
  expectInputError(read(p), p, 0, "empty file");
  p = put(dir, "garbage.stl", "hello");
  expectInputError(read(p), p, 0, "not an STL file");
}

// ---------------------------------------------------------------------------------------- PLY

TEST(Ply, BinaryRoundTripKeepsCoordinatesExactlyPartsIdsAndNames) {
  const FeModel original = makeModel();
  for (bool binary : {true, false}) {
    Warnings warnings;
    std::string bytes;
    io::writePly(original, bytes, binary, warnings);
    const fs::path path =
        put(test::scratchDir(binary ? "ply_bin" : "ply_ascii"), "model.ply", bytes);
    const FeModel read = io::readPly(path, warnings);
    EXPECT_EQ(read.sourceFormat, DeckFormat::Ply);
    EXPECT_EQ(read.nodes.size(), original.nodes.size());
    EXPECT_EQ(read.shells.size(), original.shells.size());
    EXPECT_EQ(nonManifoldEdges(read), static_cast<std::size_t>(kNx));
    expectSameFaces(original, read, false, 0.0);
    expectElementIdsOneToM(read);
    ASSERT_EQ(read.parts.size(), 2u);
    ASSERT_NE(read.findPart(7), nullptr);
    ASSERT_NE(read.findPart(12), nullptr);
    EXPECT_EQ(read.findPart(7)->name, "Floor Panel");
    EXPECT_EQ(read.findPart(12)->name, "RIB");
    for (std::size_t i = 0; i < read.shells.size(); ++i)
      EXPECT_EQ(read.shells[i].part, original.shells[i].part);
  }
}

namespace {

template <typename T>
void appendBigEndian(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  std::reverse(bytes, bytes + sizeof(T));  // the test machine is little-endian (x86-64)
  out.append(bytes, sizeof(T));
}

}  // namespace

TEST(Ply, BigEndianFloatsWithOtherPropertiesAndElementsAreSkippedCorrectly) {
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\ncomment made by hand\n"
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty uchar red\nproperty list uchar short extra\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
      "element face 2\nproperty uchar flags\nproperty list uchar uint vertex_indices\n"
      "property int part\nproperty double quality\nend_header\n";
  const float xyz[4][3] = {
      {0.1f, 0.2f, 0.3f}, {1.5f, 0.f, -2.f}, {1.f, 1.f, 0.f}, {0.f, 1.f, 1e-3f}};
  for (int v = 0; v < 4; ++v) {
    for (float c : xyz[v]) appendBigEndian(bytes, c);
    appendBigEndian(bytes, 0.5f);
    bytes += static_cast<char>(200);
    bytes += static_cast<char>(v);  // a list of v shorts
    for (int k = 0; k < v; ++k) appendBigEndian(bytes, static_cast<std::int16_t>(k));
  }
  appendBigEndian(bytes, std::int32_t{0});
  appendBigEndian(bytes, std::int32_t{1});
  bytes += '\x01';
  bytes += '\x03';
  for (std::uint32_t i : {0u, 1u, 2u}) appendBigEndian(bytes, i);
  appendBigEndian(bytes, std::int32_t{42});
  appendBigEndian(bytes, 0.25);
  bytes += '\x01';
  bytes += '\x04';
  for (std::uint32_t i : {0u, 1u, 2u, 3u}) appendBigEndian(bytes, i);
  appendBigEndian(bytes, std::int32_t{43});
  appendBigEndian(bytes, 0.75);
  const fs::path path = put(test::scratchDir("ply_big"), "big.ply", bytes);
  Warnings w;
  const FeModel m = io::readPly(path, w);
  ASSERT_EQ(m.nodes.size(), 4u);
  for (int v = 0; v < 4; ++v)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(m.nodes[v].xyz[a], static_cast<double>(xyz[v][a]));
  ASSERT_EQ(m.shells.size(), 2u);
  EXPECT_EQ(m.shells[0].nodeCount, 3);
  EXPECT_EQ(m.shells[1].nodeCount, 4);
  EXPECT_EQ(m.shells[1].nodes[3], 4);
  EXPECT_EQ(m.shells[0].part, 42);
  EXPECT_EQ(m.shells[1].part, 43);
  ASSERT_NE(m.findPart(42), nullptr);
  EXPECT_EQ(m.findPart(42)->name, "part_42");
}

TEST(Ply, AsciiWithVertexIndexListAndIntCounts) {
  const fs::path path = put(test::scratchDir("ply_ascii_hand"), "hand.ply",
                            "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty double x\r\n"
                            "property double y\r\nproperty double z\r\nproperty uchar red\r\n"
                            "element face 1\r\nproperty list int int vertex_index\r\nend_header\r\n"
                            "0 0 0 1\r\n1 0 0.125 2\r\n1 1 0 3\r\n3 2 1 0\r\n");
  Warnings w;
  const FeModel m = io::readPly(path, w);
  ASSERT_EQ(m.nodes.size(), 3u);
  EXPECT_EQ(m.nodes[1].xyz[2], 0.125);
  ASSERT_EQ(m.shells.size(), 1u);
  EXPECT_EQ(m.shells[0].nodes[0], 3);
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.parts[0].name, "hand");
}

TEST(Ply, BadInputNamesFileAndLineOrByteOffset) {
  const fs::path dir = test::scratchDir("ply_bad");
  Warnings w;
  const auto read = [&](const fs::path& p) { return [&w, p] { io::readPly(p, w); }; };
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  fs::path p = put(dir, "number.ply", header + "0 0 0\n1 0 zz\n1 1 0\n3 0 1 2\n");
  expectInputError(read(p), p, 11, "malformed z coordinate 'zz' in vertex 1");
  p = put(dir, "missing.ply", header + "0 0 0\n1 0 0\n1 1 0\n3 0 1 7\n");
  expectInputError(read(p), p, 13, "names vertex 7, but the file defines only 3 vertices");
  p = put(dir, "polygon.ply", header + "0 0 0\n1 0 0\n1 1 0\n5 0 1 2 0 1\n");
  expectInputError(read(p), p, 13, "polygon with 5 vertices");
  p = put(dir, "truncated.ply", header + "0 0 0\n1 0 0\n");
  expectInputError(read(p), p, 11, "file ends after 2 of 3 vertex elements");
  std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const std::size_t body = binary.size();
  binary.append(3 * 12, '\0');
  binary += '\x03';
  binary.append(6, '\0');  // two of the three indices
  p = put(dir, "truncated_binary.ply", binary);
  expectInputError(
      read(p), p, 0,
      "file ends at byte offset " + std::to_string(body + 36 + 7) + " while reading face 0 of 1");
  // An element without properties holds no bytes, whatever its count (a count of 15,555,555,555
  // once looped for ever: ../shared/data/malformed/empty_element_hang.ply).
  std::string empty = binary.substr(0, body - 11) + "element nothing 15555555555\nend_header\n";
  const float corners[9] = {0, 0, 0, 1, 0, 0, 1, 1, 0};
  const std::int32_t face[3] = {0, 1, 2};
  empty.append(reinterpret_cast<const char*>(corners), sizeof corners);
  empty += '\x03';
  empty.append(reinterpret_cast<const char*>(face), sizeof face);
  p = put(dir, "empty_element.ply", empty);
  EXPECT_EQ(io::readPly(p, w).shells.size(), 1u);
  p = put(dir, "notply.ply", "solid x\n");
  expectInputError(read(p), p, 1, "not a PLY file");
  p = put(dir, "noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  expectInputError(read(p), p, 3, "no 'end_header'");
  p = put(dir, "empty.ply", "");
  expectInputError(read(p), p, 0, "empty file");
}

TEST(SurfaceWriters, RefuseShellsNamingMissingNodes) {
  FeModel m = makeModel();
  m.shells[3].nodes[1] = 999999;
  Warnings w;
  std::string out;
  EXPECT_THROW(io::writeObj(m, out, w), std::invalid_argument);
  EXPECT_THROW(io::writeOff(m, out, w), std::invalid_argument);
  EXPECT_THROW(io::writeStl(m, out, true, w), std::invalid_argument);
  EXPECT_THROW(io::writePly(m, out, true, w), std::invalid_argument);
}
