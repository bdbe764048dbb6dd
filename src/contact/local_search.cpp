#include "contact/local_search.hpp"

#include "contact/methods/kernel_support.hpp"

namespace exdyn::contact {

ProjectFn select_method(SearchMethod method) {
  switch (method) {
    case SearchMethod::newton:
      return &project_newton;
    case SearchMethod::lsp:
      return &project_lsp;
    case SearchMethod::steepest_descent:
      return &project_steepest_descent;
    case SearchMethod::broyden:
      return &project_broyden;
    case SearchMethod::bfgs:
      return &project_bfgs;
    case SearchMethod::dfp:
      return &project_dfp;
    case SearchMethod::simplex:
      return &project_simplex;
    case SearchMethod::hybrid:
      return &project_hybrid;
    case SearchMethod::robust:
      return &project_robust;
  }
  return &project_robust;  // unreachable for a valid enumerator
}

ProjectionResult project(const Segment& segment, const Vec3& point, Xi initial,
                         const ProjectionSettings& settings) {
  return select_method(settings.method)(segment, point, initial, settings);
}

namespace {
template <int Terms>
Xi lsp_step_from_centre(const Surface<Terms>& s, const Vec3& ys) {
  const detail::Local l = detail::evaluate_local(s, ys, Xi{0.0, 0.0});
  if (detail::is_singular(l.A)) return {0.0, 0.0};
  return detail::scaled(-0.5, detail::inverse(l.A) * l.g);
}
}  // namespace

Xi initial_guess_lsp(const Segment& segment, const Vec3& point) {
  return segment.type == SegmentType::quad4 ? lsp_step_from_centre(make_surface<4>(segment), point)
                                            : lsp_step_from_centre(make_surface<8>(segment), point);
}

}  // namespace exdyn::contact
