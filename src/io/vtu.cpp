// VTK XML unstructured grid (.vtu, version 0.1, ascii data) for looking at a model and its
// per-element / per-node values in ParaView.
#include <stdexcept>
#include <string>
#include <vector>

#include "io/formats.h"
#include "io/surface_builder.h"
#include "io/text_scan.h"

namespace voxremesh::io {

namespace {

constexpr int kVtkTriangle = 5;
constexpr int kVtkQuad = 9;
constexpr std::size_t kValuesPerLine = 12;

/// Escapes text for an XML attribute value.
std::string xmlAttribute(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\n':
        escaped += "&#10;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

void openArray(std::string& out, const char* type, const std::string& name, int components = 1) {
  out += "        <DataArray type=\"";
  out += type;
  out += "\" Name=\"" + xmlAttribute(name) + "\"";
  if (components != 1) out += " NumberOfComponents=\"" + std::to_string(components) + "\"";
  out += " format=\"ascii\">\n";
}

void closeArray(std::string& out) {
  out += "        </DataArray>\n";
}

/// Writes values, kValuesPerLine to a line; `append(out, i)` appends value i.
template <typename Append>
void writeValues(std::string& out, std::size_t count, Append append) {
  for (std::size_t i = 0; i < count; ++i) {
    out += (i % kValuesPerLine == 0) ? "          " : " ";
    append(out, i);
    if (i % kValuesPerLine == kValuesPerLine - 1 || i + 1 == count) out += '\n';
  }
}

void writeReals(std::string& out, const std::vector<double>& values) {
  writeValues(out, values.size(),
              [&](std::string& o, std::size_t i) { appendShortest(o, values[i]); });
}

void checkSizes(const std::vector<FieldData>& fields, std::size_t expected, const char* what) {
  for (const FieldData& field : fields)
    if (field.values.size() != expected)
      throw std::invalid_argument(std::string(what) + " field '" + field.name + "' has " +
                                  std::to_string(field.values.size()) + " values, expected " +
                                  std::to_string(expected));
}

}  // namespace

void writeVtuContent(const FeModel& model, std::string& out, const std::vector<FieldData>& cellData,
                     const std::vector<FieldData>& pointData) {
  checkSizes(cellData, model.shells.size(), "cell");
  checkSizes(pointData, model.nodes.size(), "point");
  const surface::NodeIndexer indexer(model);
  const std::size_t points = model.nodes.size();
  const std::size_t cells = model.shells.size();
  out.reserve(out.size() + 1024 + points * (60 + 24 * pointData.size()) +
              cells * (60 + 24 * cellData.size()));

  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(points) + "\" NumberOfCells=\"" +
         std::to_string(cells) + "\">\n";

  out += "      <PointData Scalars=\"node_id\">\n";
  openArray(out, "Int64", "node_id");
  writeValues(out, points,
              [&](std::string& o, std::size_t i) { surface::appendInt(o, model.nodes[i].id); });
  closeArray(out);
  for (const FieldData& field : pointData) {
    openArray(out, "Float64", field.name);
    writeReals(out, field.values);
    closeArray(out);
  }
  out += "      </PointData>\n";

  out += "      <CellData Scalars=\"part_id\">\n";
  openArray(out, "Int64", "part_id");
  writeValues(out, cells,
              [&](std::string& o, std::size_t i) { surface::appendInt(o, model.shells[i].part); });
  closeArray(out);
  openArray(out, "Int64", "element_id");
  writeValues(out, cells,
              [&](std::string& o, std::size_t i) { surface::appendInt(o, model.shells[i].id); });
  closeArray(out);
  for (const FieldData& field : cellData) {
    openArray(out, "Float64", field.name);
    writeReals(out, field.values);
    closeArray(out);
  }
  out += "      </CellData>\n";

  out += "      <Points>\n";
  openArray(out, "Float64", "Points", 3);
  for (const Node& node : model.nodes) {
    out += "          ";
    surface::appendXyz(out, node.xyz);
    out += '\n';
  }
  closeArray(out);
  out += "      </Points>\n";

  out += "      <Cells>\n";
  openArray(out, "Int64", "connectivity");
  for (const Shell& shell : model.shells) {
    out += "          ";
    for (int k = 0; k < shell.nodeCount; ++k) {
      if (k > 0) out += ' ';
      surface::appendInt(out, static_cast<std::int64_t>(indexer.index(
                                  shell.nodes[static_cast<std::size_t>(k)], shell.id)));
    }
    out += '\n';
  }
  closeArray(out);
  openArray(out, "Int64", "offsets");
  std::int64_t offset = 0;
  writeValues(out, cells, [&](std::string& o, std::size_t i) {
    offset += model.shells[i].nodeCount;
    surface::appendInt(o, offset);
  });
  closeArray(out);
  openArray(out, "UInt8", "types");
  writeValues(out, cells, [&](std::string& o, std::size_t i) {
    surface::appendInt(o, model.shells[i].nodeCount == 3 ? kVtkTriangle : kVtkQuad);
  });
  closeArray(out);
  out += "      </Cells>\n";
  out += "    </Piece>\n";
  out += "  </UnstructuredGrid>\n";
  out += "</VTKFile>\n";
}

}  // namespace voxremesh::io
