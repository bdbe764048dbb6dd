#include "contact/edge_contact.hpp"

#include <algorithm>
#include <cmath>

namespace exdyn::contact {

EdgeContact edge_contact(const Segment& segment, const Vec3& point, const ProjectionResult& result,
                         const SegmentEdges& edges) {
  EdgeContact contact;
  if (!result.converged || result.stationary == StationaryKind::saddle ||
      result.stationary == StationaryKind::maximum || !std::isfinite(result.xi[0]) ||
      !std::isfinite(result.xi[1]))
    return contact;
  // The edges left across: coordinate a at or past -1 or +1.
  Xi xi = result.xi;
  int free_coordinate = -1, fixed = 0;
  bool goes_on = true;
  std::array<int, 2> crossed{-1, -1};  // the edge left across in each coordinate
  for (int a = 0; a < 2; ++a) {
    const std::uint8_t minus = a == 0 ? edge_xi1_minus : edge_xi2_minus;
    const std::uint8_t plus = a == 0 ? edge_xi1_plus : edge_xi2_plus;
    if (xi[std::size_t(a)] <= -1.0) {
      goes_on = goes_on && (edges.continued & minus) != 0;
      xi[std::size_t(a)] = -1.0, ++fixed, crossed[std::size_t(a)] = 2 * a;
    } else if (xi[std::size_t(a)] >= 1.0) {
      goes_on = goes_on && (edges.continued & plus) != 0;
      xi[std::size_t(a)] = 1.0, ++fixed, crossed[std::size_t(a)] = 2 * a + 1;
    } else {
      free_coordinate = a;
    }
  }
  if (fixed == 0) return contact;  // inside: the ordinary projection's business
  if (fixed == 1) {
    // f'(t) = -(ys - y).y_t, f''(t) = y_t.y_t - (ys - y).y_tt along the edge.
    const auto b = std::size_t(free_coordinate);
    for (int k = 0; k < 20; ++k) {
      const SurfacePoint p = evaluate(segment, xi);
      const Vec3 r = point - p.y;
      const Vec3 tangent = b == 0 ? p.a1 : p.a2;
      const Vec3 curvature = b == 0 ? p.y11 : p.y22;
      const double slope = -dot(r, tangent);
      double stiffness = dot(tangent, tangent) - dot(r, curvature);
      if (!(stiffness > 0.0)) stiffness = dot(tangent, tangent);  // a concave edge: a gradient step
      if (!(stiffness > 0.0)) return contact;                     // a degenerate edge
      const double next = std::clamp(xi[b] - slope / stiffness, -1.0, 1.0);
      const double step = std::fabs(next - xi[b]);
      xi[b] = next;
      if (step <= 1.0e-12) break;
    }
  }
  const SurfacePoint p = evaluate(segment, xi);
  Vec3 n = outward_normal(p);
  for (const int e : crossed) {
    if (e < 0) continue;
    const int axis = edges.mirror_axis[std::size_t(e)];
    if (axis == 0) n.x = 0.0;
    if (axis == 1) n.y = 0.0;
    if (axis == 2) n.z = 0.0;
  }
  const double length = norm(n);
  if (!(length > 0.0)) return contact;  // a degenerate segment, or one normal to the plane
  contact.found = true;
  contact.continued = goes_on;
  contact.xi = xi;
  contact.y = p.y;
  contact.distance = norm(point - p.y);
  contact.normal = (1.0 / length) * n;
  return contact;
}

}  // namespace exdyn::contact
