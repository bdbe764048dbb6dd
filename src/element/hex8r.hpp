// The one-point hexahedron with hourglass stiffness (docs/theory.md, "hex8r").
// Small strain, total (not incremental) form, so the element is linear and
// conservative: f = (K_mean + K_hourglass) u.
//
//   b_jI = integral of dN_I/dx_j dV      (the uniform-strain B vectors, m^2)
//   H    = (1/V) sum_I u_I (x) b_I        (mean displacement gradient)
//   gamma_alpha = h_alpha - (h_alpha . x_j) b_j / V    (alpha = 1..4)
//   q_i,alpha = sum_I gamma_alpha,I u_iI,  Q_alpha = K_alpha q_alpha
//   f_iI = sigma_ij b_jI + sum_alpha Q_i,alpha gamma_alpha,I
//   E_strain = V sigma : eps / 2,  E_hourglass = (1/2) sum_alpha q_alpha . K_alpha q_alpha
//   K_alpha: the assumed-strain stiffness of hourglass.hpp (default), or k I with
//   k = coefficient * 2 mu * (b_jI b_jI) / (8 V) (Flanagan-Belytschko; PRONTO3D/Presto scaling)
//
// Computed in the mode basis of hex8.hpp: with c_m the modes of u,
// H = sum_m c_m (x) beta_m (beta_mj = phi_m . b_j / V) and q_alpha = 8 c_(3+alpha) - H g_alpha
// (g_alpha,j = h_alpha . x_j), so the element never forms b or gamma node by node.
#pragma once

#include <array>

#include "element/hex8.hpp"
#include "element/hex8_parallelepiped.hpp"
#include "element/hourglass.hpp"
#include "input/options.hpp"

