// Local contact search: the closest point ys -> y(xi) of one master segment,
//   minimise f(xi) = (ys - y(xi)).(ys - y(xi)),
//   g_a = -2 r.a_a,  H_ab = 2 (a_a.a_b - r.y_,ab),  r = ys - y(xi),
// by every method of Gabriel, Kopacka, Plesek, Ulbin, "Searching for local
// contact constraints by the quasi-Newton methods", plus `robust`.
// docs/local-search.md describes each method as implemented.
//
// Use: choose the method once, outside the contact loop, and call many times:
//   const ProjectFn project_fn = select_method(settings.method);
//   for (...) { ProjectionResult r = project_fn(segment, point, xi0, settings); }
// A projection allocates nothing, throws nothing and makes no virtual call.
//
// Every method stops when ||xi^k - xi^(k-1)|| <= tolerance (simplex: when the
// simplex size <= tolerance) or after max_iterations. Where the paper's step
// is undefined (a singular matrix, eq. 19 with p.H.p <= 0) the method stops
// and says why in `failure`: the point is to measure where methods fail.
#pragma once

#include <string_view>

#include "contact/search_names.hpp"
#include "contact/segment.hpp"

namespace exdyn::contact {

// What the Hessian H says about the point found.
enum class StationaryKind {
  none,     // not a stationary point of f (gradient not small), or H degenerate
  minimum,  // both eigenvalues > 0
  saddle,   // one > 0, one < 0
  maximum,  // both < 0
};

// Why a method stopped without meeting its stopping test, or why the answer
// is not regular.
enum class FailureReason {
  none,
  singular_matrix,         // the matrix to solve with (H, A, a quasi-Newton update) is singular
  non_positive_curvature,  // steepest descent: g.H.g <= 0, the step of eq. 19 is undefined
  max_iterations,          // stopping test not met within max_iterations
  non_finite,              // an iterate or f became inf/NaN (divergence)
  singular_jacobian,       // a_1 x a_2 = 0 at the point found: no normal, no gap (set even when converged)
};

inline constexpr std::array<std::pair<StationaryKind, std::string_view>, 4> stationary_kind_names{{
    {StationaryKind::none, "none"},
    {StationaryKind::minimum, "minimum"},
    {StationaryKind::saddle, "saddle"},
    {StationaryKind::maximum, "maximum"},
}};
inline constexpr std::array<std::pair<FailureReason, std::string_view>, 6> failure_reason_names{{
    {FailureReason::none, "none"},
    {FailureReason::singular_matrix, "singular_matrix"},
    {FailureReason::non_positive_curvature, "non_positive_curvature"},
    {FailureReason::max_iterations, "max_iterations"},
    {FailureReason::non_finite, "non_finite"},
    {FailureReason::singular_jacobian, "singular_jacobian"},
}};
constexpr std::string_view name(StationaryKind k) { return name_of(stationary_kind_names, k); }
constexpr std::string_view name(FailureReason r) { return name_of(failure_reason_names, r); }

struct ProjectionSettings {
  SearchMethod method = SearchMethod::bfgs;
  double tolerance = 1.0e-10;  // on ||xi^k - xi^(k-1)|| (simplex: on the simplex size)
  int max_iterations = 100;
  // Nelder-Mead: the initial simplex is xi0, xi0 + h e1, xi0 + h e2.
  double simplex_initial_size = 0.5;
  // hybrid: the simplex runs until its size <= this, then BFGS finishes.
  double hybrid_switch_size = 1.0e-3;
};

// Tolerances of the classification (relative; documented in docs/local-search.md).
inline constexpr double inside_tolerance = 1.0e-8;               // inside: |xi_a| <= 1 + this
inline constexpr double stationary_gradient_tolerance = 1.0e-6;  // |g| <= this * 2 |a| (|r| + L)
inline constexpr double eigenvalue_tolerance =
    1.0e-8;  // |lambda| <= this * 2 (|a1|^2 + |a2|^2 + |r||y''|): zero
inline constexpr double singular_matrix_tolerance = 1.0e-14;    // |det M| <= this * ||M||_F^2: singular
inline constexpr double singular_jacobian_tolerance = 1.0e-12;  // |a1 x a2| <= this * L^2

struct ProjectionResult {
  Xi xi{};                 // the point found (unconstrained methods: may lie outside [-1,1]^2)
  bool converged = false;  // the stopping test was met within max_iterations
  int iterations = 0;      // updates of xi (simplex: Nelder-Mead iterations; hybrid and robust: all phases)
  int evaluations = 0;     // points at which f (with whatever derivatives the method uses) was evaluated
  StationaryKind stationary = StationaryKind::none;
  FailureReason failure = FailureReason::none;
  bool inside = false;       // |xi_1|, |xi_2| <= 1 + inside_tolerance
  bool on_boundary = false;  // robust only: the closest point is on an edge or a corner, where f's gradient
                             // points out of the segment (the unconstrained closest point lies outside)
  double distance = 0.0;     // |ys - y(xi)|
  double gap = 0.0;          // (ys - y(xi)).n, negative behind the segment; 0 when n is undefined
};

using ProjectFn = ProjectionResult (*)(const Segment& segment, const Vec3& point, Xi initial,
                                       const ProjectionSettings& settings);

// The kernel of one method (never null).
ProjectFn select_method(SearchMethod method);

// Convenience: select_method(settings.method)(...). In a loop, select once instead.
ProjectionResult project(const Segment& segment, const Vec3& point, Xi initial,
                         const ProjectionSettings& settings);

// One least-squares (Gauss-Newton) step from the centre: xi = A^-1 (r.a) at xi = 0,
// A_ab = a_a.a_b. The centre itself when A is singular there.
Xi initial_guess_lsp(const Segment& segment, const Vec3& point);

// The kernels, one per method (methods/<method>.cpp).
ProjectionResult project_newton(const Segment&, const Vec3&, Xi, const ProjectionSettings&);
ProjectionResult project_lsp(const Segment&, const Vec3&, Xi, const ProjectionSettings&);
ProjectionResult project_steepest_descent(const Segment&, const Vec3&, Xi, const ProjectionSettings&);
ProjectionResult project_broyden(const Segment&, const Vec3&, Xi, const ProjectionSettings&);
ProjectionResult project_bfgs(const Segment&, const Vec3&, Xi, const ProjectionSettings&);
ProjectionResult project_dfp(const Segment&, const Vec3&, Xi, const ProjectionSettings&);
ProjectionResult project_simplex(const Segment&, const Vec3&, Xi, const ProjectionSettings&);
ProjectionResult project_hybrid(const Segment&, const Vec3&, Xi, const ProjectionSettings&);
ProjectionResult project_robust(const Segment&, const Vec3&, Xi, const ProjectionSettings&);

}  // namespace exdyn::contact
