// OFF (Object File Format) reader and writer: ASCII OFF with its COFF/NOFF/CNOFF/STOFF
// variants, triangle and quad faces (every face kept, also at non-manifold edges). No parts.
#include <algorithm>
#include <array>
#include <string>
#include <string_view>

#include "io/formats.h"
#include "io/surface_builder.h"
#include "io/text_scan.h"
#include "voxremesh/errors.h"

namespace voxremesh::io {

namespace {

using surface::MeshBuilder;

constexpr std::size_t kMaxTokens = 24;

/// The line without its `#` comment, trimmed.
std::string_view content(std::string_view line) {
  const std::size_t hash = line.find('#');
  return trim(hash == std::string_view::npos ? line : line.substr(0, hash));
}

/// True for the OFF header keywords voxremesh reads: [ST][C][N]OFF.
bool isHeader(std::string_view word) {
  if (word.size() < 3 || word.substr(word.size() - 3) != "OFF") return false;
  std::string_view prefix = word.substr(0, word.size() - 3);
  if (prefix.substr(0, 2) == "ST") prefix.remove_prefix(2);
  if (!prefix.empty() && prefix.front() == 'C') prefix.remove_prefix(1);
  if (!prefix.empty() && prefix.front() == 'N') prefix.remove_prefix(1);
  return prefix.empty();
}

}  // namespace

FeModel readOff(const std::filesystem::path& path, Warnings& warnings) {
  const std::string text = loadFile(path);
  requireText(text, path);
  MeshBuilder builder(DeckFormat::Off, path, 0);
  std::array<std::string_view, kMaxTokens> tokens;
  LineCursor cursor(text);
  std::size_t n = 0;
  auto fail = [&](const std::string& message) {
    throw InputError(builder.file(), cursor.lineNumber(), message,
                     std::string(trim(cursor.line())));
  };
  // The header keyword, then the counts (possibly on the same line).
  bool header = false;
  bool counts = false;
  std::int64_t vertexCount = 0;
  std::int64_t faceCount = 0;
  while (!counts && cursor.next()) {
    const std::string_view line = content(cursor.line());
    if (line.empty()) continue;
    n = surface::splitBlanks(line, tokens.data(), tokens.size());
    std::size_t first = 0;
    if (!header) {
      if (tokens[0].find("OFF") != std::string_view::npos && !isHeader(tokens[0]))
        fail("OFF variant " + surface::quoted(tokens[0]) +
             " is not supported (voxremesh reads OFF, COFF, NOFF, CNOFF and STOFF)");
      if (!isHeader(tokens[0]))
        fail("not an OFF file: expected the header 'OFF', found " + surface::quoted(tokens[0]));
      if (n > 1 && tokens[1] == "BINARY") fail("binary OFF is not supported; write it as text");
      header = true;
      first = 1;
      if (n == 1) continue;
    }
    if (n - first < 2 || n - first > 3) fail("expected the counts 'vertices faces edges'");
    std::int64_t edges = 0;
    if (!parseInt(tokens[first], vertexCount) || vertexCount < 0)
      fail("malformed vertex count " + surface::quoted(tokens[first]));
    if (!parseInt(tokens[first + 1], faceCount) || faceCount < 0)
      fail("malformed face count " + surface::quoted(tokens[first + 1]));
    if (n - first == 3 && !parseInt(tokens[first + 2], edges))
      fail("malformed edge count " + surface::quoted(tokens[first + 2]));
    counts = true;
  }
  if (!counts) fail("file ends before the vertex and face counts");
  // Room for what the file can hold: a vertex line takes at least 6 bytes ("0 0 0\n"), a face
  // line at least 8 ("3 0 1 2\n"), whatever counts the header claims.
  const auto fits = [&](std::int64_t count, std::size_t lineBytes) {
    return static_cast<std::size_t>(
        std::min<std::int64_t>(count, static_cast<std::int64_t>(text.size() / lineBytes)));
  };
  builder.reserve(fits(vertexCount, 6), fits(faceCount, 8));
  builder.usePartNamed(path.stem().string());

  std::int64_t vertices = 0;
  std::int64_t faces = 0;
  std::size_t trailing = 0;
  while (cursor.next()) {
    const std::string_view line = content(cursor.line());
    if (line.empty()) continue;
    n = surface::splitBlanks(line, tokens.data(), tokens.size());
    if (vertices < vertexCount) {
      if (n < 3) fail("vertex " + std::to_string(vertices) + " has fewer than three coordinates");
      std::array<double, 3> xyz{};
      static constexpr const char* kAxis[] = {"x", "y", "z"};
      for (std::size_t k = 0; k < 3; ++k)
        if (!parseReal(tokens[k], xyz[k]))
          fail("malformed " + std::string(kAxis[k]) + " coordinate " + surface::quoted(tokens[k]) +
               " in vertex " + std::to_string(vertices));
      builder.addVertex(xyz, cursor.lineNumber());
      ++vertices;
    } else if (faces < faceCount) {
      std::int64_t corners = 0;
      if (!parseInt(tokens[0], corners))
        fail("malformed vertex count " + surface::quoted(tokens[0]) + " of face " +
             std::to_string(faces));
      if (corners > 4)
        fail("polygon with " + std::to_string(corners) +
             " vertices (voxremesh reads triangles and quadrilaterals)");
      if (corners < 3) fail("face with " + std::to_string(corners) + " vertices");
      if (n < static_cast<std::size_t>(corners) + 1)
        fail("face " + std::to_string(faces) + " lists fewer than " + std::to_string(corners) +
             " vertices");
      std::int64_t indices[4];
      for (std::int64_t k = 0; k < corners; ++k) {
        const std::string_view token = tokens[static_cast<std::size_t>(k) + 1];
        std::int64_t index = 0;
        if (!parseInt(token, index))
          fail("malformed vertex index " + surface::quoted(token) + " in face " +
               std::to_string(faces));
        if (index < 0 || index >= vertexCount)
          fail("face " + std::to_string(faces) + " names vertex " + std::to_string(index) +
               ", but the file has " + std::to_string(vertexCount) + " vertices (numbered from 0)");
        indices[k] = index + 1;
      }
      builder.addFace(indices, static_cast<int>(corners), cursor.lineNumber());
      ++faces;
    } else {
      ++trailing;
    }
  }
  if (vertices < vertexCount)
    fail("file ends after " + std::to_string(vertices) + " of " + std::to_string(vertexCount) +
         " vertices (truncated)");
  if (faces < faceCount)
    fail("file ends after " + std::to_string(faces) + " of " + std::to_string(faceCount) +
         " faces (truncated)");
  if (trailing > 0)
    warnings.push_back(path.string() + ": " + std::to_string(trailing) +
                       " line(s) after the last face are not read");
  return builder.finish(warnings);
}

void writeOff(const FeModel& model, std::string& out, Warnings& warnings) {
  const surface::NodeIndexer indexer(model);
  surface::warnExtrasLost(model, "OFF", warnings);
  if (model.parts.size() > 1)
    warnings.push_back("OFF has no parts: the " + std::to_string(model.parts.size()) +
                       " parts are written as one mesh");
  out.reserve(out.size() + model.nodes.size() * 60 + model.shells.size() * 32);
  out += "OFF\n";
  surface::appendInt(out, static_cast<std::int64_t>(model.nodes.size()));
  out += ' ';
  surface::appendInt(out, static_cast<std::int64_t>(model.shells.size()));
  out += " 0\n";
  for (const Node& node : model.nodes) {
    surface::appendXyz(out, node.xyz);
    out += '\n';
  }
  for (const Shell& shell : model.shells) {
    out += shell.nodeCount == 3 ? '3' : '4';
    indexer.appendCorners(out, shell);
    out += '\n';
  }
}

}  // namespace voxremesh::io
