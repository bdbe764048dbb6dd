// Von Mises plasticity with isotropic hardening at one integration point, for small
// strain and for large deformation, around a flow rule that gives the plastic strain
// increment of a step (NoYield in elastic.hpp, Hardening in elastic_plastic.hpp,
// JohnsonCook in johnson_cook.hpp). docs/theory.md, "Materials" and "Finite strain".
//
// Small strain (additive split, radial return):
//   sigma_tr = lambda tr(eps - eps_p) I + 2 G (eps - eps_p),  q_tr = sqrt(3/2 s_tr : s_tr)
//   d = flow.increment(q_tr, 3 G, eps_bar_p, dt),  sigma = sigma_tr - 3 G d s_tr / q_tr
//   eps_p += (3/2) d s_tr / q_tr
// Finite strain (Simo 1992, multiplicative split, hyperelastic in the Kirchhoff stress):
//   J = det F, b_e_tr = J^(-2/3) F Cp^-1 F^T (isochoric), mu_bar = G tr(b_e_tr) / 3
//   s_tr = G dev(b_e_tr), d = flow.increment(q_tr, 3 mu_bar, ...), s = s_tr (1 - 3 mu_bar d / q_tr)
//   b_e = s / G + (tr b_e_tr / 3) I,  Cp^-1 = J^(2/3) F^-1 b_e F^-T
//   tau = K J_v (J_v - 1) I + s (U(J) = K/2 (J - 1)^2, J_v the volume ratio the element
//   supplies: J, or the element mean for F-bar), Cauchy sigma = tau / J.
// Rigid rotations leave b_e, s and so the stress unchanged: objective exactly.
//
// State per point (state_size doubles): the plastic strain tensor (small) or the
// isochoric inverse plastic right Cauchy-Green tensor Cp^-1 (finite), xx yy zz xy yz
// xz; the equivalent plastic strain eps_bar_p; the plastic work per reference volume
// (J/m^3); the deviatoric stress s (Cauchy, or Kirchhoff for finite; Pa) the step
// ended with; finite strain, F and tr b_e / 3 the step ended with (unused under small
// strain).
// The plastic work takes the trapezoid of the step, W_p += (sigma_n + sigma_n+1)/2 :
// d eps_p with d eps_p = (3/2) d s_tr / q_tr, so W_p += d (q_n+1 + (3/2) s_n : s_tr /
// q_tr) / 2: the rule of the central difference's work (f_n + f_n+1)/2 . du, under which
// the stored energy plus W_p is the work the stresses did, to round-off for small strain
// (docs/theory.md, "Energy"). The backward sum q_n+1 d misses (sigma_n - sigma_n+1)/2 :
// d eps_p a step, first order: 8e-4 of the plane plastic wave's energy. Finite strain
// takes the same trapezoid on P : dF (finite_plastic_work_increment). A Real is one
// point (double) or the points of a pack of elements (Pack<L>, their states
// interleaved: load<Real>).
#pragma once

#include <array>

#include "common/simd_pack.hpp"
#include "material/elastic.hpp"

