// PLY reader and writer (ascii, binary_little_endian, binary_big_endian): vertex x y z of any
// numeric type, faces from a vertex_indices / vertex_index list, an optional face property
// `part`; every other property and element is skipped by its declared types.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "io/formats.h"
#include "io/surface_builder.h"
#include "io/text_scan.h"
#include "voxremesh/errors.h"

namespace voxremesh::io {

namespace {

using surface::MeshBuilder;

constexpr std::string_view kPartComment = "comment voxremesh part ";

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool parseType(std::string_view name, Type& type) {
  static constexpr std::pair<std::string_view, Type> kTypes[] = {
      {"char", Type::Int8},      {"int8", Type::Int8},       {"uchar", Type::UInt8},
      {"uint8", Type::UInt8},    {"short", Type::Int16},     {"int16", Type::Int16},
      {"ushort", Type::UInt16},  {"uint16", Type::UInt16},   {"int", Type::Int32},
      {"int32", Type::Int32},    {"uint", Type::UInt32},     {"uint32", Type::UInt32},
      {"float", Type::Float32},  {"float32", Type::Float32}, {"double", Type::Float64},
      {"float64", Type::Float64}};
  for (const auto& [text, value] : kTypes)
    if (name == text) {
      type = value;
      return true;
    }
  return false;
}

std::size_t sizeOf(Type type) {
  switch (type) {
    case Type::Int8:
    case Type::UInt8:
      return 1;
    case Type::Int16:
    case Type::UInt16:
      return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32:
      return 4;
    case Type::Float64:
      return 8;
  }
  return 0;
}

bool isIntegral(Type type) {
  return type != Type::Float32 && type != Type::Float64;
}

/// Reads one binary value of `type` at `p` and converts it to Out.
template <typename Out>
Out readAs(Type type, const char* p, bool little) {
  switch (type) {
    case Type::Int8:
      return static_cast<Out>(surface::readBytes<std::int8_t>(p, little));
    case Type::UInt8:
      return static_cast<Out>(surface::readBytes<std::uint8_t>(p, little));
    case Type::Int16:
      return static_cast<Out>(surface::readBytes<std::int16_t>(p, little));
    case Type::UInt16:
      return static_cast<Out>(surface::readBytes<std::uint16_t>(p, little));
    case Type::Int32:
      return static_cast<Out>(surface::readBytes<std::int32_t>(p, little));
    case Type::UInt32:
      return static_cast<Out>(surface::readBytes<std::uint32_t>(p, little));
    case Type::Float32:
      return static_cast<Out>(surface::readBytes<float>(p, little));
    case Type::Float64:
      return static_cast<Out>(surface::readBytes<double>(p, little));
  }
  return Out{};
}

double readReal(Type type, const char* p, bool little) {
  return readAs<double>(type, p, little);
}

/// An integer value; 0 for a real type (callers check isIntegral where it matters).
std::int64_t readInteger(Type type, const char* p, bool little) {
  return isIntegral(type) ? readAs<std::int64_t>(type, p, little) : 0;
}

struct Property {
  std::string name;
  Type type = Type::Float32;  ///< the item type for lists
  bool list = false;
  Type countType = Type::UInt8;
};

/// What a property means to voxremesh.
enum class Role { Skip, X, Y, Z, Indices, Part };

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> properties;
  std::vector<Role> roles;
};

enum class Encoding { Ascii, Little, Big };

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::size_t bodyOffset = 0;
};

