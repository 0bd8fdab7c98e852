#include "common/io/xdmf_writer.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "common/io/exact_number.hpp"

namespace tankfsi {

namespace {

/// Text for XML attribute values and element content.
std::string xml_escaped(const std::string& text) {
  std::string escaped;
  escaped.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      case '\'': escaped += "&apos;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

std::string dimensions_text(const std::vector<std::int64_t>& dimensions) {
  std::string text;
  for (const auto d : dimensions) {
    if (!text.empty()) text += ' ';
    text += std::to_string(d);
  }
  return text;
}

void write_data_item(std::ostream& out, const std::string& indent, const std::string& h5_file_name,
                     const XdmfDataItem& item) {
  const char* number_type = item.number == XdmfNumber::float64 ? "Float" : "Int";
  out << indent << "<DataItem Dimensions=\"" << dimensions_text(item.dimensions) << "\" NumberType=\""
      << number_type << "\" Precision=\"8\" Format=\"HDF\">" << xml_escaped(h5_file_name + ":" + item.dataset)
      << "</DataItem>\n";
}

std::string attribute_type(const XdmfAttribute& attribute) {
  const auto& dims = attribute.data.dimensions;
  if (dims.size() == 1) return "Scalar";
  if (dims.size() == 2 && dims[1] == 3) return "Vector";
  throw std::invalid_argument("XDMF attribute '" + attribute.name + "' has dimensions '" + dimensions_text(dims) +
                              "': only n (Scalar) and n 3 (Vector) are written");
}

void write_topology(std::ostream& out, const std::string& h5_file_name, const XdmfGrid& grid) {
  const auto& topology = grid.topology;
  if (topology.type == XdmfTopologyType::polyvertex) {
    out << "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << topology.elements
        << "\" NodesPerElement=\"1\"/>\n";
    return;
  }
  if (!topology.connectivity)
    throw std::invalid_argument("XDMF grid '" + grid.name + "': a Mixed topology needs its connectivity");
  out << "      <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << topology.elements << "\">\n";
  write_data_item(out, "        ", h5_file_name, *topology.connectivity);
  out << "      </Topology>\n";
}

void write_grid(std::ostream& out, const std::string& h5_file_name, const XdmfGrid& grid) {
  out << "    <Grid Name=\"" << xml_escaped(grid.name) << "\" GridType=\"Uniform\">\n";
  out << "      <Time Value=\"" << exact_text(grid.time) << "\"/>\n";
  write_topology(out, h5_file_name, grid);
  out << "      <Geometry GeometryType=\"XYZ\">\n";
  write_data_item(out, "        ", h5_file_name, grid.geometry);
  out << "      </Geometry>\n";
  for (const auto& attribute : grid.attributes) {
    out << "      <Attribute Name=\"" << xml_escaped(attribute.name) << "\" AttributeType=\""
        << attribute_type(attribute) << "\" Center=\"" << (attribute.center == XdmfCenter::node ? "Node" : "Cell")
        << "\">\n";
    write_data_item(out, "        ", h5_file_name, attribute.data);
    out << "      </Attribute>\n";
  }
  out << "    </Grid>\n";
}

}  // namespace

std::string xdmf_document(const std::string& series_name, const std::string& h5_file_name,
                          std::span<const XdmfGrid> grids) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      << "<Xdmf Version=\"3.0\">\n"
      << "<Domain>\n"
      << "  <Grid Name=\"" << xml_escaped(series_name) << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& grid : grids) write_grid(out, h5_file_name, grid);
  out << "  </Grid>\n"
      << "</Domain>\n"
      << "</Xdmf>\n";
  return out.str();
}

void replace_file_atomically(const std::filesystem::path& target, const std::string& text) {
  auto temporary = target;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) throw std::runtime_error("could not write " + temporary.string());
  }
  std::error_code error;
  std::filesystem::rename(temporary, target, error);  // atomic within one file system (POSIX rename)
  if (error) throw std::runtime_error("could not rename " + temporary.string() + " to " + target.string() + ": " +
                                      error.message());
}

}  // namespace tankfsi
