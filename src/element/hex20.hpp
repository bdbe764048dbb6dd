// The 20-node serendipity hexahedron: shape functions, Gauss rules, reference
// geometry and the small-strain force kernel on any geometry. Free functions on
// fixed-size local data; no allocation, no exceptions (docs/theory.md, "hex20").
//
// Nodes in VTK quadratic hexahedron order: 0..7 the corners as in hex8.hpp, then the
// mid-edge nodes of the bottom face (8: 0-1, 9: 1-2, 10: 2-3, 11: 3-0), of the top
// face (12: 4-5, 13: 5-6, 14: 6-7, 15: 7-4) and of the vertical edges (16: 0-4,
// 17: 1-5, 18: 2-6, 19: 3-7).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "element/hex8.hpp"
#include "element/node_values.hpp"
#include "material/elastic.hpp"

namespace exdyn::element::hex20 {

inline constexpr int node_count = 20;
using ElementVectors20 = NodeValues<20>;

// (xi, eta, zeta) of node I.
inline constexpr std::array<Vector3, 20> node_natural_coordinates{{
    {-1, -1, -1}, {1, -1, -1}, {1, 1, -1},  {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1},
    {-1, 1, 1},   {0, -1, -1}, {1, 0, -1},  {0, 1, -1},  {-1, 0, -1}, {0, -1, 1}, {1, 0, 1},
    {0, 1, 1},    {-1, 0, 1},  {-1, -1, 0}, {1, -1, 0},  {1, 1, 0},   {-1, 1, 0},
}};

// Corner (s_a = +-1): N = (1 + s.xi products)(s1 xi + s2 eta + s3 zeta - 2) / 8;
// mid-edge with s_a = 0: N = (1 - xi_a^2) prod_{b != a} (1 + s_b xi_b) / 4.
inline std::array<double, 20> shape_functions(double xi, double eta, double zeta) {
  std::array<double, 20> n{};
  const double p[3] = {xi, eta, zeta};
  for (int node = 0; node < 20; ++node) {
    const Vector3& s = node_natural_coordinates[node];
    if (node < 8) {
      n[node] = 0.125 * (1 + s[0] * xi) * (1 + s[1] * eta) * (1 + s[2] * zeta) *
                (s[0] * xi + s[1] * eta + s[2] * zeta - 2);
    } else {
      double value = 0.25;
      for (int a = 0; a < 3; ++a) value *= s[a] == 0.0 ? 1 - p[a] * p[a] : 1 + s[a] * p[a];
      n[node] = value;
    }
  }
  return n;
}

// dN_I/dxi_a, a = xi, eta, zeta.
inline std::array<Vector3, 20> shape_function_derivatives(double xi, double eta, double zeta) {
  std::array<Vector3, 20> d{};
  const double p[3] = {xi, eta, zeta};
  for (int node = 0; node < 20; ++node) {
    const Vector3& s = node_natural_coordinates[node];
    const double f[3] = {1 + s[0] * xi, 1 + s[1] * eta, 1 + s[2] * zeta};
    if (node < 8) {
      // d/dxi_a of f0 f1 f2 (sum - 2) / 8 = s_a (prod_{b != a} f_b) (sum - 2 + f_a) / 8.
      const double sum = s[0] * xi + s[1] * eta + s[2] * zeta - 2;
      for (int a = 0; a < 3; ++a) {
        const double others = f[(a + 1) % 3] * f[(a + 2) % 3];
        d[node][a] = 0.125 * s[a] * others * (sum + f[a]);
      }
    } else {
      int axis = 0;  // the edge's direction, s_axis = 0
      while (s[axis] != 0.0) ++axis;
      const int b = (axis + 1) % 3, c = (axis + 2) % 3;
      const double bubble = 1 - p[axis] * p[axis];
      d[node][axis] = 0.25 * (-2 * p[axis]) * f[b] * f[c];
      d[node][b] = 0.25 * bubble * s[b] * f[c];
      d[node][c] = 0.25 * bubble * f[b] * s[c];
    }
  }
  return d;
}

// ---------------------------------------------------------------------------
// Gauss-Legendre rules of n = 1 .. 3 points per direction (hex20: 3, hex20r: 2),
// points ordered xi fastest; weights multiply to 8 over the cube.
// ---------------------------------------------------------------------------
inline constexpr int max_gauss_points = 27;

struct GaussRule {
  int count = 0;
  std::array<Vector3, max_gauss_points> point{};
  std::array<double, max_gauss_points> weight{};
};

// One direction: abscissae and weights of the n-point rule (exact to degree 2n - 1).
inline void gauss_legendre_1d(int n, double* abscissa, double* weight) {
  if (n == 1) {
    abscissa[0] = 0.0, weight[0] = 2.0;
  } else if (n == 2) {
    constexpr double a = 0.57735026918962576451;  // 1/sqrt(3)
    abscissa[0] = -a, abscissa[1] = a, weight[0] = weight[1] = 1.0;
  } else {
    constexpr double a = 0.77459666924148337704;  // sqrt(3/5)
    abscissa[0] = -a, abscissa[1] = 0.0, abscissa[2] = a;
    weight[0] = weight[2] = 5.0 / 9.0, weight[1] = 8.0 / 9.0;
  }
}

inline GaussRule gauss_rule(int n) {
  GaussRule rule;
  double a[3], w[3];
  gauss_legendre_1d(n, a, w);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        rule.point[static_cast<std::size_t>(rule.count)] = {a[i], a[j], a[k]};
        rule.weight[static_cast<std::size_t>(rule.count)] = w[i] * w[j] * w[k];
        ++rule.count;
      }
  return rule;
}

