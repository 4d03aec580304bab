#include "analysis/xdmf_sidecar.hpp"

#include <charconv>
#include <ostream>
#include <string>

#include "analysis/atomic_file.hpp"
#include "analysis/xml_escape.hpp"

namespace granjet::analysis {
namespace {

// The shortest text that reads back as the same double, so frame times match the .h5 exactly.
std::string exact(double value) {
  char text[32];
  return {text, std::to_chars(text, text + sizeof text, value).ptr};
}

std::string indent(int level) { return std::string(2 * static_cast<std::size_t>(level), ' '); }

// A [frames][rows] dataset of the .h5, or [frames][rows][width] if width > 0.
struct Dataset {
  std::string path;  // e.g. "/particles/all/position/value"
  std::size_t rows;
  int width;
  bool integer;
};

// Each frame is a uniform grid of the grains (Polyvertex), or, when the file holds contacts, a
// spatial collection of that grid and one of the contacts (Polyline), in a temporal collection.
class SidecarWriter {
 public:
  SidecarWriter(std::ostream& out, const std::string& h5_name, const XdmfLayout& layout,
                std::size_t frames)
      : out_(out), h5_(xml_escape(h5_name)), layout_(layout), frames_(frames) {}

  void frame(std::size_t k, const XdmfFrame& frame) {
    // A frame without grains has nothing to draw (and no contacts), so it gets no grid.
    if (frame.grains == 0) return;
    const std::string time = std::string("<Time Value=\"").append(exact(frame.time)) + "\"/>";
    if (layout_.contact_rows == 0) {
      grains(3, k, frame.grains, time);
      return;
    }
    out_ << indent(3) << "<Grid Name=\"frame " << k
         << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
         << indent(4) << time << '\n';
    grains(4, k, frame.grains, "");
    if (frame.contacts > 0) contacts(4, k, frame.contacts);
    out_ << indent(3) << "</Grid>\n";
  }

 private:
  // The present grains as vertices over the frame's full position row: absent rows hold NaN,
  // but no cell refers to them, so they are neither drawn nor counted in the bounds.
  void grains(int level, std::size_t k, std::size_t count, const std::string& time) {
    out_ << indent(level) << "<Grid Name=\"grains\" GridType=\"Uniform\">\n";
    if (!time.empty()) out_ << indent(level + 1) << time << '\n';
    out_ << indent(level + 1) << "<Topology TopologyType=\"Polyvertex\" NumberOfElements=\""
         << count << "\" NodesPerElement=\"1\">\n";
    slab(level + 2, grain("present", 0, true), k, count);
    out_ << indent(level + 1) << "</Topology>\n";
    geometry(level + 1, k);
    const int d = layout_.dimension;
    const std::size_t rows = layout_.rows;
    attribute(level + 1, "velocity", "Node", grain("velocity", d, false), k, rows);
    attribute(level + 1, "radius", "Node", grain("radius", 0, false), k, rows);
    attribute(level + 1, "id", "Node", grain("id", 0, true), k, rows);
    if (layout_.omega)
      attribute(level + 1, "omega", "Node", grain("omega", d == 3 ? 3 : 0, false), k, rows);
    if (layout_.force) attribute(level + 1, "force", "Node", grain("force", d, false), k, rows);
    out_ << indent(level) << "</Grid>\n";
  }

  // Touching pairs as lines between their grains' rows of the same position row.
  void contacts(int level, std::size_t k, std::size_t count) {
    out_ << indent(level) << "<Grid Name=\"contacts\" GridType=\"Uniform\">\n"
         << indent(level + 1) << "<Topology TopologyType=\"Polyline\" NumberOfElements=\"" << count
         << "\" NodesPerElement=\"2\">\n";
    slab(level + 2, {"/connectivity/contacts/value", layout_.contact_rows, 2, true}, k, count);
    out_ << indent(level + 1) << "</Topology>\n";
    geometry(level + 1, k);
    const int d = layout_.dimension;
    attribute(level + 1, "normal_force", "Cell", contact("normal_force", d), k, count);
    attribute(level + 1, "tangential_force", "Cell", contact("tangential_force", d), k, count);
    attribute(level + 1, "overlap", "Cell", contact("overlap", 0), k, count);
    out_ << indent(level) << "</Grid>\n";
  }

