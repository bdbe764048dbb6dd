// Penalty node-to-segment contact: the normal force of one slave node, the
// automatic stiffness and its stability bound (docs/contact.md derives them;
// ../shared/reference/plate-impact.md gives the measurements behind them).
#pragma once

#include <algorithm>
#include <cmath>

namespace exdyn::contact {

// The automatic stiffness before the stability cap: k = kappa M A / L (N/m), with
// M = lambda + 2 mu the uniaxial-strain modulus (Pa), A the slave node's
// tributary area (m^2) and L the element length normal to the face (m). For a
// cube of side h this is kappa M h; kappa = 8 keeps the plate front within
// 0.04 h of the rigid wall's (plate-impact.md, chain with zeta = 0.2).
inline constexpr double automatic_stiffness_factor = 8.0;
inline double automatic_stiffness(double modulus, double area, double length) {
  return automatic_stiffness_factor * modulus * area / length;
}

// The automatic pressure per length of slave quadrature points (Pa/m): the same rule
// per unit area, kappa = 8 M / L, so that a point of weight w dA carries kappa w dA,
// as a node of tributary area A carries kappa A.
inline double automatic_pressure_stiffness(double modulus, double length) {
  return automatic_stiffness_factor * modulus / length;
}

// The contact oscillator's frequency omega_c = sqrt(k inverse_mass) is held to
// omega_c dt <= 1/sqrt(2): a stiffer spring rings with the step and makes the
// contact chatter. In the plate chain (k = kappa M h, node masses rho h / 2 per
// unit area) omega_c dt = 2 sqrt(kappa) courant, so this is kappa = 8 at the
// paper's Courant number 0.125 and kappa = 2 at 0.25.
inline constexpr double contact_frequency_limit = 0.70710678118654752;  // omega_c dt
inline double accurate_stiffness_bound(double dt, double inverse_mass) {
  return contact_frequency_limit * contact_frequency_limit / (dt * dt * inverse_mass);
}

// The largest stiffness (N/m) that does not lower the stable step dt (s) of a
// mesh whose own highest frequency is omega_mesh = 2 courant / dt, for a spring
// between a slave node and a segment whose inverse masses add up to at most
// inverse_mass = 1/m_s + max_i 1/m_i (1/kg, an upper bound of 1/m_s + sum N_i^2 / m_i):
//  - the undamped system: omega_mesh^2 + k inverse_mass <= (2 / dt)^2;
//  - the spring-dashpot alone, damping ratio zeta: omega dt <= 2 (sqrt(1 + zeta^2) - zeta).
// Zero when the mesh step leaves no room (courant >= 1).
inline double stable_stiffness_bound(double dt, double courant, double zeta, double inverse_mass) {
  const double undamped = 4.0 * (1.0 - courant * courant) / (dt * dt);
  const double omega_damped = 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta) / dt;
  return std::max(0.0, std::min(undamped, omega_damped * omega_damped)) / inverse_mass;
}

// Dashpot coefficient c = zeta 2 sqrt(k m) (N s/m) of a spring k between masses
// m_s and m_m, with m = m_s m_m / (m_s + m_m) the reduced mass.
inline double damping_coefficient(double zeta, double stiffness, double slave_mass, double master_mass) {
  const double reduced = slave_mass * master_mass / (slave_mass + master_mass);
  return zeta * 2.0 * std::sqrt(stiffness * reduced);
}

// Normal contact force (N) on the slave node along the master's outward normal:
// spring on the penetration -gap plus dashpot on the approach speed
// -normal_velocity (v_slave - v_master).n, kept compressive (>= 0): contact pushes,
// never pulls.
inline double normal_force(double stiffness, double damping, double gap, double normal_velocity) {
  return std::max(0.0, -stiffness * gap - damping * normal_velocity);
}

}  // namespace exdyn::contact
