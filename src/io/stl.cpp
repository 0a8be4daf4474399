// STL reader and writer, ASCII and binary. Vertices are merged by exact coordinates in
// first-seen order; every facet is kept (also at non-manifold edges); ASCII solids are parts.
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "io/formats.h"
#include "io/surface_builder.h"
#include "io/text_scan.h"
#include "voxremesh/errors.h"

namespace voxremesh::io {

namespace {

using surface::MeshBuilder;

constexpr std::size_t kHeaderBytes = 84;
constexpr std::size_t kTriangleBytes = 50;

/// Merges vertices with exactly equal coordinates (+0 and -0 count as equal): an open-addressing
/// hash table of vertex numbers whose coordinates live in the builder.
class VertexMerger {
 public:
  explicit VertexMerger(std::size_t expected) { resize(expected * 2 + 16); }

  /// The 1-based vertex number of `xyz`, adding the vertex to `builder` when it is new.
  std::int64_t id(std::array<double, 3> xyz, MeshBuilder& builder, std::size_t line) {
    for (double& v : xyz) v += 0.0;  // -0 becomes +0
    std::size_t slot = hash(xyz) & mask_;
    while (slots_[slot] != 0) {
      const std::int64_t id = slots_[slot];
      if (builder.vertex(static_cast<std::size_t>(id - 1)) == xyz) return id;
      slot = (slot + 1) & mask_;
    }
    builder.addVertex(xyz, line);
    const auto id = static_cast<std::int64_t>(builder.vertexCount());
    slots_[slot] = id;
    if (2 * static_cast<std::size_t>(id) > slots_.size()) rehash(builder);
    return id;
  }

 private:
  static std::size_t hash(const std::array<double, 3>& p) {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (double v : p) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &v, sizeof bits);
      h = (h ^ bits) * 0xff51afd7ed558ccdull;
      h ^= h >> 32;
    }
    return static_cast<std::size_t>(h);
  }

  void resize(std::size_t capacity) {
    std::size_t size = 1024;
    while (size < capacity) size *= 2;
    slots_.assign(size, 0);
    mask_ = size - 1;
  }

  void rehash(const MeshBuilder& builder) {
    resize(slots_.size() * 2);
    for (std::size_t i = 0; i < builder.vertexCount(); ++i) {
      std::size_t slot = hash(builder.vertex(i)) & mask_;
      while (slots_[slot] != 0) slot = (slot + 1) & mask_;
      slots_[slot] = static_cast<std::int64_t>(i + 1);
    }
  }

  std::vector<std::int64_t> slots_;
  std::size_t mask_ = 0;
};

bool isBinaryStl(const std::string& content) {
  if (content.size() < kHeaderBytes) return false;
  const auto count = surface::readBytes<std::uint32_t>(content.data() + 80, true);
  return kHeaderBytes + kTriangleBytes * static_cast<std::uint64_t>(count) == content.size();
}

void readBinary(const std::string& content, MeshBuilder& builder) {
  const auto count = surface::readBytes<std::uint32_t>(content.data() + 80, true);
  builder.reserve(count / 2 + 1, count);
  VertexMerger merger(count / 2 + 1);
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::size_t record = kHeaderBytes + kTriangleBytes * i;
    std::int64_t corners[3];
    for (std::size_t k = 0; k < 3; ++k) {
      std::array<double, 3> xyz{};
      for (std::size_t a = 0; a < 3; ++a) {
        const std::size_t offset = record + 12 + 12 * k + 4 * a;
        xyz[a] = surface::readBytes<float>(content.data() + offset, true);
        if (!std::isfinite(xyz[a]))
          throw InputError(builder.file(), 0,
                           "coordinate of triangle " + std::to_string(i + 1) +
                               " is not a finite number (byte offset " + std::to_string(offset) +
                               ")");
      }
      corners[k] = merger.id(xyz, builder, 0);
    }
    builder.addFace(corners, 3, 0);
  }
}

