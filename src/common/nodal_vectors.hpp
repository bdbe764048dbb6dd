// Nodal vector data as a structure of arrays: one contiguous array per
// component, so that loops over nodes stream through memory and vectorise.
// Every nodal vector field (coordinates, displacement, velocity, force) uses
// this one type, so the layout can change in one place.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace exdyn {

struct NodalVectors {
  std::vector<double> x, y, z;

  NodalVectors() = default;
  explicit NodalVectors(std::size_t n) : x(n, 0.0), y(n, 0.0), z(n, 0.0) {}

  std::size_t size() const { return x.size(); }
  bool empty() const { return x.empty(); }
  void resize(std::size_t n) {
    x.assign(n, 0.0);
    y.assign(n, 0.0);
    z.assign(n, 0.0);
  }
  void fill(double value) {
    x.assign(x.size(), value);
    y.assign(y.size(), value);
    z.assign(z.size(), value);
  }
  std::vector<double>& component(int c) { return c == 0 ? x : (c == 1 ? y : z); }
  const std::vector<double>& component(int c) const { return c == 0 ? x : (c == 1 ? y : z); }
  std::array<double, 3> at(std::size_t i) const { return {x[i], y[i], z[i]}; }
};

}  // namespace exdyn
