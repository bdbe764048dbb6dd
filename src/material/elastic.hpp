// The linear_elastic material: small-strain isotropic linear elasticity,
//   sigma = lambda tr(eps) I + 2 mu eps,
// and, under finite kinematics, the hyperelastic model of j2.hpp with no yield
// (NoYield). The elastic constants are every model's: they give the wave speed.
// Tensor components in the order xx yy zz xy yz xz (the output order of
// ../shared/spec/output.md; shear entries are tensor, not engineering, strains).
#pragma once

#include <array>
#include <cmath>

namespace exdyn::material {

using SymTensor = std::array<double, 6>;  // xx yy zz xy yz xz

struct ElasticConstants {
  double density = 0.0;  // rho, kg/m^3
  double lambda = 0.0;   // Lame's first parameter, Pa
  double mu = 0.0;       // shear modulus, Pa

  // M = lambda + 2 mu: the modulus of uniaxial strain (P-wave modulus), Pa.
  double dilatational_modulus() const { return lambda + 2.0 * mu; }
  // K = lambda + 2/3 mu, Pa.
  double bulk_modulus() const { return lambda + 2.0 / 3.0 * mu; }
  // c1 = sqrt(M / rho), m/s: the fastest wave, which bounds the stable step.
  double dilatational_wave_speed() const { return std::sqrt(dilatational_modulus() / density); }
};

// The flow rule of a material that never yields (linear_elastic under finite
// kinematics: j2.hpp's hyperelastic model without a plastic state).
struct NoYield {
  static constexpr bool plastic = false;
  template <class Real>
  Real increment(const Real&, const Real&, const Real&, double) const {
    return Real{};
  }
};

// From Young's modulus E, Poisson's ratio nu and density rho:
// lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)).
inline ElasticConstants elastic_constants(double youngs_modulus, double poissons_ratio, double density) {
  const double E = youngs_modulus, nu = poissons_ratio;
  return {density, E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))};
}

// sigma = lambda tr(eps) I + 2 mu eps.
inline SymTensor stress_from_strain(const ElasticConstants& c, const SymTensor& eps) {
  const double lambda_trace = c.lambda * (eps[0] + eps[1] + eps[2]);
  const double two_mu = 2.0 * c.mu;
  return {lambda_trace + two_mu * eps[0],
          lambda_trace + two_mu * eps[1],
          lambda_trace + two_mu * eps[2],
          two_mu * eps[3],
          two_mu * eps[4],
          two_mu * eps[5]};
}

// Strain energy density W = sigma : eps / 2 (J/m^3).
inline double strain_energy_density(const SymTensor& sigma, const SymTensor& eps) {
  return 0.5 * (sigma[0] * eps[0] + sigma[1] * eps[1] + sigma[2] * eps[2] +
                2.0 * (sigma[3] * eps[3] + sigma[4] * eps[4] + sigma[5] * eps[5]));
}

// von Mises equivalent stress sqrt(3 J2), Pa.
inline double von_mises(const SymTensor& s) {
  const double dxy = s[0] - s[1], dyz = s[1] - s[2], dzx = s[2] - s[0];
  return std::sqrt(0.5 * (dxy * dxy + dyz * dyz + dzx * dzx) +
                   3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

}  // namespace exdyn::material
