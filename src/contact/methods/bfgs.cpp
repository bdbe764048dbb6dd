// BFGS (the paper's eq. 23-24): the inverse-Hessian update
//   B+ = (I - rho s y^T) B (I - rho y s^T) + rho s s^T,  rho = 1 / (y.s),
// full steps xi+ = xi - B g, B0 = H(xi0)^-1, no line search. y.s = 0 stops the
// method (singular_matrix); y.s < 0 is applied as the formula says (B then
// loses positive definiteness, as in the paper's method).
#include "contact/methods/quasi_newton.hpp"

namespace exdyn::contact {
namespace detail {

bool bfgs_update(Mat2& B, Xi s, Xi y) {
  const double sy = dot2(s, y);
  if (vanishes(sy, s, y)) return false;
  const double rho = 1.0 / sy;
  const Xi By = B * y;  // B symmetric: B y = (y^T B)^T
  const double yBy = dot2(y, By);
  const double c = rho * rho * yBy + rho;
  // B - rho (s (By)^T + (By) s^T) + (rho^2 y.B.y + rho) s s^T
  B.m00 += -rho * 2.0 * s[0] * By[0] + c * s[0] * s[0];
  B.m01 += -rho * (s[0] * By[1] + By[0] * s[1]) + c * s[0] * s[1];
  B.m10 += -rho * (s[1] * By[0] + By[1] * s[0]) + c * s[1] * s[0];
  B.m11 += -rho * 2.0 * s[1] * By[1] + c * s[1] * s[1];
  return true;
}

template <int Terms>
ProjectionResult bfgs_kernel(const Surface<Terms>& s, const Vec3& ys, Xi xi0,
                             const ProjectionSettings& settings) {
  return quasi_newton_loop(s, ys, xi0, settings, bfgs_update);
}
template ProjectionResult bfgs_kernel<4>(const Surface<4>&, const Vec3&, Xi, const ProjectionSettings&);
template ProjectionResult bfgs_kernel<8>(const Surface<8>&, const Vec3&, Xi, const ProjectionSettings&);

}  // namespace detail

ProjectionResult project_bfgs(const Segment& segment, const Vec3& point, Xi xi0,
                              const ProjectionSettings& settings) {
  return detail::dispatch(segment, point, xi0, settings,
                          [](const auto& s, const Vec3& ys, Xi x, const ProjectionSettings& st) {
                            return detail::quasi_newton_loop(s, ys, x, st, detail::bfgs_update);
                          });
}

}  // namespace exdyn::contact
