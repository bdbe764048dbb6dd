// DFP (the paper's eq. 25-27): the inverse-Hessian update
//   B+ = B + s s^T / (s.y) - (B y)(B y)^T / (y.B.y),
// full steps xi+ = xi - B g, B0 = H(xi0)^-1, no line search. A vanishing s.y
// or y.B.y stops the method (singular_matrix).
#include "contact/methods/quasi_newton.hpp"

namespace exdyn::contact {
namespace {

bool dfp_update(detail::Mat2& B, Xi s, Xi y) {
  using namespace detail;
  const double sy = dot2(s, y);
  if (vanishes(sy, s, y)) return false;
  const Xi By = B * y;
  const double yBy = dot2(y, By);
  if (vanishes(yBy, y, By)) return false;
  const double a = 1.0 / sy, b = 1.0 / yBy;
  B.m00 += a * s[0] * s[0] - b * By[0] * By[0];
  B.m01 += a * s[0] * s[1] - b * By[0] * By[1];
  B.m10 += a * s[1] * s[0] - b * By[1] * By[0];
  B.m11 += a * s[1] * s[1] - b * By[1] * By[1];
  return true;
}

}  // namespace

ProjectionResult project_dfp(const Segment& segment, const Vec3& point, Xi xi0,
                             const ProjectionSettings& settings) {
  return detail::dispatch(segment, point, xi0, settings,
                          [](const auto& s, const Vec3& ys, Xi x, const ProjectionSettings& st) {
                            return detail::quasi_newton_loop(s, ys, x, st, dfp_update);
                          });
}

}  // namespace exdyn::contact
