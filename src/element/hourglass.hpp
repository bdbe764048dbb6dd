// The assumed-strain hourglass control of the one-point brick (docs/theory.md,
// "Assumed-strain hourglass control"): a physical stiffness for each hourglass mode
// and direction, from the strain field that the mode is in a rectangular brick, in
// the spirit of Belytschko and Bindeman (1993, CMAME 105, 225-260) and Puso (2000,
// IJNME 49, 1029-1064), and a plastic limit from the same field at the flow stress.
//
// Element axes: T = [t_0 t_1 t_2] from c_1, c_2, c_3 by Gram-Schmidt (x = c_0 +
// c_1 xi + c_2 eta + c_3 zeta + ..., the modes of the coordinates), half lengths
// a_j = |c_j| (m), volume V (m^3); on the current configuration under finite strain. Hourglass modes alpha =
// 0..3 are eta zeta, xi zeta, xi eta, xi eta zeta; a displacement u = c t_j h_alpha has the amplitude q =
// h_alpha . u = 8 c along t_j.
//   bending   (alpha = 0..2, j one of the mode's two coordinates, r the other):
//       eps_jj = c xi_r / a_j  -> uniaxial stress, E:
//       k = E V / (192 a_j^2),      Q_p = sigma_y V / (8 sqrt(3) a_j)
//     the shear eps_jr the bilinear field carries with it is the parasitic one of
//     shear locking and is left out: an element of the field u_x = kappa x y,
//     u_y = -kappa x^2 / 2 then stores E I kappa^2 L / 2, beam theory's energy.
//   warping   (alpha = 0..2, j not in the mode, p and r the mode's coordinates):
//       eps_jp = c xi_r / (2 a_p), eps_jr = c xi_p / (2 a_r):
//       k = mu V (1/a_p^2 + 1/a_r^2) / 192,   Q_p = sigma_y V sqrt(1/a_p^2 + 1/a_r^2) / 24
//     (u_j = c xi_p xi_r is a field the trilinear brick holds exactly: its energy).
//   twist     (alpha = 3, j; k and l the other two):
//       k = V (E/a_j^2 + mu (1/a_k^2 + 1/a_l^2)) / 576,
//       Q_p = sigma_y V sqrt(1/a_j^2 + (1/a_k^2 + 1/a_l^2)/3) / 24
//     (E, not lambda + 2 mu, on the normal strain: no volumetric locking).
// k from E_mode = (1/2) k q^2 with q = 8 c; Q_p = sigma_y times the von Mises
// equivalent of the mode's isochoric strain at the 2x2x2 Gauss points, integrated:
// the generalized force at which every Gauss point of a fully integrated brick
// deformed in that mode alone flows.
#pragma once

#include <array>
#include <cmath>

#include "common/simd_pack.hpp"
#include "element/hex8.hpp"