// dN_I/dxi_a at every point of a rule: table[60 g + 20 a + I] (the shared data of a block).
inline constexpr int table_stride = 60;
inline void derivative_table(const GaussRule& rule, double* table) {
  for (int g = 0; g < rule.count; ++g) {
    const Vector3& p = rule.point[static_cast<std::size_t>(g)];
    const std::array<Vector3, 20> d = shape_function_derivatives(p[0], p[1], p[2]);
    for (int a = 0; a < 3; ++a)
      for (int node = 0; node < 20; ++node) table[table_stride * g + 20 * a + node] = d[node][a];
  }
}

// J_ja = dx_j/dxi_a at one point from the derivative table there (row-major j, a).
inline Matrix3 jacobian(const ElementVectors20& x, const double* dn) {
  Matrix3 j{};
  const std::array<const std::array<double, 20>*, 3> component{&x.x, &x.y, &x.z};
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a) {
      double sum = 0.0;
      for (int node = 0; node < 20; ++node) sum += (*component[i])[node] * dn[20 * a + node];
      j[3 * i + a] = sum;
    }
  return j;
}

// ---------------------------------------------------------------------------
// The general kernel. Reference data per element (reference_size(G) doubles): at
// each Gauss point g, dxi_a/dx_j (9, row a) then w_g det J_g (m^3) at [10 g .. 10 g + 9];
// then 1 / V at [10 G].
// ---------------------------------------------------------------------------
constexpr int reference_size(int gauss_points) { return 10 * gauss_points + 1; }

// Fills reference[0 .. reference_size(rule.count)). Returns the smallest det J at the
// Gauss points (<= 0: inverted or degenerate).
inline double make_reference(const ElementVectors20& x_ref, const GaussRule& rule, const double* table,
                             double* reference) {
  double volume = 0.0, smallest = std::numeric_limits<double>::infinity();
  for (int g = 0; g < rule.count; ++g) {
    const Matrix3 j = jacobian(x_ref, table + table_stride * g);
    const double det = hex8::determinant(j);
    smallest = std::min(smallest, det);
    const Matrix3 r = det > 0.0 ? hex8::inverse(j) : Matrix3{};
    for (int k = 0; k < 9; ++k) reference[10 * g + k] = r[k];
    const double w_det = rule.weight[static_cast<std::size_t>(g)] * det;
    reference[10 * g + 9] = w_det;
    volume += w_det;
  }
  reference[10 * rule.count] = volume > 0.0 ? 1.0 / volume : 0.0;
  return smallest;
}

// H_ij = du_i/dx_j at a point: D_ia = sum_I u_iI dN_I/dxi_a (dn: the point's row of the
// derivative table), nine sums carried together over the nodes, so the adds of one sum
// do not wait on each other (nine 20-term chains would be bound by the add latency;
// the order of each sum is still node 0 to 19); then H = D r, r = dxi/dx (row a).
template <class Real>
inline void gradient_at_point(const double* dn, const NodeValues<20, Real>& u, const Real r[9], Real h[9]) {
  const std::array<const std::array<Real, 20>*, 3> u_component{&u.x, &u.y, &u.z};
  Real d[3][3] = {};
  for (int node = 0; node < 20; ++node) {
    const double n0 = dn[node], n1 = dn[20 + node], n2 = dn[40 + node];
    for (int i = 0; i < 3; ++i) {
      const Real ui = (*u_component[i])[node];
      d[i][0] += ui * n0;
      d[i][1] += ui * n1;
      d[i][2] += ui * n2;
    }
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) h[3 * i + j] = d[i][0] * r[j] + d[i][1] * r[3 + j] + d[i][2] * r[6 + j];
}

// f_iI += sum_a q_a dN_I/dxi_a at a point, for one component i.
template <class Real>
inline void add_point_forces(const double* dn, const Real q[3], std::array<Real, 20>& out) {
  for (int node = 0; node < 20; ++node)
    out[node] += q[0] * dn[node] + q[1] * dn[20 + node] + q[2] * dn[40 + node];
}