namespace exdyn::element::hex8r {

// The uniform-strain B vectors b_jI = integral of dN_I/dx_j dV (m^2) by the
// 2x2x2 rule, which is exact for them (the integrand has degree <= 2 in each
// natural coordinate); equal to the closed form dV/dx_jI of Flanagan-Belytschko.
inline std::array<std::array<double, 8>, 3> b_vectors(const ElementVectors& x_ref) {
  const hex8::GaussGeometry geometry = hex8::gauss_geometry(x_ref);
  std::array<std::array<double, 8>, 3> b{};
  for (int g = 0; g < 8; ++g) {
    const Vector3& s = hex8::node_natural_coordinates[g];
    const std::array<Vector3, 8> dn = hex8::shape_function_derivatives(
        hex8::gauss_abscissa * s[0], hex8::gauss_abscissa * s[1], hex8::gauss_abscissa * s[2]);
    const Matrix3& inverse_jacobian = geometry.inverse_jacobian[g];
    for (int node = 0; node < 8; ++node)
      for (int j = 0; j < 3; ++j)
        b[j][node] += geometry.det_jacobian[g] *
                      (dn[node][0] * inverse_jacobian[j] + dn[node][1] * inverse_jacobian[3 + j] +
                       dn[node][2] * inverse_jacobian[6 + j]);
  }
  return b;
}

// The Flanagan-Belytschko hourglass stiffness k (N/m) of one element:
//   k = coefficient * 2 mu * (b_jI b_jI) / (8 V),
// the stiffness form of Flanagan and Belytschko (1981) with the scaling of
// Sandia's PRONTO3D/Presto uniform-gradient hexahedron. For a cube of side h,
// b.b = 3 h^4 / 2 and k = 0.375 coefficient mu h.
inline double hourglass_stiffness(double mu, double coefficient, double b_dot_b, double volume) {
  return coefficient * 2.0 * mu * b_dot_b / (8.0 * volume);
}

// How a part's hourglass modes are resisted (docs/theory.md): the assumed-strain
// stiffness of hourglass.hpp (coefficient 1 = physical), or Flanagan-Belytschko's
// isotropic k (coefficient 0.05 by default there).
struct Stabilization {
  input::HourglassModel model = input::HourglassModel::assumed_strain;
  double coefficient = 1.0;
  double youngs = 0.0;  // Pa
  double mu = 0.0;      // Pa
};

// Reference data per element (reference_size doubles):
//   [0, 21)  beta_mj = phi_m . b_j / V for modes m = 1..7 (row m-1), 1/m
//   [21, 33) g_alpha,j = h_alpha . x_j for alpha = 0..3 (modes 4..7), m
//   33: V (m^3), 34: 1/V
//   [35, 59) K_alpha (N/m), xx yy zz xy yz xz for alpha = 0..3: Q_alpha = K_alpha q_alpha
//            (Flanagan-Belytschko: k I, so that 35 is k)
// The assumed-strain law kernel (law_reference_size) has instead
//   [35, 44) the modes c_1, c_2, c_3 of the reference coordinates (c_j,i at 35 + 3 j + i), m
//   44: coefficient E, 45: coefficient mu (Pa)
inline constexpr int reference_size = 59;
inline constexpr int law_reference_size = 46;

// Fills reference[0..reference_size), or [0..law_reference_size) with `law_layout`
// for the assumed-strain model. Returns the smallest det J at the 2x2x2 Gauss points
// (<= 0: inverted).
inline double make_reference(const ElementVectors& x_ref, const Stabilization& stabilization,
                             double* reference, bool law_layout = false) {
  const hex8::GaussGeometry geometry = hex8::gauss_geometry(x_ref);
  const double volume = geometry.volume;
  const std::array<std::array<double, 8>, 3> b = b_vectors(x_ref);
  const hex8::ElementModes x_modes = hex8::modes_from_nodal(x_ref);
  double b_dot_b = 0.0;
  for (int j = 0; j < 3; ++j) {
    // phi_m . b_j = 8 * (mode m of b_j).
    const std::array<double, 8> b_modes = hex8::modes_from_nodal(b[j]);
    for (int m = 1; m < 8; ++m) reference[3 * (m - 1) + j] = 8.0 * b_modes[m] / volume;
    for (int node = 0; node < 8; ++node) b_dot_b += b[j][node] * b[j][node];
  }
  for (int alpha = 0; alpha < 4; ++alpha) {
    reference[21 + 3 * alpha + 0] = 8.0 * x_modes.x[4 + alpha];
    reference[21 + 3 * alpha + 1] = 8.0 * x_modes.y[4 + alpha];
    reference[21 + 3 * alpha + 2] = 8.0 * x_modes.z[4 + alpha];
  }
  reference[33] = volume;
  reference[34] = 1.0 / volume;
  if (stabilization.model == input::HourglassModel::flanagan_belytschko) {
    const double k = hourglass_stiffness(stabilization.mu, stabilization.coefficient, b_dot_b, volume);
    for (int alpha = 0; alpha < 4; ++alpha)
      for (int s = 0; s < 6; ++s) reference[35 + 6 * alpha + s] = s < 3 ? k : 0.0;
    return geometry.min_det_jacobian;
  }
  const hourglass::AssumedStrain a = hourglass::assumed_strain(x_modes, volume, stabilization.youngs,
                                                               stabilization.mu, stabilization.coefficient);
  if (law_layout) {
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) reference[35 + 3 * j + i] = x_modes[1 + j][std::size_t(i)];
    reference[44] = stabilization.coefficient * stabilization.youngs;
    reference[45] = stabilization.coefficient * stabilization.mu;
  } else {
    for (int alpha = 0; alpha < 4; ++alpha) {
      const std::array<double, 6> k = hourglass::global_stiffness(a, alpha);
      for (int s = 0; s < 6; ++s) reference[35 + 6 * alpha + s] = k[s];
    }
  }
  return geometry.min_det_jacobian;
}

template <class Real>
struct BasicEnergies {
  Real strain{};     // V sigma : eps / 2, J
  Real hourglass{};  // k/2 sum q^2, J
};

using Energies = BasicEnergies<double>;

// The one point of an element (the general layouts): beta and g from the reference
// data, the mean gradient H_ij = sum_m c_m,i beta_mj and the hourglass amplitudes
// q_alpha,i = h_alpha . u_i - g_alpha . H_i.
template <class Real>
struct OnePoint {
  std::array<Real, 21> beta;
  std::array<Real, 12> g;
  std::array<Real, 9> h{};
  Real q[4][3];
};

