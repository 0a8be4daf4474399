// VTK XML unstructured grid writer: the XML is well formed, every array has the right length
// and content, and (where python3 with VTK is installed) VTK itself reads the file.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "support/test_support.h"

namespace fs = std::filesystem;
using namespace voxremesh;

namespace {

/// An XML element: name, attributes, text and children.
struct XmlNode {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<std::unique_ptr<XmlNode>> children;

  const XmlNode* child(const std::string& childName) const {
    for (const auto& c : children)
      if (c->name == childName) return c.get();
    return nullptr;
  }
};

/// A strict little XML parser for what the writer produces: a prolog, elements, attributes
/// in double quotes, entities, text. Throws std::runtime_error on anything not well formed.
class XmlParser {
 public:
  explicit XmlParser(std::string text) : s_(std::move(text)) {}

  std::unique_ptr<XmlNode> parseDocument() {
    skipSpace();
    if (s_.compare(pos_, 5, "<?xml") == 0) {
      const std::size_t end = s_.find("?>", pos_);
      if (end == std::string::npos) fail("unterminated prolog");
      pos_ = end + 2;
    }
    skipSpace();
    auto root = parseElement();
    skipSpace();
    if (pos_ != s_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error("XML not well formed at offset " + std::to_string(pos_) + ": " + what);
  }
  void skipSpace() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  std::string parseName() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) ||
                                s_[pos_] == '_' || s_[pos_] == ':' || s_[pos_] == '-'))
      ++pos_;
    if (pos_ == start) fail("expected a name");
    return s_.substr(start, pos_ - start);
  }
  std::string decode(const std::string& raw) {
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] == '<') fail("'<' in text");
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const std::size_t semi = raw.find(';', i);
      if (semi == std::string::npos) fail("unterminated entity");
      const std::string entity = raw.substr(i + 1, semi - i - 1);
      if (entity == "amp")
        out += '&';
      else if (entity == "lt")
        out += '<';
      else if (entity == "gt")
        out += '>';
      else if (entity == "quot")
        out += '"';
      else if (entity == "#10")
        out += '\n';
      else
        fail("unknown entity &" + entity + ";");
      i = semi;
    }
    return out;
  }
  std::unique_ptr<XmlNode> parseElement() {
    if (pos_ >= s_.size() || s_[pos_] != '<') fail("expected '<'");
    ++pos_;
    auto node = std::make_unique<XmlNode>();
    node->name = parseName();
    while (true) {
      skipSpace();
      if (pos_ >= s_.size()) fail("unterminated start tag");
      if (s_.compare(pos_, 2, "/>") == 0) {
        pos_ += 2;
        return node;
      }
      if (s_[pos_] == '>') {
        ++pos_;
        break;
      }
      const std::string key = parseName();
      skipSpace();
      if (pos_ >= s_.size() || s_[pos_] != '=') fail("expected '=' after attribute " + key);
      ++pos_;
      skipSpace();
      if (pos_ >= s_.size() || s_[pos_] != '"') fail("expected a quoted value");
      const std::size_t end = s_.find('"', pos_ + 1);
      if (end == std::string::npos) fail("unterminated attribute value");
      if (!node->attributes.emplace(key, decode(s_.substr(pos_ + 1, end - pos_ - 1))).second)
        fail("duplicate attribute " + key);
      pos_ = end + 1;
    }
    while (true) {
      const std::size_t lt = s_.find('<', pos_);
      if (lt == std::string::npos) fail("unterminated element " + node->name);
      node->text += decode(s_.substr(pos_, lt - pos_));
      pos_ = lt;
      if (s_.compare(pos_, 2, "</") == 0) {
        pos_ += 2;
        if (parseName() != node->name) fail("mismatched end tag for " + node->name);
        skipSpace();
        if (pos_ >= s_.size() || s_[pos_] != '>') fail("expected '>'");
        ++pos_;
        return node;
      }
      node->children.push_back(parseElement());
    }
  }

  std::string s_;
  std::size_t pos_ = 0;
};

std::vector<double> numbers(const std::string& text) {
  std::vector<double> values;
  std::istringstream in(text);
  std::string token;
  while (in >> token) values.push_back(std::strtod(token.c_str(), nullptr));
  return values;
}