Header readHeader(LineCursor& cursor, const std::string& file, MeshBuilder& builder) {
  Header header;
  bool format = false;
  std::array<std::string_view, 8> tokens;
  auto fail = [&](const std::string& message) {
    throw InputError(file, cursor.lineNumber(), message, std::string(trim(cursor.line())));
  };
  if (!cursor.next() || trim(cursor.line()) != "ply")
    fail("not a PLY file: the first line must be 'ply'");
  while (true) {
    if (!cursor.next()) fail("file ends inside the header (no 'end_header')");
    const std::string_view line = trim(cursor.line());
    if (line.find('\0') != std::string_view::npos) fail("binary data inside the PLY header");
    const std::size_t n = surface::splitBlanks(line, tokens.data(), tokens.size());
    if (n == 0) continue;
    const std::string_view keyword = tokens[0];
    if (keyword == "end_header") {
      header.bodyOffset = cursor.end();
      break;
    }
    if (keyword == "comment") {
      if (line.substr(0, kPartComment.size()) == kPartComment) {
        const std::string_view rest = trim(line.substr(kPartComment.size()));
        const std::size_t blank = rest.find(' ');
        std::int64_t id = 0;
        if (blank != std::string_view::npos && parseInt(rest.substr(0, blank), id))
          builder.restorePartName(id, std::string(trim(rest.substr(blank + 1))));
      }
    } else if (keyword == "obj_info") {
    } else if (keyword == "format") {
      if (n != 3) fail("malformed format line");
      if (tokens[1] == "ascii")
        header.encoding = Encoding::Ascii;
      else if (tokens[1] == "binary_little_endian")
        header.encoding = Encoding::Little;
      else if (tokens[1] == "binary_big_endian")
        header.encoding = Encoding::Big;
      else
        fail("unknown PLY format " + surface::quoted(tokens[1]));
      format = true;
    } else if (keyword == "element") {
      if (n != 3) fail("malformed element line (expected 'element NAME COUNT')");
      Element element;
      element.name = std::string(tokens[1]);
      if (!parseInt(tokens[2], element.count) || element.count < 0)
        fail("malformed element count " + surface::quoted(tokens[2]));
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) fail("property before any element");
      Element& element = header.elements.back();
      Property property;
      if (n >= 2 && tokens[1] == "list") {
        if (n != 5) fail("malformed list property (expected 'property list COUNT ITEM NAME')");
        if (!parseType(tokens[2], property.countType) || !isIntegral(property.countType))
          fail("bad list count type " + surface::quoted(tokens[2]));
        if (!parseType(tokens[3], property.type))
          fail("unknown type " + surface::quoted(tokens[3]));
        property.list = true;
        property.name = std::string(tokens[4]);
      } else {
        if (n != 3) fail("malformed property line (expected 'property TYPE NAME')");
        if (!parseType(tokens[1], property.type))
          fail("unknown type " + surface::quoted(tokens[1]));
        property.name = std::string(tokens[2]);
      }
      Role role = Role::Skip;
      if (element.name == "vertex" && !property.list) {
        if (property.name == "x") role = Role::X;
        if (property.name == "y") role = Role::Y;
        if (property.name == "z") role = Role::Z;
      } else if (element.name == "face") {
        if (property.list &&
            (property.name == "vertex_indices" || property.name == "vertex_index")) {
          if (!isIntegral(property.type)) fail("vertex indices of floating-point type");
          role = Role::Indices;
        }
        if (!property.list && property.name == "part") role = Role::Part;
      }
      element.properties.push_back(std::move(property));
      element.roles.push_back(role);
    } else {
      fail("unknown PLY header line " + surface::quoted(keyword));
    }
  }
  if (!format) throw InputError(file, cursor.lineNumber(), "PLY header without a format line");
  for (const Element& element : header.elements) {
    auto has = [&](Role role) {
      for (Role r : element.roles)
        if (r == role) return true;
      return false;
    };
    if (element.name == "vertex" && !(has(Role::X) && has(Role::Y) && has(Role::Z)))
      throw InputError(file, cursor.lineNumber(), "vertex element without x, y and z properties");
    if (element.name == "face" && !has(Role::Indices))
      throw InputError(file, cursor.lineNumber(),
                       "face element without a vertex_indices (or vertex_index) list");
  }
  return header;
}

/// Adds a face after checking its size. For binary files `line` is 0 and `offset` is the byte
/// offset of the face record; for ASCII files `card` is the face's line.
void addFace(MeshBuilder& builder, const std::int64_t* indices, std::int64_t count,
             std::size_t line, std::size_t face, std::size_t offset, std::string_view card) {
  if (count < 3 || count > 4) {
    const std::string where =
        line == 0 ? " (byte offset " + std::to_string(offset) + ")" : std::string();
    if (count > 4)
      throw InputError(builder.file(), line,
                       "polygon with " + std::to_string(count) + " vertices in face " +
                           std::to_string(face) + where +
                           " (voxremesh reads triangles and quadrilaterals)",
                       std::string(card));
    throw InputError(
        builder.file(), line,
        "face " + std::to_string(face) + " with " + std::to_string(count) + " vertices" + where,
        std::string(card));
  }
  std::int64_t oneBased[4];
  for (std::int64_t k = 0; k < count; ++k) oneBased[k] = indices[k] + 1;
  builder.addFace(oneBased, static_cast<int>(count), line);
}

