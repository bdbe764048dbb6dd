// Structured hexahedral meshes of box parts, and their named faces.
// Each part is its own body: parts share no nodes. Within a part, node (i,j,k)
// is first_node + i + (nx+1) (j + (ny+1) k) and element (i,j,k) is
// first_element + i + nx (j + ny k). Elements use the VTK hexahedron order.
// A part with a perturbation (parts[i].perturbation) has its grid points moved at
// random inside the box, each by at most fraction h, faces kept plane
// (mesh.cpp states the rule); its topology and numbering are those of the grid.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "common/nodal_vectors.hpp"
#include "input/options.hpp"

namespace exdyn::mesh {

struct PartRange {
  std::uint32_t first_node = 0;
  std::uint32_t node_count = 0;
  std::uint32_t first_element = 0;
  std::uint32_t element_count = 0;
  std::array<int, 3> elements{};  // nx, ny, nz
};

struct Mesh {
  NodalVectors x_ref;                       // reference coordinates, m
  std::vector<std::uint32_t> connectivity;  // 8 node ids per element
  std::vector<std::int32_t> element_part;   // part index of each element
  std::vector<PartRange> parts;             // in deck order

  std::size_t node_count() const { return x_ref.size(); }
  std::size_t element_count() const { return element_part.size(); }
};

// A named face of a part: its nodes and its quadrilaterals, each ordered
// counter-clockwise seen from outside, so (y1 - y0) x (y3 - y0) points out of the body.
struct Face {
  std::vector<std::uint32_t> nodes;
  std::vector<std::array<std::uint32_t, 4>> quads;
};

// Builds every part of the deck (checks the node count fits 32-bit indices, and that
// a perturbed part has no element with a non-positive corner Jacobian).
Mesh build_mesh(const input::Deck& deck);

// The nodes and outward-oriented quadrilaterals of one face of a part.
Face face_of(const Mesh& mesh, int part, input::BoxSide side);

}  // namespace exdyn::mesh
