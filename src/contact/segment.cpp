#include "contact/segment.hpp"

#include <algorithm>
#include <limits>

namespace exdyn::contact {

SurfacePoint evaluate(const Segment& segment, Xi xi) {
  return segment.type == SegmentType::quad4 ? evaluate(make_surface<4>(segment), xi)
                                            : evaluate(make_surface<8>(segment), xi);
}

Vec3 position(const Segment& segment, Xi xi) {
  return segment.type == SegmentType::quad4 ? position(make_surface<4>(segment), xi)
                                            : position(make_surface<8>(segment), xi);
}

Vec3 outward_normal(const Segment& segment, Xi xi) { return outward_normal(evaluate(segment, xi)); }

std::array<double, 8> shape_functions(SegmentType type, Xi xi) {
  std::array<double, 8> N{};
  const double u = xi[0], v = xi[1];
  if (type == SegmentType::quad4) {
    for (int i = 0; i < 4; ++i) N[i] = 0.25 * (1.0 + node_xi[i][0] * u) * (1.0 + node_xi[i][1] * v);
    return N;
  }
  for (int i = 0; i < 4; ++i) {
    const double su = node_xi[i][0], sv = node_xi[i][1];
    N[i] = 0.25 * (1.0 + su * u) * (1.0 + sv * v) * (su * u + sv * v - 1.0);
  }
  for (int i = 4; i < 8; ++i) {
    const double su = node_xi[i][0], sv = node_xi[i][1];
    N[i] = su == 0.0 ? 0.5 * (1.0 - u * u) * (1.0 + sv * v) : 0.5 * (1.0 + su * u) * (1.0 - v * v);
  }
  return N;
}

SegmentBox segment_box(const Segment& segment) {
  const auto& y = segment.nodes;
  std::array<Vec3, 9> points;
  int count = 4;
  for (int i = 0; i < 4; ++i) points[i] = y[i];
  if (segment.type == SegmentType::quad8) {
    // The serendipity surface is a biquadratic one whose centre value is
    // y(0, 0) = (y4 + y5 + y6 + y7) / 2 - (y0 + y1 + y2 + y3) / 4. A quadratic through
    // p(-1), p(0), p(1) has the Bezier control points p(-1), 2 p(0) - (p(-1) + p(1)) / 2,
    // p(1), and the tensor product of that map gives the 9 control points, whose
    // convex hull holds the patch.
    const Vec3 centre = 0.5 * (y[4] + y[5] + y[6] + y[7]) - 0.25 * (y[0] + y[1] + y[2] + y[3]);
    auto middle = [](Vec3 end0, Vec3 mid, Vec3 end1) { return 2.0 * mid - 0.5 * (end0 + end1); };
    const Vec3 b4 = middle(y[0], y[4], y[1]);  // edge xi2 = -1
    const Vec3 b5 = middle(y[1], y[5], y[2]);  // edge xi1 = +1
    const Vec3 b6 = middle(y[3], y[6], y[2]);  // edge xi2 = +1
    const Vec3 b7 = middle(y[0], y[7], y[3]);  // edge xi1 = -1
    // Centre control point: the map applied along xi2 to the column of xi1-midpoints.
    const Vec3 column_mid = middle(y[7], centre, y[5]);  // Bezier along xi1 at xi2 = 0
    const Vec3 b8 = middle(b4, column_mid, b6);          // then along xi2
    points[4] = b4, points[5] = b5, points[6] = b6, points[7] = b7, points[8] = b8;
    count = 9;
  }
  SegmentBox box{points[0], points[0]};
  for (int i = 1; i < count; ++i) {
    const Vec3& p = points[static_cast<std::size_t>(i)];
    box.lo = {std::min(box.lo.x, p.x), std::min(box.lo.y, p.y), std::min(box.lo.z, p.z)};
    box.hi = {std::max(box.hi.x, p.x), std::max(box.hi.y, p.y), std::max(box.hi.z, p.z)};
  }
  return box;
}

double segment_size(const Segment& segment) {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi = -1.0 * lo;
  for (int i = 0; i < node_count(segment.type); ++i) {
    const Vec3& p = segment.nodes[i];
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return norm(hi - lo);
}

}  // namespace exdyn::contact
