// The element side of a material law (material/material_law.hpp): from the
// displacement gradients H_g = du/dX at an element's integration points to the
// weighted first Piola-Kirchhoff stresses w_g P_g that the element turns into nodal
// forces f_I = sum_g w_g P_g dN_I/dX (total Lagrangian on the reference
// configuration). docs/theory.md, "Finite strain".
//   small:  P = sigma(sym H), the point law of material/j2.hpp (update_small);
//   finite: F = I + H, tau from update_finite, P = tau F^-T. With F-bar (hex8) the
//     volume ratio of every point is the element's J_bar = sum w J_g / sum w, and
//     P_g = (s_g + K J_g (J_bar - 1) I) F_g^-T: the derivative of
//     V0 U(J_bar) + sum_g w_g W_iso(F_g), so the forces stay conservative.
// Real is one element (double) or a pack of elements (Pack<L>), the point states
// interleaved by lane: point g's state starts at state + g * state_size * L.
#pragma once

#include <array>

#include "common/simd_pack.hpp"
#include "element/element_block.hpp"
#include "material/material_law.hpp"

namespace exdyn::element {

template <class Real>
struct ConstitutiveResult {
  std::array<Real, 6> mean_stress{};  // Cauchy, volume average over the current element, Pa
  Real internal{};                    // stored elastic energy + plastic work, J
  Real plastic{};                     // plastic work, J
  Real eps_p{};                       // reference-volume average of the equivalent plastic strain
};

// The flow rule object of a law, for a loop instantiated on Flow.
template <class Flow>
const Flow& flow_of(const material::MaterialLaw& law) {
  if constexpr (std::is_same_v<Flow, material::Hardening>) {
    return law.hardening;
  } else if constexpr (std::is_same_v<Flow, material::JohnsonCook>) {
    return law.johnson_cook;
  } else {
    return law.no_yield;
  }
}

// h[g]: H at point g (row-major); w[g]: w_g det J0_g (m^3); writes w_g P_g over h[g].
template <class Flow, bool Finite, int Points, class Real>
ConstitutiveResult<Real> integrate_points(const material::ElasticConstants& elastic, const Flow& flow,
                                          bool f_bar, std::array<std::array<Real, 9>, Points>& h,
                                          const std::array<Real, Points>& w, const double* state_old,
                                          double* state_new, double dt) {
  constexpr int lanes = lanes_of<Real>;
  constexpr int state_stride = Flow::plastic ? material::j2_state_size * lanes : 0;
  ConstitutiveResult<Real> out;
  Real volume{}, current_volume{};
  if constexpr (!Finite) {
    for (int g = 0; g < Points; ++g) {
      const material::PointResponse<Real> r = material::update_small(
          elastic, flow, h[g], state_old + g * state_stride, state_new + g * state_stride, dt);
      const Real wg = w[g];
      volume += wg;
      for (int k = 0; k < 6; ++k) out.mean_stress[k] += wg * r.stress[k];
      out.internal += wg * (r.elastic_energy + r.plastic_work);
      out.plastic += wg * r.plastic_work;
      out.eps_p += wg * r.eps_p;
      const std::array<Real, 6>& s = r.stress;
      h[g] = {wg * s[0], wg * s[3], wg * s[5], wg * s[3], wg * s[1],
              wg * s[4], wg * s[5], wg * s[4], wg * s[2]};
    }
    current_volume = volume;
  } else {
    std::array<Real, Points> det;
    for (int g = 0; g < Points; ++g) {
      std::array<Real, 9>& f = h[g];
      f[0] += 1.0, f[4] += 1.0, f[8] += 1.0;  // F = I + H
      det[g] = f[0] * (f[4] * f[8] - f[5] * f[7]) - f[1] * (f[3] * f[8] - f[5] * f[6]) +
               f[2] * (f[3] * f[7] - f[4] * f[6]);
      volume += w[g];
      current_volume += w[g] * det[g];
    }
    const Real j_bar = current_volume / volume;
    const double bulk = elastic.bulk_modulus();
    for (int g = 0; g < Points; ++g) {
      std::array<Real, 9>& f = h[g];
      const Real jv = f_bar ? j_bar : det[g];
      // F^-T = cof(F) / J, cof(F)_jk = d det F / d F_jk: for P = tau F^-T and for the law.
      const Real inverse_det = 1.0 / det[g];
      const std::array<Real, 9> f_inverse_transpose = {
          (f[4] * f[8] - f[5] * f[7]) * inverse_det, (f[5] * f[6] - f[3] * f[8]) * inverse_det,
          (f[3] * f[7] - f[4] * f[6]) * inverse_det, (f[2] * f[7] - f[1] * f[8]) * inverse_det,
          (f[0] * f[8] - f[2] * f[6]) * inverse_det, (f[1] * f[6] - f[0] * f[7]) * inverse_det,
          (f[1] * f[5] - f[2] * f[4]) * inverse_det, (f[2] * f[3] - f[0] * f[5]) * inverse_det,
          (f[0] * f[4] - f[1] * f[3]) * inverse_det};
      const material::PointResponse<Real> r = material::update_finite(
          elastic, flow, f, f_inverse_transpose, jv, material::inverse_cube_root_squared(det[g]),
          state_old + g * state_stride, state_new + g * state_stride, dt);
      const Real wg = w[g];
      // tau_eff = tau + K (J_g - J_v)(J_v - 1) I: the F-bar pressure term (0 without it).
      const Real shift = bulk * (det[g] - jv) * (jv - 1.0);
      const Real t[3][3] = {{r.stress[0] + shift, r.stress[3], r.stress[5]},
                            {r.stress[3], r.stress[1] + shift, r.stress[4]},
                            {r.stress[5], r.stress[4], r.stress[2] + shift}};
      for (int k = 0; k < 3; ++k) out.mean_stress[k] += wg * t[k][k];
      out.mean_stress[3] += wg * t[0][1], out.mean_stress[4] += wg * t[1][2],
          out.mean_stress[5] += wg * t[0][2];
      out.internal += wg * (r.elastic_energy + r.plastic_work);
      out.plastic += wg * r.plastic_work;
      out.eps_p += wg * r.eps_p;
      // w P = w tau_eff F^-T.
      const std::array<Real, 9>& fit = f_inverse_transpose;
      std::array<Real, 9> p;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          p[3 * i + j] = wg * (t[i][0] * fit[j] + t[i][1] * fit[3 + j] + t[i][2] * fit[6 + j]);
      h[g] = p;
    }
  }
  const Real inverse_current = 1.0 / current_volume;
  for (int k = 0; k < 6; ++k) out.mean_stress[k] *= inverse_current;  // sum w tau / sum w J
  out.eps_p *= 1.0 / volume;
  return out;
}

// The one place where a law's flow rule and kinematics become a loop: choose is a
// lambda template<class Flow, bool Finite> returning a family's loop for them (the
// family then picks the ISA). Small-strain linear elasticity has the linear kernels.
template <class Choose>
ElementLoopFn law_loop(const material::MaterialLaw& law, const Choose& choose) {
  using namespace material;
  switch (law.flow) {
    case FlowRule::none:
      break;
    case FlowRule::hardening:
      return law.finite ? choose.template operator()<Hardening, true>()
                        : choose.template operator()<Hardening, false>();
    case FlowRule::johnson_cook:
      return law.finite ? choose.template operator()<JohnsonCook, true>()
                        : choose.template operator()<JohnsonCook, false>();
  }
  return choose.template operator()<NoYield, true>();
}

// Writes the packs' mean equivalent plastic strains to the block's per-element array.
template <class Real>
void store_plastic_strain(const ElementBlock& block, std::uint32_t pack, const Real& eps_p) {
  double* out = block.material_state.plastic_strain.data();
  for (int l = 0; l < lanes_of<Real>; ++l) {
    const std::uint32_t element = std::uint32_t(lanes_of<Real>) * pack + std::uint32_t(l);
    if (element < block.count) out[element] = lane(eps_p, l);
  }
}

// The committed and the written point states of a pack (points per element, Flow's size).
template <class Flow, int Lanes>
struct PackStates {
  const double* old_state;
  double* new_state;
  static constexpr std::size_t per_pack(int points) {
    return Flow::plastic ? std::size_t(Lanes) * std::size_t(points) * material::j2_state_size : 0;
  }
  PackStates(const ElementBlock& block, std::uint32_t pack, int points) {
    MaterialState& s = block.material_state;
    const std::size_t offset = per_pack(points) * pack;
    old_state = Flow::plastic ? s.points[std::size_t(s.committed)].data() + offset : nullptr;
    new_state = Flow::plastic ? s.points[std::size_t(s.committed ^ 1)].data() + offset : nullptr;
  }
};

}  // namespace exdyn::element
