// Steepest descent with the analytic step of the paper's eq. 19: p = -g,
// alpha = g.g / (g.H.g) (the exact minimiser of the quadratic model along p).
// When g.H.g <= 0 that step is undefined: the method stops with
// non_positive_curvature instead of dividing by zero or stepping uphill.
#include "contact/methods/kernel_support.hpp"

namespace exdyn::contact {
namespace {

template <int Terms>
ProjectionResult steepest_descent_kernel(const Surface<Terms>& s, const Vec3& ys, Xi xi0,
                                         const ProjectionSettings& settings) {
  using namespace detail;
  ProjectionResult result;
  Xi xi = xi0;
  Local l = evaluate_local(s, ys, xi);
  result.evaluations = 1;
  result.failure = FailureReason::max_iterations;
  for (int k = 1; k <= settings.max_iterations; ++k) {
    const double gg = dot2(l.g, l.g);
    Xi step{0.0, 0.0};
    if (gg > 0.0) {  // g = 0: a zero step, the stopping test is met
      const double curvature = dot2(l.g, l.H * l.g);
      if (!(curvature > 0.0)) {
        result.failure = FailureReason::non_positive_curvature;
        break;
      }
      step = scaled(-gg / curvature, l.g);
    }
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
    l = evaluate_local(s, ys, xi);
    ++result.evaluations;
  }
  result.xi = xi;
  return result;
}

}  // namespace

ProjectionResult project_steepest_descent(const Segment& segment, const Vec3& point, Xi xi0,
                                          const ProjectionSettings& settings) {
  return detail::dispatch(segment, point, xi0, settings,
                          [](const auto& s, const Vec3& ys, Xi x, const ProjectionSettings& st) {
                            return steepest_descent_kernel(s, ys, x, st);
                          });
}

}  // namespace exdyn::contact
