// Values at the nodes of one element: the local data of the element kernels.
#pragma once

#include <array>

namespace exdyn::element {

// One vector per node of one element (or of a pack of elements, Real = Pack<L>), the
// components apart: x[I], y[I], z[I] for local node I.
template <int Nodes, class Real = double>
struct NodeValues {
  std::array<Real, Nodes> x, y, z;
  NodeValues() : x{}, y{}, z{} {}  // zero
  // Left uninitialised, for the element loops' gather and force arrays that are
  // written whole before they are read (zeroing them cost 11-23 % of the loop:
  // docs/performance.md).
  struct Uninitialized {};
  explicit NodeValues(Uninitialized) {}
};

}  // namespace exdyn::element
