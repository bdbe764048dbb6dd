// The one-dimensional lumped-mass chain of ../shared/reference/plate-impact.md:
// along a row of elements in uniaxial strain the fully integrated brick with a
// lumped mass reduces exactly to masses rho h (rho h / 2 at the ends) and springs
// M / h (per unit area), integrated by the same central differences.
#pragma once

#include <vector>

namespace exdyn::testing {

struct ChainOptions {
  int elements = 100;     // node 0 is the free end, node `elements` the wall
  double h = 0.0;         // element length, m
  double density = 0.0;   // rho, kg/m^3
  double modulus = 0.0;   // M = lambda + 2 mu (uniaxial strain), Pa
  double velocity = 0.0;  // initial velocity of every node but the wall, m/s
  double dt = 0.0;        // s
  long steps = 0;
  bool wall_fixed = true;  // the last node held (rigid wall)
};

// sigma_x of every element after `steps` steps (element 0 at the free end), Pa.
inline std::vector<double> chain_stress(const ChainOptions& o) {
  const int n = o.elements;
  std::vector<double> u(n + 1, 0.0), v(n + 1, o.velocity), m(n + 1, o.density * o.h), f(n + 1);
  m[0] *= 0.5;
  m[n] *= 0.5;
  if (o.wall_fixed) v[n] = 0.0;
  auto stresses = [&] {
    std::vector<double> s(n);
    for (int e = 0; e < n; ++e) s[e] = o.modulus * (u[e + 1] - u[e]) / o.h;
    return s;
  };
  for (long step = 0; step < o.steps; ++step) {
    const std::vector<double> s = stresses();
    std::fill(f.begin(), f.end(), 0.0);
    for (int e = 0; e < n; ++e) {  // f = -f_int: a stretched spring pulls its nodes together
      f[e] += s[e];
      f[e + 1] -= s[e];
    }
    for (int i = 0; i <= n; ++i) {
      if (o.wall_fixed && i == n) continue;
      v[i] += o.dt * f[i] / m[i];  // a^0 = 0 here, so v^{1/2} = v^0 + dt a^0 = v^0 + dt/2 a^0
      u[i] += o.dt * v[i];
    }
  }
  return stresses();
}

}  // namespace exdyn::testing
