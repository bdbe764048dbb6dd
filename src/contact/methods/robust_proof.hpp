// The certificates of the `robust` method (docs/local-search.md, "The robust
// method"): a bound that proves f = |ys - y(xi)|^2 strictly convex on the whole square
// (the fast path), and the proof that the closest point of the square lies within
// epsilon of a point Newton converged to. Inline, for robust.cpp alone (its hot path).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "contact/methods/kernel_support.hpp"

namespace exdyn::contact::robust_proof {

using namespace detail;

// True when f = |ys - y(xi)|^2 is strictly convex on the whole square [-1,1]^2, by a
// bound that costs about 60 flops. H / 2 = J^T J - [r.y_ab] (r = ys - y, J = [a1 a2]):
// - sigma_min(J(xi)) >= sigma_min(J(0)) - |J(xi) - J(0)|_F, and |J(xi) - J(0)|_F is
//   bounded by the coefficients' norms (|u|, |v| <= 1 on the square):
//   |a1 - a1(0)| <= |c3| + 2|c4| + 2|c6| + |c7|, |a2 - a2(0)| <= |c3| + 2|c5| + |c6| + 2|c7|;
// - |r| <= |ys - c0| + sum_{k >= 1} |c_k|, and |[r.y_ab]|_2 <= |r| |[b_ab]|_F with
//   |y11| <= 2(|c4| + |c6|), |y22| <= 2(|c5| + |c7|), |y12| <= |c3| + 2|c6| + 2|c7|.
// So lambda_min(H / 2) >= s_lo^2 - |r|_max |b|_F on the square, and > 0 proves it.
// Flat parallelograms (c3 = ... = c7 = 0) always pass; twisted or strongly curved
// segments with the point far from them fail, and take the full search.
template <int Terms>
bool convex_bound(const Surface<Terms>& s, const Vec3& ys) {
  const auto& c = s.c;
  std::array<double, 8> n{};
  for (int k = 0; k < Terms; ++k) n[std::size_t(k)] = norm(c[std::size_t(k)]);
  const double d1 = n[3] + 2.0 * n[4] + 2.0 * n[6] + n[7];
  const double d2 = n[3] + 2.0 * n[5] + n[6] + 2.0 * n[7];
  const Sym2 A0{dot(c[1], c[1]), dot(c[1], c[2]), dot(c[2], c[2])};
  const double sigma0 = std::sqrt(std::max(eigenvalues(A0)[0], 0.0));
  const double s_lo = sigma0 - std::sqrt(d1 * d1 + d2 * d2);
  if (!(s_lo > 0.0)) return false;
  double r_max = norm(ys - c[0]);
  for (int k = 1; k < Terms; ++k) r_max += n[std::size_t(k)];
  const double b11 = 2.0 * (n[4] + n[6]), b22 = 2.0 * (n[5] + n[7]), b12 = n[3] + 2.0 * n[6] + 2.0 * n[7];
  const double curvature = std::sqrt(b11 * b11 + 2.0 * b12 * b12 + b22 * b22);
  // A margin of 1e-6 of J^T J's scale covers the rounding of the bound itself.
  return s_lo * s_lo > r_max * curvature + 1.0e-6 * sigma0 * sigma0;
}

// The quad8 part of closest_within: the bound mu on boxes of delta, and the two ways
// of covering the square with them. Kept out of the function so that the second way, a
// loop over cells that few projections reach, does not weigh on the first.
struct QuadraticProof {
  double u = 0.0, v = 0.0;  // xi
  std::array<Xi, 8> k{};    // K c_3 ... K c_7 (k[3] ... k[7])
  double sigma = 0.0, reach = 0.0, curvature_max = 0.0, cubic = 0.0, g2 = 0.0, epsilon = 0.0;