class PartSelector {
 public:
  PartSelector(MeshBuilder& builder, std::string stem)
      : builder_(builder), stem_(std::move(stem)) {}
  void select(bool hasPart, std::int64_t id) {
    if (!hasPart) {
      if (!named_) builder_.usePartNamed(stem_);
      named_ = true;
      return;
    }
    if (selected_ && id == current_) return;
    builder_.usePartId(id);
    current_ = id;
    selected_ = true;
  }

 private:
  MeshBuilder& builder_;
  std::string stem_;
  bool named_ = false;
  bool selected_ = false;
  std::int64_t current_ = 0;
};

void readAsciiBody(const Header& header, LineCursor& cursor, MeshBuilder& builder,
                   PartSelector& parts) {
  std::array<std::string_view, 64> tokens;
  for (const Element& element : header.elements) {
    const bool isVertex = element.name == "vertex";
    const bool isFace = element.name == "face";
    for (std::int64_t i = 0; i < element.count; ++i) {
      bool found = false;
      while (cursor.next())
        if (!trim(cursor.line()).empty()) {
          found = true;
          break;
        }
      auto fail = [&](const std::string& message) {
        throw InputError(builder.file(), cursor.lineNumber(), message,
                         std::string(trim(cursor.line())));
      };
      if (!found)
        fail("file ends after " + std::to_string(i) + " of " + std::to_string(element.count) + " " +
             element.name + " elements (truncated)");
      if (!isVertex && !isFace) continue;
      const std::string_view line = trim(cursor.line());
      const std::size_t n = surface::splitBlanks(line, tokens.data(), tokens.size());
      std::size_t at = 0;
      std::array<double, 3> xyz{};
      std::int64_t indices[4] = {0, 0, 0, 0};
      std::int64_t corners = 0;
      std::int64_t part = 0;
      bool hasPart = false;
      auto token = [&](const char* what) {
        if (at >= n || at >= tokens.size())
          fail(std::string("missing ") + what + " in " + element.name + " " + std::to_string(i));
        return tokens[at++];
      };
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        const Role role = element.roles[p];
        if (property.list) {
          std::int64_t count = 0;
          const std::string_view text = token("list count");
          if (!parseInt(text, count) || count < 0)
            fail("malformed list count " + surface::quoted(text) + " in " + element.name + " " +
                 std::to_string(i));
          if (role == Role::Indices) {
            corners = count;
            if (count > 4 || count < 3) {
              addFace(builder, indices, count, cursor.lineNumber(), static_cast<std::size_t>(i), 0,
                      line);
            }
            for (std::int64_t k = 0; k < count; ++k) {
              const std::string_view value = token("vertex index");
              if (!parseInt(value, indices[k]))
                fail("malformed vertex index " + surface::quoted(value) + " in face " +
                     std::to_string(i));
            }
          } else {
            for (std::int64_t k = 0; k < count; ++k) token("list item");
          }
          continue;
        }
        const std::string_view value = token(property.name.c_str());
        if (role == Role::X || role == Role::Y || role == Role::Z) {
          const auto axis =
              static_cast<std::size_t>(static_cast<int>(role) - static_cast<int>(Role::X));
          if (!parseReal(value, xyz[axis]) || !std::isfinite(xyz[axis]))
            fail("malformed " + property.name + " coordinate " + surface::quoted(value) +
                 " in vertex " + std::to_string(i));
        } else if (role == Role::Part) {
          double real = 0;
          if (!parseInt(value, part)) {
            if (!parseReal(value, real) || real != std::floor(real))
              fail("malformed part " + surface::quoted(value) + " in face " + std::to_string(i));
            part = static_cast<std::int64_t>(real);
          }
          hasPart = true;
        } else {
          double ignored = 0;
          if (!parseReal(value, ignored))
            fail("malformed " + property.name + " value " + surface::quoted(value) + " in " +
                 element.name + " " + std::to_string(i));
        }
      }
      if (at < n)
        fail("more values than the header declares in " + element.name + " " + std::to_string(i));
      if (isVertex) {
        builder.addVertex(xyz, cursor.lineNumber());
      } else {
        parts.select(hasPart, part);
        addFace(builder, indices, corners, cursor.lineNumber(), static_cast<std::size_t>(i), 0,
                line);
      }
    }
  }
}

