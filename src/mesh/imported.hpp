// Parts read from Gmsh mesh files (`mesh: {file, volume}`; docs/input.md, "Mesh parts").
//
// The hexahedra of one physical volume become a part with nodes of its own: two volumes
// of one file that share nodes are two bodies, joined only through `contact`, as every
// two parts are. Gmsh numbers the 20-node hexahedron's mid-edge nodes in its own edge
// order; they are put in the VTK order of mesh.hpp. With `reorder` (the default) the
// elements are numbered along a Hilbert curve through their centroids and the nodes in
// order of first use, so that neighbours lie near each other in memory whatever order
// the mesher wrote. A physical surface's quadrilaterals that are boundary faces of the
// volume become the face <part>.<surface>, oriented outward from the volume whatever
// their orientation in the file; <part>.surface is the whole boundary.
#pragma once

#include <array>
#include <string>

#include "common/errors.hpp"
#include "input/gmsh_file.hpp"
#include "input/options.hpp"
#include "mesh/mesh.hpp"

namespace exdyn::mesh {

// gmsh_hex20_node[v]: the Gmsh node of VTK node v of a 20-node hexahedron. The corners
// agree; Gmsh orders the edges 0-1, 0-3, 0-4, 1-2, 1-5, 2-3, 2-6, 3-7, 4-5, 4-7, 5-6, 6-7,
// VTK 0-1, 1-2, 2-3, 3-0, 4-5, 5-6, 6-7, 7-4, 0-4, 1-5, 2-6, 3-7.
inline constexpr std::array<int, 20> gmsh_hex20_node{0,  1, 2,  3,  4,  5,  6,  7,  8,  11,
                                                     13, 9, 16, 18, 19, 17, 10, 12, 14, 15};

// Appends the physical volume options.mesh.volume of `file` to the mesh as part
// `part_index`, with its faces. Throws InputError(where, key_path, ...) naming the file
// and, where it is one element's fault, the element's Gmsh tag: an unknown volume; no
// hexahedra; tetrahedra, prisms, pyramids or 27-node hexahedra (each type with its
// count); 8- and 20-node hexahedra mixed or not those of the formulation; an element
// whose node the file lacks, that repeats a node, or whose corner Jacobian is not
// positive (inverted or degenerate); a face shared by more than two elements; no face
// on the boundary (every face shared by two elements).
void add_imported_part(Mesh& mesh, const input::PartOptions& options, int part_index,
                       const input::GmshMesh& file, const SourceLocation& where, const std::string& key_path);

// The Hilbert-curve index of a point of the unit cube [0, 1]^3, 21 bits per axis.
std::uint64_t hilbert_index(const std::array<double, 3>& unit_point);

}  // namespace exdyn::mesh
