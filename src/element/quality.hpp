// Element shape quality and volume from the nodal coordinates, for `exdyn check` and
// the mesh tests. Free functions on fixed-size data (docs/theory.md, "Mapped meshes").
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "element/hex20.hpp"
#include "element/hex8.hpp"

namespace exdyn::element {

struct ElementQuality {
  // min over sample points of det J / (|dx/dxi| |dx/deta| |dx/dzeta|): 1 for a cube
  // or a box, smaller as the element shears or tapers, <= 0 inverted or degenerate.
  double scaled_jacobian = 0.0;
  double volume = 0.0;  // integral of det J, m^3
};

// x[I] the coordinates of node I (8 or 20 nodes, VTK order). Samples: a hex8 at its 8
// corners (the classic hex scaled Jacobian); a hex20 at the 27 points with xi, eta,
// zeta in {-1, 0, 1}. Volume: 2x2x2 Gauss points (exact for the trilinear brick) or
// 3x3x3 (a hex20; exact for an affine one).
inline ElementQuality element_quality(const std::array<double, 3>* x, int nodes) {
  auto jacobian = [&](double xi, double eta, double zeta) {
    std::array<double, 9> j{};  // j[3 c + a] = dx_c / dxi_a
    if (nodes == 8) {
      const auto d = hex8::shape_function_derivatives(xi, eta, zeta);
      for (int n = 0; n < 8; ++n)
        for (int c = 0; c < 3; ++c)
          for (int a = 0; a < 3; ++a)
            j[std::size_t(3 * c + a)] += x[n][std::size_t(c)] * d[std::size_t(n)][std::size_t(a)];
    } else {
      const auto d = hex20::shape_function_derivatives(xi, eta, zeta);
      for (int n = 0; n < 20; ++n)
        for (int c = 0; c < 3; ++c)
          for (int a = 0; a < 3; ++a)
            j[std::size_t(3 * c + a)] += x[n][std::size_t(c)] * d[std::size_t(n)][std::size_t(a)];
    }
    return j;
  };
  auto determinant = [](const std::array<double, 9>& j) {
    return j[0] * (j[4] * j[8] - j[5] * j[7]) - j[1] * (j[3] * j[8] - j[5] * j[6]) +
           j[2] * (j[3] * j[7] - j[4] * j[6]);
  };
  ElementQuality q;
  q.scaled_jacobian = std::numeric_limits<double>::infinity();
  auto sample = [&](double xi, double eta, double zeta) {
    const auto j = jacobian(xi, eta, zeta);
    double lengths = 1.0;
    for (int a = 0; a < 3; ++a)
      lengths *=
          std::sqrt(j[std::size_t(a)] * j[std::size_t(a)] + j[std::size_t(3 + a)] * j[std::size_t(3 + a)] +
                    j[std::size_t(6 + a)] * j[std::size_t(6 + a)]);
    q.scaled_jacobian = std::min(q.scaled_jacobian, lengths > 0.0 ? determinant(j) / lengths : 0.0);
  };
  if (nodes == 8) {
    for (const auto& corner : hex8::node_natural_coordinates) sample(corner[0], corner[1], corner[2]);
  } else {
    for (int k = -1; k <= 1; ++k)
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) sample(i, j, k);
  }
  const hex20::GaussRule rule = hex20::gauss_rule(nodes == 8 ? 2 : 3);
  for (int g = 0; g < rule.count; ++g) {
    const auto& p = rule.point[std::size_t(g)];
    q.volume += rule.weight[std::size_t(g)] * determinant(jacobian(p[0], p[1], p[2]));
  }
  return q;
}

}  // namespace exdyn::element
