// Mapped meshes of round parts: a solid cylinder (an O-grid) and a solid ball (a
// cube-sphere), with `keep` cuts by symmetry planes and radial grading
// (docs/input.md, "Cylinder and sphere parts"; docs/theory.md, "Mapped meshes").
//
// Cylinder, in the cross-section: a square core of half-width a = core_fraction R
// with n_around x n_around elements, and four blocks of n_around x n_radius elements
// between the core's sides and the circle, each side mapped onto a quarter of the
// circle at equal angles; n_axis elements along the axis. Ball: a cube core of
// n_around^3 elements and six blocks of n_around x n_around x n_radius between the
// cube's faces and the sphere (equal angles on the sphere along each grid line). A
// point of a block between the core and the surface is x = (1 - tau) P + tau S: P on
// the core's side, S on the circle or sphere, tau the graded radial fraction; so every
// node of the surface, the mid-edge nodes of 20-node elements included, lies on the
// circle or the sphere to round-off.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "input/options.hpp"
#include "mesh/mesh.hpp"

namespace exdyn::mesh {

// Half-width of the square (cube) core over the radius.
inline constexpr double core_fraction = 0.5;

// The elements of a cylinder or sphere part after its `keep` cuts.
std::uint64_t mapped_element_count(const input::PartOptions& options);

// Appends a cylinder or sphere part to the mesh, with its named faces.
void add_mapped_part(Mesh& mesh, const input::PartOptions& options, int part_index);

// A cylinder or sphere part by numbers, for a rank that builds only its own elements
// (ranks/rank_setup.hpp): add_mapped_part's nodes (numbered from 0), elements and
// faces, the same numbering and bits, each computed when asked for from the layout
// of blocks. It holds one figure per lattice row of each block, the node ids of the
// points on the blocks' sides and the part's faces: O(n^2) for n^3 elements.
//
// The numbering without the merging: each block's sides are glued to the other
// blocks' sides they coincide with (found once from their corners), so a point on a
// side has its appearances in the blocks that share it; add_mapped_part numbers the
// points of the kept elements in the order of their first appearance (blocks in
// order, each along its lattice, K then J then I). The kept elements of a block form
// a box of its lattice (the cuts run along grid planes through the centre), the
// element order of a block is that box's.
class MappedLattice {
 public:
  MappedLattice(const input::PartOptions& options, int part_index);
  MappedLattice(MappedLattice&&) noexcept;
  MappedLattice& operator=(MappedLattice&&) noexcept;
  ~MappedLattice();

  std::uint32_t node_count() const;
  std::uint32_t element_count() const;
  int order() const;
  int nodes_per_element() const;
  // Element e's nodes (VTK order; nodes_per_element() of them).
  std::array<std::uint32_t, 20> element_nodes(std::uint32_t e) const;
  // Node k's coordinates, m.
  std::array<double, 3> point(std::uint32_t k) const;
  // The elements around node k, ascending.
  std::vector<std::uint32_t> elements_around(std::uint32_t k) const;
  // The part's named faces (PartRange::faces).
  const std::vector<std::pair<input::PartFace, Face>>& faces() const;

 private:
  struct Layout;
  std::unique_ptr<Layout> layout_;
};

}  // namespace exdyn::mesh
