// The 8-node kernels under a material law (element/constitutive.hpp): small strain
// with a plastic material, or finite strain (total Lagrangian). The same reference
// data as the linear kernels' general layouts (hex8.hpp make_reference, hex8r.hpp
// make_reference); the law's point states in the block (ElementBlock::material_state);
// and the characteristic length of the current configuration, for the step that
// follows the deformation.
#pragma once

#include <array>

#include "element/constitutive.hpp"
#include "element/hex8.hpp"
#include "element/hex8r.hpp"

namespace exdyn::element {

namespace hex8 {

// hex8, 2x2x2 Gauss points: H_g = D_g dxi/dX (D from the modes of u, as in
// internal_forces), the law at the eight points, then f from w_g P_g in mode space.
template <class Flow, bool Finite, class Real>
inline ConstitutiveResult<Real> constitutive_forces(const double* reference,
                                                    const material::ElasticConstants& elastic,
                                                    const Flow& flow, bool f_bar,
                                                    const BasicElementVectors<Real>& u,
                                                    BasicElementVectors<Real>& f, const double* state_old,
                                                    double* state_new, double dt) {
  using namespace detail;
  const BasicElementModes<Real> c = modes_from_nodal(u);
  constexpr double a = gauss_abscissa, a2 = gauss_abscissa * gauss_abscissa;
  const GradientModes<Real> m = gradient_modes(c);
  std::array<std::array<Real, 9>, 8> h;
  std::array<Real, 8> w;
#pragma GCC unroll 8
  for (int g = 0; g < 8; ++g) {
    Real r[9];
    for (int k = 0; k < 9; ++k) r[k] = load<Real>(reference, 10 * g + k);
    gradient_at_point(m, g, r, h[g].data());
    w[g] = 8.0 * load<Real>(reference, 10 * g + 9);  // w det J (the layout stores it / 8)
  }
  const ConstitutiveResult<Real> result =
      integrate_points<Flow, Finite, 8>(elastic, flow, f_bar, h, w, state_old, state_new, dt);
  Real force[3][8] = {};
#pragma GCC unroll 8
  for (int g = 0; g < 8; ++g) {
    Real r[9];
    for (int k = 0; k < 9; ++k) r[k] = load<Real>(reference, 10 * g + k);
    const std::array<Real, 9>& p = h[g];  // w_g P_g
    for (int i = 0; i < 3; ++i) {
      Real q[3];  // sum_j P_ij dxi_k/dX_j
      for (int k = 0; k < 3; ++k)
        q[k] = p[3 * i] * r[3 * k] + p[3 * i + 1] * r[3 * k + 1] + p[3 * i + 2] * r[3 * k + 2];
      add_mode_forces(g, q, force[i]);
    }
  }
  std::array<Real, 8> fx{}, fy{}, fz{};
  const std::array<std::array<Real, 8>*, 3> force_modes{&fx, &fy, &fz};
  for (int i = 0; i < 3; ++i) {
    const Real* fm = force[i];
    // f_I = sum_m phi_m(I) F_m / 8, the abscissa scaling of the modes 4..7.
    *force_modes[i] = {Real{},
                       0.125 * fm[1],
                       0.125 * fm[2],
                       0.125 * fm[3],
                       (0.125 * a) * fm[4],
                       (0.125 * a) * fm[5],
                       (0.125 * a) * fm[6],
                       (0.125 * a2) * fm[7]};
  }
  f.x = nodal_from_modes(fx);
  f.y = nodal_from_modes(fy);
  f.z = nodal_from_modes(fz);
  return result;
}

// The triple product a . (b x c) of three modes' vectors.
template <class Real>
inline Real triple_product(const BasicElementModes<Real>& c, int a, int b, int d) {
  return c.x[a] * (c.y[b] * c.z[d] - c.z[b] * c.y[d]) - c.y[a] * (c.x[b] * c.z[d] - c.z[b] * c.x[d]) +
         c.z[a] * (c.x[b] * c.y[d] - c.y[b] * c.x[d]);
}

// The characteristic length of the current configuration, V / (largest face area),
// for one element (Real = double) or a pack of elements (Real = Pack<L>), without
// inverses, for the step that follows the deformation every step. V is the exact
// volume of the trilinear brick, the integral of det J over the cube in closed form:
// with x = c0 + c1 xi + c2 eta + c3 zeta + c4 eta zeta + c5 xi zeta + c6 xi eta
// + c7 xi eta zeta (modes_from_nodal) and [a, b, c] = a . (b x c),
//   V = 8 [c1, c2, c3] + 8/3 ([c1, c6, c5] + [c5, c4, c3] + [c6, c2, c4])
// (the monomials of det J with an odd power integrate to zero, and the terms left
// with c7, or a mode twice, are triple products with a vector twice). The 2 x 2 x 2
// Gauss sum of det J (exact too) takes eight 3 x 3 determinants. Each face's area by
// its diagonals as in face_area: the same value as characteristic_length to round-off.
template <class Real>
inline Real current_characteristic_length(const BasicElementVectors<Real>& x) {
  const BasicElementModes<Real> c = modes_from_nodal(x);
  const Real volume =
      8.0 * triple_product(c, 1, 2, 3) +
      (8.0 / 3.0) * (triple_product(c, 1, 6, 5) + triple_product(c, 5, 4, 3) + triple_product(c, 6, 2, 4));
  Real largest{};  // |d1 x d2|^2 = (2 A)^2
  for (const auto& face : faces) {
    const Real d1x = x.x[face[2]] - x.x[face[0]], d1y = x.y[face[2]] - x.y[face[0]],
               d1z = x.z[face[2]] - x.z[face[0]];
    const Real d2x = x.x[face[3]] - x.x[face[1]], d2y = x.y[face[3]] - x.y[face[1]],
               d2z = x.z[face[3]] - x.z[face[1]];
    const Real nx = d1y * d2z - d1z * d2y, ny = d1z * d2x - d1x * d2z, nz = d1x * d2y - d1y * d2x;
    largest = lane_max(largest, nx * nx + ny * ny + nz * nz);
  }
  return 2.0 * volume / lane_sqrt(largest);  // V / (|n| / 2)
}

}  // namespace hex8

namespace hex8r {

// hex8r: the mean gradient H = sum_m c_m (x) beta_m (the exact reference-volume mean
// of du/dX), the law at that one point with weight V, f_I = V P b_I / V plus the
// Flanagan-Belytschko hourglass forces in their total form. The hourglass energy
// k/2 sum |q|^2 with q = gamma . x_cur does not change under a rigid rotation (gamma
// annihilates linear fields), so it stays objective under large rotations.
template <class Flow, bool Finite, class Real>
inline ConstitutiveResult<Real> constitutive_forces(const double* reference,
                                                    const material::ElasticConstants& elastic,
                                                    const Flow& flow, const BasicElementVectors<Real>& u,
                                                    BasicElementVectors<Real>& f, const double* state_old,
                                                    double* state_new, double dt, Real& hourglass_energy) {
  const hex8::BasicElementModes<Real> c = hex8::modes_from_nodal(u);
  std::array<Real, 21> beta;
  for (int k = 0; k < 21; ++k) beta[k] = load<Real>(reference, k);
  std::array<Real, 12> g;
  for (int k = 0; k < 12; ++k) g[k] = load<Real>(reference, 21 + k);
  const Real volume = load<Real>(reference, 33), inverse_volume = load<Real>(reference, 34),
             k = load<Real>(reference, 35);
  std::array<std::array<Real, 9>, 1> h{};
  for (int m = 1; m < 8; ++m) {
    const std::array<Real, 3> cm = c[m];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) h[0][3 * i + j] += cm[i] * beta[3 * (m - 1) + j];
  }
  Real q[4][3];
  Real q_squared{};
  for (int alpha = 0; alpha < 4; ++alpha) {
    const std::array<Real, 3> ch = c[4 + alpha];
    for (int i = 0; i < 3; ++i) {
      q[alpha][i] = 8.0 * ch[i] - (g[3 * alpha] * h[0][3 * i] + g[3 * alpha + 1] * h[0][3 * i + 1] +
                                   g[3 * alpha + 2] * h[0][3 * i + 2]);
      q_squared += q[alpha][i] * q[alpha][i];
    }
  }
  hourglass_energy = 0.5 * k * q_squared;
  const std::array<Real, 1> w{volume};
  const ConstitutiveResult<Real> result =
      integrate_points<Flow, Finite, 1>(elastic, flow, false, h, w, state_old, state_new, dt);
  const std::array<Real, 9>& p = h[0];  // V P
  const Real k_over_volume = k * inverse_volume;
  std::array<Real, 8> fm[3] = {};
  for (int i = 0; i < 3; ++i) {
    Real s[3];
    for (int j = 0; j < 3; ++j)
      s[j] = 0.125 * p[3 * i + j] -
             (0.125 * volume) * k_over_volume *
                 (q[0][i] * g[j] + q[1][i] * g[3 + j] + q[2][i] * g[6 + j] + q[3][i] * g[9 + j]);
    for (int m = 1; m < 8; ++m)
      fm[i][m] = s[0] * beta[3 * (m - 1)] + s[1] * beta[3 * (m - 1) + 1] + s[2] * beta[3 * (m - 1) + 2];
    for (int alpha = 0; alpha < 4; ++alpha) fm[i][4 + alpha] += k * q[alpha][i];
  }
  f.x = hex8::nodal_from_modes(fm[0]);
  f.y = hex8::nodal_from_modes(fm[1]);
  f.z = hex8::nodal_from_modes(fm[2]);
  return result;
}

}  // namespace hex8r

}  // namespace exdyn::element
