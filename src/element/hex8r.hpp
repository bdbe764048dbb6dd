// The one-point hexahedron with Flanagan-Belytschko hourglass stiffness
// (docs/theory.md, "hex8r"). Small strain, total (not incremental) form, so the
// element is linear and conservative: f = (K_mean + K_hourglass) u.
//
//   b_jI = integral of dN_I/dx_j dV      (the uniform-strain B vectors, m^2)
//   H    = (1/V) sum_I u_I (x) b_I        (mean displacement gradient)
//   gamma_alpha = h_alpha - (h_alpha . x_j) b_j / V    (alpha = 1..4)
//   q_i,alpha = sum_I gamma_alpha,I u_iI,  Q = k q
//   f_iI = sigma_ij b_jI + sum_alpha Q_i,alpha gamma_alpha,I
//   E_strain = V sigma : eps / 2,  E_hourglass = k/2 sum q^2
//   k = coefficient * 2 mu * (b_jI b_jI) / (8 V)       (N/m; PRONTO3D/Presto scaling)
//
// Computed in the mode basis of hex8.hpp: with c_m the modes of u,
// H = sum_m c_m (x) beta_m (beta_mj = phi_m . b_j / V) and q_alpha = 8 c_(3+alpha) - H g_alpha
// (g_alpha,j = h_alpha . x_j), so the element never forms b or gamma node by node.
#pragma once

#include <array>

#include "element/hex8.hpp"
#include "element/hex8_parallelepiped.hpp"

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

// The hourglass stiffness k (N/m) of one element:
//   k = coefficient * 2 mu * (b_jI b_jI) / (8 V),
// the stiffness form of Flanagan and Belytschko (1981) with the scaling of
// Sandia's PRONTO3D/Presto uniform-gradient hexahedron. For a cube of side h,
// b.b = 3 h^4 / 2 and k = 0.375 coefficient mu h.
inline double hourglass_stiffness(double mu, double coefficient, double b_dot_b, double volume) {
  return coefficient * 2.0 * mu * b_dot_b / (8.0 * volume);
}

// Reference data per element (reference_size doubles):
//   [0, 21)  beta_mj = phi_m . b_j / V for modes m = 1..7 (row m-1), 1/m
//   [21, 33) g_alpha,j = h_alpha . x_j for alpha = 0..3 (modes 4..7), m
//   33: V (m^3), 34: 1/V, 35: k (N/m)
inline constexpr int reference_size = 36;

// Fills reference[0..reference_size). Returns the smallest det J at the 2x2x2
// Gauss points (<= 0: inverted).
inline double make_reference(const ElementVectors& x_ref, double mu, double hourglass_coefficient,
                             double* reference) {
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
  reference[35] = hourglass_stiffness(mu, hourglass_coefficient, b_dot_b, volume);
  return geometry.min_det_jacobian;
}

template <class Real>
struct BasicEnergies {
  Real strain{};     // V sigma : eps / 2, J
  Real hourglass{};  // k/2 sum q^2, J
};

using Energies = BasicEnergies<double>;

