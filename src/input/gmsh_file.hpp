// A Gmsh mesh file as the Gmsh library returns it (docs/input.md, "Mesh parts"): the
// nodes, and the elements of each physical volume and physical surface by Gmsh element
// type, in Gmsh's node order. mesh/imported.hpp turns one volume into a part.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "common/errors.hpp"

namespace exdyn::input {

// Gmsh element type numbers (Gmsh's "MSH file format" documentation, element types).
namespace gmsh_type {
inline constexpr int quad4 = 3;
inline constexpr int hex8 = 5;
inline constexpr int quad8 = 16;
inline constexpr int hex20 = 17;
}  // namespace gmsh_type

// The elements of one Gmsh type in a physical group.
struct GmshElements {
  int type = 0;       // Gmsh element type number
  std::string name;   // Gmsh's name of the type, e.g. "Hexahedron 20"
  int dimension = 0;  // 0 to 3
  int nodes_per_element = 0;
  std::vector<std::size_t> tags;   // element tags
  std::vector<std::size_t> nodes;  // nodes_per_element node tags per element, Gmsh order
};

// A physical group: its name (the tag as text when the file gives it none) and its
// elements, one entry per type.
struct GmshGroup {
  std::string name;
  std::vector<GmshElements> elements;
};

struct GmshMesh {
  std::string file;                    // the path it was read from
  std::vector<std::size_t> node_tags;  // every node of the file
  std::vector<double> coordinates;     // x, y, z of each node of node_tags, m
  std::vector<GmshGroup> volumes;      // physical groups of dimension 3
  std::vector<GmshGroup> surfaces;     // physical groups of dimension 2
};

// Reads `file` through the Gmsh library. A missing or unreadable file, one that is not a
// Gmsh mesh (its first line is not $MeshFormat, or $NOD for version 1) or one the
// library rejects throws InputError(where, key_path, message naming the file).
GmshMesh read_gmsh(const std::string& file, const SourceLocation& where, const std::string& key_path);

}  // namespace exdyn::input
