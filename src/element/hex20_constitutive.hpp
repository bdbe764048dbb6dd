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
  const std::array<const std::array<Real, 20>*, 3> u_component{&u.x, &u.y, &u.z};
  std::array<std::array<Real, 9>, Points> h;
  std::array<Real, Points> w;
  for (int g = 0; g < Points; ++g) {
    const double* dn = table + table_stride * g;
    Real d[3][3] = {};
    for (int node = 0; node < 20; ++node) {
      const double n0 = dn[node], n1 = dn[20 + node], n2 = dn[40 + node];
      for (int i = 0; i < 3; ++i) {
        const Real ui = (*u_component[i])[node];
        d[i][0] += ui * n0;
        d[i][1] += ui * n1;
        d[i][2] += ui * n2;
      }
    }
    Real r[9];
    for (int k = 0; k < 9; ++k) r[k] = load<Real>(reference, 10 * g + k);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) h[g][3 * i + j] = d[i][0] * r[j] + d[i][1] * r[3 + j] + d[i][2] * r[6 + j];
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
      std::array<Real, 20>& out = *f_component[i];
      for (int node = 0; node < 20; ++node)
        out[node] += q[0] * dn[node] + q[1] * dn[20 + node] + q[2] * dn[40 + node];
    }
  }
  return result;
}

}  // namespace exdyn::element::hex20
