// The trilinear eight-node hexahedron's fully integrated small-strain kernels for a
// parallelepiped (constant Jacobian) and an axis-aligned brick: the 2x2x2 sums in closed
// form (docs/theory.md, "Element library"). The general element is in element/hex8.hpp.
#pragma once

#include <array>
#include <cmath>

#include "common/simd_pack.hpp"
#include "element/hex8.hpp"

namespace exdyn::element {

namespace hex8 {

// ---------------------------------------------------------------------------
// Full integration, parallelepiped (constant Jacobian). The natural gradient is
//   D(xi) = M_1 + xi M_xi + eta M_eta + zeta M_zeta + eta zeta M_etazeta + zeta xi M_zetaxi + xi eta M_xieta,
// and these seven functions are orthogonal under the 2x2x2 rule with
// sum_g phi^2 = 8 n, n = 1, 1/3 (linear), 1/9 (bilinear). With V = 8 det J the
// 8-point sums collapse to seven terms: E = V/2 sum_t n_t sigma_t : eps_t, and the
// mean stress is sigma of M_1. Exactly the 2x2x2 result, at a fraction of the cost.
// Reference data per element: dxi_a/dx_j (9, row a), V (1).
// ---------------------------------------------------------------------------
inline constexpr int parallelepiped_reference_size = 10;

inline double make_parallelepiped_reference(const ElementVectors& x_ref, double* reference) {
  const ElementModes c = modes_from_nodal(x_ref);
  const Matrix3 jacobian = natural_gradient(c, 0.0, 0.0, 0.0);
  const double det = determinant(jacobian);
  if (det > 0.0) {
    const Matrix3 inverse_jacobian = inverse(jacobian);
    for (int k = 0; k < 9; ++k) reference[k] = inverse_jacobian[k];
  } else {
    for (int k = 0; k < 9; ++k) reference[k] = 0.0;
  }
  reference[9] = 8.0 * det;
  return det;
}

// True when the parallelepiped's edges run along x, y and z (the boxes of this
// program): its inverse Jacobian is diagonal, to `tolerance` relative to the largest
// entry, and the axis-aligned kernel below applies.
inline bool is_axis_aligned(const double* parallelepiped_reference, double tolerance = 1.0e-12) {
  const double* r = parallelepiped_reference;
  const double diagonal = std::max({std::abs(r[0]), std::abs(r[4]), std::abs(r[8])});
  const double off_diagonal = std::max(
      {std::abs(r[1]), std::abs(r[2]), std::abs(r[3]), std::abs(r[5]), std::abs(r[6]), std::abs(r[7])});
  return off_diagonal <= tolerance * diagonal;
}

namespace detail {
// One term t whose natural gradient M_t has the columns flagged (the others are
// zero): sigma_t = C : sym(M_t dxi/dx), and out_a += weight (sigma_t (dxi/dx)^T)[:, a]
// for the same columns. Returns sigma_t.
template <bool column0, bool column1, bool column2, class Real>
inline std::array<Real, 6> parallelepiped_term(double lambda, double mu,
                                               const std::array<Real, 9>& inverse_jacobian,
                                               const std::array<Real, 3>& d0, const std::array<Real, 3>& d1,
                                               const std::array<Real, 3>& d2, Real weight,
                                               std::array<Real, 3>& out0, std::array<Real, 3>& out1,
                                               std::array<Real, 3>& out2) {
  const std::array<Real, 9>& r = inverse_jacobian;
  std::array<Real, 9> h{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Real sum{};
      if constexpr (column0) sum += d0[i] * r[j];
      if constexpr (column1) sum += d1[i] * r[3 + j];
      if constexpr (column2) sum += d2[i] * r[6 + j];
      h[3 * i + j] = sum;
    }
  const std::array<Real, 6> s = stress_from_gradient(lambda, mu, h);
  const std::array<Real, 6> ws{weight * s[0], weight * s[1], weight * s[2],
                               weight * s[3], weight * s[4], weight * s[5]};
  // (sigma (dxi/dx)^T)_ia = sum_j sigma_ij dxi_a/dx_j, sigma rows (xx xy xz), (xy yy yz), (xz yz zz).
  const auto column = [&](int a, std::array<Real, 3>& out) {
    out[0] += ws[0] * r[3 * a] + ws[3] * r[3 * a + 1] + ws[5] * r[3 * a + 2];
    out[1] += ws[3] * r[3 * a] + ws[1] * r[3 * a + 1] + ws[4] * r[3 * a + 2];
    out[2] += ws[5] * r[3 * a] + ws[4] * r[3 * a + 1] + ws[2] * r[3 * a + 2];
  };
  if constexpr (column0) column(0, out0);
  if constexpr (column1) column(1, out1);
  if constexpr (column2) column(2, out2);
  return s;
}
}  // namespace detail

// For one element (Real = double, reference data as written by
// make_parallelepiped_reference) or a pack of elements (Real = Pack<L>, the
// elements' data interleaved value by value).
template <class Real>
inline Real parallelepiped_internal_forces(const double* reference, double lambda, double mu,
                                           const BasicElementVectors<Real>& u, BasicElementVectors<Real>& f,
                                           std::array<Real, 6>& mean_stress) {
  const BasicElementModes<Real> c = modes_from_nodal(u);
  std::array<Real, 9> inverse_jacobian;
  for (int k = 0; k < 9; ++k) inverse_jacobian[k] = load<Real>(reference, k);
  const Real w = 0.125 * load<Real>(reference, 9);  // V/8: the 1/8 of the inverse mode transform folded in
  const Real w_linear = w * (1.0 / 3.0), w_bilinear = w * (1.0 / 9.0);
  std::array<std::array<Real, 3>, 8> cm{};
  for (int k = 1; k < 8; ++k) cm[k] = c[k];
  std::array<std::array<Real, 3>, 8> force{};
  std::array<Real, 3> unused{};
  const std::array<Real, 3>& none = unused;
  // M_1 = [c1 | c2 | c3]
  mean_stress = detail::parallelepiped_term<true, true, true>(lambda, mu, inverse_jacobian, cm[1], cm[2],
                                                              cm[3], w, force[1], force[2], force[3]);
  // M_xi = [0 | c6 | c5], M_eta = [c6 | 0 | c4], M_zeta = [c5 | c4 | 0]
  detail::parallelepiped_term<false, true, true>(lambda, mu, inverse_jacobian, none, cm[6], cm[5], w_linear,
                                                 unused, force[6], force[5]);
  detail::parallelepiped_term<true, false, true>(lambda, mu, inverse_jacobian, cm[6], none, cm[4], w_linear,
                                                 force[6], unused, force[4]);
  detail::parallelepiped_term<true, true, false>(lambda, mu, inverse_jacobian, cm[5], cm[4], none, w_linear,
                                                 force[5], force[4], unused);
  // M_etazeta = [c7 | 0 | 0], M_zetaxi = [0 | c7 | 0], M_xieta = [0 | 0 | c7]
  detail::parallelepiped_term<true, false, false>(lambda, mu, inverse_jacobian, cm[7], none, none, w_bilinear,
                                                  force[7], unused, unused);
  detail::parallelepiped_term<false, true, false>(lambda, mu, inverse_jacobian, none, cm[7], none, w_bilinear,
                                                  unused, force[7], unused);
  detail::parallelepiped_term<false, false, true>(lambda, mu, inverse_jacobian, none, none, cm[7], w_bilinear,
                                                  unused, unused, force[7]);
  std::array<Real, 8> fx{}, fy{}, fz{};
  Real energy{};
  for (int k = 1; k < 8; ++k) {
    fx[k] = force[k][0];
    fy[k] = force[k][1];
    fz[k] = force[k][2];
    energy += c.x[k] * fx[k] + c.y[k] * fy[k] + c.z[k] * fz[k];
  }
  f.x = nodal_from_modes(fx);
  f.y = nodal_from_modes(fy);
  f.z = nodal_from_modes(fz);
  return 4.0 * energy;  // u.f / 2
}

// ---------------------------------------------------------------------------
// Full integration, axis-aligned brick (is_axis_aligned: dxi/dx = diag(r0, r1, r2),
// entries 0, 4, 8 of the parallelepiped reference data). The seven terms above with
// the zeros taken out by hand: a term's gradient H = M_t diag(r) has
// H_ij = (M_t)_ij r_j, and its force is out_a = weight r_a sigma[:, a] (row a of the
// symmetric sigma). Columns that are zero, and stress components that no force of
// the term reads, are never formed (in floating point the compiler cannot drop an
// addition of zero). The same operations as parallelepiped_internal_forces for a
// diagonal dxi/dx, up to the association of weight r_a sigma: round-off apart, the
// same result (tested to 1e-14).
// ---------------------------------------------------------------------------
template <class Real>
inline Real axis_aligned_internal_forces(const double* reference, double lambda, double mu,
                                         const BasicElementVectors<Real>& u, BasicElementVectors<Real>& f,
                                         std::array<Real, 6>& mean_stress) {
  const BasicElementModes<Real> c = modes_from_nodal(u);
  const Real r0 = load<Real>(reference, 0), r1 = load<Real>(reference, 4), r2 = load<Real>(reference, 8);
  const Real w = 0.125 * load<Real>(reference, 9);  // V/8, as in parallelepiped_internal_forces
  const double two_mu = 2.0 * mu, lambda_two_mu = lambda + 2.0 * mu;
  // weight r_a for the constant term (w), the linear ones (w/3) and the bilinear ones (w/9).
  const Real w0 = w * r0, w1 = w * r1, w2 = w * r2;
  const Real l0 = w0 * (1.0 / 3.0), l1 = w1 * (1.0 / 3.0), l2 = w2 * (1.0 / 3.0);
  const Real b0 = w0 * (1.0 / 9.0), b1 = w1 * (1.0 / 9.0), b2 = w2 * (1.0 / 9.0);
  std::array<Real, 8> fx{}, fy{}, fz{};
  {  // M_1 = [c1 | c2 | c3]: the mean stress; force modes 1, 2, 3 from rows 0, 1, 2.
    const Real exx = c.x[1] * r0, eyy = c.y[2] * r1, ezz = c.z[3] * r2;
    const Real lambda_trace = lambda * (exx + eyy + ezz);
    const Real sxx = lambda_trace + two_mu * exx, syy = lambda_trace + two_mu * eyy,
               szz = lambda_trace + two_mu * ezz;
    const Real sxy = mu * (c.x[2] * r1 + c.y[1] * r0), syz = mu * (c.y[3] * r2 + c.z[2] * r1),
               sxz = mu * (c.x[3] * r2 + c.z[1] * r0);
    mean_stress = {sxx, syy, szz, sxy, syz, sxz};
    fx[1] = w0 * sxx, fy[1] = w0 * sxy, fz[1] = w0 * sxz;
    fx[2] = w1 * sxy, fy[2] = w1 * syy, fz[2] = w1 * syz;
    fx[3] = w2 * sxz, fy[3] = w2 * syz, fz[3] = w2 * szz;
  }
  {  // M_xi = [0 | c6 | c5]: rows 1 -> mode 6, 2 -> mode 5 (sigma_xx unused).
    const Real eyy = c.y[6] * r1, ezz = c.z[5] * r2;
    const Real lambda_trace = lambda * (eyy + ezz);
    const Real syy = lambda_trace + two_mu * eyy, szz = lambda_trace + two_mu * ezz;
    const Real sxy = mu * (c.x[6] * r1), syz = mu * (c.y[5] * r2 + c.z[6] * r1), sxz = mu * (c.x[5] * r2);
    fx[6] = l1 * sxy, fy[6] = l1 * syy, fz[6] = l1 * syz;
    fx[5] = l2 * sxz, fy[5] = l2 * syz, fz[5] = l2 * szz;
  }
  {  // M_eta = [c6 | 0 | c4]: rows 0 -> mode 6, 2 -> mode 4 (sigma_yy unused).
    const Real exx = c.x[6] * r0, ezz = c.z[4] * r2;
    const Real lambda_trace = lambda * (exx + ezz);
    const Real sxx = lambda_trace + two_mu * exx, szz = lambda_trace + two_mu * ezz;
    const Real sxy = mu * (c.y[6] * r0), syz = mu * (c.y[4] * r2), sxz = mu * (c.x[4] * r2 + c.z[6] * r0);
    fx[6] += l0 * sxx, fy[6] += l0 * sxy, fz[6] += l0 * sxz;
    fx[4] = l2 * sxz, fy[4] = l2 * syz, fz[4] = l2 * szz;
  }
  {  // M_zeta = [c5 | c4 | 0]: rows 0 -> mode 5, 1 -> mode 4 (sigma_zz unused).
    const Real exx = c.x[5] * r0, eyy = c.y[4] * r1;
    const Real lambda_trace = lambda * (exx + eyy);
    const Real sxx = lambda_trace + two_mu * exx, syy = lambda_trace + two_mu * eyy;
    const Real sxy = mu * (c.x[4] * r1 + c.y[5] * r0), syz = mu * (c.z[4] * r1), sxz = mu * (c.z[5] * r0);
    fx[5] += l0 * sxx, fy[5] += l0 * sxy, fz[5] += l0 * sxz;
    fx[4] += l1 * sxy, fy[4] += l1 * syy, fz[4] += l1 * syz;
  }
  // M_etazeta = [c7 | 0 | 0], M_zetaxi = [0 | c7 | 0], M_xieta = [0 | 0 | c7]: one
  // non-zero strain column each, so sigma_aa = (lambda + 2 mu) e_aa; all into mode 7.
  // [c7 | 0 | 0]: row 0 = ((lambda + 2 mu) c7x r0, mu c7y r0, mu c7z r0).
  fx[7] = b0 * (lambda_two_mu * (c.x[7] * r0));
  fy[7] = b0 * (mu * (c.y[7] * r0));
  fz[7] = b0 * (mu * (c.z[7] * r0));
  // [0 | c7 | 0]: row 1 = (mu c7x r1, (lambda + 2 mu) c7y r1, mu c7z r1).
  fx[7] += b1 * (mu * (c.x[7] * r1));
  fy[7] += b1 * (lambda_two_mu * (c.y[7] * r1));
  fz[7] += b1 * (mu * (c.z[7] * r1));
  // [0 | 0 | c7]: row 2 = (mu c7x r2, mu c7y r2, (lambda + 2 mu) c7z r2).
  fx[7] += b2 * (mu * (c.x[7] * r2));
  fy[7] += b2 * (mu * (c.y[7] * r2));
  fz[7] += b2 * (lambda_two_mu * (c.z[7] * r2));
  Real energy{};
  for (int k = 1; k < 8; ++k) energy += c.x[k] * fx[k] + c.y[k] * fy[k] + c.z[k] * fz[k];
  f.x = nodal_from_modes(fx);
  f.y = nodal_from_modes(fy);
  f.z = nodal_from_modes(fz);
  return 4.0 * energy;  // u.f / 2
}

}  // namespace hex8

}  // namespace exdyn::element
