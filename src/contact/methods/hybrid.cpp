// The paper's recommendation: Nelder-Mead for the coarse search (until the
// simplex size <= hybrid_switch_size), then BFGS (B0 = H^-1 at the simplex's
// best vertex) to finish to `tolerance`. Iterations and evaluations are the
// sums over both phases; converged and failure are those of the BFGS phase.
#include "contact/methods/kernel_support.hpp"

namespace exdyn::contact {
namespace {

template <int Terms>
ProjectionResult hybrid_kernel(const Surface<Terms>& s, const Vec3& ys, Xi xi0,
                               const ProjectionSettings& settings) {
  const ProjectionResult coarse = detail::simplex_kernel(s, ys, xi0, settings, settings.hybrid_switch_size);
  ProjectionResult fine = detail::bfgs_kernel(s, ys, coarse.xi, settings);
  fine.iterations += coarse.iterations;
  fine.evaluations += coarse.evaluations;
  return fine;
}

}  // namespace

ProjectionResult project_hybrid(const Segment& segment, const Vec3& point, Xi xi0,
                                const ProjectionSettings& settings) {
  return detail::dispatch(segment, point, xi0, settings,
                          [](const auto& s, const Vec3& ys, Xi x, const ProjectionSettings& st) {
                            return hybrid_kernel(s, ys, x, st);
                          });
}

}  // namespace exdyn::contact
