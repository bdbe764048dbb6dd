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
#include "element/hourglass.hpp"

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
  const OnePoint<Real> point = one_point(reference, hex8::modes_from_nodal(u));
  const Real volume = load<Real>(reference, 33), k = load<Real>(reference, 35);
  Real force[4][3];
  Real q_squared{};
  for (int alpha = 0; alpha < 4; ++alpha)
    for (int i = 0; i < 3; ++i) {
      force[alpha][i] = k * point.q[alpha][i];
      q_squared += point.q[alpha][i] * point.q[alpha][i];
    }
  hourglass_energy = 0.5 * k * q_squared;
  std::array<std::array<Real, 9>, 1> h{point.h};
  const std::array<Real, 1> w{volume};
  const ConstitutiveResult<Real> result =
      integrate_points<Flow, Finite, 1>(elastic, flow, false, h, w, state_old, state_new, dt);
  one_point_forces(point, h[0], force, f);  // h[0] is now V P
  return result;
}

// The hourglass state per element (assumed-strain law kernel): the plastic parts
// P^_alpha,j of the forces (12, N, element axes), the amplitudes q^_alpha,j they were
// last updated to (12, m) and the hourglass work so far (1, J).
inline constexpr int hourglass_state_size = 25;

// hex8r with the assumed-strain hourglass control (hourglass.hpp) under a law: the
// mean-gradient point as constitutive_forces, and the hourglass forces in rate form on
// the element's axes T, with k and Q_p of its current shape (the reference one in
// small strain):
//   q^_alpha = T^T q_alpha
//   P^ = clamp(P^_old + (1 - beta) k (q^ - q^_old), -Q_p, Q_p),
//   Q_p = limit sqrt(max(sigma_y(eps_p)^2 - sigma_vm^2, 0))    (what the mean stress leaves)
//   Q^ = P^ + beta k q^,  Q_alpha = T Q^_alpha   (f_I = sum_alpha gamma_alpha,I Q_alpha)
// beta = hourglass::elastic_share. The axes turn with the element, so P^ and q^ do not
// change under a rigid rotation; the clamp makes the modes' plastic parts perfectly
// plastic (NoYield: no clamp, Q^ = k q^). The hourglass work
// W += (Q^_old + Q^) . (q^ - q^_old) / 2 is reported as the hourglass energy: stored and
// dissipated together.
template <class Flow, bool Finite, class Real>
inline ConstitutiveResult<Real> assumed_strain_forces(const double* reference,
                                                      const material::ElasticConstants& elastic,
                                                      const Flow& flow, const BasicElementVectors<Real>& u,
                                                      BasicElementVectors<Real>& f, const double* state_old,
                                                      double* state_new, const double* hourglass_old,
                                                      double* hourglass_new, double dt,
                                                      Real& hourglass_energy) {
  constexpr int lanes = lanes_of<Real>;
  const hex8::BasicElementModes<Real> c = hex8::modes_from_nodal(u);
  const OnePoint<Real> point = one_point(reference, c);
  const Real volume = load<Real>(reference, 33);
  std::array<std::array<Real, 9>, 1> h{point.h};
  const auto& q = point.q;
  // The element's shape: c_j of the coordinates, current (finite) or reference (small).
  Real shape[3][3];
  Real shape_volume = volume;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      shape[j][i] = load<Real>(reference, 35 + 3 * j + i);
      if constexpr (Finite) shape[j][i] += c[1 + j][i];
    }
  if constexpr (Finite) {
    const std::array<Real, 9>& d = h[0];  // V_current = V det(I + H)
    const Real f0 = d[0] + 1.0, f4 = d[4] + 1.0, f8 = d[8] + 1.0;
    shape_volume = volume * (f0 * (f4 * f8 - d[5] * d[7]) - d[1] * (d[3] * f8 - d[5] * d[6]) +
                             d[2] * (d[3] * d[7] - f4 * d[6]));
  }
  Real axes[9], inverse_a2[3], k[12], limit[12];
  hourglass::element_axes(shape, axes, inverse_a2);
  hourglass::mode_constants(inverse_a2, shape_volume, load<Real>(reference, 44), load<Real>(reference, 45), k,
                            limit);
  const std::array<Real, 1> w{volume};
  const ConstitutiveResult<Real> result =
      integrate_points<Flow, Finite, 1>(elastic, flow, false, h, w, state_old, state_new, dt);
  // What the mean stress leaves to the modes, sqrt(sigma_y^2 - sigma_vm^2) (Pa), and so
  // the limit of each mode's plastic part.
  Real reserve{};
  if constexpr (Flow::plastic) {
    const Real yield = flow.yield_at(result.eps_p);
    const std::array<Real, 6>& t = result.mean_stress;
    const Real pressure = (1.0 / 3.0) * (t[0] + t[1] + t[2]);
    const Real s0 = t[0] - pressure, s1 = t[1] - pressure, s2 = t[2] - pressure;
    const Real vm2 = 1.5 * (s0 * s0 + s1 * s1 + s2 * s2 + 2.0 * (t[3] * t[3] + t[4] * t[4] + t[5] * t[5]));
    reserve = lane_sqrt(lane_max(yield * yield - vm2, Real{}));
  }
  constexpr double kept = hourglass::elastic_share, limited = 1.0 - hourglass::elastic_share;
  Real work = load<Real>(hourglass_old, 24);
  Real force[4][3];
  for (int alpha = 0; alpha < 4; ++alpha) {
    Real local[3];
    for (int j = 0; j < 3; ++j) {
      const int index = 3 * alpha + j;
      const Real amplitude = axes[j] * q[alpha][0] + axes[3 + j] * q[alpha][1] + axes[6 + j] * q[alpha][2];
      const Real old_amplitude = load<Real>(hourglass_old, 12 + index);
      const Real old_plastic = load<Real>(hourglass_old, index);
      const Real change = amplitude - old_amplitude;
      Real next = old_plastic + (limited * k[index]) * change;
      if constexpr (Flow::plastic) {
        const Real cap = reserve * limit[index];
        next = lane_max(-cap, -lane_max(-next, -cap));  // clamp to [-cap, cap]
      }
      const Real total = next + (kept * k[index]) * amplitude;
      const Real old_total = old_plastic + (kept * k[index]) * old_amplitude;
      work += 0.5 * (old_total + total) * change;
      store(hourglass_new + lanes * index, next);
      store(hourglass_new + lanes * (12 + index), amplitude);
      local[j] = total;
    }
    for (int i = 0; i < 3; ++i)
      force[alpha][i] = axes[3 * i] * local[0] + axes[3 * i + 1] * local[1] + axes[3 * i + 2] * local[2];
  }
  store(hourglass_new + lanes * 24, work);
  hourglass_energy = work;
  one_point_forces(point, h[0], force, f);  // h[0] is now V P
  return result;
}

}  // namespace hex8r

}  // namespace exdyn::element