namespace exdyn::element::hourglass {

// The element axes of a configuration from its modes c_1, c_2, c_3 (c[j][i]: component
// i of c_(j+1), m): Gram-Schmidt in the order xi, eta, zeta, t_2 = t_0 x t_1, as the
// columns of T (row-major, T_ij = t_j,i), and 1 / a_j^2 = 1 / |c_j|^2. The axes turn
// with the element, so forces on them are objective.
template <class Real>
inline void element_axes(const Real c[3][3], Real axes[9], Real inverse_a2[3]) {
  for (int j = 0; j < 3; ++j)
    inverse_a2[j] = 1.0 / (c[j][0] * c[j][0] + c[j][1] * c[j][1] + c[j][2] * c[j][2]);
  const Real n0 = lane_sqrt(inverse_a2[0]);
  const Real t0[3] = {n0 * c[0][0], n0 * c[0][1], n0 * c[0][2]};
  const Real along = t0[0] * c[1][0] + t0[1] * c[1][1] + t0[2] * c[1][2];
  Real t1[3] = {c[1][0] - along * t0[0], c[1][1] - along * t0[1], c[1][2] - along * t0[2]};
  const Real n1 = 1.0 / lane_sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (Real& v : t1) v = v * n1;
  const Real t2[3] = {t0[1] * t1[2] - t0[2] * t1[1], t0[2] * t1[0] - t0[0] * t1[2],
                      t0[0] * t1[1] - t0[1] * t1[0]};
  for (int i = 0; i < 3; ++i) {
    axes[3 * i] = t0[i];
    axes[3 * i + 1] = t1[i];
    axes[3 * i + 2] = t2[i];
  }
}

// For mode alpha and direction j (index 3 alpha + j): the stiffness k (N/m, youngs and
// mu already times the coefficient) and the plastic limit per unit flow stress
// Q_p / sigma_y (m^2), from the volume V and 1 / a_j^2 (the formulas above).
template <class Real>
inline void mode_constants(const Real inverse_a2[3], const Real& volume, const Real& youngs, const Real& mu,
                           Real k[12], Real limit[12]) {
  // The two natural coordinates of modes 0..2 (eta zeta, xi zeta, xi eta).
  constexpr int pair[3][2] = {{1, 2}, {0, 2}, {0, 1}};
  const double inverse_8_root3 = 1.0 / (8.0 * std::sqrt(3.0));
  for (int alpha = 0; alpha < 3; ++alpha) {
    const int p = pair[alpha][0], r = pair[alpha][1];
    for (int j = 0; j < 3; ++j) {
      const int index = 3 * alpha + j;
      if (j == p || j == r) {
        k[index] = (1.0 / 192.0) * youngs * volume * inverse_a2[j];
        limit[index] = inverse_8_root3 * volume * lane_sqrt(inverse_a2[j]);
      } else {
        const Real sum = inverse_a2[p] + inverse_a2[r];
        k[index] = (1.0 / 192.0) * mu * volume * sum;
        limit[index] = (1.0 / 24.0) * volume * lane_sqrt(sum);
      }
    }
  }
  for (int j = 0; j < 3; ++j) {
    const Real others = inverse_a2[(j + 1) % 3] + inverse_a2[(j + 2) % 3];
    k[9 + j] = (1.0 / 576.0) * volume * (youngs * inverse_a2[j] + mu * others);
    limit[9 + j] = (1.0 / 24.0) * volume * lane_sqrt(inverse_a2[j] + (1.0 / 3.0) * others);
  }
}

// Under a law with a yield stress, the share of each mode's stiffness that stays
// elastic (total form, never limited); the rest is perfectly plastic. The one-point
// brick's modes are linear in q: without it a mode at its limit lets an element fold
// flat at a constant force (docs/theory.md, "In plastic flow").
inline constexpr double elastic_share = 0.05;

// Per element on its reference configuration: the axes T (9, row-major, columns t_j),
// and k (N/m) and Q_p / sigma_y (m^2) for mode alpha and direction j (3 alpha + j).
struct AssumedStrain {
  Matrix3 axes{};
  std::array<double, 12> stiffness{};
  std::array<double, 12> limit{};
};

// x_modes: the modes of the reference coordinates; youngs and mu in Pa; coefficient
// scales k (1: the physical stiffness).
inline AssumedStrain assumed_strain(const hex8::ElementModes& x_modes, double volume, double youngs,
                                    double mu, double coefficient) {
  AssumedStrain out;
  double c[3][3], inverse_a2[3];
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) c[j][i] = x_modes[1 + j][std::size_t(i)];
  element_axes(c, out.axes.data(), inverse_a2);
  mode_constants(inverse_a2, volume, coefficient * youngs, coefficient * mu, out.stiffness.data(),
                 out.limit.data());
  return out;
}

// The global stiffness of mode alpha, K = sum_j k_j t_j t_j^T (N/m), as xx yy zz xy yz xz.
inline std::array<double, 6> global_stiffness(const AssumedStrain& a, int alpha) {
  std::array<double, 6> k{};
  constexpr int row[6] = {0, 1, 2, 0, 1, 0}, column[6] = {0, 1, 2, 1, 2, 2};
  for (int j = 0; j < 3; ++j) {
    const double kj = a.stiffness[3 * alpha + j];
    for (int s = 0; s < 6; ++s) k[s] += kj * a.axes[3 * row[s] + j] * a.axes[3 * column[s] + j];
  }
  return k;
}

// Q = K q with K as written by global_stiffness (xx yy zz xy yz xz).
template <class Real>
inline std::array<Real, 3> apply(const Real* k, const Real* q) {
  return {k[0] * q[0] + k[3] * q[1] + k[5] * q[2], k[3] * q[0] + k[1] * q[1] + k[4] * q[2],
          k[5] * q[0] + k[4] * q[1] + k[2] * q[2]};
}

}  // namespace exdyn::element::hourglass
