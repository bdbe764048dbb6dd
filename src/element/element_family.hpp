// An element family: what one formulation's elements are and do. The generic
// block code (element_block.cpp) asks the family once per block, outside every
// loop; the family's kernels are free functions on fixed-size data.
//
// To add a formulation: write its family in this folder (a kernel header and a
// <name>_family.cpp defining an ElementFamily) and register it in element_family.cpp.
#pragma once

#include <vector>

#include "common/nodal_vectors.hpp"
#include "element/element_block.hpp"
#include "input/options.hpp"

namespace exdyn::element {

struct ElementFamily {
  const char* name = "";
  int nodes_per_element = 8;  // the first 8 are the corners, in VTK order
  // Fills block.reference (and block.shared, block.reference_index), sets block.loop
  // and block.constant_jacobian. Throws InputError naming an inverted element.
  void (*prepare)(ElementBlock& block, const NodalVectors& x_ref) = nullptr;
  // Adds the block's lumped nodal masses, kg.
  void (*add_lumped_mass)(const ElementBlock& block, const NodalVectors& x_ref,
                          std::vector<double>& mass) = nullptr;
  // The block's smallest stable step without the Courant factor, s.
  double (*critical_time_step)(const ElementBlock& block, const NodalVectors& x_ref) = nullptr;
  // The layout `count` elements allow alone (WholeBlock's flags; no group points).
  WholeBlock (*layout)(std::uint32_t count, const std::uint32_t* connectivity,
                       const NodalVectors& x_ref) = nullptr;
};

// The family of a formulation (never null).
const ElementFamily& element_family(input::Formulation formulation);

// The families (hex8_family.cpp, hex20_family.cpp).
extern const ElementFamily hex8_family;
extern const ElementFamily hex8r_family;
extern const ElementFamily hex20_family;
extern const ElementFamily hex20r_family;

}  // namespace exdyn::element