/// The DataArray called `name` under `parent`.
const XmlNode* dataArray(const XmlNode& parent, const std::string& name) {
  for (const auto& c : parent.children)
    if (c->name == "DataArray" && c->attributes.count("Name") && c->attributes.at("Name") == name)
      return c.get();
  return nullptr;
}

FeModel sampleModel() {
  FeModel model;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i)
      model.nodes.push_back(Node{100 + 10 * j + i, {0.5 * i, 0.25 * j, 1.0 / 3.0}});
  model.nodes.push_back(Node{999, {0.75, 0.25, 1.0}});
  model.parts = {Part{3, "a", false}, Part{8, "b", false}};
  Id element = 40;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      const Id a = 100 + 10 * j + i, b = a + 1, c = a + 11, d = a + 10;
      if (i == 1) {
        model.shells.push_back(Shell{element++, 3, {a, b, c, 0}, 3});
        model.shells.push_back(Shell{element++, 3, {a, c, d, 0}, 3});
      } else {
        model.shells.push_back(Shell{element++, 3, {a, b, c, d}, 4});
      }
    }
  model.shells.push_back(Shell{element++, 8, {111, 112, 999, 0}, 3});  // a T-junction face
  return model;
}

/// A python interpreter that can `import vtk`, or "" when there is none.
std::string pythonWithVtk() {
  for (const char* python : {"python3", "/usr/bin/python3"}) {
    const std::string command = std::string(python) + " -c 'import vtk' > /dev/null 2>&1";
    if (std::system(command.c_str()) == 0) return python;
  }
  return {};
}

}  // namespace

TEST(Vtu, XmlIsWellFormedAndArraysHaveTheRightLengthsAndValues) {
  const FeModel model = sampleModel();
  std::vector<double> quality;
  for (std::size_t i = 0; i < model.shells.size(); ++i)
    quality.push_back(0.1 * static_cast<double>(i));
  std::vector<double> height;
  for (const Node& n : model.nodes) height.push_back(n.xyz[2]);
  std::string out;
  io::writeVtuContent(model, out, {{"warping <deg> & \"max\"", quality}}, {{"height", height}});

  const auto root = XmlParser(out).parseDocument();
  ASSERT_EQ(root->name, "VTKFile");
  EXPECT_EQ(root->attributes.at("type"), "UnstructuredGrid");
  EXPECT_EQ(root->attributes.at("version"), "0.1");
  const XmlNode* grid = root->child("UnstructuredGrid");
  ASSERT_NE(grid, nullptr);
  const XmlNode* piece = grid->child("Piece");
  ASSERT_NE(piece, nullptr);
  const std::size_t points = model.nodes.size();
  const std::size_t cells = model.shells.size();
  EXPECT_EQ(piece->attributes.at("NumberOfPoints"), std::to_string(points));
  EXPECT_EQ(piece->attributes.at("NumberOfCells"), std::to_string(cells));

  const XmlNode* pointData = piece->child("PointData");
  const XmlNode* cellData = piece->child("CellData");
  const XmlNode* pts = piece->child("Points");
  const XmlNode* cellsNode = piece->child("Cells");
  ASSERT_TRUE(pointData && cellData && pts && cellsNode);

  const XmlNode* nodeId = dataArray(*pointData, "node_id");
  ASSERT_NE(nodeId, nullptr);
  EXPECT_EQ(nodeId->attributes.at("type"), "Int64");
  const auto nodeIds = numbers(nodeId->text);
  ASSERT_EQ(nodeIds.size(), points);
  for (std::size_t i = 0; i < points; ++i)
    EXPECT_EQ(nodeIds[i], static_cast<double>(model.nodes[i].id));
  const XmlNode* heightArray = dataArray(*pointData, "height");
  ASSERT_NE(heightArray, nullptr);
  EXPECT_EQ(heightArray->attributes.at("type"), "Float64");
  EXPECT_EQ(numbers(heightArray->text), height);

  const auto partIds = numbers(dataArray(*cellData, "part_id")->text);
  const auto elementIds = numbers(dataArray(*cellData, "element_id")->text);
  ASSERT_EQ(partIds.size(), cells);
  ASSERT_EQ(elementIds.size(), cells);
  for (std::size_t i = 0; i < cells; ++i) {
    EXPECT_EQ(partIds[i], static_cast<double>(model.shells[i].part));
    EXPECT_EQ(elementIds[i], static_cast<double>(model.shells[i].id));
  }
  const XmlNode* warping = dataArray(*cellData, "warping <deg> & \"max\"");
  ASSERT_NE(warping, nullptr);
  EXPECT_EQ(numbers(warping->text), quality);

  const XmlNode* coordinates = pts->child("DataArray");
  ASSERT_NE(coordinates, nullptr);
  EXPECT_EQ(coordinates->attributes.at("NumberOfComponents"), "3");
  const auto xyz = numbers(coordinates->text);
  ASSERT_EQ(xyz.size(), 3 * points);
  for (std::size_t i = 0; i < points; ++i)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(xyz[3 * i + a], model.nodes[i].xyz[a]);

  const auto connectivity = numbers(dataArray(*cellsNode, "connectivity")->text);
  const auto offsets = numbers(dataArray(*cellsNode, "offsets")->text);
  const auto types = numbers(dataArray(*cellsNode, "types")->text);
  ASSERT_EQ(offsets.size(), cells);
  ASSERT_EQ(types.size(), cells);
  std::size_t corners = 0;
  for (std::size_t i = 0; i < cells; ++i) {
    const Shell& s = model.shells[i];
    EXPECT_EQ(types[i], s.nodeCount == 3 ? 5.0 : 9.0);
    for (int k = 0; k < s.nodeCount; ++k) {
      ASSERT_LT(corners, connectivity.size());
      const auto index = static_cast<std::size_t>(connectivity[corners++]);
      ASSERT_LT(index, points);
      EXPECT_EQ(model.nodes[index].id, s.nodes[k]);
    }
    EXPECT_EQ(offsets[i], static_cast<double>(corners));
  }
  EXPECT_EQ(connectivity.size(), corners);
}