// f = (K_mean + K_hourglass) u (N), the stress (Pa) and the energies (J) of one
// element (Real = double, reference data as written by make_reference) or an
// pack of elements (Real = Pack<L>, their data interleaved value by value).
template <class Real>
inline BasicEnergies<Real> internal_forces(const double* reference, double lambda, double mu,
                                           const BasicElementVectors<Real>& u, BasicElementVectors<Real>& f,
                                           std::array<Real, 6>& stress) {
  const hex8::BasicElementModes<Real> c = hex8::modes_from_nodal(u);
  std::array<Real, 21> beta;
  for (int k = 0; k < 21; ++k) beta[k] = load<Real>(reference, k);
  std::array<Real, 12> g;
  for (int k = 0; k < 12; ++k) g[k] = load<Real>(reference, 21 + k);
  const Real volume = load<Real>(reference, 33), inverse_volume = load<Real>(reference, 34),
             k = load<Real>(reference, 35);

  // H_ij = sum_m c_m,i beta_mj.
  std::array<Real, 9> h{};
  for (int m = 1; m < 8; ++m) {
    const std::array<Real, 3> cm = c[m];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) h[3 * i + j] += cm[i] * beta[3 * (m - 1) + j];
  }
  stress = hex8::stress_from_gradient(lambda, mu, h);
  BasicEnergies<Real> energies;
  // V sigma : eps / 2 with eps = sym(H).
  energies.strain = 0.5 * volume *
                    (stress[0] * h[0] + stress[1] * h[4] + stress[2] * h[8] + stress[3] * (h[1] + h[3]) +
                     stress[4] * (h[5] + h[7]) + stress[5] * (h[2] + h[6]));

  // q_alpha,i = h_alpha . u_i - g_alpha . H_i  and  Q = k q.
  Real q[4][3];
  Real q_squared{};
  for (int alpha = 0; alpha < 4; ++alpha) {
    const std::array<Real, 3> ch = c[4 + alpha];
    for (int i = 0; i < 3; ++i) {
      q[alpha][i] = 8.0 * ch[i] - (g[3 * alpha] * h[3 * i] + g[3 * alpha + 1] * h[3 * i + 1] +
                                   g[3 * alpha + 2] * h[3 * i + 2]);
      q_squared += q[alpha][i] * q[alpha][i];
    }
  }
  energies.hourglass = 0.5 * k * q_squared;

  // f_iI = S_ij b_jI + sum_alpha Q_i,alpha h_alpha,I with S = sigma - (1/V) sum_alpha Q_alpha (x) g_alpha.
  const Real sm[3][3] = {{stress[0], stress[3], stress[5]},
                         {stress[3], stress[1], stress[4]},
                         {stress[5], stress[4], stress[2]}};
  // Mode forces F'_m = (V/8) sum_j S_ij beta_mj (+ Q for the hourglass modes);
  // b_jI = (V/8) sum_m phi_m(I) beta_mj, so f_I = sum_m phi_m(I) F'_m.
  const Real k_over_volume = k * inverse_volume, volume_8 = 0.125 * volume;
  std::array<Real, 8> fm[3] = {};
  for (int i = 0; i < 3; ++i) {
    Real s[3];
    for (int j = 0; j < 3; ++j)
      s[j] = volume_8 * (sm[i][j] - k_over_volume * (q[0][i] * g[j] + q[1][i] * g[3 + j] +
                                                     q[2][i] * g[6 + j] + q[3][i] * g[9 + j]));
    for (int m = 1; m < 8; ++m)
      fm[i][m] = s[0] * beta[3 * (m - 1)] + s[1] * beta[3 * (m - 1) + 1] + s[2] * beta[3 * (m - 1) + 2];
    for (int alpha = 0; alpha < 4; ++alpha) fm[i][4 + alpha] += k * q[alpha][i];
  }
  f.x = hex8::nodal_from_modes(fm[0]);
  f.y = hex8::nodal_from_modes(fm[1]);
  f.z = hex8::nodal_from_modes(fm[2]);
  return energies;
}

// ---------------------------------------------------------------------------
// Parallelepiped (constant Jacobian): the hourglass base vectors are orthogonal
// to b (beta_m = 0 for m = 4..7) and to the coordinates (g = 0), so gamma = h and
// q_alpha = 8 c_(3+alpha); beta_1..3 are the rows of dxi/dx.
// Reference data per element: beta_1..3 (9, row m-1), V (1), k (1).
// ---------------------------------------------------------------------------
inline constexpr int parallelepiped_reference_size = 11;

inline double make_parallelepiped_reference(const ElementVectors& x_ref, double mu,
                                            double hourglass_coefficient, double* reference) {
  std::array<double, reference_size> general{};
  const double min_det_jacobian = make_reference(x_ref, mu, hourglass_coefficient, general.data());
  for (int k = 0; k < 9; ++k) reference[k] = general[k];
  reference[9] = general[33];
  reference[10] = general[35];
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
  const Real volume = load<Real>(reference, 9), k = load<Real>(reference, 10);
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
  // F'_m = (V/8) sigma beta_m (m = 1..3), F'_(3+alpha) = k q_alpha = 8 k c_(3+alpha).
  const Real volume_8 = 0.125 * volume, k8 = 8.0 * k;
  std::array<Real, 8> fx{}, fy{}, fz{};
  for (int m = 1; m < 4; ++m) {
    const Real b0 = beta[3 * (m - 1)], b1 = beta[3 * (m - 1) + 1], b2 = beta[3 * (m - 1) + 2];
    fx[m] = volume_8 * (stress[0] * b0 + stress[3] * b1 + stress[5] * b2);
    fy[m] = volume_8 * (stress[3] * b0 + stress[1] * b1 + stress[4] * b2);
    fz[m] = volume_8 * (stress[5] * b0 + stress[4] * b1 + stress[2] * b2);
  }
  Real hourglass_sum{};
  for (int m = 4; m < 8; ++m) {
    fx[m] = k8 * c.x[m];
    fy[m] = k8 * c.y[m];
    fz[m] = k8 * c.z[m];
    hourglass_sum += c.x[m] * c.x[m] + c.y[m] * c.y[m] + c.z[m] * c.z[m];
  }
  energies.hourglass = 32.0 * k * hourglass_sum;  // k/2 sum (8 c)^2
  f.x = hex8::nodal_from_modes(fx);
  f.y = hex8::nodal_from_modes(fy);
  f.z = hex8::nodal_from_modes(fz);
  return energies;
}

}  // namespace exdyn::element::hex8r
