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

struct ElementEnergies {
  double strain = 0.0;     // sum of int sigma:eps/2 dV, J
  double hourglass = 0.0;  // sum of hourglass spring energies (hex8r), J
};

// Elements per chunk of the parallel element loop (even: an element pair is never split).
inline constexpr std::uint32_t element_chunk = 512;

struct ElementBlock {
  input::Formulation formulation = input::Formulation::hex8;
  material::ElasticConstants material;
  double hourglass_coefficient = 0.0;           // hex8r only
  std::uint32_t first_element = 0;              // global index of the block's first element
  std::uint32_t count = 0;                      // number of elements
  const std::uint32_t* connectivity = nullptr;  // 8 node ids per element (VTK order), `count` elements
  // Reference-configuration data precomputed once per element (layout private
  // to the kernels: e.g. inverse Jacobians and weights at the Gauss points).
  std::vector<double> reference;
  // The parallel schedule (docs/performance.md): the elements in chunks of
  // element_chunk consecutive ones, grouped in colours whose chunks share no node,
  // so that the chunks of a colour scatter their forces at once without a race and
  // every node adds its elements' forces in the same order on any number of threads.
  std::vector<std::uint32_t> chunk_begin;               // chunk c is [chunk_begin[c], chunk_begin[c + 1])
  std::vector<std::vector<std::uint32_t>> colours;      // the chunks of each colour, ascending
  mutable std::vector<ElementEnergies> chunk_energies;  // scratch: the energies of each chunk
};

// Builds a block and precomputes its reference data from the reference
// coordinates. `connectivity` must outlive the block.
ElementBlock make_element_block(input::Formulation formulation, const material::ElasticConstants& material,
                                double hourglass_coefficient, std::uint32_t first_element,
                                std::uint32_t count, const std::uint32_t* connectivity,
                                const NodalVectors& x_ref);

// f_int += internal forces (N) of the block's elements for the displacement u
// (small strain, reference configuration). Writes each element's volume-averaged
// Cauchy stress (xx yy zz xy yz xz, Pa) to stress[6 * global_element ...] and
// returns the block's energies. Runs the colours one after the other and the chunks
// of a colour on the threads; the result does not depend on the number of threads.
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

// An element whose current configuration x = x_ref + u is inverted.
struct InvertedElement {
  bool found = false;
  std::uint32_t element = 0;  // global element index
  int corner = 0;             // local node (VTK order) where det J <= 0
  double det_jacobian = 0.0;  // det of the corner's edge vectors there, m^3
  // When none is inverted: no element can invert before some node has moved by this
  // much from the configuration checked, m (a lower bound, see below).
  double safety_radius = 0.0;
};

// The lowest-indexed element of [element_begin, element_end) (local indices) with a
// non-positive corner Jacobian in the current configuration: at each corner a,
// det[e_xi, e_eta, e_zeta] with e the edges from a towards its three neighbours,
// oriented along +xi, +eta, +zeta (the trilinear map's Jacobian at a, times 8).
// All eight positive is the usual validity test of a hexahedron. The safety radius:
// moving the nodes by at most delta changes each edge by at most 2 delta, so the
// corner matrix J by ||E||_2 <= ||E||_F <= 2 sqrt(3) delta, and det J keeps its sign
// while that stays below sigma_min(J) >= det J / ||J||_F^2 (as sigma_1 sigma_2 <=
// ||J||_F^2); hence delta < min over corners of det J / (2 sqrt(3) ||J||_F^2).
InvertedElement find_inverted_element(const ElementBlock& block, std::uint32_t element_begin,
                                      std::uint32_t element_end, const NodalVectors& x_ref,
                                      const NodalVectors& u);
InvertedElement find_inverted_element(const ElementBlock& block, const NodalVectors& x_ref,
                                      const NodalVectors& u);

// True when every element of the block is a parallelepiped, so that the block
// runs the constant-Jacobian kernels (hex8::parallelepiped_internal_forces,
// hex8r::parallelepiped_internal_forces).
bool uses_parallelepiped_kernel(const ElementBlock& block);

}  // namespace exdyn::element