void readAscii(const std::string& content, MeshBuilder& builder, const std::string& stem) {
  enum class State { Outside, Solid, Facet, Loop };
  State state = State::Outside;
  VertexMerger merger(content.size() / 200 + 16);
  builder.reserve(content.size() / 200 + 16, content.size() / 250 + 16);
  std::array<std::string_view, 8> tokens;
  std::int64_t corners[3] = {0, 0, 0};
  int cornerCount = 0;
  LineCursor cursor(content);
  auto fail = [&](const std::string& message) {
    throw InputError(builder.file(), cursor.lineNumber(), message,
                     std::string(trim(cursor.line())));
  };
  while (cursor.next()) {
    const std::string_view line = trim(cursor.line());
    if (line.empty()) continue;
    const std::size_t n = surface::splitBlanks(line, tokens.data(), tokens.size());
    const std::string_view keyword = tokens[0];
    if (keyword == "vertex" || keyword == "VERTEX") {
      if (state != State::Loop) fail("'vertex' outside 'outer loop'");
      if (cornerCount == 3) fail("facet with more than three vertices (STL holds triangles)");
      if (n != 4) fail("vertex needs three coordinates");
      std::array<double, 3> xyz{};
      static constexpr const char* kAxis[] = {"x", "y", "z"};
      for (std::size_t k = 0; k < 3; ++k)
        if (!parseReal(tokens[k + 1], xyz[k]) || !std::isfinite(xyz[k]))
          fail("malformed " + std::string(kAxis[k]) + " coordinate " +
               surface::quoted(tokens[k + 1]) + " in vertex");
      corners[cornerCount++] = merger.id(xyz, builder, cursor.lineNumber());
    } else if (iequals(keyword, "facet")) {
      if (state != State::Solid) fail("'facet' outside a solid or inside another facet");
      state = State::Facet;
      cornerCount = 0;
    } else if (iequals(keyword, "outer")) {
      if (state != State::Facet) fail("'outer loop' outside a facet");
      state = State::Loop;
    } else if (iequals(keyword, "endloop")) {
      if (state != State::Loop) fail("'endloop' without 'outer loop'");
      state = State::Facet;
    } else if (iequals(keyword, "endfacet")) {
      if (state != State::Facet) fail("'endfacet' without a complete facet");
      if (cornerCount != 3)
        fail("facet with " + std::to_string(cornerCount) + " vertices (STL holds triangles)");
      builder.addFace(corners, 3, cursor.lineNumber());
      state = State::Solid;
    } else if (iequals(keyword, "solid")) {
      if (state != State::Outside) fail("'solid' inside another solid (missing 'endsolid')");
      const std::string_view name = trim(line.substr(5));
      builder.usePartNamed(name.empty() ? std::string_view(stem) : name);
      state = State::Solid;
    } else if (iequals(keyword, "endsolid")) {
      if (state != State::Solid) fail("'endsolid' inside a facet");
      state = State::Outside;
    } else {
      fail("unexpected " + surface::quoted(keyword) + " in ASCII STL");
    }
  }
  if (state != State::Outside) fail("file ends inside a solid (truncated: no 'endsolid')");
}

/// The unit normal of a triangle (zero for a degenerate one).
std::array<double, 3> normalOf(const Node& a, const Node& b, const Node& c) {
  const double u[3] = {b.xyz[0] - a.xyz[0], b.xyz[1] - a.xyz[1], b.xyz[2] - a.xyz[2]};
  const double v[3] = {c.xyz[0] - a.xyz[0], c.xyz[1] - a.xyz[1], c.xyz[2] - a.xyz[2]};
  std::array<double, 3> n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                             u[0] * v[1] - u[1] * v[0]};
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (length > 0)
    for (double& x : n) x /= length;
  return n;
}

/// Calls `emit(a, b, c)` with the node indices of each triangle of each shell (quads split
/// along their 1-3 diagonal), in model order.
template <typename Emit>
void forEachTriangle(const FeModel& model, const surface::NodeIndexer& indexer, Emit emit) {
  for (const Shell& shell : model.shells) {
    std::size_t v[4] = {0, 0, 0, 0};
    for (int k = 0; k < shell.nodeCount; ++k)
      v[k] = indexer.index(shell.nodes[static_cast<std::size_t>(k)], shell.id);
    emit(shell, v[0], v[1], v[2]);
    if (shell.nodeCount == 4) emit(shell, v[0], v[2], v[3]);
  }
}

/// Appends one ASCII facet: the normal to float precision (it is informational; readers
/// recompute it), the corners with full precision.
void appendAsciiFacet(std::string& out, const Node& a, const Node& b, const Node& c) {
  out += "  facet normal";
  for (double v : normalOf(a, b, c)) {
    char buffer[24];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, static_cast<float>(v));
    out += ' ';
    out.append(buffer, result.ptr);
  }
  out += "\n    outer loop\n";
  for (const Node* node : {&a, &b, &c}) {
    out += "      vertex";
    for (double v : node->xyz) {
      out += ' ';
      appendShortest(out, v);
    }
    out += '\n';
  }
  out += "    endloop\n  endfacet\n";
}

}  // namespace

