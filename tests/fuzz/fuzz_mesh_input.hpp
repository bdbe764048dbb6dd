// The mesh import's fuzz check (fuzz_mesh.cpp; replayed by tests/mesh/test_imported.cpp):
// bytes drive a generator of what the Gmsh library could return, a structured block of
// 8- or 20-node hexahedra in Gmsh's node order, then broken by the bytes (nodes swapped,
// lost, repeated or moved to NaN; elements repeated or of other types; counts that do
// not match; physical surfaces of stray quadrilaterals); the import must either throw an
// InputError or give a part that keeps the promises of mesh/imported.hpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.hpp"
#include "input/gmsh_file.hpp"
#include "mesh/imported.hpp"
#include "mesh/mesh.hpp"

namespace exdyn::fuzz {

class ByteSource {
 public:
  explicit ByteSource(std::string_view bytes) : bytes_(bytes) {}
  std::uint8_t next() { return at_ < bytes_.size() ? static_cast<std::uint8_t>(bytes_[at_++]) : 0; }
  int below(int n) { return n <= 0 ? 0 : next() % n; }
  bool empty() const { return at_ >= bytes_.size(); }

 private:
  std::string_view bytes_;
  std::size_t at_ = 0;
};

// Returns "" when the import kept its promises (or refused with an InputError, which
// escapes to the caller), else what broke.
inline std::string check_mesh_input(std::string_view bytes) {
  ByteSource in(bytes);
  const bool quadratic = in.below(2) == 1;
  const int order = quadratic ? 2 : 1;
  const int npe = quadratic ? 20 : 8;
  const std::array<int, 3> n{1 + in.below(3), 1 + in.below(3), 1 + in.below(3)};
  // The lattice of a serendipity block (order 2: no face or body centres), tags 1, 2, ...
  input::GmshMesh file;
  file.file = "fuzz.msh";
  const std::array<int, 3> size{order * n[0] + 1, order * n[1] + 1, order * n[2] + 1};
  std::vector<std::size_t> tag_at(std::size_t(size[0] * size[1] * size[2]), 0);
  for (int k = 0; k < size[2]; ++k)
    for (int j = 0; j < size[1]; ++j)
      for (int i = 0; i < size[0]; ++i) {
        if ((i % order) + (j % order) + (k % order) > 1) continue;
        file.node_tags.push_back(file.node_tags.size() + 1);
        tag_at[std::size_t(i + size[0] * (j + size[1] * k))] = file.node_tags.back();
        file.coordinates.insert(file.coordinates.end(), {0.5 * i, 0.5 * j, 0.5 * k});
      }
  input::GmshElements hexes;
  hexes.type = quadratic ? input::gmsh_type::hex20 : input::gmsh_type::hex8;
  hexes.name = quadratic ? "Hexahedron 20" : "Hexahedron 8";
  hexes.dimension = 3;
  hexes.nodes_per_element = npe;
  input::GmshElements quads;
  quads.type = quadratic ? input::gmsh_type::quad8 : input::gmsh_type::quad4;
  quads.name = "Quadrilateral";
  quads.dimension = 2;
  quads.nodes_per_element = quadratic ? 8 : 4;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        std::array<std::size_t, 20> vtk{};
        for (int v = 0; v < npe; ++v) {
          const auto& d = mesh::brick_offsets[std::size_t(v)];
          vtk[std::size_t(v)] = tag_at[std::size_t(
              order * i + d[0] * order / 2 +
              size[0] * (order * j + d[1] * order / 2 + size[1] * (order * k + d[2] * order / 2)))];
        }
        std::array<std::size_t, 20> gmsh{};
        for (int v = 0; v < npe; ++v)
          gmsh[std::size_t(quadratic ? mesh::gmsh_hex20_node[std::size_t(v)] : v)] = vtk[std::size_t(v)];
        hexes.tags.push_back(hexes.tags.size() + 100);
        hexes.nodes.insert(hexes.nodes.end(), gmsh.begin(), gmsh.begin() + npe);
        if (k == 0)  // the bottom face, as a physical surface of quadrilaterals
          for (int q = 0; q < quads.nodes_per_element; ++q)
            quads.nodes.push_back(vtk[std::size_t(mesh::brick_faces[0][q])]);
        if (k == 0) quads.tags.push_back(quads.tags.size() + 1000);
      }
  file.volumes.push_back({"v", {hexes}});
  file.surfaces.push_back({"bottom", {quads}});

