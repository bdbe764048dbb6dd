// The johnson_cook material's flow stress:
//   sigma_y = (A + B eps_p^n) (1 + C ln(max(eps_dot_p / eps_dot_0, 1))) (1 - T*^m)
// with the thermal term where the material has thermal_softening (else 1): the
// adiabatic temperature of the point from its plastic work per reference volume W_p
// at the start of the step, T* = (T - T_r) / (T_m - T_r) = chi W_p / (rho c_p (T_m -
// T_r)), held in [0, 1]. And its return: the plastic strain increment of a step, with
// the rate of that increment over the step (backward Euler). The elasticity, the
// kinematics and the radial return around it are j2.hpp's.
#pragma once

#include <algorithm>
#include <cmath>

#include "common/simd_pack.hpp"

namespace exdyn::material {

struct JohnsonCook {
  static constexpr bool plastic = true;
  double a = 0.0;  // A, Pa
  double b = 0.0;  // B, Pa
  double n = 1.0;
  double c = 0.0;
  double reference_rate = 1.0;  // eps_dot_0, 1/s
  double heating = 0.0;         // chi / (rho c_p (T_m - T_r)): T* per J/m^3 of plastic work; 0: none
  double m = 1.0;               // the thermal exponent

  // 1 - T*^m at the plastic work W_p (J/m^3); 1 without thermal softening.
  double thermal_factor(double plastic_work) const {
    if (heating == 0.0 || !(plastic_work > 0.0)) return 1.0;  // cold: no power to take
    const double t = std::clamp(heating * plastic_work, 0.0, 1.0);
    return 1.0 - std::pow(t, m);
  }

  // sigma_y at plastic strain eps_p (>= 0) and plastic strain rate (1/s), Pa.
  double flow_stress(double eps_p, double rate) const {
    const double strain_part = a + (eps_p > 0.0 ? b * std::pow(eps_p, n) : 0.0);
    const double ratio = rate / reference_rate;
    return strain_part * (ratio > 1.0 ? 1.0 + c * std::log(ratio) : 1.0);
  }

  // The quasi-static sigma_y (rate term 1) at each lane's eps_p, Pa.
  template <class Real>
  Real yield_at(const Real& eps_p) const {
    Real out{};
    for (int l = 0; l < lanes_of<Real>; ++l) set_lane(out, l, flow_stress(lane(eps_p, l), 0.0));
    return out;
  }

  // The increment d >= 0 of eps_p with q_trial - three_mu d = sigma_y(eps_p + d, d / dt)
  // (0 when q_trial <= sigma_y(eps_p, 0)), the thermal factor that of the plastic work
  // W_p of the point at the start of the step (J/m^3); each lane on its own.
  template <class Real>
  Real increment(const Real& q_trial, const Real& three_mu, const Real& eps_p, double dt,
                 const Real& plastic_work) const {
    Real d{};
    for (int l = 0; l < lanes_of<Real>; ++l)
      set_lane(d, l,
               increment_scalar(lane(q_trial, l), lane(three_mu, l), lane(eps_p, l), dt,
                                thermal_factor(lane(plastic_work, l))));
    return d;
  }

  // g(d) = q_trial - three_mu d - sigma_y(eps_p + d, d / dt) falls strictly from g(0) > 0
  // to g(q_trial / three_mu) < 0: Newton's steps kept inside the bracket that the
  // signs of g shrink (bisection where a step would leave it). Converges to a
  // relative 1e-13 of the bracket in a few steps.
  double increment_scalar(double q_trial, double three_mu, double eps_p, double dt,
                          double thermal = 1.0) const {
    const double yield = flow_stress(eps_p, 0.0) * thermal;
    if (q_trial <= yield) return 0.0;
    double low = 0.0, high = q_trial / three_mu;
    double d = std::min(high, (q_trial - yield) / three_mu);
    for (int iteration = 0; iteration < 60; ++iteration) {
      const double e = eps_p + d, rate = d / dt;
      // B e^n, and B n e^(n-1) = n (B e^n) / e from the same power: the power is most
      // of a plastic point's cost.
      const double hardening = e > 0.0 ? b * std::pow(e, n) : 0.0;
      const double strain_part = a + hardening;
      const double ratio = rate / reference_rate;
      const bool rate_active = ratio > 1.0;
      const double rate_part = rate_active ? 1.0 + c * std::log(ratio) : 1.0;
      const double g = q_trial - three_mu * d - strain_part * rate_part * thermal;
      if (g > 0.0)
        low = d;
      else
        high = d;
      // dg/dd = -3 mu - B n e^(n-1) rate_part - strain_part C / d (rate term active)
      const double slope = -three_mu - ((e > 0.0 ? n * hardening / e : 0.0) * rate_part +
                                        (rate_active && d > 0.0 ? strain_part * c / d : 0.0)) *
                                           thermal;
      double next = d - g / slope;
      if (!(next > low && next < high)) next = 0.5 * (low + high);
      if (std::abs(next - d) <= 1.0e-13 * high) return next;
      d = next;
    }
    return d;
  }
};

}  // namespace exdyn::material
