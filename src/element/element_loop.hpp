// The gather -> kernel -> scatter loop over a range of a block's elements, for
// the element families (hex8_family.cpp, hex20_family.cpp): templates on the
// number of nodes and the value type, so a family writes only its kernel.
#pragma once

#include <array>
#include <cstdint>

#include "common/nodal_vectors.hpp"
#include "element/element_block.hpp"
#include "element/node_values.hpp"

namespace exdyn::element {

template <int Nodes, class Vectors>
inline void gather(const NodalVectors& v, const std::uint32_t* nodes, Vectors& local) {
  const double* x = v.x.data();
  const double* y = v.y.data();
  const double* z = v.z.data();
  for (int k = 0; k < Nodes; ++k) {
    const std::uint32_t n = nodes[k];
    local.x[k] = x[n];
    local.y[k] = y[n];
    local.z[k] = z[n];
  }
}

template <int Nodes, class Vectors>
inline void scatter_add(const Vectors& local, const std::uint32_t* nodes, NodalVectors& v) {
  double* x = v.x.data();
  double* y = v.y.data();
  double* z = v.z.data();
  for (int k = 0; k < Nodes; ++k) {
    const std::uint32_t n = nodes[k];
    x[n] += local.x[k];
    y[n] += local.y[k];
    z[n] += local.z[k];
  }
}

// The element loop, one instantiation per kernel: kernel(reference, u, f, stress)
// returns the element's energies; `stride` doubles of reference data per element.
template <int Nodes, class Vectors, class Kernel>
ElementEnergies element_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                             const double* reference, std::size_t stride, const NodalVectors& u,
                             NodalVectors& f_int, double* stress, Kernel kernel) {
  ElementEnergies total;
  for (std::uint32_t e = begin; e < end; ++e) {
    const std::uint32_t* nodes = block.connectivity + Nodes * static_cast<std::size_t>(e);
    Vectors u_local{typename Vectors::Uninitialized{}};  // written whole by gather
    gather<Nodes>(u, nodes, u_local);
    Vectors f_local{typename Vectors::Uninitialized{}};  // the kernel writes every entry
    material::SymTensor element_stress;
    const ElementEnergies energies = kernel(reference + stride * e, u_local, f_local, element_stress);
    scatter_add<Nodes>(f_local, nodes, f_int);
    total.strain += energies.strain;
    total.hourglass += energies.hourglass;
    if (stress != nullptr) {
      double* out = stress + 6 * (static_cast<std::size_t>(block.first_element) + e);
      for (int k = 0; k < 6; ++k) out[k] = element_stress[k];
    }
  }
  return total;
}

// An element that failed its reference check: bad input (the mesh, not the run).
[[noreturn]] void throw_inverted(std::uint32_t global_element, double det_jacobian);

}  // namespace exdyn::element
