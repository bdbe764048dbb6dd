// Broyden's method (the paper's eq. 21-22) on grad f = 0: the rank-one
// ("good") update of the inverse Jacobian of the gradient,
//   B+ = B + (s - B y)(s^T B) / (s^T B y),
// full steps xi+ = xi - B g, B0 = H(xi0)^-1. B need not stay symmetric.
#include "contact/methods/quasi_newton.hpp"

namespace exdyn::contact {
namespace {

bool broyden_update(detail::Mat2& B, Xi s, Xi y) {
  using namespace detail;
  const Xi By = B * y;
  const double denominator = dot2(s, By);
  if (vanishes(denominator, s, By)) return false;
  const Xi u = scaled(1.0 / denominator, s - By);
  const Xi sB = row_times(s, B);
  B.m00 += u[0] * sB[0];
  B.m01 += u[0] * sB[1];
  B.m10 += u[1] * sB[0];
  B.m11 += u[1] * sB[1];
  return true;
}

}  // namespace

ProjectionResult project_broyden(const Segment& segment, const Vec3& point, Xi xi0,
                                 const ProjectionSettings& settings) {
  return detail::dispatch(segment, point, xi0, settings,
                          [](const auto& s, const Vec3& ys, Xi x, const ProjectionSettings& st) {
                            return detail::quasi_newton_loop(s, ys, x, st, broyden_update);
                          });
}

}  // namespace exdyn::contact
