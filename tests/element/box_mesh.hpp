// Test helper: a structured box mesh of 8-node bricks for the element tests.
#pragma once

#include <cstdint>
#include <vector>

#include "common/nodal_vectors.hpp"

namespace exdyn::element {

// A structured box of nx x ny x nz elements of sides h, node (i, j, k) at
// index i + (nx+1) (j + (ny+1) k), elements in VTK order.
struct Box {
  NodalVectors x_ref;
  std::vector<std::uint32_t> connectivity;
  std::uint32_t count = 0;
};

inline Box make_box(int nx, int ny, int nz, double h) {
  Box box;
  const auto node = [&](int i, int j, int k) {
    return static_cast<std::uint32_t>(i + (nx + 1) * (j + (ny + 1) * k));
  };
  box.x_ref.resize(static_cast<std::size_t>((nx + 1) * (ny + 1) * (nz + 1)));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        box.x_ref.x[node(i, j, k)] = i * h;
        box.x_ref.y[node(i, j, k)] = j * h;
        box.x_ref.z[node(i, j, k)] = k * h;
      }
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::uint32_t element[8] = {
            node(i, j, k),     node(i + 1, j, k),     node(i + 1, j + 1, k),     node(i, j + 1, k),
            node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        box.connectivity.insert(box.connectivity.end(), element, element + 8);
        ++box.count;
      }
  return box;
}

}  // namespace exdyn::element
