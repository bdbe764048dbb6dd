// Newton-Raphson on grad f = 0 (the paper's eq. 8): xi+ = xi - H^-1 g with the
// exact Hessian. Converges to whatever stationary point is near: minimum,
// saddle or maximum alike (the classification of the result says which).
#include "contact/methods/kernel_support.hpp"

namespace exdyn::contact {
namespace {

template <int Terms>
ProjectionResult newton_kernel(const Surface<Terms>& s, const Vec3& ys, Xi xi0,
                               const ProjectionSettings& settings) {
  using namespace detail;
  ProjectionResult result;
  Xi xi = xi0;
  Local l = evaluate_local(s, ys, xi);
  result.evaluations = 1;
  result.failure = FailureReason::max_iterations;
  for (int k = 1; k <= settings.max_iterations; ++k) {
    if (is_singular(l.H)) {
      result.failure = FailureReason::singular_matrix;
      break;
    }
    const Xi step = scaled(-1.0, inverse(l.H) * l.g);
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

ProjectionResult project_newton(const Segment& segment, const Vec3& point, Xi xi0,
                                const ProjectionSettings& settings) {
  return detail::dispatch(segment, point, xi0, settings,
                          [](const auto& s, const Vec3& ys, Xi x, const ProjectionSettings& st) {
                            return newton_kernel(s, ys, x, st);
                          });
}

}  // namespace exdyn::contact