template <class Real>
inline OnePoint<Real> one_point(const double* reference, const hex8::BasicElementModes<Real>& c) {
  OnePoint<Real> p;
  for (int k = 0; k < 21; ++k) p.beta[k] = load<Real>(reference, k);
  for (int k = 0; k < 12; ++k) p.g[k] = load<Real>(reference, 21 + k);
  for (int m = 1; m < 8; ++m) {
    const std::array<Real, 3> cm = c[m];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) p.h[3 * i + j] += cm[i] * p.beta[3 * (m - 1) + j];
  }
  for (int alpha = 0; alpha < 4; ++alpha) {
    const std::array<Real, 3> ch = c[4 + alpha];
    for (int i = 0; i < 3; ++i)
      p.q[alpha][i] = 8.0 * ch[i] - (p.g[3 * alpha] * p.h[3 * i] + p.g[3 * alpha + 1] * p.h[3 * i + 1] +
                                     p.g[3 * alpha + 2] * p.h[3 * i + 2]);
  }
  return p;
}

// The nodal forces from a = V sigma (or V P, row-major, N m) and the hourglass forces
// Q_alpha (N): f_iI = S_ij b_jI / V + sum_alpha Q_i,alpha h_alpha,I with
// S = a - sum_alpha Q_alpha (x) g_alpha. In modes, F'_m = (1/8) sum_j S_ij beta_mj
// (+ Q for the hourglass modes); b_jI = (V/8) sum_m phi_m(I) beta_mj, so
// f_I = sum_m phi_m(I) F'_m.
template <class Real>
inline void one_point_forces(const OnePoint<Real>& p, const std::array<Real, 9>& a, const Real force[4][3],
                             BasicElementVectors<Real>& f) {
  const std::array<Real, 21>& beta = p.beta;
  const std::array<Real, 12>& g = p.g;
  std::array<Real, 8> fm[3] = {};
  for (int i = 0; i < 3; ++i) {
    Real s[3];
    for (int j = 0; j < 3; ++j)
      s[j] = 0.125 * (a[3 * i + j] - (force[0][i] * g[j] + force[1][i] * g[3 + j] + force[2][i] * g[6 + j] +
                                      force[3][i] * g[9 + j]));
    for (int m = 1; m < 8; ++m)
      fm[i][m] = s[0] * beta[3 * (m - 1)] + s[1] * beta[3 * (m - 1) + 1] + s[2] * beta[3 * (m - 1) + 2];
    for (int alpha = 0; alpha < 4; ++alpha) fm[i][4 + alpha] += force[alpha][i];
  }
  f.x = hex8::nodal_from_modes(fm[0]);
  f.y = hex8::nodal_from_modes(fm[1]);
  f.z = hex8::nodal_from_modes(fm[2]);
}

// f = (K_mean + K_hourglass) u (N), the stress (Pa) and the energies (J) of one
// element (Real = double, reference data as written by make_reference) or an
// pack of elements (Real = Pack<L>, their data interleaved value by value).
template <class Real>
inline BasicEnergies<Real> internal_forces(const double* reference, double lambda, double mu,
                                           const BasicElementVectors<Real>& u, BasicElementVectors<Real>& f,
                                           std::array<Real, 6>& stress) {
  const OnePoint<Real> p = one_point(reference, hex8::modes_from_nodal(u));
  const std::array<Real, 9>& h = p.h;
  const Real volume = load<Real>(reference, 33);
  stress = hex8::stress_from_gradient(lambda, mu, h);
  BasicEnergies<Real> energies;
  // V sigma : eps / 2 with eps = sym(H).
  energies.strain = 0.5 * volume *
                    (stress[0] * h[0] + stress[1] * h[4] + stress[2] * h[8] + stress[3] * (h[1] + h[3]) +
                     stress[4] * (h[5] + h[7]) + stress[5] * (h[2] + h[6]));
  // Q_alpha = K_alpha q_alpha.
  Real force[4][3];
  Real q_dot_force{};
  for (int alpha = 0; alpha < 4; ++alpha) {
    Real k[6];
    for (int s = 0; s < 6; ++s) k[s] = load<Real>(reference, 35 + 6 * alpha + s);
    const std::array<Real, 3> q_force = hourglass::apply(k, p.q[alpha]);
    for (int i = 0; i < 3; ++i) {
      force[alpha][i] = q_force[i];
      q_dot_force += p.q[alpha][i] * q_force[i];
    }
  }
  energies.hourglass = 0.5 * q_dot_force;
  const std::array<Real, 9> a = {volume * stress[0], volume * stress[3], volume * stress[5],
                                 volume * stress[3], volume * stress[1], volume * stress[4],
                                 volume * stress[5], volume * stress[4], volume * stress[2]};
  one_point_forces(p, a, force, f);
  return energies;
}

