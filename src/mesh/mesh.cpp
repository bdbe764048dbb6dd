#include "mesh/mesh.hpp"

#include <limits>
#include <string>

#include "common/errors.hpp"

namespace exdyn::mesh {

namespace {

// Node id of grid point (i, j, k) of a part.
std::uint32_t node_id(const PartRange& part, int i, int j, int k) {
  const auto& n = part.elements;
  return part.first_node + static_cast<std::uint32_t>(i + (n[0] + 1) * (j + (n[1] + 1) * k));
}

void add_part(Mesh& mesh, const input::PartOptions& options, int part_index) {
  PartRange part;
  part.elements = options.elements;
  const auto& n = options.elements;
  part.first_node = static_cast<std::uint32_t>(mesh.node_count());
  part.node_count = static_cast<std::uint32_t>((n[0] + 1) * (n[1] + 1) * (n[2] + 1));
  part.first_element = static_cast<std::uint32_t>(mesh.element_count());
  part.element_count = static_cast<std::uint32_t>(n[0] * n[1] * n[2]);

  // Grid coordinates x_i = min + (max - min) i / n, written so that the last
  // node lands exactly on max.
  auto coordinate = [&](int axis, int index) {
    const double lo = options.box_min[axis], hi = options.box_max[axis];
    return index == n[axis] ? hi : lo + (hi - lo) * static_cast<double>(index) / static_cast<double>(n[axis]);
  };
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i) {
        mesh.x_ref.x.push_back(coordinate(0, i));
        mesh.x_ref.y.push_back(coordinate(1, j));
        mesh.x_ref.z.push_back(coordinate(2, k));
      }
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        // VTK hexahedron: the face k counter-clockwise, then the face k+1.
        const std::array<std::uint32_t, 8> element{
            node_id(part, i, j, k),         node_id(part, i + 1, j, k),
            node_id(part, i + 1, j + 1, k), node_id(part, i, j + 1, k),
            node_id(part, i, j, k + 1),     node_id(part, i + 1, j, k + 1),
            node_id(part, i + 1, j + 1, k + 1), node_id(part, i, j + 1, k + 1)};
        mesh.connectivity.insert(mesh.connectivity.end(), element.begin(), element.end());
        mesh.element_part.push_back(part_index);
      }
  mesh.parts.push_back(part);
}

}  // namespace

Mesh build_mesh(const input::Deck& deck) {
  std::uint64_t nodes = 0, elements = 0;
  for (const auto& part : deck.parts) {
    const auto& n = part.elements;
    nodes += std::uint64_t(n[0] + 1) * std::uint64_t(n[1] + 1) * std::uint64_t(n[2] + 1);
    elements += std::uint64_t(n[0]) * std::uint64_t(n[1]) * std::uint64_t(n[2]);
  }
  // 32-bit node ids (connectivity) and element ids.
  if (nodes > std::numeric_limits<std::uint32_t>::max() || elements > std::numeric_limits<std::int32_t>::max())
    throw InputError(SourceLocation{deck.source_file, 0, 0}, "parts",
                     "the mesh has " + std::to_string(nodes) + " nodes and " + std::to_string(elements) +
                         " elements; at most 4294967295 nodes and 2147483647 elements are supported");
  Mesh mesh;
  mesh.x_ref.x.reserve(nodes);
  mesh.x_ref.y.reserve(nodes);
  mesh.x_ref.z.reserve(nodes);
  mesh.connectivity.reserve(8 * elements);
  mesh.element_part.reserve(elements);
  for (std::size_t p = 0; p < deck.parts.size(); ++p) add_part(mesh, deck.parts[p], static_cast<int>(p));
  return mesh;
}

Face face_of(const Mesh& mesh, int part_index, input::BoxSide side) {
  const PartRange& part = mesh.parts.at(static_cast<std::size_t>(part_index));
  const auto& n = part.elements;
  // The face is the grid plane axis = fixed; (p, q) are its in-plane axes,
  // ordered so that e_p x e_q is the outward normal.
  int axis = 0, p = 0, q = 0, fixed = 0;
  switch (side) {
    case input::BoxSide::xmin: axis = 0, p = 2, q = 1, fixed = 0; break;
    case input::BoxSide::xmax: axis = 0, p = 1, q = 2, fixed = n[0]; break;
    case input::BoxSide::ymin: axis = 1, p = 0, q = 2, fixed = 0; break;
    case input::BoxSide::ymax: axis = 1, p = 2, q = 0, fixed = n[1]; break;
    case input::BoxSide::zmin: axis = 2, p = 1, q = 0, fixed = 0; break;
    case input::BoxSide::zmax: axis = 2, p = 0, q = 1, fixed = n[2]; break;
  }
  auto node_at = [&](int a, int b) {
    std::array<int, 3> ijk{};
    ijk[axis] = fixed;
    ijk[p] = a;
    ijk[q] = b;
    return node_id(part, ijk[0], ijk[1], ijk[2]);
  };
  Face face;
  for (int b = 0; b <= n[q]; ++b)
    for (int a = 0; a <= n[p]; ++a) face.nodes.push_back(node_at(a, b));
  for (int b = 0; b < n[q]; ++b)
    for (int a = 0; a < n[p]; ++a)
      face.quads.push_back({node_at(a, b), node_at(a + 1, b), node_at(a + 1, b + 1), node_at(a, b + 1)});
  return face;
}

}  // namespace exdyn::mesh
