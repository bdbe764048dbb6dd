// The trilinear eight-node hexahedron: shape functions, its mode basis, geometry,
// and the fully integrated (2x2x2 Gauss) small-strain kernel of a general element
// (the closed forms for parallelepipeds: element/hex8_parallelepiped.hpp). Free
// functions on fixed-size local data; no allocation, no exceptions (docs/theory.md,
// "Element library").
//
// Nodes in VTK hexahedron order: 0..3 the face zeta = -1 counter-clockwise seen
// from +zeta, (-1,-1,-1) (1,-1,-1) (1,1,-1) (-1,1,-1); 4..7 the same at zeta = +1.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "common/simd_pack.hpp"
#include "element/node_values.hpp"
#include "material/elastic.hpp"

namespace exdyn::element {

using Vector3 = std::array<double, 3>;
using Matrix3 = std::array<double, 9>;  // row-major

// One vector per node of one element (or of a pack of elements), the components apart
// (x[I], y[I], z[I] for node I in VTK order): gathered from and scattered to NodalVectors.
template <class Real>
using BasicElementVectors = NodeValues<8, Real>;
using ElementVectors = BasicElementVectors<double>;

namespace hex8 {

// (xi, eta, zeta) of node I.
inline constexpr std::array<Vector3, 8> node_natural_coordinates{{{-1.0, -1.0, -1.0},
                                                                  {1.0, -1.0, -1.0},
                                                                  {1.0, 1.0, -1.0},
                                                                  {-1.0, 1.0, -1.0},
                                                                  {-1.0, -1.0, 1.0},
                                                                  {1.0, -1.0, 1.0},
                                                                  {1.0, 1.0, 1.0},
                                                                  {-1.0, 1.0, 1.0}}};

// 2x2x2 Gauss-Legendre rule: point g at gauss_abscissa * (natural coordinates of
// node g), weight 1. Exact for polynomials of degree 3 in each variable.
inline constexpr double gauss_abscissa = 0.57735026918962576451;  // 1/sqrt(3)

// N_I = (1 + xi_I xi)(1 + eta_I eta)(1 + zeta_I zeta) / 8.
inline std::array<double, 8> shape_functions(double xi, double eta, double zeta) {
  std::array<double, 8> n{};
  for (int node = 0; node < 8; ++node) {
    const Vector3& s = node_natural_coordinates[node];
    n[node] = 0.125 * (1.0 + s[0] * xi) * (1.0 + s[1] * eta) * (1.0 + s[2] * zeta);
  }
  return n;
}

// dN_I/dxi_a, a = xi, eta, zeta.
inline std::array<Vector3, 8> shape_function_derivatives(double xi, double eta, double zeta) {
  std::array<Vector3, 8> d{};
  for (int node = 0; node < 8; ++node) {
    const Vector3& s = node_natural_coordinates[node];
    const double a = 1.0 + s[0] * xi, b = 1.0 + s[1] * eta, c = 1.0 + s[2] * zeta;
    d[node] = {0.125 * s[0] * b * c, 0.125 * a * s[1] * c, 0.125 * a * b * s[2]};
  }
  return d;
}

// ---------------------------------------------------------------------------
// Mode basis. A trilinear field is
//   u(xi) = c_0 + c_1 xi + c_2 eta + c_3 zeta + c_4 eta zeta + c_5 zeta xi + c_6 xi eta + c_7 xi eta zeta.
// The basis functions evaluated at the nodes, phi_m(I), are orthogonal vectors of
// squared length 8, so c_m = (1/8) sum_I phi_m(I) u_I; modes 4..7 are the
// hourglass base vectors h_alpha of Flanagan and Belytschko (1981).
// ---------------------------------------------------------------------------
inline constexpr int mode_count = 8;

// phi_m(I): the value of basis function m at node I.
inline constexpr double mode_value(int mode, int node) {
  const Vector3& s = node_natural_coordinates[node];
  switch (mode) {
    case 0:
      return 1.0;
    case 1:
      return s[0];
    case 2:
      return s[1];
    case 3:
      return s[2];
    case 4:
      return s[1] * s[2];
    case 5:
      return s[2] * s[0];
    case 6:
      return s[0] * s[1];
    default:
      return s[0] * s[1] * s[2];
  }
}

// c_m = (1/8) sum_I phi_m(I) u_I, by a fast Walsh-Hadamard butterfly (24 additions).
template <class Real>
inline std::array<Real, 8> modes_from_nodal(const std::array<Real, 8>& u) {
  // Along xi: pairs (0,1), (3,2), (4,5), (7,6).
  const Real s01 = u[0] + u[1], d01 = u[1] - u[0];
  const Real s32 = u[3] + u[2], d32 = u[2] - u[3];
  const Real s45 = u[4] + u[5], d45 = u[5] - u[4];
  const Real s76 = u[7] + u[6], d76 = u[6] - u[7];
  // Along eta.
  const Real ss0 = s01 + s32, ds0 = s32 - s01, sd0 = d01 + d32, dd0 = d32 - d01;
  const Real ss1 = s45 + s76, ds1 = s76 - s45, sd1 = d45 + d76, dd1 = d76 - d45;
  // Along zeta.
  return {0.125 * (ss0 + ss1), 0.125 * (sd0 + sd1), 0.125 * (ds0 + ds1), 0.125 * (ss1 - ss0),
          0.125 * (ds1 - ds0), 0.125 * (sd1 - sd0), 0.125 * (dd0 + dd1), 0.125 * (dd1 - dd0)};
}

// f_I = sum_m phi_m(I) F_m: the transpose of modes_from_nodal without the 1/8.
template <class Real>
inline std::array<Real, 8> nodal_from_modes(const std::array<Real, 8>& c) {
  const Real ss0 = c[0] - c[3], ss1 = c[0] + c[3];
  const Real ds0 = c[2] - c[4], ds1 = c[2] + c[4];
  const Real sd0 = c[1] - c[5], sd1 = c[1] + c[5];
  const Real dd0 = c[6] - c[7], dd1 = c[6] + c[7];
  const Real s01 = ss0 - ds0, s32 = ss0 + ds0, d01 = sd0 - dd0, d32 = sd0 + dd0;
  const Real s45 = ss1 - ds1, s76 = ss1 + ds1, d45 = sd1 - dd1, d76 = sd1 + dd1;
  return {s01 - d01, s01 + d01, s32 + d32, s32 - d32, s45 - d45, s45 + d45, s76 + d76, s76 - d76};
}

// The modes of the three components of an element vector field.
template <class Real>
struct BasicElementModes {
  std::array<Real, 8> x, y, z;
  std::array<Real, 3> operator[](int mode) const { return {x[mode], y[mode], z[mode]}; }
};
using ElementModes = BasicElementModes<double>;

template <class Real>
inline BasicElementModes<Real> modes_from_nodal(const BasicElementVectors<Real>& v) {
  return {modes_from_nodal(v.x), modes_from_nodal(v.y), modes_from_nodal(v.z)};
}

// G_ia = du_i/dxi_a at (xi, eta, zeta) of the field with modes c:
//   du/dxi = c1 + c5 zeta + c6 eta + c7 eta zeta, and cyclically.
inline Matrix3 natural_gradient(const ElementModes& c, double xi, double eta, double zeta) {
  Matrix3 g{};
  const std::array<const std::array<double, 8>*, 3> component{&c.x, &c.y, &c.z};
  for (int i = 0; i < 3; ++i) {
    const std::array<double, 8>& m = *component[i];
    g[3 * i + 0] = m[1] + m[5] * zeta + m[6] * eta + m[7] * eta * zeta;
    g[3 * i + 1] = m[2] + m[4] * zeta + m[6] * xi + m[7] * xi * zeta;
    g[3 * i + 2] = m[3] + m[4] * eta + m[5] * xi + m[7] * xi * eta;
  }
  return g;
}

inline double determinant(const Matrix3& a) {
  return a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
         a[2] * (a[3] * a[7] - a[4] * a[6]);
}

// a^-1 for det(a) != 0.
inline Matrix3 inverse(const Matrix3& a) {
  const double inv_det = 1.0 / determinant(a);
  return {(a[4] * a[8] - a[5] * a[7]) * inv_det, (a[2] * a[7] - a[1] * a[8]) * inv_det,
          (a[1] * a[5] - a[2] * a[4]) * inv_det, (a[5] * a[6] - a[3] * a[8]) * inv_det,
          (a[0] * a[8] - a[2] * a[6]) * inv_det, (a[2] * a[3] - a[0] * a[5]) * inv_det,
          (a[3] * a[7] - a[4] * a[6]) * inv_det, (a[1] * a[6] - a[0] * a[7]) * inv_det,
          (a[0] * a[4] - a[1] * a[3]) * inv_det};
}

// ---------------------------------------------------------------------------
// Geometry of the reference configuration.
// ---------------------------------------------------------------------------

// The Jacobian at the 2x2x2 Gauss points, the volume V = sum_g det J_g (m^3) and
// the smallest det J (<= 0: an inverted or degenerate element).
struct GaussGeometry {
  std::array<Matrix3, 8> inverse_jacobian{};  // dxi_a/dx_j at each Gauss point, row a
  std::array<double, 8> det_jacobian{};       // det(dx_j/dxi_a), m^3 (weights are 1)
  double volume = 0.0;
  double min_det_jacobian = 0.0;
};

inline GaussGeometry gauss_geometry(const ElementVectors& x_ref) {
  GaussGeometry geometry;
  const ElementModes c = modes_from_nodal(x_ref);
  geometry.min_det_jacobian = std::numeric_limits<double>::infinity();
  for (int g = 0; g < 8; ++g) {
    const Vector3& s = node_natural_coordinates[g];
    const Matrix3 jacobian =
        natural_gradient(c, gauss_abscissa * s[0], gauss_abscissa * s[1], gauss_abscissa * s[2]);
    const double det = determinant(jacobian);
    geometry.det_jacobian[g] = det;
    geometry.volume += det;
    geometry.min_det_jacobian = std::min(geometry.min_det_jacobian, det);
    if (det > 0.0) geometry.inverse_jacobian[g] = inverse(jacobian);
  }
  return geometry;
}

// Element volume (m^3), exact for the trilinear hexahedron.
inline double volume(const ElementVectors& x_ref) { return gauss_geometry(x_ref).volume; }

// Faces as node quadruples (outward normal by the right-hand rule).
inline constexpr std::array<std::array<int, 4>, 6> faces{
    {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};

// Area of a bilinear face projected on its mean plane: |d1 x d2| / 2 with the
// diagonals d1 = x2 - x0, d2 = x3 - x1 (exact for a planar face), m^2.
inline double face_area(const ElementVectors& x, const std::array<int, 4>& face) {
  const Vector3 d1{x.x[face[2]] - x.x[face[0]], x.y[face[2]] - x.y[face[0]], x.z[face[2]] - x.z[face[0]]};
  const Vector3 d2{x.x[face[3]] - x.x[face[1]], x.y[face[3]] - x.y[face[1]], x.z[face[3]] - x.z[face[1]]};
  const Vector3 n{d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                  d1[0] * d2[1] - d1[1] * d2[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// Characteristic length L = V / (largest face area), m; L = h for a cube of side h.
inline double characteristic_length(const ElementVectors& x_ref) {
  double largest = 0.0;
  for (const auto& face : faces) largest = std::max(largest, face_area(x_ref, face));
  return volume(x_ref) / largest;
}

// integral of N_I dV (m^3) for each node: the row sums of the consistent mass / rho.
inline std::array<double, 8> shape_function_integrals(const ElementVectors& x_ref) {
  const GaussGeometry geometry = gauss_geometry(x_ref);
  std::array<double, 8> integral{};
  for (int g = 0; g < 8; ++g) {
    const Vector3& s = node_natural_coordinates[g];
    const std::array<double, 8> n =
        shape_functions(gauss_abscissa * s[0], gauss_abscissa * s[1], gauss_abscissa * s[2]);
    for (int node = 0; node < 8; ++node) integral[node] += n[node] * geometry.det_jacobian[g];
  }
  return integral;
}

// True when the element is a parallelepiped (x linear in xi: the hourglass modes
// of the coordinates vanish), so that its Jacobian is constant. `tolerance` is
// relative to the largest edge-like mode.
inline bool is_parallelepiped(const ElementVectors& x_ref, double tolerance = 1.0e-12) {
  const ElementModes c = modes_from_nodal(x_ref);
  double linear = 0.0, hourglass = 0.0;
  for (int m = 1; m < 4; ++m)
    linear = std::max({linear, std::abs(c.x[m]), std::abs(c.y[m]), std::abs(c.z[m])});
  for (int m = 4; m < 8; ++m)
    hourglass = std::max({hourglass, std::abs(c.x[m]), std::abs(c.y[m]), std::abs(c.z[m])});
  return hourglass <= tolerance * linear;
}

// ---------------------------------------------------------------------------
// Small-strain helpers. Stress and strain as SymTensor (xx yy zz xy yz xz).
// ---------------------------------------------------------------------------

// eps = sym(H) for the displacement gradient H_ij = du_i/dx_j.
inline material::SymTensor symmetric_part(const Matrix3& h) {
  return {h[0], h[4], h[8], 0.5 * (h[1] + h[3]), 0.5 * (h[5] + h[7]), 0.5 * (h[2] + h[6])};
}

// sigma = lambda tr(eps) I + 2 mu eps from H directly.
template <class Real>
inline std::array<Real, 6> stress_from_gradient(double lambda, double mu, const std::array<Real, 9>& h) {
  const Real lambda_trace = lambda * (h[0] + h[4] + h[8]);
  const double two_mu = 2.0 * mu;
  return {lambda_trace + two_mu * h[0], lambda_trace + two_mu * h[4], lambda_trace + two_mu * h[8],
          mu * (h[1] + h[3]),           mu * (h[5] + h[7]),           mu * (h[2] + h[6])};
}

// The stress (Pa) at each Gauss point g (at gauss_abscissa * node g) for the
// displacement u: sigma_g = C : sym(du/dxi dxi/dx). For checks and output; the
// kernels below never form it this way.
inline std::array<material::SymTensor, 8> gauss_point_stresses(const ElementVectors& x_ref, double lambda,
                                                               double mu, const ElementVectors& u) {
  const GaussGeometry geometry = gauss_geometry(x_ref);
  const ElementModes c = modes_from_nodal(u);
  std::array<material::SymTensor, 8> stresses{};
  for (int g = 0; g < 8; ++g) {
    const Vector3& s = node_natural_coordinates[g];
    const Matrix3 d =
        natural_gradient(c, gauss_abscissa * s[0], gauss_abscissa * s[1], gauss_abscissa * s[2]);
    const Matrix3& r = geometry.inverse_jacobian[g];
    Matrix3 h{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int a = 0; a < 3; ++a) h[3 * i + j] += d[3 * i + a] * r[3 * a + j];
    stresses[g] = stress_from_gradient(lambda, mu, h);
  }
  return stresses;
}

// ---------------------------------------------------------------------------
// Full integration, general hexahedron.
// Reference data per element (reference_size doubles), point by point in the order
// the kernel reads them (one stream for the prefetcher): entry [10 g + k] is component
// k (row-major a, j) of the inverse Jacobian dxi_a/dx_j at point g (k < 9),
// [10 g + 9] is w det J_g / 8; then 8 / V at [80]. (The 1/8 of the inverse mode
// transform is folded into the stored weight.)
// ---------------------------------------------------------------------------
inline constexpr int reference_size = 81;

// Fills reference[0..reference_size). Returns the smallest det J (<= 0: inverted).
inline double make_reference(const ElementVectors& x_ref, double* reference) {
  const GaussGeometry geometry = gauss_geometry(x_ref);
  for (int g = 0; g < 8; ++g) {
    for (int k = 0; k < 9; ++k) reference[10 * g + k] = geometry.inverse_jacobian[g][k];
    reference[10 * g + 9] = 0.125 * geometry.det_jacobian[g];
  }
  reference[80] = 8.0 / geometry.volume;
  return geometry.min_det_jacobian;
}

namespace detail {
// Signs of the Gauss points' natural coordinates, and their products.
inline constexpr double gauss_sign_xi[8] = {-1, 1, 1, -1, -1, 1, 1, -1};
inline constexpr double gauss_sign_eta[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
inline constexpr double gauss_sign_zeta[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
inline constexpr double gauss_sign_eta_zeta[8] = {1, 1, -1, -1, -1, -1, 1, 1};
inline constexpr double gauss_sign_zeta_xi[8] = {1, -1, -1, 1, -1, 1, 1, -1};
inline constexpr double gauss_sign_xi_eta[8] = {1, -1, 1, -1, 1, -1, 1, -1};

// The mode coefficients of u that the gradients need (modes 1..7 of each component),
// the abscissa folded into the higher ones (4..7).
template <class Real>
struct GradientModes {
  Real m1[3], m2[3], m3[3], m4[3], m5[3], m6[3], m7[3];
};

template <class Real>
inline GradientModes<Real> gradient_modes(const BasicElementModes<Real>& c) {
  constexpr double a = gauss_abscissa, a2 = gauss_abscissa * gauss_abscissa;
  const std::array<const std::array<Real, 8>*, 3> modes{&c.x, &c.y, &c.z};
  GradientModes<Real> g;
  for (int i = 0; i < 3; ++i) {
    const std::array<Real, 8>& m = *modes[i];
    g.m1[i] = m[1], g.m2[i] = m[2], g.m3[i] = m[3];
    g.m4[i] = a * m[4], g.m5[i] = a * m[5], g.m6[i] = a * m[6], g.m7[i] = a2 * m[7];
  }
  return g;
}

// H_ij = du_i/dx_j at Gauss point g: D[3 i + a] = du_i/dxi_a from the modes, times
// r = dxi/dx at the point (row-major (a, j)).
template <class Real>
inline void gradient_at_point(const GradientModes<Real>& m, int g, const Real r[9], Real h[9]) {
  const double sx = gauss_sign_xi[g], se = gauss_sign_eta[g], sz = gauss_sign_zeta[g];
  const double sez = gauss_sign_eta_zeta[g], szx = gauss_sign_zeta_xi[g], sxe = gauss_sign_xi_eta[g];
  Real d[9];
  for (int i = 0; i < 3; ++i) {
    d[3 * i + 0] = m.m1[i] + sz * m.m5[i] + se * m.m6[i] + sez * m.m7[i];
    d[3 * i + 1] = m.m2[i] + sz * m.m4[i] + sx * m.m6[i] + szx * m.m7[i];
    d[3 * i + 2] = m.m3[i] + se * m.m4[i] + sx * m.m5[i] + sxe * m.m7[i];
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      h[3 * i + j] = d[3 * i] * r[j] + d[3 * i + 1] * r[3 + j] + d[3 * i + 2] * r[6 + j];
}

// The mode forces of one component at Gauss point g: F_m += sum_a q_a dphi_m/dxi_a (g)
// (m = 1..7, before the abscissa scaling of 4..7), q_a = sum_j P_ij dxi_a/dx_j.
template <class Real>
inline void add_mode_forces(int g, const Real q[3], Real fm[8]) {
  const double sx = gauss_sign_xi[g], se = gauss_sign_eta[g], sz = gauss_sign_zeta[g];
  const double sez = gauss_sign_eta_zeta[g], szx = gauss_sign_zeta_xi[g], sxe = gauss_sign_xi_eta[g];
  fm[1] += q[0];
  fm[2] += q[1];
  fm[3] += q[2];
  fm[4] += sz * q[1] + se * q[2];
  fm[5] += sz * q[0] + sx * q[2];
  fm[6] += se * q[0] + sx * q[1];
  fm[7] += sez * q[0] + szx * q[1] + sxe * q[2];
}
}  // namespace detail

// f = K u for one element (Real = double) or a pack of elements (Real = Pack<L>,
// their reference data interleaved value by value: load<Real>), in N for u in m;
// the volume-averaged stress (Pa) and the strain energy
// sum_g w det J sigma:eps / 2 = u.f / 2 (J).
//   D_g = du/dxi at g (from the modes of u), H_g = D_g dxi/dx, sigma_g = C : sym(H_g),
//   P_g = w det J sigma_g (dxi/dx)^T, and f = sum_g B_g^T sigma_g w det J assembled
//   in mode space: F_m = sum_g sum_a P_g[:, a] d phi_m/dxi_a (g), f_I = sum_m phi_m(I) F_m / 8.
// One Gauss point after the other, each fully unrolled (the signs are constants):
// the vector lanes are the elements of the pack, so every operation is a full-width
// one (the single-element version's 8-point vectors fill only 2 or 4 lanes and need
// reductions). Sums over g run in the order g = 0..7 for any Real.
template <class Real>
inline Real internal_forces(const double* reference, double lambda, double mu,
                            const BasicElementVectors<Real>& u, BasicElementVectors<Real>& f,
                            std::array<Real, 6>& mean_stress) {
  using namespace detail;
  const BasicElementModes<Real> c = modes_from_nodal(u);
  constexpr double a = gauss_abscissa, a2 = gauss_abscissa * gauss_abscissa;
  const GradientModes<Real> m = gradient_modes(c);
  const double two_mu = 2.0 * mu;
  std::array<Real, 6> stress_sum{};
  // F_m per component i (m = 1..7, before the abscissa scaling of 4..7).
  Real force[3][8] = {};
  constexpr int row[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};  // s_ij in SymTensor order
#pragma GCC unroll 8
  for (int g = 0; g < 8; ++g) {
    Real r[9];  // dxi_a/dx_j at g, row-major (a, j)
    for (int k = 0; k < 9; ++k) r[k] = load<Real>(reference, 10 * g + k);
    // H_ij = sum_a D_ia dxi_a/dx_j, then the weighted stress s = (w det J / 8) sigma.
    Real h[9];
    gradient_at_point(m, g, r, h);
    const Real w = load<Real>(reference, 10 * g + 9);
    const Real lambda_trace = lambda * (h[0] + h[4] + h[8]);
    const Real s[6] = {w * (lambda_trace + two_mu * h[0]), w * (lambda_trace + two_mu * h[4]),
                       w * (lambda_trace + two_mu * h[8]), w * (mu * (h[1] + h[3])),
                       w * (mu * (h[5] + h[7])),           w * (mu * (h[2] + h[6]))};
    for (int k = 0; k < 6; ++k) stress_sum[k] += s[k];
    // P_ia = sum_j s_ij dxi_a/dx_j; the mode forces are sums over g of P with signs.
    for (int i = 0; i < 3; ++i) {
      Real p[3];
      for (int k = 0; k < 3; ++k)
        p[k] = s[row[i][0]] * r[3 * k] + s[row[i][1]] * r[3 * k + 1] + s[row[i][2]] * r[3 * k + 2];
      add_mode_forces(g, p, force[i]);
    }
  }
  const Real inverse_volume_8 = load<Real>(reference, 80);
  for (int k = 0; k < 6; ++k) mean_stress[k] = stress_sum[k] * inverse_volume_8;
  std::array<Real, 8> fx{}, fy{}, fz{};
  const std::array<std::array<Real, 8>*, 3> force_modes{&fx, &fy, &fz};
  for (int i = 0; i < 3; ++i) {
    const Real* fm = force[i];
    *force_modes[i] = {Real{}, fm[1], fm[2], fm[3], a * fm[4], a * fm[5], a * fm[6], a2 * fm[7]};
  }
  f.x = nodal_from_modes(fx);
  f.y = nodal_from_modes(fy);
  f.z = nodal_from_modes(fz);
  // Strain energy = u.f / 2 = (8/2) sum_m c_m . F_m / 8 (orthogonality of the modes).
  Real energy{};
  for (int k = 1; k < 8; ++k) energy += c.x[k] * fx[k] + c.y[k] * fy[k] + c.z[k] * fz[k];
  return 4.0 * energy;
}

}  // namespace hex8
}  // namespace exdyn::element
