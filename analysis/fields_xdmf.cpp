#include "analysis/fields_xdmf.hpp"

#include <cmath>
#include <numbers>
#include <ostream>

#include "analysis/atomic_file.hpp"
#include "analysis/field_writer.hpp"
#include "analysis/xml_escape.hpp"

namespace granjet::analysis {
namespace {

// `item` n times, joined by `separator`.
std::string repeated(const std::string& item, const char* separator, std::size_t n) {
  std::string out = item;
  for (std::size_t k = 1; k < n; ++k) out.append(separator).append(item);
  return out;
}

}  // namespace

FieldCells field_cells(const EnsembleResult& result) {
  const MeshEdges& edges = result.edges;
  FieldCells cells;
  cells.sectors = result.dimension == 3 ? kRingSectors : 1;
  cells.layers = edges.height.size() - 1;
  cells.lateral = edges.lateral.size() - 1;
  for (std::size_t s = 0; s <= cells.sectors; ++s) {
    const double angle =
        2.0 * std::numbers::pi * static_cast<double>(s % cells.sectors) / cells.sectors;
    for (double h : edges.height) {
      const double axial = edges.height_origin + h;
      for (double w : edges.lateral) {
        if (result.dimension == 3)
          cells.corners.insert(cells.corners.end(),
                               {w * std::cos(angle), w * std::sin(angle), axial});
        else
          cells.corners.insert(cells.corners.end(), {axial, w, s == 0 ? -0.5 : 0.5});
      }
    }
  }
  return cells;
}

void write_fields_xdmf(const std::filesystem::path& xmf, const std::string& h5_name,
                       const EnsembleResult& result) {
  const FieldCells cells = field_cells(result);
  const std::string file = xml_escape(h5_name);
  const std::string bins = std::to_string(cells.layers) + " " + std::to_string(cells.lateral);
  const std::string corners = std::to_string(cells.sectors + 1) + " " +
                              std::to_string(cells.layers + 1) + " " +
                              std::to_string(cells.lateral + 1);
  const char* floats = "NumberType=\"Float\" Precision=\"8\" Format=\"HDF\"";
  write_file_atomically(xmf, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n"
        << "  <Grid Name=\"fields\" GridType=\"Uniform\">\n"
        << "   <Topology TopologyType=\"3DSMesh\" Dimensions=\"" << corners << "\"/>\n"
        << "   <Geometry GeometryType=\"XYZ\">\n"
        << "    <DataItem Dimensions=\"" << corners << " 3\" " << floats << ">" << file
        << ":/fields/mesh/points</DataItem>\n"
        << "   </Geometry>\n";
    // A cell takes its bin's mean, repeated over the sectors, in each reader's own spelling. The
    // Xdmf3 readers evaluate a <Function> element's Expression as they load the file ('|'
    // joins; Function is what a re-read would evaluate); a Function DataItem they would leave
    // unread and then drop, its type unknown. The Xdmf2 reader ignores that element and
    // evaluates the Function DataItem (';' joins), whose result must have the grid's cell shape
    // (sectors, layers, lateral) to be taken whole.
    for (const std::string& name : result.fields.names()) {
      const std::string mean = file + ":/fields/" + field_path(name) + "/mean";
      out << "   <Attribute Name=\"" << name << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
          << "    <Function ItemType=\"Function\" Function=\"" << repeated("$0", "|", cells.sectors)
          << "\" Expression=\"" << repeated("A", "|", cells.sectors) << "\" VariableNames=\"A\">\n"
          << "     <DataItem Dimensions=\"" << bins << "\" " << floats << ">" << mean
          << "</DataItem>\n"
          << "    </Function>\n"
          << "    <DataItem ItemType=\"Function\" Function=\"" << repeated("$0", ";", cells.sectors)
          << "\" Dimensions=\"" << cells.sectors << " " << bins << "\">\n"
          << "     <DataItem Dimensions=\"1 " << bins << "\" " << floats << ">" << mean
          << "</DataItem>\n"
          << "    </DataItem>\n"
          << "   </Attribute>\n";
    }
    out << "  </Grid>\n </Domain>\n</Xdmf>\n";
  });
}

}  // namespace granjet::analysis