namespace exdyn::material {

inline constexpr int j2_state_size = 24;
inline constexpr int state_eps_p = 6;         // equivalent plastic strain
inline constexpr int state_plastic_work = 7;  // J/m^3
inline constexpr int state_deviator = 8;      // s at the end of the step, 6 values, Pa
// Finite strain only: F the step ended at (9 values, row-major) and the mean trace
// tr b_e / 3 of its isochoric elastic b_e, for the next step's plastic work.
inline constexpr int state_deformation = 14;
inline constexpr int state_mean_trace = 23;

// The state of a point before any load: eps_p = 0 (small) or Cp^-1 = I, F = I (finite).
inline void initial_state(bool finite, double* state) {
  for (int k = 0; k < j2_state_size; ++k) state[k] = 0.0;
  if (finite) {
    state[0] = state[1] = state[2] = 1.0;
    state[state_deformation] = state[state_deformation + 4] = state[state_deformation + 8] = 1.0;
    state[state_mean_trace] = 1.0;
  }
}

// What a point's update returns.
template <class Real>
struct PointResponse {
  std::array<Real, 6> stress;  // small: sigma; finite: tau (Kirchhoff), Pa; xx yy zz xy yz xz
  Real elastic_energy{};       // stored energy per reference volume, J/m^3
  Real plastic_work{};         // total plastic work per reference volume, J/m^3
  Real eps_p{};                // equivalent plastic strain
};

namespace detail {
// 1 - 3 mu d / q (1 where q = 0, where d = 0 too).
template <class Real>
inline Real return_factor(const Real& three_mu, const Real& d, const Real& q) {
  const Real safe_q = select(q > 0.0, q, Real{} + 1.0);
  return 1.0 - three_mu * d / safe_q;
}
template <class Real>
inline Real von_mises_of_deviator(const std::array<Real, 6>& s) {
  return lane_sqrt(1.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) +
                   3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}
// The step's plastic work per reference volume by the trapezoid (above), J/m^3: the
// trial deviator s_tr, its q_tr, the increment d and the return's factor (s = factor
// s_tr); the old deviator from state_old.
template <class Real>
inline Real plastic_work_increment(const std::array<Real, 6>& s_trial, const Real& q, const Real& d,
                                   const Real& factor, const double* state_old) {
  Real old_dot_trial{};  // s_n : s_tr
  for (int k = 0; k < 6; ++k)
    old_dot_trial += (k < 3 ? 1.0 : 2.0) * load<Real>(state_old, state_deviator + k) * s_trial[k];
  const Real safe_q = select(q > 0.0, q, Real{} + 1.0);
  return 0.5 * d * (factor * q + 1.5 * old_dot_trial / safe_q);
}
// Finite strain: the work of the step by the trapezoid, as the element's forces do it
// (f^n + f^{n+1})/2 . du = sum_g w_g (P^n + P^{n+1})/2 : (F^{n+1} - F^n): of the
// isochoric part P = s F^-T, with tr s = 0 and R = F^{n+1} (F^n)^-1,
//   (s_n F_n^-T + s F^-T)/2 : (F - F_n) = (s_n : R - s : R^-1) / 2,
// less the change of the isochoric stored energy 3 G / 2 (i1 - i1_n): the plastic work
// of the step, so that the stored energy plus W_p is the trapezoid's work to round-off
// at the point (the volumetric part is elastic: U(J) against its trapezoid). f: F,
// g: F^-1, s: the returned deviator, i1 its b_e's mean trace; F_n, s_n and i1_n from
// state_old.
template <class Real>
inline Real finite_plastic_work_increment(double mu, const std::array<Real, 9>& f, const Real (&g)[9],
                                          const std::array<Real, 6>& s, const Real& i1,
                                          const double* state_old) {
  Real fo[9];  // F_n
  for (int k = 0; k < 9; ++k) fo[k] = load<Real>(state_old, state_deformation + k);
  const Real det_old = fo[0] * (fo[4] * fo[8] - fo[5] * fo[7]) - fo[1] * (fo[3] * fo[8] - fo[5] * fo[6]) +
                       fo[2] * (fo[3] * fo[7] - fo[4] * fo[6]);
  const Real inv = 1.0 / det_old;
  const Real go[9] = {(fo[4] * fo[8] - fo[5] * fo[7]) * inv, (fo[2] * fo[7] - fo[1] * fo[8]) * inv,
                      (fo[1] * fo[5] - fo[2] * fo[4]) * inv, (fo[5] * fo[6] - fo[3] * fo[8]) * inv,
                      (fo[0] * fo[8] - fo[2] * fo[6]) * inv, (fo[2] * fo[3] - fo[0] * fo[5]) * inv,
                      (fo[3] * fo[7] - fo[4] * fo[6]) * inv, (fo[1] * fo[6] - fo[0] * fo[7]) * inv,
                      (fo[0] * fo[4] - fo[1] * fo[3]) * inv};  // F_n^-1
  Real r[9], r_inverse[9];                                     // R = F F_n^-1, R^-1 = F_n F^-1
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      r[3 * i + j] = f[3 * i] * go[j] + f[3 * i + 1] * go[3 + j] + f[3 * i + 2] * go[6 + j];
      r_inverse[3 * i + j] = fo[3 * i] * g[j] + fo[3 * i + 1] * g[3 + j] + fo[3 * i + 2] * g[6 + j];
    }
  // s : A for a symmetric s (xx yy zz xy yz xz) and any A.
  const auto contract = [](const auto& t, const Real(&a)[9]) {
    return t[0] * a[0] + t[1] * a[4] + t[2] * a[8] + t[3] * (a[1] + a[3]) + t[4] * (a[5] + a[7]) +
           t[5] * (a[2] + a[6]);
  };
  std::array<Real, 6> s_old;
  for (int k = 0; k < 6; ++k) s_old[k] = load<Real>(state_old, state_deviator + k);
  return 0.5 * (contract(s_old, r) - contract(s, r_inverse)) -
         (1.5 * mu) * (i1 - load<Real>(state_old, state_mean_trace));
}
template <class Real>
inline void store_deviator(const std::array<Real, 6>& s, double* state_new) {
  for (int k = 0; k < 6; ++k) store(state_new + lanes_of<Real> * (state_deviator + k), s[k]);
}
}  // namespace detail