void readBinaryBody(const Header& header, const std::string& content, MeshBuilder& builder,
                    PartSelector& parts) {
  const bool little = header.encoding == Encoding::Little;
  const char* data = content.data();
  const std::size_t size = content.size();
  std::size_t pos = header.bodyOffset;
  // Binary records have no line: vertex indices are checked here, where their offset is known.
  std::int64_t vertexTotal = 0;
  for (const Element& element : header.elements)
    if (element.name == "vertex")  // saturating: counts come from the file
      vertexTotal +=
          std::min(element.count, std::numeric_limits<std::int64_t>::max() - vertexTotal);
  for (const Element& element : header.elements) {
    const bool isVertex = element.name == "vertex";
    const bool isFace = element.name == "face";
    if (element.properties.empty()) continue;  // its records hold no bytes, whatever its count
    for (std::int64_t i = 0; i < element.count; ++i) {
      auto need = [&](std::uint64_t bytes) {
        if (bytes > size - pos)
          throw InputError(builder.file(), 0,
                           "file ends at byte offset " + std::to_string(size) + " while reading " +
                               element.name + " " + std::to_string(i) + " of " +
                               std::to_string(element.count) + " (truncated)");
      };
      std::array<double, 3> xyz{};
      std::int64_t indices[4] = {0, 0, 0, 0};
      std::int64_t corners = 0;
      std::int64_t part = 0;
      bool hasPart = false;
      const std::size_t start = pos;
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        const Role role = element.roles[p];
        const std::size_t itemSize = sizeOf(property.type);
        if (property.list) {
          need(sizeOf(property.countType));
          const std::int64_t count = readInteger(property.countType, data + pos, little);
          pos += sizeOf(property.countType);
          if (count < 0)
            throw InputError(builder.file(), 0,
                             "negative list count in " + element.name + " " + std::to_string(i) +
                                 " (byte offset " + std::to_string(pos) + ")");
          need(static_cast<std::uint64_t>(count) * itemSize);
          if (role == Role::Indices) {
            corners = count;
            if (count > 4 || count < 3)
              addFace(builder, indices, count, 0, static_cast<std::size_t>(i), start, {});
            for (std::int64_t k = 0; k < count; ++k) {
              const std::size_t at = pos + static_cast<std::size_t>(k) * itemSize;
              indices[k] = readInteger(property.type, data + at, little);
              if (isFace && (indices[k] < 0 || indices[k] >= vertexTotal))
                throw InputError(
                    builder.file(), 0,
                    "face " + std::to_string(i) + " names vertex " + std::to_string(indices[k]) +
                        ", but the file defines only " + std::to_string(vertexTotal) +
                        " vertices (numbered from 0; byte offset " + std::to_string(at) + ")");
            }
          }
          pos += static_cast<std::size_t>(count) * itemSize;
          continue;
        }
        need(itemSize);
        if (role == Role::X || role == Role::Y || role == Role::Z) {
          const auto axis =
              static_cast<std::size_t>(static_cast<int>(role) - static_cast<int>(Role::X));
          xyz[axis] = readReal(property.type, data + pos, little);
          if (!std::isfinite(xyz[axis]))
            throw InputError(builder.file(), 0,
                             property.name + " coordinate of vertex " + std::to_string(i) +
                                 " is not a finite number (byte offset " + std::to_string(pos) +
                                 ")");
        } else if (role == Role::Part) {
          part = isIntegral(property.type)
                     ? readInteger(property.type, data + pos, little)
                     : static_cast<std::int64_t>(readReal(property.type, data + pos, little));
          hasPart = true;
        }
        pos += itemSize;
      }
      if (isVertex) {
        builder.addVertex(xyz, 0);
      } else if (isFace) {
        parts.select(hasPart, part);
        addFace(builder, indices, corners, 0, static_cast<std::size_t>(i), start, {});
      }
    }
  }
}

}  // namespace