FeModel readStl(const std::filesystem::path& path, Warnings& warnings) {
  const std::string content = loadFile(path);
  const std::string file = path.string();
  if (trim(content).find_first_not_of(" \t\r\n") == std::string_view::npos)
    throw InputError(file, 0, "empty file");
  MeshBuilder builder(DeckFormat::Stl, path, 1);
  if (isBinaryStl(content)) {
    builder.usePartNamed(path.stem().string());
    readBinary(content, builder);
    return builder.finish(warnings);
  }
  const std::string_view start = trim(std::string_view(content).substr(0, 256));
  const bool looksAscii = istartsWith(start, "solid") && content.find('\0') == std::string::npos;
  if (!looksAscii) {
    if (content.size() < kHeaderBytes)
      throw InputError(file, 0,
                       "not an STL file: no 'solid' header for ASCII STL, and shorter than the "
                       "84-byte header of binary STL (" +
                           std::to_string(content.size()) + " bytes)");
    const auto count = surface::readBytes<std::uint32_t>(content.data() + 80, true);
    const std::uint64_t expected =
        kHeaderBytes + kTriangleBytes * static_cast<std::uint64_t>(count);
    throw InputError(file, 0,
                     "binary STL of the wrong size: the header announces " + std::to_string(count) +
                         " triangles (" + std::to_string(expected) + " bytes) but the file has " +
                         std::to_string(content.size()) +
                         " bytes (truncated or not an STL file; the data ends at byte offset " +
                         std::to_string(content.size()) + ")");
  }
  readAscii(content, builder, path.stem().string());
  return builder.finish(warnings);
}

void writeStl(const FeModel& model, std::string& out, bool binary, Warnings& warnings) {
  const surface::NodeIndexer indexer(model);
  surface::warnExtrasLost(model, "STL", warnings);
  std::size_t quads = 0;
  for (const Shell& shell : model.shells) quads += shell.nodeCount == 4;
  if (quads > 0)
    warnings.push_back(
        std::to_string(quads) +
        " quadrilateral(s) written as two triangles each (STL holds triangles only)");
  const std::size_t triangles = model.shells.size() + quads;

  if (binary) {
    if (triangles > 0xffffffffull)
      throw std::length_error("binary STL holds at most 4294967295 triangles");
    if (model.parts.size() > 1)
      warnings.push_back("binary STL has no parts: the " + std::to_string(model.parts.size()) +
                         " parts are written as one mesh (ASCII STL keeps them as solids)");
    out.reserve(out.size() + kHeaderBytes + kTriangleBytes * triangles);
    std::string header = "binary STL written by voxremesh " VOXREMESH_VERSION;
    header.resize(80, ' ');
    out += header;
    surface::appendLittleEndian(out, static_cast<std::uint32_t>(triangles));
    forEachTriangle(model, indexer, [&](const Shell&, std::size_t a, std::size_t b, std::size_t c) {
      const Node* corners[3] = {&model.nodes[a], &model.nodes[b], &model.nodes[c]};
      for (double v : normalOf(*corners[0], *corners[1], *corners[2]))
        surface::appendLittleEndian(out, static_cast<float>(v));
      for (const Node* node : corners)
        for (double v : node->xyz) surface::appendLittleEndian(out, static_cast<float>(v));
      surface::appendLittleEndian(out, std::uint16_t{0});
    });
    return;
  }

  out.reserve(out.size() + triangles * 240);
  bool open = false;
  Id current = 0;
  std::string name;
  auto close = [&]() {
    if (open) out += "endsolid " + name + '\n';
  };
  auto facet = [&](const Shell& shell, std::size_t a, std::size_t b, std::size_t c) {
    if (!open || shell.part != current) {
      close();
      name = surface::partLabel(model, shell.part);
      for (char& ch : name)
        if (ch == '\n' || ch == '\r') ch = ' ';
      out += "solid " + name + '\n';
      current = shell.part;
      open = true;
    }
    appendAsciiFacet(out, model.nodes[a], model.nodes[b], model.nodes[c]);
  };
  forEachTriangle(model, indexer, facet);
  close();
  if (!open) out += "solid empty\nendsolid empty\n";
}

}  // namespace voxremesh::io