  void geometry(int level, std::size_t k) {
    out_ << indent(level) << "<Geometry GeometryType=\"" << (layout_.dimension == 3 ? "XYZ" : "XY")
         << "\">\n";
    slab(level + 1, grain("position", layout_.dimension, false), k, layout_.rows);
    out_ << indent(level) << "</Geometry>\n";
  }

  void attribute(int level, const char* name, const char* center, const Dataset& data,
                 std::size_t k, std::size_t count) {
    out_ << indent(level) << "<Attribute Name=\"" << name << "\" AttributeType=\""
         << (data.width > 0 ? "Vector" : "Scalar") << "\" Center=\"" << center << "\">\n";
    slab(level + 1, data, k, count);
    out_ << indent(level) << "</Attribute>\n";
  }

  // Rows 0..count-1 of frame k. ParaView's two XDMF libraries read no common spelling of this
  // selection: Xdmf3 (Xdmf3 Reader S/T) asks a HyperSlab item for its number type before
  // reading it and so drops hyperslab geometry and attributes ("Skipping unrecognized array type
  // [None]"); Xdmf2 (XDMF Reader) cannot parse Xdmf3's "file:/path|start:stride:count:space".
  // This item is read as each: Xdmf2 honours the version-1 attribute Type="HyperSlab" (Xdmf3
  // only reads ItemType) and reads the two child items, ignoring the text; Xdmf3 takes a plain
  // HDF item whose text is its own hyperslab.
  void slab(int level, const Dataset& data, std::size_t k, std::size_t count) {
    const bool vector = data.width > 0;
    // append(), not "literal" + string: GCC 12 reports a false -Wrestrict for the latter.
    const std::string tail = vector ? std::string(" ").append(std::to_string(data.width)) : "";
    const std::string start = std::to_string(k).append(vector ? " 0 0" : " 0");
    const char* stride = vector ? "1 1 1" : "1 1";
    const std::string counts = std::string("1 ").append(std::to_string(count)).append(tail);
    const std::string space =
        std::to_string(frames_).append(" ").append(std::to_string(data.rows)).append(tail);
    const std::string type = std::string(" NumberType=\"")
                                 .append(data.integer ? "Int" : "Float")
                                 .append("\" Precision=\"8\" Format=\"HDF\">");
    const std::string file = h5_ + ":" + data.path;
    out_ << indent(level) << "<DataItem Type=\"HyperSlab\" Dimensions=\"" << count << tail << '"'
         << type << file << '|' << start << ':' << stride << ':' << counts << ':' << space << '\n'
         << indent(level + 1) << "<DataItem Dimensions=\"3 " << (vector ? 3 : 2)
         << "\" Format=\"XML\">" << start << ' ' << stride << ' ' << counts << "</DataItem>\n"
         << indent(level + 1) << "<DataItem Dimensions=\"" << space << '"' << type << file
         << "</DataItem>\n"
         << indent(level) << "</DataItem>\n";
  }

  Dataset grain(const std::string& name, int width, bool integer) const {
    return {std::string("/particles/all/").append(name).append("/value"), layout_.rows, width,
            integer};
  }
  Dataset contact(const std::string& name, int width) const {
    return {std::string("/contacts/").append(name).append("/value"), layout_.contact_rows, width,
            false};
  }

  std::ostream& out_;
  std::string h5_;  // XML-escaped
  const XdmfLayout& layout_;
  std::size_t frames_;
};

}  // namespace

std::filesystem::path xdmf_path_for(const std::filesystem::path& h5_file) {
  std::filesystem::path xmf = h5_file;
  return xmf.replace_extension(".xmf");
}

void write_xdmf_sidecar(const std::filesystem::path& xmf, const std::string& h5_name,
                        const XdmfLayout& layout, std::span<const XdmfFrame> frames) {
  write_file_atomically(xmf, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\" ?>\n"
        << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
        << "<Xdmf Version=\"2.0\">\n"
        << indent(1) << "<Domain>\n"
        << indent(2)
        << "<Grid Name=\"frames\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    SidecarWriter writer(out, h5_name, layout, frames.size());
    for (std::size_t k = 0; k < frames.size(); ++k) writer.frame(k, frames[k]);
    out << indent(2) << "</Grid>\n" << indent(1) << "</Domain>\n</Xdmf>\n";
  });
}

}  // namespace granjet::analysis