FeModel readPly(const std::filesystem::path& path, Warnings& warnings) {
  const std::string content = loadFile(path);
  const std::string file = path.string();
  if (trim(content).find_first_not_of(" \t\r\n") == std::string_view::npos)
    throw InputError(file, 0, "empty file");
  MeshBuilder builder(DeckFormat::Ply, path, 0);
  LineCursor cursor(content);
  const Header header = readHeader(cursor, file, builder);
  std::size_t vertices = 0;
  std::size_t faces = 0;
  for (const Element& element : header.elements) {
    if (element.name == "vertex") vertices += static_cast<std::size_t>(element.count);
    if (element.name == "face") faces += static_cast<std::size_t>(element.count);
  }
  builder.reserve(std::min<std::size_t>(vertices, content.size() / 3),
                  std::min<std::size_t>(faces, content.size() / 4));
  PartSelector parts(builder, path.stem().string());
  if (header.encoding == Encoding::Ascii) {
    if (content.find('\0', header.bodyOffset) != std::string::npos)
      requireText(std::string_view(content), path);
    readAsciiBody(header, cursor, builder, parts);
  } else {
    readBinaryBody(header, content, builder, parts);
  }
  return builder.finish(warnings);
}

void writePly(const FeModel& model, std::string& out, bool binary, Warnings& warnings) {
  const surface::NodeIndexer indexer(model);
  surface::warnExtrasLost(model, "PLY", warnings);
  if (model.nodes.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw std::length_error("PLY vertex indices are 32-bit: too many nodes");
  // Part IDs go into an int property; IDs beyond 32 bits are written as ordinals 1..n.
  bool fits = true;
  for (const Part& part : model.parts)
    fits = fits && part.id >= std::numeric_limits<std::int32_t>::min() &&
           part.id <= std::numeric_limits<std::int32_t>::max();
  for (const Shell& shell : model.shells)
    fits = fits && shell.part >= std::numeric_limits<std::int32_t>::min() &&
           shell.part <= std::numeric_limits<std::int32_t>::max();
  std::unordered_map<Id, std::int32_t> partValue;
  std::vector<std::pair<std::int32_t, std::string>> comments;
  auto value = [&](Id id) {
    const auto it = partValue.find(id);
    if (it != partValue.end()) return it->second;
    const auto v =
        fits ? static_cast<std::int32_t>(id) : static_cast<std::int32_t>(partValue.size() + 1);
    partValue.emplace(id, v);
    std::string name = surface::partLabel(model, id);
    for (char& c : name)
      if (c == '\n' || c == '\r') c = ' ';
    comments.emplace_back(v, name);
    return v;
  };
  for (const Part& part : model.parts) value(part.id);
  for (const Shell& shell : model.shells) value(shell.part);
  if (!fits)
    warnings.push_back(
        "part IDs beyond 32 bits are written to the PLY 'part' property as "
        "ordinals 1.." +
        std::to_string(partValue.size()));

  out.reserve(out.size() + 512 + model.nodes.size() * (binary ? 24 : 60) +
              model.shells.size() * (binary ? 21 : 40));
  out += "ply\nformat ";
  out += binary ? "binary_little_endian" : "ascii";
  out += " 1.0\ncomment written by voxremesh " VOXREMESH_VERSION "\n";
  for (const auto& [v, name] : comments) {
    out += kPartComment;
    surface::appendInt(out, v);
    out += ' ' + name + '\n';
  }
  out += "element vertex ";
  surface::appendInt(out, static_cast<std::int64_t>(model.nodes.size()));
  out += "\nproperty double x\nproperty double y\nproperty double z\nelement face ";
  surface::appendInt(out, static_cast<std::int64_t>(model.shells.size()));
  out += "\nproperty list uchar int vertex_indices\nproperty int part\nend_header\n";
  if (binary) {
    for (const Node& node : model.nodes)
      for (double v : node.xyz) surface::appendLittleEndian(out, v);
    for (const Shell& shell : model.shells) {
      surface::appendLittleEndian(out, static_cast<std::uint8_t>(shell.nodeCount));
      for (int k = 0; k < shell.nodeCount; ++k)
        surface::appendLittleEndian(out, static_cast<std::int32_t>(indexer.index(
                                             shell.nodes[static_cast<std::size_t>(k)], shell.id)));
      surface::appendLittleEndian(out, partValue.at(shell.part));
    }
    return;
  }
  for (const Node& node : model.nodes) {
    surface::appendXyz(out, node.xyz);
    out += '\n';
  }
  for (const Shell& shell : model.shells) {
    out += shell.nodeCount == 3 ? '3' : '4';
    indexer.appendCorners(out, shell);
    out += ' ';
    surface::appendInt(out, partValue.at(shell.part));
    out += '\n';
  }
}

}  // namespace voxremesh::io
