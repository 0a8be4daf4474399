// Wavefront OBJ reader and writer: vertices, triangle and quad faces (every face kept, also at
// non-manifold edges), groups/objects as parts.
#include <array>
#include <map>
#include <string>
#include <string_view>

#include "io/formats.h"
#include "io/surface_builder.h"
#include "io/text_scan.h"
#include "voxremesh/errors.h"

namespace voxremesh::io {

namespace {

using surface::MeshBuilder;

constexpr std::string_view kPartComment = "# voxremesh part ";
constexpr std::size_t kMaxTokens = 16;

/// Statements of the OBJ format that carry nothing voxremesh reads.
bool isIgnored(std::string_view keyword) {
  static constexpr std::string_view kIgnored[] = {
      "vt",     "vn",    "vp",         "s",         "usemtl", "mtllib",   "maplib",
      "usemap", "lod",   "shadow_obj", "trace_obj", "bevel",  "c_interp", "d_interp",
      "ctech",  "stech", "mg",         "call",      "csh"};
  for (std::string_view name : kIgnored)
    if (keyword == name) return true;
  return false;
}

/// Free-form curve and surface statements, which voxremesh does not evaluate.
bool isFreeForm(std::string_view keyword) {
  static constexpr std::string_view kFreeForm[] = {"cstype", "deg",  "bmat", "step", "curv",
                                                   "curv2",  "surf", "parm", "trim", "hole",
                                                   "scrv",   "sp",   "end",  "con"};
  for (std::string_view name : kFreeForm)
    if (keyword == name) return true;
  return false;
}

/// Takes `# voxremesh part <id> <name>`; returns false for any other comment.
bool takePartComment(std::string_view line, MeshBuilder& builder) {
  if (line.substr(0, kPartComment.size()) != kPartComment) return false;
  const std::string_view rest = trim(line.substr(kPartComment.size()));
  const std::size_t blank = rest.find(' ');
  if (blank == std::string_view::npos) return false;
  std::int64_t id = 0;
  if (!parseInt(rest.substr(0, blank), id)) return false;
  builder.restorePartId(std::string(trim(rest.substr(blank + 1))), id);
  return true;
}

}  // namespace

FeModel readObj(const std::filesystem::path& path, Warnings& warnings) {
  const std::string content = loadFile(path);
  requireText(content, path);
  MeshBuilder builder(DeckFormat::Obj, path, 1);
  builder.reserve(content.size() / 48, content.size() / 48);
  std::size_t lineElements = 0;
  std::size_t pointElements = 0;
  std::map<std::string, std::size_t> freeForm;
  std::array<std::string_view, kMaxTokens> tokens;
  LineCursor cursor(content);
  while (cursor.next()) {
    const std::string_view line = trim(cursor.line());
    if (line.empty()) continue;
    auto fail = [&](const std::string& message) {
      throw InputError(builder.file(), cursor.lineNumber(), message, std::string(line));
    };
    if (line[0] == '#') {
      takePartComment(line, builder);
      continue;
    }
    const std::size_t n = surface::splitBlanks(line, tokens.data(), tokens.size());
    const std::string_view keyword = tokens[0];
    if (keyword == "v") {
      if (n < 4) fail("vertex with fewer than three coordinates");
      if (n > 8) fail("vertex with more than seven values");
      std::array<double, 3> xyz{};
      static constexpr const char* kAxis[] = {"x", "y", "z"};
      for (std::size_t k = 0; k < 3; ++k)
        if (tokens[k + 1].empty() || !parseReal(tokens[k + 1], xyz[k]))
          fail("malformed " + std::string(kAxis[k]) + " coordinate " +
               surface::quoted(tokens[k + 1]) + " in vertex " +
               std::to_string(builder.vertexCount() + 1));
      double extra = 0;
      for (std::size_t k = 4; k < n; ++k)
        if (!parseReal(tokens[k], extra))
          fail("malformed number " + surface::quoted(tokens[k]) + " in vertex " +
               std::to_string(builder.vertexCount() + 1));
      builder.addVertex(xyz, cursor.lineNumber());
    } else if (keyword == "f" || keyword == "fo") {
      const std::size_t corners = n - 1;
      if (corners > 4)
        fail("polygon with " + std::to_string(corners) +
             " vertices (voxremesh reads triangles and quadrilaterals)");
      if (corners < 3) fail("face with " + std::to_string(corners) + " vertices");
      std::int64_t vertices[4];
      for (std::size_t k = 0; k < corners; ++k) {
        const std::string_view token = tokens[k + 1];
        const std::string_view index = token.substr(0, token.find('/'));
        std::int64_t value = 0;
        if (index.empty() || !parseInt(index, value))
          fail("malformed vertex index " + surface::quoted(token) + " in face");
        if (value == 0) fail("vertex index 0 in face (OBJ numbers vertices from 1)");
        if (value < 0) {
          const auto count = static_cast<std::int64_t>(builder.vertexCount());
          if (-value > count)
            fail("relative vertex index " + std::to_string(value) +
                 " reaches before the first "
                 "vertex (" +
                 std::to_string(count) + " defined so far)");
          value = count + value + 1;
        }
        vertices[k] = value;
      }
      if (!builder.hasPart()) builder.usePartNamed("default");
      builder.addFace(vertices, static_cast<int>(corners), cursor.lineNumber());
    } else if (keyword == "g" || keyword == "o") {
      const std::string_view name = trim(line.substr(keyword.size()));
      builder.usePartNamed(name.empty() ? std::string_view("default") : name);
    } else if (keyword == "l") {
      ++lineElements;
    } else if (keyword == "p") {
      ++pointElements;
    } else if (isFreeForm(keyword)) {
      ++freeForm[std::string(keyword)];
    } else if (!isIgnored(keyword)) {
      fail("unknown OBJ statement " + surface::quoted(keyword));
    }
  }
  if (lineElements > 0)
    warnings.push_back(path.string() + ": " + std::to_string(lineElements) +
                       " line element(s) ('l') are not read (voxremesh reads faces)");
  if (pointElements > 0)
    warnings.push_back(path.string() + ": " + std::to_string(pointElements) +
                       " point element(s) ('p') are not read (voxremesh reads faces)");
  for (const auto& [keyword, count] : freeForm)
    warnings.push_back(path.string() + ": " + std::to_string(count) + " free-form '" + keyword +
                       "' statement(s) are not evaluated");
  return builder.finish(warnings);
}

void writeObj(const FeModel& model, std::string& out, Warnings& warnings) {
  const surface::NodeIndexer indexer(model);
  surface::warnExtrasLost(model, "OBJ", warnings);
  out.reserve(out.size() + model.nodes.size() * 60 + model.shells.size() * 32);
  out += "# written by voxremesh " VOXREMESH_VERSION ": ";
  surface::appendInt(out, static_cast<std::int64_t>(model.nodes.size()));
  out += " vertices, ";
  surface::appendInt(out, static_cast<std::int64_t>(model.shells.size()));
  out += " faces\n";
  for (const Node& node : model.nodes) {
    out += 'v';
    for (double v : node.xyz) {
      out += ' ';
      appendShortest(out, v);
    }
    out += '\n';
  }
  Id current = 0;
  bool started = false;
  for (const Shell& shell : model.shells) {
    if (!started || shell.part != current) {
      std::string name = surface::partLabel(model, shell.part);
      for (char& c : name)
        if (c == '\n' || c == '\r') c = ' ';
      out += kPartComment;
      surface::appendInt(out, shell.part);
      out += ' ' + name + "\ng " + name + '\n';
      current = shell.part;
      started = true;
    }
    out += 'f';
    indexer.appendCorners(out, shell, 1);
    out += '\n';
  }
}

}  // namespace voxremesh::io
