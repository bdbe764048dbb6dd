// Internal: the loop shared by the quasi-Newton methods (Broyden, BFGS, DFP).
// As in the paper: full (unit) steps xi+ = xi - B g, no line search, and the
// initial matrix B0 = H(xi0)^-1, the exact inverse Hessian at the start (with
// it every method ends a flat case in two iterations, as the paper reports).
// After each step B is updated from s = xi+ - xi and y = g+ - g by `update`,
// which returns false when its denominator vanishes (reported as singular_matrix).
#pragma once

#include "contact/methods/kernel_support.hpp"

namespace exdyn::contact::detail {

inline Xi row_times(Xi s, const Mat2& m) {
  return {s[0] * m.m00 + s[1] * m.m10, s[0] * m.m01 + s[1] * m.m11};
}

// Relative test for a vanishing denominator u.v of an update.
inline bool vanishes(double denominator, Xi u, Xi v) {
  return !(std::fabs(denominator) > singular_matrix_tolerance * norm2(u) * norm2(v));
}

template <int Terms, class Update>
ProjectionResult quasi_newton_loop(const Surface<Terms>& s, const Vec3& ys, Xi xi0,
                                   const ProjectionSettings& settings, Update update) {
  ProjectionResult result;
  Xi xi = xi0;
  const Local l0 = evaluate_local(s, ys, xi);
  result.evaluations = 1;
  result.xi = xi;
  if (is_singular(l0.H)) {
    result.failure = FailureReason::singular_matrix;
    return result;
  }
  Mat2 B = inverse(l0.H);
  Xi g = l0.g;
  result.failure = FailureReason::max_iterations;
  for (int k = 1; k <= settings.max_iterations; ++k) {
    const Xi step = scaled(-1.0, B * g);
    const Xi next = xi + step;
    result.iterations = k;
    if (!finite(next)) {
      result.failure = FailureReason::non_finite;
      break;
    }
    xi = next;
    if (norm2(step) <= settings.tolerance) {
      result.converged = true;
      result.failure = FailureReason::none;
      break;
    }
    const LocalGradient lg = evaluate_gradient(s, ys, xi);
    ++result.evaluations;
    const Xi y = lg.g - g;
    g = lg.g;
    if (!update(B, step, y)) {
      result.failure = FailureReason::singular_matrix;
      break;
    }
  }
  result.xi = xi;
  return result;
}

}  // namespace exdyn::contact::detail
