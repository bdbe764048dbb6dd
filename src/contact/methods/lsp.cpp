// Least-squares projection (the paper's eq. 14), i.e. Gauss-Newton:
// xi+ = xi + A^-1 (r.a), A_ab = a_a.a_b: Newton without the r.y_,ab term of H.
// A is never indefinite, but it is singular where a_1 x a_2 = 0; convergence is
// only linear when r != 0 on a curved segment.
#include "contact/methods/kernel_support.hpp"

namespace exdyn::contact {
namespace {

template <int Terms>
ProjectionResult lsp_kernel(const Surface<Terms>& s, const Vec3& ys, Xi xi0,
                            const ProjectionSettings& settings) {
  using namespace detail;
  ProjectionResult result;
  Xi xi = xi0;
  Local l = evaluate_local(s, ys, xi);
  result.evaluations = 1;
  result.failure = FailureReason::max_iterations;
  for (int k = 1; k <= settings.max_iterations; ++k) {
    if (is_singular(l.A)) {
      result.failure = FailureReason::singular_matrix;
      break;
    }
    // A^-1 (r.a) = -A^-1 g / 2
    const Xi step = scaled(-0.5, inverse(l.A) * l.g);
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

ProjectionResult project_lsp(const Segment& segment, const Vec3& point, Xi xi0,
                             const ProjectionSettings& settings) {
  return detail::dispatch(segment, point, xi0, settings,
                          [](const auto& s, const Vec3& ys, Xi x, const ProjectionSettings& st) {
                            return lsp_kernel(s, ys, x, st);
                          });
}

}  // namespace exdyn::contact
