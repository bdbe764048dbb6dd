// The XDMF 3 text of a result's index (../shared/spec/output.md): one temporal
// collection of uniform grids, one per written step, every array a reference into
// NAME.h5. ParaView's XDMF readers open it (../shared/tools/paraview/README.md).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace exdyn::output::xdmf {

inline constexpr std::string_view head =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
    "  <Domain>\n"
    "    <Grid Name=\"TimeSeries\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
inline constexpr std::string_view tail =
    "    </Grid>\n"
    "  </Domain>\n"
    "</Xdmf>\n";

// %.17g: the shortest form that round-trips every double, so distinct times stay
// distinct (ParaView merges equal times and shows an empty mesh).
std::string format_time(double time);

// The text with & < > " ' as XML entities.
std::string escape(std::string_view text);

// A field of a step: its dataset /steps/GROUP/NAME.
struct Attribute {
  std::string name;
  bool on_nodes = true;         // else on the elements
  int components = 1;           // 1: stored as (n,), else (n, components)
  const char* type = "Scalar";  // XDMF AttributeType
};

// What every step's grid shares: the mesh and the fields.
struct Grid {
  std::string h5_reference;  // "NAME.h5", relative to the .xmf's directory, XML-escaped
  std::size_t node_count = 0, element_count = 0;
  bool mixed = false;                   // 8- and 20-node elements: /mesh/mixed_topology
  std::size_t mixed_topology_size = 0;  // its length when mixed
  int nodes_per_element = 8;            // 8 or 20 when not mixed
  std::vector<Attribute> attributes;
};

// One step's <Grid> at `time` (s), its fields in /steps/`group`.
std::string grid(const Grid& grid, double time, const std::string& group);

}  // namespace exdyn::output::xdmf
