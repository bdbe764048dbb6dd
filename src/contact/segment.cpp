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
