// Ductile damage of a plastic material (docs/theory.md, "Damage and erosion"): the
// damage D of an element grows with its equivalent plastic strain,
//   D += d eps_p / eps_f(sigma*, eps_dot_p),
// and the element fails at D = 1. `plastic_strain`: eps_f constant (D = eps_p / eps_f);
// `johnson_cook` (Johnson and Cook 1985, without the temperature term):
//   eps_f = (D1 + D2 exp(D3 sigma*)) (1 + D4 ln(max(eps_dot_p / eps_dot_0, 1))),
// sigma* = sigma_m / sigma_vm the stress triaxiality. Where it is used: no damage below
// sigma* = -1/3 (no ductile fracture in compression beyond uniaxial: Bao and Wierzbicki
// 2005), eps_f held at its sigma* = 1.5 value above 1.5, the rate ratio held at 1e12
// (input/options.hpp); the deck reader has checked that eps_f > 0 there.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "input/options.hpp"

namespace exdyn::material {

struct Failure {
  input::FailureModel model = input::FailureModel::none;
  double strain = 0.0;          // eps_f of plastic_strain
  std::array<double, 5> d{};    // D1 .. D5 of johnson_cook
  double reference_rate = 1.0;  // eps_dot_0, 1/s (the johnson_cook material's, else 1)

  bool active() const { return model != input::FailureModel::none; }

  // sigma* = sigma_m / sigma_vm of a stress (xx yy zz xy yz xz, Pa); 0 for no deviator.
  static double triaxiality(const double* s) {
    const double mean = (s[0] + s[1] + s[2]) / 3.0;
    const double dx = s[0] - mean, dy = s[1] - mean, dz = s[2] - mean;
    const double vm =
        std::sqrt(1.5 * (dx * dx + dy * dy + dz * dz) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
    return vm > 0.0 ? mean / vm : 0.0;
  }

  // The damage after a plastic strain increment d_eps (>= 0) over dt (s), from the damage
  // before and the element's plastic strain after, under a stress of triaxiality sigma*.
  double damage_after(double damage, double eps_p, double d_eps, double dt, double triaxiality) const {
    if (model == input::FailureModel::plastic_strain) return eps_p / strain;
    if (d_eps <= 0.0 || triaxiality < input::failure_triaxiality_min) return damage;
    const double s = std::min(triaxiality, input::failure_triaxiality_max);
    const double ratio = std::clamp(d_eps / (dt * reference_rate), 1.0, input::failure_rate_ratio_max);
    return damage + d_eps / failure_strain(s, ratio);
  }

  // eps_f of johnson_cook at sigma* and the rate ratio eps_dot_p / eps_dot_0 (>= 1).
  double failure_strain(double triaxiality, double rate_ratio) const {
    return (d[0] + d[1] * std::exp(d[2] * triaxiality)) * (1.0 + d[3] * std::log(rate_ratio));
  }
};

inline Failure make_failure(const input::MaterialOptions& options) {
  Failure f;
  f.model = options.failure;
  f.strain = options.failure_strain;
  f.d = options.failure_d;
  if (options.model == input::MaterialModel::johnson_cook) f.reference_rate = options.reference_strain_rate;
  return f;
}

}  // namespace exdyn::material
