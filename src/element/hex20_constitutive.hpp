// The 20-node kernel under a material law (element/constitutive.hpp): small strain
// with a plastic material, or finite strain (total Lagrangian, no F-bar: the quadratic
// element carries a linear volume change). The general layout's reference data
// (hex20.hpp make_reference) and derivative table; the point states in the block.
#pragma once

#include <array>

#include "element/constitutive.hpp"
#include "element/hex20.hpp"

namespace exdyn::element::hex20 {

// Points: the rule's count (27 for hex20, 8 for hex20r).
template <class Flow, bool Finite, int Points, class Real>
inline ConstitutiveResult<Real> constitutive_forces(const double* table, const double* reference,
                                                    const material::ElasticConstants& elastic,
                                                    const Flow& flow, const NodeValues<20, Real>& u,
                                                    NodeValues<20, Real>& f, const double* state_old,
                                                    double* state_new, double dt) {
  std::array<std::array<Real, 9>, Points> h;
  std::array<Real, Points> w;
  for (int g = 0; g < Points; ++g) {
    Real r[9];
    for (int k = 0; k < 9; ++k) r[k] = load<Real>(reference, 10 * g + k);
    gradient_at_point(table + table_stride * g, u, r, h[g].data());
    w[g] = load<Real>(reference, 10 * g + 9);
  }
  const ConstitutiveResult<Real> result =
      integrate_points<Flow, Finite, Points>(elastic, flow, false, h, w, state_old, state_new, dt);
  f = NodeValues<20, Real>{};
  const std::array<std::array<Real, 20>*, 3> f_component{&f.x, &f.y, &f.z};
  for (int g = 0; g < Points; ++g) {
    const double* dn = table + table_stride * g;
    Real r[9];
    for (int k = 0; k < 9; ++k) r[k] = load<Real>(reference, 10 * g + k);
    const std::array<Real, 9>& p = h[g];  // w_g P_g
    for (int i = 0; i < 3; ++i) {
      Real q[3];  // sum_j P_ij dxi_a/dX_j
      for (int a = 0; a < 3; ++a)
        q[a] = p[3 * i] * r[3 * a] + p[3 * i + 1] * r[3 * a + 1] + p[3 * i + 2] * r[3 * a + 2];
      add_point_forces(dn, q, *f_component[i]);
    }
  }
  return result;
}

}  // namespace exdyn::element::hex20
