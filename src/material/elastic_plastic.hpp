// The elastic_plastic material's flow stress: von Mises with isotropic hardening,
// linear (sigma_y = sigma_y0 + H eps_p) or tabulated (piecewise linear in eps_p, flat
// after the last row), and its return: the plastic strain increment of a step.
// The elasticity, the kinematics and the radial return around it are j2.hpp's.
#pragma once

#include <array>
#include <vector>

#include "common/simd_pack.hpp"

namespace exdyn::material {

// Piecewise linear sigma_y(eps_p): segment k starts at (strain[k], stress[k]) with
// slope[k]; the last segment runs on for ever (slope H for linear hardening, 0 after a
// table's last row).
struct Hardening {
  static constexpr bool plastic = true;
  static constexpr int max_segments = 32;
  int segments = 1;
  std::array<double, max_segments> strain{};  // eps_p at each segment's start
  std::array<double, max_segments> stress{};  // sigma_y there, Pa
  std::array<double, max_segments> slope{};   // d sigma_y / d eps_p on the segment, Pa

  static Hardening linear(double yield_stress, double modulus) {
    Hardening h;
    h.stress[0] = yield_stress;
    h.slope[0] = modulus;
    return h;
  }

  // From rows (eps_p, sigma_y), eps_p[0] = 0 and increasing, sigma_y non-decreasing.
  // The deck reader allows at most max_segments rows.
  static Hardening table(const std::vector<std::array<double, 2>>& rows) {
    Hardening h;
    h.segments = int(rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      h.strain[k] = rows[k][0];
      h.stress[k] = rows[k][1];
      h.slope[k] = k + 1 < rows.size() ? (rows[k + 1][1] - rows[k][1]) / (rows[k + 1][0] - rows[k][0]) : 0.0;
    }
    return h;
  }

  // sigma_y(eps_p), Pa.
  double flow_stress(double eps_p) const {
    int k = 0;
    while (k + 1 < segments && eps_p >= strain[std::size_t(k + 1)]) ++k;
    return stress[std::size_t(k)] + slope[std::size_t(k)] * (eps_p - strain[std::size_t(k)]);
  }

  // sigma_y at each lane's eps_p, Pa.
  template <class Real>
  Real yield_at(const Real& eps_p) const {
    if (segments == 1) return stress[0] + slope[0] * eps_p;
    Real out{};
    for (int l = 0; l < lanes_of<Real>; ++l) set_lane(out, l, flow_stress(lane(eps_p, l)));
    return out;
  }

  // The increment d >= 0 of eps_p that returns the trial state to the yield surface:
  //   q_trial - three_mu d = sigma_y(eps_p + d)   (0 when q_trial <= sigma_y(eps_p)),
  // with q_trial the trial von Mises stress and three_mu = 3 G (small strain) or
  // 3 G tr(b_e)/3 (finite strain), Pa. Linear hardening in closed form, lane by lane
  // in the vector lanes; a table segment by segment, each lane on its own.
  template <class Real>
  Real increment(const Real& q_trial, const Real& three_mu, const Real& eps_p, double /*dt*/) const {
    if (segments == 1) {
      const Real excess = q_trial - (stress[0] + slope[0] * eps_p);
      return lane_max(excess, Real{}) / (three_mu + slope[0]);
    }
    Real d{};
    for (int l = 0; l < lanes_of<Real>; ++l)
      set_lane(d, l, increment_scalar(lane(q_trial, l), lane(three_mu, l), lane(eps_p, l)));
    return d;
  }

  double increment_scalar(double q_trial, double three_mu, double eps_p) const {
    if (q_trial <= flow_stress(eps_p)) return 0.0;
    int k = 0;
    while (k + 1 < segments && eps_p >= strain[std::size_t(k + 1)]) ++k;
    // On segment k: q_trial - three_mu d = stress_k + slope_k (eps_p + d - strain_k).
    for (;; ++k) {
      const std::size_t s = std::size_t(k);
      const double d = (q_trial - stress[s] - slope[s] * (eps_p - strain[s])) / (three_mu + slope[s]);
      if (k + 1 == segments || eps_p + d <= strain[s + 1]) return d;
    }
  }
};

}  // namespace exdyn::material
