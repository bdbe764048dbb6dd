// Internal to the local search: the distance function f = r.r, r = ys - y(xi),
// its gradient and Hessian, 2x2 linear algebra, and the post-processing
// common to every method. Not part of the library's interface.
#pragma once

#include <cmath>
#include <limits>

#include "contact/local_search.hpp"

namespace exdyn::contact::detail {

// A symmetric 2x2 matrix [[xx, xy], [xy, yy]].
struct Sym2 {
  double xx = 0.0, xy = 0.0, yy = 0.0;
};
// A general 2x2 matrix [[m00, m01], [m10, m11]].
struct Mat2 {
  double m00 = 0.0, m01 = 0.0, m10 = 0.0, m11 = 0.0;
};

inline double det(const Sym2& m) { return m.xx * m.yy - m.xy * m.xy; }
inline double frobenius2(const Sym2& m) { return m.xx * m.xx + 2.0 * m.xy * m.xy + m.yy * m.yy; }
inline bool is_singular(const Sym2& m) {
  const double d = det(m);
  return !(std::fabs(d) > singular_matrix_tolerance * frobenius2(m));
}
// m^-1 (caller checked is_singular).
inline Mat2 inverse(const Sym2& m) {
  const double inv = 1.0 / det(m);
  return {m.yy * inv, -m.xy * inv, -m.xy * inv, m.xx * inv};
}
inline Xi operator*(const Mat2& m, Xi v) {
  return {m.m00 * v[0] + m.m01 * v[1], m.m10 * v[0] + m.m11 * v[1]};
}
inline Xi operator*(const Sym2& m, Xi v) { return {m.xx * v[0] + m.xy * v[1], m.xy * v[0] + m.yy * v[1]}; }
inline double dot2(Xi a, Xi b) { return a[0] * b[0] + a[1] * b[1]; }
inline double norm2(Xi a) { return std::sqrt(dot2(a, a)); }
inline Xi operator-(Xi a, Xi b) { return {a[0] - b[0], a[1] - b[1]}; }
inline Xi operator+(Xi a, Xi b) { return {a[0] + b[0], a[1] + b[1]}; }
inline Xi scaled(double s, Xi a) { return {s * a[0], s * a[1]}; }
inline bool finite(Xi a) { return std::isfinite(a[0]) && std::isfinite(a[1]); }

// Eigenvalues of a symmetric 2x2, ascending.
inline Xi eigenvalues(const Sym2& m) {
  const double mean = 0.5 * (m.xx + m.yy);
  const double half_diff = 0.5 * (m.xx - m.yy);
  const double radius = std::sqrt(half_diff * half_diff + m.xy * m.xy);
  return {mean - radius, mean + radius};
}

// f, g and H at one point (with the surface point they came from).
struct Local {
  SurfacePoint p;
  Vec3 r;    // ys - y
  double f;  // r.r
  Xi g;      // g_a = -2 r.a_a
  Sym2 H;    // H_ab = 2 (a_a.a_b - r.y_,ab)
  Sym2 A;    // Gauss-Newton matrix A_ab = a_a.a_b (LSP)
};

template <int Terms>
inline Local evaluate_local(const Surface<Terms>& s, const Vec3& ys, Xi xi) {
  Local l;
  l.p = evaluate(s, xi);
  l.r = ys - l.p.y;
  l.f = dot(l.r, l.r);
  l.g = {-2.0 * dot(l.r, l.p.a1), -2.0 * dot(l.r, l.p.a2)};
  l.A = {dot(l.p.a1, l.p.a1), dot(l.p.a1, l.p.a2), dot(l.p.a2, l.p.a2)};
  l.H = {2.0 * (l.A.xx - dot(l.r, l.p.y11)), 2.0 * (l.A.xy - dot(l.r, l.p.y12)),
         2.0 * (l.A.yy - dot(l.r, l.p.y22))};
  return l;
}

// f and g only (quasi-Newton methods do not need H after the start).
struct LocalGradient {
  double f;
  Xi g;
};
template <int Terms>
inline LocalGradient evaluate_gradient(const Surface<Terms>& s, const Vec3& ys, Xi xi) {
  const auto& c = s.c;
  const double u = xi[0], v = xi[1];
  Vec3 y = c[0] + u * (c[1] + v * c[3]) + v * c[2];
  Vec3 a1 = c[1] + v * c[3];
  Vec3 a2 = c[2] + u * c[3];
  if constexpr (Terms == 8) {
    y = y + u * u * (c[4] + v * c[6]) + v * v * (c[5] + u * c[7]);
    a1 = a1 + (2.0 * u) * (c[4] + v * c[6]) + (v * v) * c[7];
    a2 = a2 + (2.0 * v) * (c[5] + u * c[7]) + (u * u) * c[6];
  }
  const Vec3 r = ys - y;
  return {dot(r, r), {-2.0 * dot(r, a1), -2.0 * dot(r, a2)}};
}

template <int Terms>
inline double evaluate_f(const Surface<Terms>& s, const Vec3& ys, Xi xi) {
  const Vec3 r = ys - position(s, xi);
  return dot(r, r);
}

// Square of the segment's size: sum of |c_k|^2, k >= 1 (invariant under rigid
// motions; the scale of the relative tolerances).
template <int Terms>
inline double size2(const Surface<Terms>& s) {
  double sum = 0.0;
  for (int k = 1; k < Terms; ++k) sum += dot(s.c[k], s.c[k]);
  return sum;
}

inline bool is_inside(Xi xi) {
  return std::fabs(xi[0]) <= 1.0 + inside_tolerance && std::fabs(xi[1]) <= 1.0 + inside_tolerance;
}

// Classifies the point from H's eigenvalues, when it is a stationary point.
inline StationaryKind classify(const Local& l, double size) {
  const double a_norm = std::sqrt(l.A.xx + l.A.yy);
  const double r_norm = std::sqrt(l.f);
  const double gradient_scale = 2.0 * a_norm * (r_norm + size);
  if (!(norm2(l.g) <= stationary_gradient_tolerance * gradient_scale)) return StationaryKind::none;
  const double curvature_scale =
      2.0 * (l.A.xx + l.A.yy + r_norm * (norm(l.p.y11) + 2.0 * norm(l.p.y12) + norm(l.p.y22)));
  const double zero = eigenvalue_tolerance * curvature_scale;
  const Xi lambda = eigenvalues(l.H);
  if (lambda[0] > zero) return StationaryKind::minimum;
  if (lambda[1] < -zero) return StationaryKind::maximum;
  if (lambda[0] < -zero && lambda[1] > zero) return StationaryKind::saddle;
  return StationaryKind::none;
}

// Fills stationary, inside, distance, gap (and singular_jacobian) at r.xi from l, the
// local values there (a kernel that has them saves finish's evaluation).
template <int Terms>
inline void finish_at(const Surface<Terms>& s, const Local& l, ProjectionResult& result) {
  const double s2 = size2(s);
  result.stationary = classify(l, std::sqrt(s2));
  result.inside = is_inside(result.xi);
  result.distance = std::sqrt(l.f);
  const Vec3 normal_raw = cross(l.p.a1, l.p.a2);
  const double normal_length = norm(normal_raw);
  if (!(normal_length > singular_jacobian_tolerance * s2)) {
    result.gap = 0.0;
    if (result.failure == FailureReason::none) result.failure = FailureReason::singular_jacobian;
  } else {
    result.gap = dot(l.r, normal_raw) / normal_length;
  }
}

// The same at r.xi, evaluated here.
template <int Terms>
inline void finish(const Surface<Terms>& s, const Vec3& ys, ProjectionResult& result) {
  if (!finite(result.xi)) {
    if (result.failure == FailureReason::none) result.failure = FailureReason::non_finite;
    result.converged = false;
    result.stationary = StationaryKind::none;
    result.inside = false;
    result.distance = std::numeric_limits<double>::infinity();
    result.gap = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  finish_at(s, evaluate_local(s, ys, result.xi), result);
}

// Converts the segment once, runs the method's kernel, finishes the result (unless
// the kernel does: finished = true).
template <bool finished = false, class Kernel>
inline ProjectionResult dispatch(const Segment& segment, const Vec3& ys, Xi xi0,
                                 const ProjectionSettings& settings, Kernel kernel) {
  if (segment.type == SegmentType::quad4) {
    const Quad4Surface s = make_surface<4>(segment);
    ProjectionResult r = kernel(s, ys, xi0, settings);
    if constexpr (!finished) finish(s, ys, r);
    return r;
  }
  const Quad8Surface s = make_surface<8>(segment);
  ProjectionResult r = kernel(s, ys, xi0, settings);
  if constexpr (!finished) finish(s, ys, r);
  return r;
}

// Kernels shared between methods (explicitly instantiated for 4 and 8 terms
// in their own files). They fill xi, converged, iterations, evaluations, failure.
template <int Terms>
ProjectionResult simplex_kernel(const Surface<Terms>& s, const Vec3& ys, Xi xi0,
                                const ProjectionSettings& settings, double stop_size);
template <int Terms>
ProjectionResult bfgs_kernel(const Surface<Terms>& s, const Vec3& ys, Xi xi0,
                             const ProjectionSettings& settings);
// True when f = |ys - y(xi)|^2 is proven strictly convex on the whole square
// (robust.cpp: the fast path of `robust`).
template <int Terms>
bool strictly_convex_on_square(const Surface<Terms>& s, const Vec3& ys);
// True when the closest point of the square is proven to lie within epsilon of xi, a
// point of the square (robust.cpp: the certified Newton path of `robust`).
template <int Terms>
bool closest_point_proven(const Surface<Terms>& s, const Vec3& ys, Xi xi, double epsilon);

}  // namespace exdyn::contact::detail
