// Nelder-Mead simplex on f, derivative-free, with the standard coefficients:
// reflection 1, expansion 2, contraction 1/2 (outside and inside), shrink 1/2.
// Initial simplex xi0, xi0 + h e1, xi0 + h e2 (h = simplex_initial_size). Stops
// when the simplex size max_i |v_i - v_best| <= tolerance. Never stops on a
// saddle (it only compares values of f).
#include <algorithm>
#include <utility>

#include "contact/methods/kernel_support.hpp"

namespace exdyn::contact {
namespace detail {

template <int Terms>
ProjectionResult simplex_kernel(const Surface<Terms>& s, const Vec3& ys, Xi xi0,
                                const ProjectionSettings& settings, double stop_size) {
  constexpr double reflection = 1.0, expansion = 2.0, contraction = 0.5, shrink = 0.5;
  ProjectionResult result;
  const double h = settings.simplex_initial_size;
  std::array<Xi, 3> v{xi0, Xi{xi0[0] + h, xi0[1]}, Xi{xi0[0], xi0[1] + h}};
  std::array<double, 3> fv{};
  for (int i = 0; i < 3; ++i) fv[i] = evaluate_f(s, ys, v[i]);
  result.evaluations = 3;
  result.failure = FailureReason::max_iterations;
  int k = 0;
  for (;;) {
    // Order best (0) to worst (2).
    if (fv[1] < fv[0]) std::swap(fv[0], fv[1]), std::swap(v[0], v[1]);
    if (fv[2] < fv[1]) std::swap(fv[1], fv[2]), std::swap(v[1], v[2]);
    if (fv[1] < fv[0]) std::swap(fv[0], fv[1]), std::swap(v[0], v[1]);
    if (!std::isfinite(fv[0]) || !finite(v[0])) {
      result.failure = FailureReason::non_finite;
      break;
    }
    const double size = std::max(norm2(v[1] - v[0]), norm2(v[2] - v[0]));
    if (size <= stop_size) {
      result.converged = true;
      result.failure = FailureReason::none;
      break;
    }
    if (k == settings.max_iterations) break;
    ++k;
    const Xi centroid = scaled(0.5, v[0] + v[1]);
    const Xi xr = centroid + scaled(reflection, centroid - v[2]);
    const double fr = evaluate_f(s, ys, xr);
    ++result.evaluations;
    if (fr < fv[0]) {
      const Xi xe = centroid + scaled(expansion, xr - centroid);
      const double fe = evaluate_f(s, ys, xe);
      ++result.evaluations;
      if (fe < fr) {
        v[2] = xe, fv[2] = fe;
      } else {
        v[2] = xr, fv[2] = fr;
      }
      continue;
    }
    if (fr < fv[1]) {
      v[2] = xr, fv[2] = fr;
      continue;
    }
    const bool outside = fr < fv[2];
    const Xi xc = outside ? centroid + scaled(contraction, xr - centroid)
                          : centroid + scaled(contraction, v[2] - centroid);
    const double fc = evaluate_f(s, ys, xc);
    ++result.evaluations;
    if (outside ? fc <= fr : fc < fv[2]) {
      v[2] = xc, fv[2] = fc;
      continue;
    }
    for (int i = 1; i < 3; ++i) {
      v[i] = v[0] + scaled(shrink, v[i] - v[0]);
      fv[i] = evaluate_f(s, ys, v[i]);
    }
    result.evaluations += 2;
  }
  result.iterations = k;
  result.xi = v[0];
  return result;
}
template ProjectionResult simplex_kernel<4>(const Surface<4>&, const Vec3&, Xi, const ProjectionSettings&,
                                            double);
template ProjectionResult simplex_kernel<8>(const Surface<8>&, const Vec3&, Xi, const ProjectionSettings&,
                                            double);

}  // namespace detail

ProjectionResult project_simplex(const Segment& segment, const Vec3& point, Xi xi0,
                                 const ProjectionSettings& settings) {
  return detail::dispatch(segment, point, xi0, settings,
                          [](const auto& s, const Vec3& ys, Xi x, const ProjectionSettings& st) {
                            return detail::simplex_kernel(s, ys, x, st, st.tolerance);
                          });
}

}  // namespace exdyn::contact
