#include "output/xdmf_text.hpp"

#include <array>
#include <charconv>

namespace exdyn::output::xdmf {

std::string format_time(double time) {
  std::array<char, 32> text{};
  const auto result =
      std::to_chars(text.data(), text.data() + text.size(), time, std::chars_format::general, 17);
  return std::string(text.data(), result.ptr);
}

std::string escape(std::string_view text) {
  std::string escaped;
  escaped.reserve(text.size());
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
      case '\'':
        escaped += "&apos;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

std::string grid(const Grid& g, double time, const std::string& group) {
  const std::string nodes = std::to_string(g.node_count);
  const std::string elements = std::to_string(g.element_count);
  auto data_item = [&](const std::string& dims, const char* number_type, const std::string& path) {
    return "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + number_type +
           "\" Precision=\"8\" Format=\"HDF\">" + g.h5_reference + ":" + path + "</DataItem>\n";
  };
  std::string xml;
  xml.reserve(1600);
  xml += "      <Grid Name=\"step_" + group + "\" GridType=\"Uniform\">\n";
  xml += "        <Time Value=\"" + format_time(time) + "\"/>\n";
  if (g.mixed) {
    xml += "        <Topology TopologyType=\"Mixed\" NumberOfElements=\"" + elements + "\">\n";
    xml += "          " + data_item(std::to_string(g.mixed_topology_size), "Int", "/mesh/mixed_topology");
  } else {
    const std::string nodes_per = std::to_string(g.nodes_per_element);
    xml += std::string("        <Topology TopologyType=\"") +
           (g.nodes_per_element == 20 ? "Hexahedron_20" : "Hexahedron") + "\" NumberOfElements=\"" +
           elements + "\" NodesPerElement=\"" + nodes_per + "\">\n";
    xml += "          " + data_item(elements + " " + nodes_per, "Int", "/mesh/connectivity");
  }
  xml += "        </Topology>\n";
  xml += "        <Geometry GeometryType=\"XYZ\">\n";
  xml += "          " + data_item(nodes + " 3", "Float", "/mesh/coordinates");
  xml += "        </Geometry>\n";
  for (const Attribute& a : g.attributes) {
    std::string dims = a.on_nodes ? nodes : elements;
    if (a.components > 1) dims += " " + std::to_string(a.components);
    xml += "        <Attribute Name=\"" + a.name + "\" AttributeType=\"" + a.type + "\" Center=\"" +
           (a.on_nodes ? "Node" : "Cell") + "\">\n";
    xml += "          " + data_item(dims, "Float", "/steps/" + group + "/" + a.name);
    xml += "        </Attribute>\n";
  }
  xml += "      </Grid>\n";
  return xml;
}

}  // namespace exdyn::output::xdmf