// The flow's increment d of eps_p; a flow that softens with the plastic work
// (johnson_cook's thermal softening) gets the point's W_p at the start of the step.
template <class Flow, class Real>
inline Real flow_increment(const Flow& flow, const Real& q, const Real& three_mu, const Real& alpha,
                           double dt, const double* state_old) {
  if constexpr (requires { flow.increment(q, three_mu, alpha, dt, q); })
    return flow.increment(q, three_mu, alpha, dt, load<Real>(state_old, state_plastic_work));
  else
    return flow.increment(q, three_mu, alpha, dt);
}

// Small strain: h = du/dx (row-major 9); old/new states as above.
template <class Flow, class Real>
inline PointResponse<Real> update_small(const ElasticConstants& elastic, const Flow& flow,
                                        const std::array<Real, 9>& h, const double* state_old,
                                        double* state_new, double dt) {
  std::array<Real, 6> eps_e = {
      h[0], h[4], h[8], 0.5 * (h[1] + h[3]), 0.5 * (h[5] + h[7]), 0.5 * (h[2] + h[6])};
  std::array<Real, 6> eps_p;
  for (int k = 0; k < 6; ++k) eps_p[k] = load<Real>(state_old, k), eps_e[k] -= eps_p[k];
  const Real trace = eps_e[0] + eps_e[1] + eps_e[2];
  const double two_mu = 2.0 * elastic.mu, three_mu = 3.0 * elastic.mu;
  const Real mean = (1.0 / 3.0) * trace;
  std::array<Real, 6> s = {two_mu * (eps_e[0] - mean), two_mu * (eps_e[1] - mean), two_mu * (eps_e[2] - mean),
                           two_mu * eps_e[3],          two_mu * eps_e[4],          two_mu * eps_e[5]};
  const Real q = detail::von_mises_of_deviator(s);
  const Real alpha = load<Real>(state_old, state_eps_p);
  const Real d = flow_increment(flow, q, Real{} + three_mu, alpha, dt, state_old);
  const Real factor = detail::return_factor(Real{} + three_mu, d, q);
  // eps_p += (3/2) d s_tr / q = (1 - factor) s_tr / (2 G)
  const Real plastic_scale = (1.0 - factor) * (1.0 / two_mu);
  PointResponse<Real> out;
  out.plastic_work =
      load<Real>(state_old, state_plastic_work) + detail::plastic_work_increment(s, q, d, factor, state_old);
  const Real pressure = elastic.bulk_modulus() * trace;
  for (int k = 0; k < 6; ++k) {
    eps_p[k] += plastic_scale * s[k];
    eps_e[k] -= plastic_scale * s[k];
    s[k] *= factor;
    out.stress[k] = s[k] + (k < 3 ? pressure : Real{});
    store(state_new + lanes_of<Real> * k, eps_p[k]);
  }
  out.eps_p = alpha + d;
  store(state_new + lanes_of<Real> * state_eps_p, out.eps_p);
  store(state_new + lanes_of<Real> * state_plastic_work, out.plastic_work);
  detail::store_deviator(s, state_new);
  out.elastic_energy =
      0.5 * (out.stress[0] * eps_e[0] + out.stress[1] * eps_e[1] + out.stress[2] * eps_e[2] +
             2.0 * (out.stress[3] * eps_e[3] + out.stress[4] * eps_e[4] + out.stress[5] * eps_e[5]));
  return out;
}

