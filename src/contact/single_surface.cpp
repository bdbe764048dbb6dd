#include "contact/single_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "contact/slave_points.hpp"

namespace exdyn::contact {

namespace {

bool has_node(const SegmentNodes& ids, std::uint32_t node) {
  const auto end = ids.nodes.begin() + node_count(ids.type);
  return std::find(ids.nodes.begin(), end, node) != end;
}

// The outward normal of a segment at its node `corner`, times the angle (rad) between
// the segment's two edge directions leaving that node (pi at a mid-side node): one
// term of the angle-weighted pseudo-normal.
Vec3 weighted_normal(const Segment& segment, int corner) {
  const Xi xi = node_xi[std::size_t(corner)];
  const SurfacePoint s = evaluate(segment, xi);
  const Vec3 n = outward_normal(s);
  double angle = M_PI;
  if (xi[0] != 0.0 && xi[1] != 0.0) {
    const Vec3 d1 = (-xi[0]) * s.a1, d2 = (-xi[1]) * s.a2;  // into the segment
    const double lengths = norm(d1) * norm(d2);
    if (!(lengths > 0.0)) return Vec3{};
    angle = std::acos(std::clamp(dot(d1, d2) / lengths, -1.0, 1.0));
  }
  return angle * n;
}

Vec3 unit(Vec3 v) {
  const double length = norm(v);
  return length > 0.0 ? (1.0 / length) * v : Vec3{};
}

}  // namespace

bool behind_beyond(const Segment& segment, Vec3 point, double depth) {
  const Vec3 n = outward_normal(evaluate(segment, Xi{0.0, 0.0}));
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (int i = 0; i < node_count(segment.type); ++i) {
    const double a = dot(segment.nodes[std::size_t(i)], n);
    lowest = std::min(lowest, a), highest = std::max(highest, a);
  }
  if (segment.type == SegmentType::quad8) lowest -= highest - lowest;
  return dot(point, n) < lowest - depth;
}

bool shares_node(const ContactSurfaces& surfaces, std::size_t p, std::uint32_t segment) {
  const SegmentNodes& master = surfaces.segments[segment];
  if (!surfaces.quadrature) return has_node(master, surfaces.slave_nodes[p]);
  const SegmentNodes& own = surfaces.slave_segments[surfaces.quadrature_points[p].segment];
  for (int i = 0; i < node_count(own.type); ++i)
    if (has_node(master, own.nodes[std::size_t(i)])) return true;
  return false;
}

bool segments_excluded(const SegmentNodes& slave, const SegmentNodes& master, const NodalVectors& x_ref,
                       const NodalVectors& u) {
  for (int i = 0; i < node_count(slave.type); ++i)
    if (has_node(master, slave.nodes[std::size_t(i)])) return true;
  const Vec3 n_s = outward_normal(current_segment(slave, x_ref, u), Xi{0.0, 0.0});
  const Vec3 n_m = outward_normal(current_segment(master, x_ref, u), Xi{0.0, 0.0});
  return dot(n_s, n_m) >= same_way_cosine;
}

Vec3 point_normal(const ContactSurfaces& surfaces, std::size_t p, const NodalVectors& x_ref,
                  const NodalVectors& u) {
  if (surfaces.quadrature) {
    const QuadraturePoint& q = surfaces.quadrature_points[p];
    return outward_normal(current_segment(surfaces.slave_segments[q.segment], x_ref, u), q.xi);
  }
  Vec3 sum{};
  for (std::uint32_t k = surfaces.corner_begin[p]; k < surfaces.corner_begin[p + 1]; ++k) {
    const NodeCorner& c = surfaces.node_corners[k];
    if (!surfaces.segment_on(c.segment)) continue;  // not on the boundary now (erosion)
    sum = sum + weighted_normal(current_segment(surfaces.segments[c.segment], x_ref, u), c.corner);
  }
  return unit(sum);
}

double side_stiffness(const ContactSurfaces& surfaces, std::size_t p, Vec3 normal, const NodalVectors& x_ref,
                      const NodalVectors& u) {
  const std::uint32_t first = surfaces.side_begin[p], sides = surfaces.side_begin[p + 1] - first;
  if (sides == 1) return surfaces.side_stiffness[first];
  std::array<Vec3, max_node_sides> side_normal{};
  for (std::uint32_t k = surfaces.corner_begin[p]; k < surfaces.corner_begin[p + 1]; ++k) {
    const NodeCorner& c = surfaces.node_corners[k];
    if (!surfaces.segment_on(c.segment)) continue;
    side_normal[c.side] = side_normal[c.side] +
                          weighted_normal(current_segment(surfaces.segments[c.segment], x_ref, u), c.corner);
  }
  std::uint32_t best = 0;  // the most opposed to `normal`; ties to the first side
  double best_cosine = 2.0;
  for (std::uint32_t s = 0; s < sides; ++s)
    if (const double cosine = dot(unit(side_normal[s]), normal);
        norm(side_normal[s]) > 0.0 && cosine < best_cosine)  // a side with no segment on: none
      best_cosine = cosine, best = s;
  return surfaces.side_stiffness[first + best];
}

}  // namespace exdyn::contact