// f = K u (f in N, u in m) by Gauss quadrature, the volume-averaged stress (Pa) and
// the strain energy u.f / 2 (J):
//   D_g = du/dxi at g, H_g = D_g dxi/dx, s_g = w det J (lambda tr H I + mu (H + H^T)),
//   P_g = s_g (dxi/dx)^T, f_I = sum_g P_g dN_I/dxi (g).
// For one element (Real = double) or a pack of elements (Real = Pack<L>, their
// reference data interleaved value by value: load<Real>); the table of dN/dxi is the
// same for every element.
template <class Real>
inline Real internal_forces(int gauss_points, const double* table, const double* reference, double lambda,
                            double mu, const NodeValues<20, Real>& u, NodeValues<20, Real>& f,
                            std::array<Real, 6>& mean_stress) {
  f = NodeValues<20, Real>{};
  std::array<Real, 6> stress_sum{};
  const std::array<std::array<Real, 20>*, 3> f_component{&f.x, &f.y, &f.z};
  for (int g = 0; g < gauss_points; ++g) {
    const double* dn = table + table_stride * g;
    Real r[10];  // dxi_a/dx_j (row a), then w det J
    for (int k = 0; k < 10; ++k) r[k] = load<Real>(reference, 10 * g + k);
    Real h[9];
    gradient_at_point(dn, u, r, h);
    const Real w = r[9];
    const Real lambda_trace = lambda * (h[0] + h[4] + h[8]);
    const Real s[6] = {w * (lambda_trace + 2.0 * mu * h[0]),
                       w * (lambda_trace + 2.0 * mu * h[4]),
                       w * (lambda_trace + 2.0 * mu * h[8]),
                       w * mu * (h[1] + h[3]),
                       w * mu * (h[5] + h[7]),
                       w * mu * (h[2] + h[6])};
    for (int k = 0; k < 6; ++k) stress_sum[k] += s[k];
    constexpr int row[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};  // s_ij in SymTensor order
    for (int i = 0; i < 3; ++i) {
      Real p[3];  // P_ia = sum_j s_ij dxi_a/dx_j
      for (int a = 0; a < 3; ++a)
        p[a] = s[row[i][0]] * r[3 * a] + s[row[i][1]] * r[3 * a + 1] + s[row[i][2]] * r[3 * a + 2];
      add_point_forces(dn, p, *f_component[i]);
    }
  }
  const Real inverse_volume = load<Real>(reference, 10 * gauss_points);
  for (int k = 0; k < 6; ++k) mean_stress[k] = stress_sum[k] * inverse_volume;
  Real energy{};
  for (int node = 0; node < 20; ++node)
    energy += u.x[node] * f.x[node] + u.y[node] * f.y[node] + u.z[node] * f.z[node];
  return 0.5 * energy;
}

// The HRZ lumped mass (Hinton, Rock and Zienkiewicz 1976), kg: the diagonal of the
// consistent mass, rho integral of N_I^2 dV by the 3x3x3 rule, scaled so that the
// entries add up to the element's mass rho V. Every entry is positive (the row sums
// of the consistent mass are not: -1/8 of rho V at each corner of a cube).
inline std::array<double, 20> hrz_masses(const ElementVectors20& x_ref, double density) {
  const GaussRule rule = gauss_rule(3);
  std::array<double, 20> diagonal{};
  double volume = 0.0, diagonal_sum = 0.0;
  for (int g = 0; g < rule.count; ++g) {
    const Vector3& p = rule.point[static_cast<std::size_t>(g)];
    const std::array<Vector3, 20> dn = shape_function_derivatives(p[0], p[1], p[2]);
    double table[table_stride];
    for (int a = 0; a < 3; ++a)
      for (int node = 0; node < 20; ++node) table[20 * a + node] = dn[node][a];
    const double w_det = rule.weight[static_cast<std::size_t>(g)] * hex8::determinant(jacobian(x_ref, table));
    const std::array<double, 20> n = shape_functions(p[0], p[1], p[2]);
    for (int node = 0; node < 20; ++node) diagonal[node] += n[node] * n[node] * w_det;
    volume += w_det;
  }
  for (double m : diagonal) diagonal_sum += m;
  std::array<double, 20> mass{};
  for (int node = 0; node < 20; ++node) mass[node] = density * volume * diagonal[node] / diagonal_sum;
  return mass;
}

// True when the element is a parallelepiped with straight edges and mid-edge nodes
// at the middle (x linear in xi, so its Jacobian is constant); `tolerance` relative
// to the element's size.
inline bool is_affine(const ElementVectors20& x, double tolerance = 1.0e-12) {
  ElementVectors corners{ElementVectors::Uninitialized{}};
  for (int k = 0; k < 8; ++k) corners.x[k] = x.x[k], corners.y[k] = x.y[k], corners.z[k] = x.z[k];
  if (!hex8::is_parallelepiped(corners, tolerance)) return false;
  // The corners of each edge, in the order of the mid-edge nodes 8..19.
  constexpr int edge[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                               {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  double size = 0.0, off = 0.0;
  for (int e = 0; e < 12; ++e) {
    const int a = edge[e][0], b = edge[e][1], m = 8 + e;
    size = std::max({size, std::abs(x.x[b] - x.x[a]), std::abs(x.y[b] - x.y[a]), std::abs(x.z[b] - x.z[a])});
    off = std::max({off, std::abs(x.x[m] - 0.5 * (x.x[a] + x.x[b])),
                    std::abs(x.y[m] - 0.5 * (x.y[a] + x.y[b])), std::abs(x.z[m] - 0.5 * (x.z[a] + x.z[b]))});
  }
  return off <= tolerance * size;
}

}  // namespace exdyn::element::hex20