  // Breakage, each driven by the bytes. `h` stays valid: case 4 adds at most 15 more
  // element types to the room reserved for them.
  file.volumes[0].elements.reserve(16);
  auto& h = file.volumes[0].elements[0];
  auto& s = file.surfaces[0].elements[0];
  while (!in.empty()) {
    const int what = in.below(12);
    const std::size_t a = in.next(), b = in.next();
    switch (what) {
      case 0:  // two nodes of an element exchanged
        if (!h.nodes.empty()) std::swap(h.nodes[a % h.nodes.size()], h.nodes[b % h.nodes.size()]);
        break;
      case 1:  // a node tag the file lacks, or one of another node
        if (!h.nodes.empty()) h.nodes[a % h.nodes.size()] = b;
        break;
      case 2:  // a coordinate moved, perhaps to NaN or infinity
        if (!file.coordinates.empty()) {
          const double values[4] = {std::nan(""), std::numeric_limits<double>::infinity(), -1.0 * double(b),
                                    1e300};
          double& c = file.coordinates[a % file.coordinates.size()];
          c = b % 5 == 4 ? c + 0.01 * double(b) : values[b % 4];
        }
        break;
      case 3:  // an element repeated
        if (!h.tags.empty() && h.nodes.size() >= std::size_t(npe) * (a % h.tags.size() + 1)) {
          const std::size_t e = a % h.tags.size();
          h.tags.push_back(h.tags[e]);
          const std::vector<std::size_t> copy(h.nodes.begin() + std::ptrdiff_t(npe * e),
                                              h.nodes.begin() + std::ptrdiff_t(npe * (e + 1)));
          h.nodes.insert(h.nodes.end(), copy.begin(), copy.end());
        }
        break;
      case 4: {  // elements of another type
        if (file.volumes[0].elements.size() == 16) break;
        input::GmshElements other;
        const int types[6] = {4, 6, 7, 12, input::gmsh_type::hex8, input::gmsh_type::hex20};
        other.type = types[a % 6];
        other.name = "other";
        other.dimension = 3;
        other.nodes_per_element = other.type == input::gmsh_type::hex20 ? 20 : 8;
        other.tags.assign(1 + b % 3, 7);
        other.nodes.assign(other.tags.size() * std::size_t(other.nodes_per_element), 1 + b % 5);
        file.volumes[0].elements.push_back(other);
        break;
      }
      case 5:  // node tags and coordinates out of step
        if (!file.coordinates.empty()) file.coordinates.pop_back();
        break;
      case 6:  // element tags and node tags out of step
        if (!h.nodes.empty()) h.nodes.pop_back();
        break;
      case 7:  // a node tag given twice
        if (file.node_tags.size() > 1)
          file.node_tags[a % file.node_tags.size()] = file.node_tags[b % file.node_tags.size()];
        break;
      case 8:  // a stray quadrilateral in the surface
        for (int q = 0; q < s.nodes_per_element; ++q) s.nodes.push_back(1 + (a + std::size_t(q) * b) % 40);
        s.tags.push_back(9999);
        break;
      case 9:  // the surface's counts out of step
        if (!s.nodes.empty()) s.nodes.pop_back();
        break;
      case 10:  // a node of the file's list dropped
        if (!file.node_tags.empty()) {
          const std::size_t i = a % file.node_tags.size();
          file.node_tags.erase(file.node_tags.begin() + std::ptrdiff_t(i));
          if (file.coordinates.size() >= 3 * (i + 1))
            file.coordinates.erase(file.coordinates.begin() + std::ptrdiff_t(3 * i),
                                   file.coordinates.begin() + std::ptrdiff_t(3 * i + 3));
        }
        break;
      default:  // the volume renamed
        if (b % 7 == 0) file.volumes[0].name = "w";
        break;
    }
  }