  // mu for du in [du0, du1], dv in [dv0, dv1]: delta^T (I + X) delta >= mu |delta|^2, X the
  // path mean of K (J - J*), whose columns are
  //   c3 dv / 2 + c4 du + c6 (u dv + v du + 2 du dv / 3) + c7 (v dv + dv^2 / 3),
  //   c3 du / 2 + c5 dv + c6 (u du + du^2 / 3) + c7 (u dv + v du + 2 du dv / 3)
  // (times K). Each monomial's range on the box (the bilinear one's at the corners, the
  // quadratics' at the ends or the vertex) gives the ranges of X11, X22 and
  // (X12 + X21) / 2; lambda_min grows with the diagonal, so mu is lambda_min at the
  // smallest diagonal and the largest off-diagonal magnitude.
  double mu(double du0, double du1, double dv0, double dv1) const {
    struct Range {
      double lo, hi;
    };
    // a times the range: its ends' products in order (min and max, no branch on the sign:
    // the signs of the K c_k are as good as random, and a mispredicted branch costs more).
    const auto times = [](double a, Range r) {
      const double p = a * r.lo, q = a * r.hi;
      return Range{std::min(p, q), std::max(p, q)};
    };
    const auto plus = [](Range a, Range b) { return Range{a.lo + b.lo, a.hi + b.hi}; };
    const Range du{du0, du1}, dv{dv0, dv1};
    Range x11 = times(0.5 * k[3][0], dv), x22 = times(0.5 * k[3][1], du);
    Range x12 = plus(times(0.5 * k[3][0], du), times(0.5 * k[3][1], dv));  // X12 + X21
    const auto cross = [this](double p, double q) { return u * q + v * p + 2.0 / 3.0 * p * q; };
    const double c00 = cross(du0, dv0), c01 = cross(du0, dv1), c10 = cross(du1, dv0), c11 = cross(du1, dv1);
    const Range cr{std::min(std::min(c00, c01), std::min(c10, c11)),
                   std::max(std::max(c00, c01), std::max(c10, c11))};
    const auto square = [](double w, Range d) {  // w d + d^2 / 3 on d
      const double a = w * d.lo + d.lo * d.lo / 3.0, b = w * d.hi + d.hi * d.hi / 3.0;
      Range r{std::min(a, b), std::max(a, b)};
      const double vertex = -1.5 * w;
      if (vertex > d.lo && vertex < d.hi) r.lo = -0.75 * w * w;
      return r;
    };
    const Range sq_u = square(u, du), sq_v = square(v, dv);
    x11 = plus(x11, plus(plus(times(k[4][0], du), times(k[6][0], cr)), times(k[7][0], sq_v)));
    x22 = plus(x22, plus(plus(times(k[5][1], dv), times(k[6][1], sq_u)), times(k[7][1], cr)));
    x12 = plus(x12, plus(plus(times(k[5][0], dv), times(k[6][0], sq_u)), times(k[7][0], cr)));
    x12 = plus(x12, plus(plus(times(k[4][1], du), times(k[6][1], cr)), times(k[7][1], sq_v)));
    const double off = 0.5 * std::max(-x12.lo, x12.hi);
    return eigenvalues(Sym2{1.0 + x11.lo, off, 1.0 + x22.lo})[0];
  }

  // The growth constant c = m^2 - lambda_max[r*.y_ab] - 0.77 (|g6| + |g7|) rho, and the
  // last test: |g| <= epsilon c.
  double growth(double m, double rho) const { return m * m - curvature_max - 0.77 * cubic * rho; }
  bool within_epsilon(double c_growth) const { return g2 <= epsilon * epsilon * c_growth * c_growth; }

  // Candidates (points with f <= f(xi)) start as the whole square, delta in the box
  // |delta|_inf <= t; with m = sigma* mu on that box they lie within reach / m of xi, so
  // they shrink to the box of that half-width, where mu is larger; until c > 0, with a
  // margin of 1e-6 m^2 for the rounding of the bound itself (at most five boxes).
  bool shrinking_boxes() const {
    double t = std::max(1.0 + std::fabs(u), 1.0 + std::fabs(v));
    for (int box = 0; box < 5; ++box) {
      const double m = sigma * mu(std::max(-t, -1.0 - u), std::min(t, 1.0 - u), std::max(-t, -1.0 - v),
                                  std::min(t, 1.0 - v));
      if (!(m > 0.0)) return false;
      const double c_growth = growth(m, std::min(std::sqrt(2.0) * t, reach / m));
      if (c_growth > 1.0e-6 * m * m) return within_epsilon(c_growth);
      const double next = reach / m * (1.0 + 1.0e-12);  // |delta|_inf > next: |P w| > reach
      if (!(next < 0.95 * t)) return false;
      t = next;
    }
    return false;
  }