TEST(Vtu, WrongFieldSizesAreRefusedNamingTheField) {
  const FeModel model = sampleModel();
  std::string out;
  try {
    io::writeVtuContent(model, out, {{"jacobian", std::vector<double>(model.shells.size() - 1)}},
                        {});
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("jacobian"), std::string::npos) << e.what();
  }
  try {
    io::writeVtuContent(model, out, {},
                        {{"distance", std::vector<double>(model.nodes.size() + 2)}});
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("distance"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(out.empty());
}

TEST(Vtu, VtkReadsTheFileWhereItIsInstalled) {
  const std::string python = pythonWithVtk();
  if (python.empty()) GTEST_SKIP() << "python3 with VTK (Debian: python3-vtk9) is not installed";
  const FeModel model = sampleModel();
  std::vector<double> quality(model.shells.size(), 0.5);
  std::string out;
  io::writeVtuContent(model, out, {{"quality", quality}}, {});
  const fs::path dir = test::scratchDir("vtu_vtk");
  const fs::path file = dir / "model.vtu";
  io::writeFileAtomically(file, out);
  const fs::path script = dir / "read.py";
  const fs::path result = dir / "result.txt";
  test::writeText(
      script,
      "import sys, vtk\n"
      "r = vtk.vtkXMLUnstructuredGridReader()\n"
      "r.SetFileName(sys.argv[1])\n"
      "r.Update()\n"
      "g = r.GetOutput()\n"
      "q = g.GetCellData().GetArray('quality')\n"
      "p = g.GetCellData().GetArray('part_id')\n"
      "open(sys.argv[2], 'w').write('%d %d %d %d' % (g.GetNumberOfPoints(), "
      "g.GetNumberOfCells(), q.GetNumberOfTuples(), p.GetValue(p.GetNumberOfTuples() - 1)))\n");
  const std::string command = python + " " + script.string() + " " + file.string() + " " +
                              result.string() + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  EXPECT_EQ(test::readText(result), std::to_string(model.nodes.size()) + " " +
                                        std::to_string(model.shells.size()) + " " +
                                        std::to_string(model.shells.size()) + " 8");
}