  input::PartOptions part;
  part.name = "p";
  part.geometry = input::Geometry::mesh;
  part.formulation = quadratic ? input::Formulation::hex20 : input::Formulation::hex8;
  part.mesh.volume = "v";
  part.mesh.surfaces = {"bottom", "absent"};
  part.mesh.reorder = bytes.size() % 2 == 0;
  mesh::Mesh mesh;
  mesh::add_imported_part(mesh, part, 0, file, SourceLocation{"fuzz.yaml", 0, 0}, "parts[0].mesh");

  // The promises: every element's nodes are the part's, no node twice in an element,
  // each corner Jacobian positive; every face segment's nodes the part's; the whole
  // boundary and the surfaces made of the part's boundary faces.
  const mesh::PartRange& p = mesh.parts.at(0);
  if (p.node_count != mesh.node_count()) return "the part's node count is not the mesh's";
  if (p.element_count == 0) return "a part without elements was accepted";
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::uint32_t* nodes = mesh.element_nodes(e);
    std::set<std::uint32_t> distinct(nodes, nodes + npe);
    if (distinct.size() != std::size_t(npe)) return "an accepted element repeats a node";
    if (*distinct.rbegin() >= p.node_count) return "an element names a node outside the part";
    auto x = [&](int v, int c) {
      const std::uint32_t node = nodes[v];
      return c == 0 ? mesh.x_ref.x[node] : (c == 1 ? mesh.x_ref.y[node] : mesh.x_ref.z[node]);
    };
    const double e1[3] = {x(1, 0) - x(0, 0), x(1, 1) - x(0, 1), x(1, 2) - x(0, 2)};
    const double e2[3] = {x(3, 0) - x(0, 0), x(3, 1) - x(0, 1), x(3, 2) - x(0, 2)};
    const double e3[3] = {x(4, 0) - x(0, 0), x(4, 1) - x(0, 1), x(4, 2) - x(0, 2)};
    const double det = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0]) +
                       e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
    if (!(det > 0.0)) return "an accepted element has a corner Jacobian that is not positive";
  }
  const mesh::Face whole = mesh::face_of(mesh, 0, input::PartFace::surface);
  if (whole.segments.empty()) return "an accepted part has no boundary";
  std::set<std::array<std::uint32_t, 4>> boundary;
  for (const mesh::FaceSegment& segment : whole.segments) {
    std::array<std::uint32_t, 4> corners{segment.nodes[0], segment.nodes[1], segment.nodes[2],
                                         segment.nodes[3]};
    for (int k = 0; k < segment.node_count; ++k)
      if (segment.nodes[std::size_t(k)] >= p.node_count)
        return "a face segment names a node outside the part";
    std::sort(corners.begin(), corners.end());
    if (!boundary.insert(corners).second) return "a boundary face is listed twice";
  }
  if (p.physical_faces.size() != 2) return "not one face per physical surface name";
  if (!p.physical_faces[1].segments.empty()) return "a surface the file lacks has segments";
  for (const mesh::FaceSegment& segment : p.physical_faces[0].segments) {
    std::array<std::uint32_t, 4> corners{segment.nodes[0], segment.nodes[1], segment.nodes[2],
                                         segment.nodes[3]};
    std::sort(corners.begin(), corners.end());
    if (boundary.count(corners) == 0) return "a physical surface's segment is not a boundary face";
  }
  return "";
}

}  // namespace exdyn::fuzz