  // Second try: cells of delta, from the four quadrants around xi, each split in four
  // until it is farther than d* from ys (m |delta| > reach on the whole cell) or the
  // growth holds on it (c > 0 with rho the cell's farthest |delta|, or reach / m); at most
  // 32 cells. On a cell mu is sharper than on the square: the monomials' ranges are narrower.
  [[gnu::noinline]] bool cells() const {
    struct Cell {
      double du0, du1, dv0, dv1;
    };
    std::array<Cell, 64> stack;  // the first `top` entries are pending
    int top = 0, budget = 32;
    stack[top++] = {-1.0 - u, 0.0, -1.0 - v, 0.0};
    stack[top++] = {0.0, 1.0 - u, -1.0 - v, 0.0};
    stack[top++] = {-1.0 - u, 0.0, 0.0, 1.0 - v};
    stack[top++] = {0.0, 1.0 - u, 0.0, 1.0 - v};
    double c_least = std::numeric_limits<double>::infinity();
    while (top > 0) {
      const Cell cell = stack[std::size_t(--top)];
      if (!(cell.du1 > cell.du0 && cell.dv1 > cell.dv0)) continue;  // empty: xi on an edge
      if (--budget < 0) return false;
      const double m = sigma * mu(cell.du0, cell.du1, cell.dv0, cell.dv1);
      if (m > 0.0) {
        // The cell's nearest and farthest |delta|.
        const double nu = cell.du0 > 0.0 ? cell.du0 : (cell.du1 < 0.0 ? -cell.du1 : 0.0);
        const double nv = cell.dv0 > 0.0 ? cell.dv0 : (cell.dv1 < 0.0 ? -cell.dv1 : 0.0);
        const double fu = std::max(-cell.du0, cell.du1), fv = std::max(-cell.dv0, cell.dv1);
        if (m * m * (nu * nu + nv * nv) > reach * reach) continue;  // farther than d* from ys
        const double c_growth = growth(m, std::min(std::sqrt(fu * fu + fv * fv), reach / m));
        if (c_growth > 1.0e-6 * m * m) {
          c_least = std::min(c_least, c_growth);
          continue;
        }
      }
      if (top + 4 > int(stack.size())) return false;
      const double um = 0.5 * (cell.du0 + cell.du1), vm = 0.5 * (cell.dv0 + cell.dv1);
      stack[std::size_t(top++)] = {cell.du0, um, cell.dv0, vm};
      stack[std::size_t(top++)] = {um, cell.du1, cell.dv0, vm};
      stack[std::size_t(top++)] = {cell.du0, um, vm, cell.dv1};
      stack[std::size_t(top++)] = {um, cell.du1, vm, cell.dv1};
    }
    return within_epsilon(c_least);
  }
};

// A proof that the closest point of the whole square lies within `epsilon` of xi
// (xi in the square; l the local values there), in about 150 flops (quad8, one box). With
// r* = ys - y(xi), d* = |r*|, w = y(xi + delta) - y(xi) and P the orthogonal projector
// onto the tangent plane J* = [a1 a2] at xi:
// - f(xi + delta) >= |P (r* - w)|^2, so f <= f(xi) needs |P w| <= reach = d* + |P r*|.
// - P w = J* K w with K = A*^-1 J*^T (A* = J*^T J*), |P w| >= sigma* |K w|, and
//   K w = [mean over the path xi -> xi + delta of K J] delta = (I + X) delta. On a box of
//   delta, delta^T (I + X) delta >= mu |delta|^2 from the ranges of X's entries (the
//   coefficients K c_k times the ranges of the path means of the monomials' changes), so
//   |P w| >= m |delta| with m = sigma* mu: points with |delta| > reach / m are farther than
//   d* from ys. The box of candidates shrinks to that size, and mu is retaken on it.
// - Within rho, exactly f(xi + delta) - f(xi) = |w|^2 + g.delta - 2 q(delta), where
//   q = r*.(w - J* delta) = delta^T [r*.y_ab] delta / 2 + g6 du^2 dv + g7 du dv^2
//   (g_k = r*.c_k) and |du^2 dv| <= 0.385 |delta|^3. So f - f(xi) >= |delta| (c |delta| - |g|)
//   with c = m^2 - lambda_max[r*.y_ab] - 0.77 (|g6| + |g7|) rho, and c > 0 puts every point
//   with f <= f(xi) within |g| / c of xi.
// Strongly curved or distorted segments (mu <= 0 over the square, or the curvature term
// eats m^2) fail the proof and take the other paths.
template <int Terms>
[[gnu::always_inline]] inline bool closest_within(const Surface<Terms>& s, Xi xi, const Local& l,
                                                  double epsilon) {
  if (!(l.f > 0.0)) return true;  // f >= 0 everywhere: on the surface is the closest there is
  const auto& c = s.c;
  const double detA = det(l.A);
  const double sigma2 = eigenvalues(l.A)[0];
  if (!(detA > 0.0 && sigma2 > 0.0)) return false;
  const double inv = 1.0 / detA;
  // K c_k = A*^-1 (a1.c_k, a2.c_k): the coefficient in the tangent plane's (a1, a2) basis.
  const auto in_plane = [&](const Vec3& ck) {
    const double p1 = dot(l.p.a1, ck), p2 = dot(l.p.a2, ck);
    return Xi{inv * (l.A.yy * p1 - l.A.xy * p2), inv * (l.A.xx * p2 - l.A.xy * p1)};
  };
  const double u = xi[0], v = xi[1];
  if constexpr (Terms == 4) {
    // Bilinear: X = K c3 [dv, du] / 2, so on the square X11 >= -|k1| (1 + |v|) / 2,
    // X22 >= -|k2| (1 + |u|) / 2 and |X12 + X21| <= (|k1| (1 + |u|) + |k2| (1 + |v|)) / 2;
    // [r*.y_ab] = r*.c3 [[0, 1], [1, 0]], no cubic term.
    const Xi k3 = in_plane(c[3]);
    const double k1 = std::fabs(k3[0]), k2 = std::fabs(k3[1]);
    const double du = 1.0 + std::fabs(u), dv = 1.0 + std::fabs(v);
    const double mu =
        eigenvalues(Sym2{1.0 - 0.5 * k1 * dv, 0.25 * (k1 * du + k2 * dv), 1.0 - 0.5 * k2 * du})[0];
    const double m2 = sigma2 * mu * mu;
    const double growth = m2 - std::fabs(dot(l.r, c[3]));
    return mu > 0.0 && growth > 1.0e-6 * m2 && dot2(l.g, l.g) <= epsilon * epsilon * growth * growth;
  } else {
    QuadraticProof proof;
    proof.u = u;
    proof.v = v;
    for (int i = 3; i < Terms; ++i) proof.k[std::size_t(i)] = in_plane(c[std::size_t(i)]);
    proof.sigma = std::sqrt(sigma2);
    // |P r*|^2 = (g/2)^T A*^-1 (g/2).
    const Xi h{0.5 * l.g[0], 0.5 * l.g[1]};
    const double pr2 = inv * (l.A.yy * h[0] * h[0] - 2.0 * l.A.xy * h[0] * h[1] + l.A.xx * h[1] * h[1]);
    proof.reach = std::sqrt(l.f) + std::sqrt(std::max(pr2, 0.0));  // d* + |P r*|
    // lambda_max [r*.y_ab] (negative where the surface bends away from ys, which helps:
    // -delta^T [r*.y_ab] delta >= -lambda_max |delta|^2) and |g6| + |g7|.
    const Sym2 curvature{l.A.xx - 0.5 * l.H.xx, l.A.xy - 0.5 * l.H.xy, l.A.yy - 0.5 * l.H.yy};
    proof.curvature_max = eigenvalues(curvature)[1];
    proof.cubic = std::fabs(dot(l.r, c[6])) + std::fabs(dot(l.r, c[7]));
    proof.g2 = dot2(l.g, l.g);
    proof.epsilon = epsilon;
    return proof.shrinking_boxes() || proof.cells();
  }
}

}  // namespace exdyn::contact::robust_proof
