#include "analysis/xdmf_sidecar.hpp"

#include <charconv>
#include <ostream>

#include "analysis/atomic_file.hpp"

namespace granjet::analysis {
namespace {

// What every hyperslab needs to know about the H5MD file it reads from.
struct Source {
  std::string h5_name;  // XML-escaped
  int dimension;
  std::size_t frames;
  std::size_t max_grains;
};

// File names may hold characters that XML reserves.
std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Selects rows 0..grains-1 of one frame from a [frames][max_grains] dataset, or from a
// [frames][max_grains][dimension] one if `vector`.
void write_hyperslab(std::ostream& out, const Source& source, const std::string& dataset,
                     const char* number_type, bool vector, std::size_t frame, std::size_t grains) {
  // append(), not "literal" + string: GCC 12 reports a false -Wrestrict for the latter.
  const std::string last_axis =
      vector ? std::string(" ").append(std::to_string(source.dimension)) : "";
  const char* more_axes = vector ? " 0" : "";
  const char* more_strides = vector ? " 1" : "";
  out << "          <DataItem ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"1 " << grains
      << last_axis << "\">\n"
      << "            <DataItem Dimensions=\"3 " << (vector ? 3 : 2) << "\" Format=\"XML\">"
      << frame << " 0" << more_axes << "  1 1" << more_strides << "  1 " << grains << last_axis
      << "</DataItem>\n"
      << "            <DataItem Dimensions=\"" << source.frames << ' ' << source.max_grains
      << last_axis << "\" NumberType=\"" << number_type << "\" Precision=\"8\" Format=\"HDF\">"
      << source.h5_name << ":/particles/all/" << dataset << "/value</DataItem>\n"
      << "          </DataItem>\n";
}

// The shortest text that reads back as the same double, so frame times match the .h5 exactly.
std::string exact(double value) {
  char text[32];
  return {text, std::to_chars(text, text + sizeof text, value).ptr};
}

void write_attribute(std::ostream& out, const Source& source, const std::string& name,
                     const char* number_type, bool vector, std::size_t frame, std::size_t grains) {
  out << "        <Attribute Name=\"" << name << "\" AttributeType=\""
      << (vector ? "Vector" : "Scalar") << "\" Center=\"Node\">\n";
  write_hyperslab(out, source, name, number_type, vector, frame, grains);
  out << "        </Attribute>\n";
}

}  // namespace

std::filesystem::path xdmf_path_for(const std::filesystem::path& h5_file) {
  std::filesystem::path xmf = h5_file;
  return xmf.replace_extension(".xmf");
}

void write_xdmf_sidecar(const std::filesystem::path& xmf, const std::string& h5_name, int dimension,
                        std::size_t max_grains, std::span<const XdmfFrame> frames) {
  const Source source{xml_escape(h5_name), dimension, frames.size(), max_grains};
  write_file_atomically(xmf, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\" ?>\n"
        << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
        << "<Xdmf Version=\"2.0\">\n"
        << "  <Domain>\n"
        << "    <Grid Name=\"grains\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const std::size_t n = frames[k].grains;
      // A frame without grains has nothing to draw, so it gets no grid.
      if (n == 0) continue;
      out << "      <Grid Name=\"frame " << k << "\" GridType=\"Uniform\">\n"
          << "        <Time Value=\"" << exact(frames[k].time) << "\"/>\n";
      // No connectivity DataItem: readers number the vertices 0..n-1 themselves, and ParaView's
      // Xdmf2 reader only caches (and would reuse) geometry for topologies that have one.
      out << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
          << "\" NodesPerElement=\"1\"/>\n"
          << "        <Geometry GeometryType=\"" << (dimension == 3 ? "XYZ" : "XY") << "\">\n";
      write_hyperslab(out, source, "position", "Float", true, k, n);
      out << "        </Geometry>\n";
      write_attribute(out, source, "velocity", "Float", true, k, n);
      write_attribute(out, source, "radius", "Float", false, k, n);
      write_attribute(out, source, "id", "Int", false, k, n);
      out << "      </Grid>\n";
    }
    out << "    </Grid>\n"
        << "  </Domain>\n"
        << "</Xdmf>\n";
  });
}

}  // namespace granjet::analysis