// ---------------------------------------------------------------------------
// Parallelepiped (constant Jacobian): the hourglass base vectors are orthogonal
// to b (beta_m = 0 for m = 4..7) and to the coordinates (g = 0), so gamma = h and
// q_alpha = 8 c_(3+alpha); beta_1..3 are the rows of dxi/dx.
// Reference data per element: beta_1..3 (9, row m-1), V (1), K_alpha (24, as in
// the general layout).
// ---------------------------------------------------------------------------
inline constexpr int parallelepiped_reference_size = 34;

inline double make_parallelepiped_reference(const ElementVectors& x_ref, const Stabilization& stabilization,
                                            double* reference) {
  std::array<double, reference_size> general{};
  const double min_det_jacobian = make_reference(x_ref, stabilization, general.data());
  for (int k = 0; k < 9; ++k) reference[k] = general[k];
  reference[9] = general[33];
  for (int k = 0; k < 24; ++k) reference[10 + k] = general[35 + k];
  return min_det_jacobian;
}

// For one element (Real = double, reference data as written by
// make_parallelepiped_reference) or a pack of elements (Real = Pack<L>, their
// data interleaved value by value).
template <class Real>
inline BasicEnergies<Real> parallelepiped_internal_forces(const double* reference, double lambda, double mu,
                                                          const BasicElementVectors<Real>& u,
                                                          BasicElementVectors<Real>& f,
                                                          std::array<Real, 6>& stress) {
  const hex8::BasicElementModes<Real> c = hex8::modes_from_nodal(u);
  std::array<Real, 9> beta;
  for (int k = 0; k < 9; ++k) beta[k] = load<Real>(reference, k);
  const Real volume = load<Real>(reference, 9);
  // H_ij = sum_{m=1..3} c_m,i beta_mj.
  std::array<Real, 9> h;
  for (int j = 0; j < 3; ++j) {
    h[j] = c.x[1] * beta[j] + c.x[2] * beta[3 + j] + c.x[3] * beta[6 + j];
    h[3 + j] = c.y[1] * beta[j] + c.y[2] * beta[3 + j] + c.y[3] * beta[6 + j];
    h[6 + j] = c.z[1] * beta[j] + c.z[2] * beta[3 + j] + c.z[3] * beta[6 + j];
  }
  stress = hex8::stress_from_gradient(lambda, mu, h);
  BasicEnergies<Real> energies;
  // V sigma : eps / 2 with eps = sym(H).
  energies.strain = 0.5 * volume *
                    (stress[0] * h[0] + stress[1] * h[4] + stress[2] * h[8] + stress[3] * (h[1] + h[3]) +
                     stress[4] * (h[5] + h[7]) + stress[5] * (h[2] + h[6]));
  // F'_m = (V/8) sigma beta_m (m = 1..3), F'_(3+alpha) = K_alpha q_alpha, q_alpha = 8 c_(3+alpha).
  const Real volume_8 = 0.125 * volume;
  std::array<Real, 8> fx{}, fy{}, fz{};
  for (int m = 1; m < 4; ++m) {
    const Real b0 = beta[3 * (m - 1)], b1 = beta[3 * (m - 1) + 1], b2 = beta[3 * (m - 1) + 2];
    fx[m] = volume_8 * (stress[0] * b0 + stress[3] * b1 + stress[5] * b2);
    fy[m] = volume_8 * (stress[3] * b0 + stress[1] * b1 + stress[4] * b2);
    fz[m] = volume_8 * (stress[5] * b0 + stress[4] * b1 + stress[2] * b2);
  }
  Real q_dot_force{};
  for (int m = 4; m < 8; ++m) {
    Real k[6];
    for (int s = 0; s < 6; ++s) k[s] = load<Real>(reference, 10 + 6 * (m - 4) + s);
    const Real q[3] = {8.0 * c.x[m], 8.0 * c.y[m], 8.0 * c.z[m]};
    const std::array<Real, 3> force = hourglass::apply(k, q);
    fx[m] = force[0];
    fy[m] = force[1];
    fz[m] = force[2];
    q_dot_force += q[0] * force[0] + q[1] * force[1] + q[2] * force[2];
  }
  energies.hourglass = 0.5 * q_dot_force;  // (1/2) sum q . K q
  f.x = hex8::nodal_from_modes(fx);
  f.y = hex8::nodal_from_modes(fy);
  f.z = hex8::nodal_from_modes(fz);
  return energies;
}

}  // namespace exdyn::element::hex8r