// Finite strain: f = F (row-major 9), f_inverse_transpose = F^-T, volume_ratio = J_v
// (J, or the element's mean for F-bar); jm23 = J^(-2/3) of F itself (the caller has
// them for the pack: the element forms F^-T for its forces anyway).
// Without a plastic flow (NoYield) the state is neither read nor written.
template <class Flow, class Real>
inline PointResponse<Real> update_finite(const ElasticConstants& elastic, const Flow& flow,
                                         const std::array<Real, 9>& f,
                                         const std::array<Real, 9>& f_inverse_transpose,
                                         const Real& volume_ratio, const Real& jm23, const double* state_old,
                                         double* state_new, double dt) {
  // c = Cp^-1 (symmetric), then b = J^(-2/3) F c F^T.
  std::array<Real, 6> c;
  if constexpr (Flow::plastic) {
    for (int k = 0; k < 6; ++k) c[k] = load<Real>(state_old, k);
  } else {
    c = {Real{} + 1.0, Real{} + 1.0, Real{} + 1.0, Real{}, Real{}, Real{}};
  }
  const Real cm[3][3] = {{c[0], c[3], c[5]}, {c[3], c[1], c[4]}, {c[5], c[4], c[2]}};
  Real fc[3][3];  // F c
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      fc[i][j] = f[3 * i] * cm[0][j] + f[3 * i + 1] * cm[1][j] + f[3 * i + 2] * cm[2][j];
  const auto b_entry = [&](int i, int j) {
    return jm23 * (fc[i][0] * f[3 * j] + fc[i][1] * f[3 * j + 1] + fc[i][2] * f[3 * j + 2]);
  };
  std::array<Real, 6> b = {b_entry(0, 0), b_entry(1, 1), b_entry(2, 2),
                           b_entry(0, 1), b_entry(1, 2), b_entry(0, 2)};
  Real i1 = (1.0 / 3.0) * (b[0] + b[1] + b[2]);
  const double mu = elastic.mu;
  std::array<Real, 6> s = {mu * (b[0] - i1), mu * (b[1] - i1), mu * (b[2] - i1),
                           mu * b[3],        mu * b[4],        mu * b[5]};
  PointResponse<Real> out;
  const Real jv = volume_ratio;
  const Real tau_volumetric = elastic.bulk_modulus() * jv * (jv - 1.0);
  if constexpr (Flow::plastic) {
    const Real q = detail::von_mises_of_deviator(s);
    const Real three_mu_bar = (3.0 * mu) * i1;
    const Real alpha = load<Real>(state_old, state_eps_p);
    const Real d = flow_increment(flow, q, three_mu_bar, alpha, dt, state_old);
    const Real factor = detail::return_factor(three_mu_bar, d, q);
    for (int k = 0; k < 6; ++k) s[k] *= factor;
    // b_e = s / G + x I with x such that det b_e = 1 (the isochoric b_e of Simo's
    // update keeps its volume; without it the trace, and so the stored energy
    // G/2 (tr b_e - 3), stays at the trial's after the return): det(d + x I) =
    // x^3 - (tr d^2 / 2) x + det d = 1, Newton from x = i1, quadratic from the start.
    const double inv_mu_d = 1.0 / mu;
    const Real dd[6] = {s[0] * inv_mu_d, s[1] * inv_mu_d, s[2] * inv_mu_d,
                        s[3] * inv_mu_d, s[4] * inv_mu_d, s[5] * inv_mu_d};
    const Real half_trace_d2 =
        0.5 * (dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]) + dd[3] * dd[3] + dd[4] * dd[4] + dd[5] * dd[5];
    const Real det_d = dd[0] * (dd[1] * dd[2] - dd[4] * dd[4]) - dd[3] * (dd[3] * dd[2] - dd[4] * dd[5]) +
                       dd[5] * (dd[3] * dd[4] - dd[1] * dd[5]);
    for (int iteration = 0; iteration < 3; ++iteration)
      i1 = i1 - (i1 * i1 * i1 - half_trace_d2 * i1 + det_d - 1.0) / (3.0 * i1 * i1 - half_trace_d2);
    out.eps_p = alpha + d;
    out.plastic_work = load<Real>(state_old, state_plastic_work);
    // Cp^-1 = J^(2/3) F^-1 b_e F^-T with b_e = s / G + i1 I; unchanged where d = 0
    // (no drift of an elastic point's state by round-off).
    const auto yielded = d > 0.0;
    if (any_lane(yielded)) {
      const std::array<Real, 9>& fit = f_inverse_transpose;
      const Real g[9] = {fit[0], fit[3], fit[6], fit[1], fit[4], fit[7], fit[2], fit[5], fit[8]};  // F^-1
      const double inv_mu = 1.0 / mu;
      const Real be[3][3] = {{s[0] * inv_mu + i1, s[3] * inv_mu, s[5] * inv_mu},
                             {s[3] * inv_mu, s[1] * inv_mu + i1, s[4] * inv_mu},
                             {s[5] * inv_mu, s[4] * inv_mu, s[2] * inv_mu + i1}};
      Real gb[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          gb[i][j] = g[3 * i] * be[0][j] + g[3 * i + 1] * be[1][j] + g[3 * i + 2] * be[2][j];
      const Real j23 = 1.0 / jm23;
      const auto c_entry = [&](int i, int j) {
        return j23 * (gb[i][0] * g[3 * j] + gb[i][1] * g[3 * j + 1] + gb[i][2] * g[3 * j + 2]);
      };
      const std::array<Real, 6> c_new = {c_entry(0, 0), c_entry(1, 1), c_entry(2, 2),
                                         c_entry(0, 1), c_entry(1, 2), c_entry(0, 2)};
      for (int k = 0; k < 6; ++k) c[k] = select(yielded, c_new[k], c[k]);
      out.plastic_work =
          out.plastic_work +
          select(yielded, detail::finite_plastic_work_increment(mu, f, g, s, i1, state_old), Real{});
    }
    for (int k = 0; k < 6; ++k) store(state_new + lanes_of<Real> * k, c[k]);
    for (int k = 0; k < 9; ++k) store(state_new + lanes_of<Real> * (state_deformation + k), f[k]);
    store(state_new + lanes_of<Real> * state_mean_trace, i1);
    store(state_new + lanes_of<Real> * state_eps_p, out.eps_p);
    store(state_new + lanes_of<Real> * state_plastic_work, out.plastic_work);
    detail::store_deviator(s, state_new);
  } else {
    (void)state_old, (void)state_new, (void)dt, (void)flow, (void)f_inverse_transpose;
  }
  for (int k = 0; k < 6; ++k) out.stress[k] = s[k] + (k < 3 ? tau_volumetric : Real{});
  // W = K/2 (J_v - 1)^2 + G/2 (tr b_e - 3), tr b_e = 3 i1 (s is deviatoric; i1 the
  // volume-preserving one after a return).
  out.elastic_energy = (0.5 * elastic.bulk_modulus()) * (jv - 1.0) * (jv - 1.0) + (1.5 * mu) * (i1 - 1.0);
  return out;
}

// J^(-2/3) lane by lane without a libm call: y = J^(-1/3) by Newton's division-free
// iteration y <- y (4 - J y^3) / 3 from a Taylor start about J = 1, then y^2. Lanes
// whose J lies outside [0.5, 2] (far beyond what an element survives) use std::cbrt.
template <class Real>
inline Real inverse_cube_root_squared(const Real& j) {
  const Real e = j - 1.0;
  Real y = 1.0 - e * (1.0 / 3.0) + e * e * (2.0 / 9.0);
  for (int k = 0; k < 6; ++k) y = y * (4.0 - j * y * y * y) * (1.0 / 3.0);
  const auto outside = (j < 0.5) | (j > 2.0);
  if (any_lane(outside)) {
    for (int l = 0; l < lanes_of<Real>; ++l) {
      const double v = lane(j, l);
      if (v < 0.5 || v > 2.0) set_lane(y, l, v > 0.0 ? 1.0 / __builtin_cbrt(v) : 0.0);
    }
  }
  return y * y;
}

}  // namespace exdyn::material
