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

#include <cstdint>

#include "input/options.hpp"
#include "mesh/mesh.hpp"

namespace exdyn::mesh {

// Half-width of the square (cube) core over the radius.
inline constexpr double core_fraction = 0.5;

// The elements of a cylinder or sphere part after its `keep` cuts.
std::uint64_t mapped_element_count(const input::PartOptions& options);

// Appends a cylinder or sphere part to the mesh, with its named faces.
void add_mapped_part(Mesh& mesh, const input::PartOptions& options, int part_index);

}  // namespace exdyn::mesh
