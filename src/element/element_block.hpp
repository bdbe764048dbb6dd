// A block of hexahedra of one formulation and one material (one part), and the
// loop that adds their internal forces: gather -> kernel -> scatter.
// Kernels (hex8.hpp, hex8r.hpp) are free functions on fixed-size local data.
#pragma once

#include <cstdint>
#include <vector>

#include "common/nodal_vectors.hpp"
#include "input/options.hpp"
#include "material/elastic.hpp"

namespace exdyn::element {

struct ElementBlock {
  input::Formulation formulation = input::Formulation::hex8;
  material::ElasticConstants material;
  double hourglass_coefficient = 0.0;  // hex8r only
  std::uint32_t first_element = 0;     // global index of the block's first element
  std::uint32_t count = 0;             // number of elements
  const std::uint32_t* connectivity = nullptr;  // 8 node ids per element (VTK order), `count` elements
  // Reference-configuration data precomputed once per element (layout private
  // to the kernels: e.g. inverse Jacobians and weights at the Gauss points).
  std::vector<double> reference;
};

// Builds a block and precomputes its reference data from the reference
// coordinates. `connectivity` must outlive the block.
ElementBlock make_element_block(input::Formulation formulation, const material::ElasticConstants& material,
                                double hourglass_coefficient, std::uint32_t first_element,
                                std::uint32_t count, const std::uint32_t* connectivity,
                                const NodalVectors& x_ref);

struct ElementEnergies {
  double strain = 0.0;     // sum of int sigma:eps/2 dV, J
  double hourglass = 0.0;  // sum of hourglass spring energies (hex8r), J
};

// f_int += internal forces (N) of the block's elements for the displacement u
// (small strain, reference configuration). Writes each element's volume-averaged
// Cauchy stress (xx yy zz xy yz xz, Pa) to stress[6 * global_element ...] and
// returns the block's energies.
ElementEnergies add_internal_forces(const ElementBlock& block, const NodalVectors& u, NodalVectors& f_int,
                                    double* stress);

// Smallest stable time step of the block, s: min over elements of L_e / c1, with
// L_e the characteristic length (element volume / largest face area) and
// c1 = sqrt((lambda + 2 mu) / rho). The caller multiplies by the Courant number.
double critical_time_step(const ElementBlock& block, const NodalVectors& x_ref);

// Lumped (row-sum) mass: adds rho * integral of N_i dV of every element to the
// nodal mass m (kg, one entry per node).
void add_lumped_mass(const ElementBlock& block, const NodalVectors& x_ref, std::vector<double>& mass);

// add_internal_forces for the block's elements [element_begin, element_end)
// (local indices), e.g. one thread's share of a coloured block.
ElementEnergies add_internal_forces(const ElementBlock& block, std::uint32_t element_begin,
                                    std::uint32_t element_end, const NodalVectors& u, NodalVectors& f_int,
                                    double* stress);

// True when every element of the block is a parallelepiped, so that the block
// runs the constant-Jacobian kernels (hex8::parallelepiped_internal_forces,
// hex8r::parallelepiped_internal_forces).
bool uses_parallelepiped_kernel(const ElementBlock& block);

}  // namespace exdyn::element
