#include "contact/mortar.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"
#include "contact/quadrature.hpp"

namespace exdyn::contact {

PieceRule piece_rule(int points) {
  PieceRule rule;
  auto add = [&rule](double a, double b, double c, double weight) {
    rule.point[std::size_t(rule.count)] = {a, b, c};
    rule.weight[std::size_t(rule.count)] = weight;
    ++rule.count;
  };
  // The three points (a, a, 1 - 2a) and its permutations, each of weight w.
  auto orbit = [&add](double a, double weight) {
    const double b = 1.0 - 2.0 * a;
    add(a, a, b, weight);
    add(a, b, a, weight);
    add(b, a, a, weight);
  };
  const double third = 1.0 / 3.0, root15 = std::sqrt(15.0);
  switch (points) {
    case 1:
      add(third, third, third, 1.0);
      rule.quad_side = 1;
      break;
    case 3:
      orbit(1.0 / 6.0, third);
      rule.quad_side = 2;
      break;
    case 6:
      orbit(0.44594849091596488632, 0.22338158967801146570);
      orbit(0.091576213509770743460, 0.10995174365532186764);
      rule.quad_side = 3;
      break;
    case 7:
      rule.quad_side = 3;
      add(third, third, third, 0.225);
      orbit((6.0 - root15) / 21.0, (155.0 - root15) / 1200.0);
      orbit((6.0 + root15) / 21.0, (155.0 + root15) / 1200.0);
      break;
    default:
      EXDYN_ASSERT(false);
  }
  return rule;
}

namespace {

double cross2(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
Vec2 minus(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }

}  // namespace

double signed_area(const Polygon& polygon) {
  double twice = 0.0;
  for (int i = 0; i < polygon.count; ++i)
    twice += cross2(polygon.vertex[std::size_t(i)], polygon.vertex[std::size_t((i + 1) % polygon.count)]);
  return 0.5 * twice;
}

bool is_convex(const Polygon& polygon) {
  for (int i = 0; i < polygon.count; ++i) {
    const Vec2 a = polygon.vertex[std::size_t(i)], b = polygon.vertex[std::size_t((i + 1) % polygon.count)],
               c = polygon.vertex[std::size_t((i + 2) % polygon.count)];
    if (cross2(minus(b, a), minus(c, b)) < 0.0) return false;
  }
  return true;
}

Polygon clip_convex(const Polygon& subject, const Polygon& clip) {
  Polygon out = subject;
  for (int e = 0; e < clip.count && out.count > 0; ++e) {
    const Vec2 a = clip.vertex[std::size_t(e)], b = clip.vertex[std::size_t((e + 1) % clip.count)];
    const Vec2 edge = minus(b, a);
    const Polygon in = out;
    out.count = 0;
    auto push = [&out](Vec2 v) {
      if (out.count < int(out.vertex.size())) out.vertex[std::size_t(out.count++)] = v;
    };
    for (int j = 0; j < in.count; ++j) {
      const Vec2 current = in.vertex[std::size_t(j)],
                 previous = in.vertex[std::size_t((j + in.count - 1) % in.count)];
      const double d_current = cross2(edge, minus(current, a)), d_previous = cross2(edge, minus(previous, a));
      // The crossing of the edge's line between previous and current.
      auto crossing = [&] {
        const double t = d_previous / (d_previous - d_current);
        return Vec2{previous.x + t * (current.x - previous.x), previous.y + t * (current.y - previous.y)};
      };
      if (d_current >= 0.0) {
        if (d_previous < 0.0) push(crossing());
        push(current);
      } else if (d_previous >= 0.0) {
        push(crossing());
      }
    }
  }
  return out;
}

Polygon corners_only(const Polygon& polygon) {
  Polygon out = polygon;
  double size = 0.0;  // the largest extent of the polygon
  for (int i = 0; i < polygon.count; ++i)
    for (int j = i + 1; j < polygon.count; ++j) {
      const Vec2 d = minus(polygon.vertex[std::size_t(i)], polygon.vertex[std::size_t(j)]);
      size = std::max(size, std::abs(d.x) + std::abs(d.y));
    }
  const double tolerance = 1.0e-12 * size;
  for (bool removed = true; removed && out.count >= 3;) {
    removed = false;
    for (int i = 0; i < out.count; ++i) {
      const Vec2 a = out.vertex[std::size_t((i + out.count - 1) % out.count)], b = out.vertex[std::size_t(i)],
                 c = out.vertex[std::size_t((i + 1) % out.count)];
      const Vec2 in = minus(b, a), next = minus(c, b);
      const double in_length = std::abs(in.x) + std::abs(in.y),
                   next_length = std::abs(next.x) + std::abs(next.y);
      // b repeats a, or lies on the line from a to c (the triangle a b c has no height at b).
      if (in_length <= tolerance || std::abs(cross2(in, next)) <= tolerance * (in_length + next_length)) {
        for (int k = i; k + 1 < out.count; ++k) out.vertex[std::size_t(k)] = out.vertex[std::size_t(k + 1)];
        --out.count;
        removed = true;
        break;
      }
    }
  }
  return out;
}

Bilinear::Bilinear(const std::array<Vec2, 4>& p)
    : c0{0.25 * (p[0].x + p[1].x + p[2].x + p[3].x), 0.25 * (p[0].y + p[1].y + p[2].y + p[3].y)},
      c1{0.25 * (p[1].x + p[2].x - p[0].x - p[3].x), 0.25 * (p[1].y + p[2].y - p[0].y - p[3].y)},
      c2{0.25 * (p[2].x + p[3].x - p[0].x - p[1].x), 0.25 * (p[2].y + p[3].y - p[0].y - p[1].y)},
      c3{0.25 * (p[0].x + p[2].x - p[1].x - p[3].x), 0.25 * (p[0].y + p[2].y - p[1].y - p[3].y)} {}

bool Bilinear::inverse(Vec2 q, double& s, double& t) const {
  s = t = 0.0;
  for (int k = 0; k < 20; ++k) {
    const Vec2 r{c0.x + c1.x * s + c2.x * t + c3.x * s * t - q.x,
                 c0.y + c1.y * s + c2.y * t + c3.y * s * t - q.y};
    const Vec2 a = ds(t), b = dt(s);
    const double det = cross2(a, b);
    if (!(std::abs(det) > 0.0)) return false;
    const double step_s = (r.x * b.y - r.y * b.x) / det, step_t = (a.x * r.y - a.y * r.x) / det;
    s -= step_s, t -= step_t;
    if (std::abs(step_s) + std::abs(step_t) <= 1.0e-14 * (1.0 + std::abs(s) + std::abs(t))) return true;
  }
  return false;
}

namespace {

// The plane through the mean of 4 corners (counter-clockwise), normal to their diagonals.
FacetPlane facet_plane(const std::array<Vec3, 8>& p) {
  FacetPlane plane;
  plane.origin = 0.25 * (p[0] + p[1] + p[2] + p[3]);
  const Vec3 n = cross(p[2] - p[0], p[3] - p[1]);
  plane.normal = (1.0 / norm(n)) * n;
  const Vec3 side = p[1] - p[0];
  const Vec3 along = side - dot(side, plane.normal) * plane.normal;
  plane.e1 = (1.0 / norm(along)) * along;
  plane.e2 = cross(plane.normal, plane.e1);
  return plane;
}

void box_of(const Polygon& polygon, Vec2& lo, Vec2& hi) {
  lo = hi = polygon.vertex[0];
  for (int i = 1; i < polygon.count; ++i) {
    const Vec2 v = polygon.vertex[std::size_t(i)];
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y)};
  }
}

}  // namespace

void snap_to_slave_corners(const SlaveFacet& slave, const std::array<Vec3, 8>& master,
                           std::array<Vec2, 4>& master_corners) {
  for (std::size_t i = 0; i < 4; ++i) {
    std::size_t nearest = 4;
    double nearest_offset = 0.0;
    for (std::size_t j = 0; j < 4; ++j) {
      const Vec2 offset = minus(master_corners[i], slave.polygon.vertex[j]);
      const double length = std::hypot(offset.x, offset.y);
      if (length <= shared_point_band * norm(master[i] - slave.corner[j]) &&
          (nearest == 4 || length < nearest_offset))
        nearest = j, nearest_offset = length;
    }
    if (nearest < 4) master_corners[i] = slave.polygon.vertex[nearest];
  }
}

SlaveFacet slave_facet(const Segment& slave) {
  SlaveFacet out;
  if (slave.type == SegmentType::quad4) {
    const Surface<4> bilinear = make_surface<4>(slave);
    for (int i = 0; i < 4; ++i) out.surface.c[std::size_t(i)] = bilinear.c[std::size_t(i)];
  } else {
    out.surface = make_surface<8>(slave);
  }
  out.plane = facet_plane(slave.nodes);
  for (std::size_t i = 0; i < 4; ++i) out.corner[i] = slave.nodes[i];
  out.polygon.count = 4;
  std::array<Vec2, 4> corners;
  for (int i = 0; i < 4; ++i)
    corners[std::size_t(i)] = out.polygon.vertex[std::size_t(i)] =
        out.plane.project(slave.nodes[std::size_t(i)]);
  out.map = Bilinear(corners);
  out.area = signed_area(out.polygon);
  out.valid = out.area > 0.0;
  if (out.valid) box_of(out.polygon, out.lo, out.hi);
  return out;
}

int mortar_points(const SlaveFacet& slave, const Segment& master, const PieceRule& rule, double reach,
                  MortarPoint* out) {
  if (!slave.valid) return 0;
  const FacetPlane& plane = slave.plane;
  const auto& m = master.nodes;
  if (!(dot(cross(m[2] - m[0], m[3] - m[1]), plane.normal) < 0.0)) return 0;  // not facing
  std::array<Vec2, 4> master_corners;
  for (int i = 0; i < 4; ++i) master_corners[std::size_t(i)] = plane.project(m[std::size_t(i)]);
  snap_to_slave_corners(slave, m, master_corners);
  // Seen along the slave normal the master's corners run clockwise: reversed.
  Polygon master_polygon;
  master_polygon.count = 4;
  for (int i = 0; i < 4; ++i)
    master_polygon.vertex[std::size_t(i)] = master_corners[std::size_t((4 - i) % 4)];
  Vec2 lo, hi;
  box_of(master_polygon, lo, hi);
  if (hi.x < slave.lo.x || slave.hi.x < lo.x || hi.y < slave.lo.y || slave.hi.y < lo.y) return 0;
  Polygon piece;
  if (is_convex(master_polygon))
    piece = clip_convex(slave.polygon, master_polygon);
  else if (is_convex(slave.polygon))
    piece = clip_convex(master_polygon, slave.polygon);
  else
    return 0;
  piece = corners_only(piece);
  const double tiny = 1.0e-12 * slave.area;
  if (piece.count < 3 || !(signed_area(piece) > tiny)) return 0;
  const Bilinear master_map(master_corners);
  // The surfaces' distance along the slave normal at the piece's centre: beyond `reach`
  // the piece is not a contact (and not looked for).
  Vec2 centre{0.0, 0.0};
  for (int i = 0; i < piece.count; ++i)
    centre = {centre.x + piece.vertex[std::size_t(i)].x / piece.count,
              centre.y + piece.vertex[std::size_t(i)].y / piece.count};
  double s = 0, t = 0, sm = 0, tm = 0;
  if (!slave.map.inverse(centre, s, t) || !master_map.inverse(centre, sm, tm)) return 0;
  if (std::abs(dot(position(master, Xi{sm, tm}) - position(slave.surface, Xi{s, t}), plane.normal)) > reach)
    return 0;
  int count = 0;
  // A point q of the plane with weight w dq (m^2): onto the slave's xi, and its weight on
  // the slave surface.
  auto add = [&](Vec2 q, double weight) {
    if (!slave.map.inverse(q, s, t) || !master_map.inverse(q, sm, tm)) return;
    const SurfacePoint y = evaluate(slave.surface, Xi{s, t});
    MortarPoint& point = out[count++];
    point.slave_xi = {s, t};
    point.master_xi = {sm, tm};
    point.weight = weight * norm(cross(y.a1, y.a2)) / std::abs(cross2(slave.map.ds(t), slave.map.dt(s)));
  };
  if (piece.count == 4) {  // Gauss points of its bilinear map
    const Bilinear map({piece.vertex[0], piece.vertex[1], piece.vertex[2], piece.vertex[3]});
    const GaussLegendre g = gauss_legendre(rule.quad_side);
    for (int j = 0; j < g.count; ++j)
      for (int i = 0; i < g.count; ++i) {
        const double a = g.abscissa[std::size_t(i)], b = g.abscissa[std::size_t(j)];
        const Vec2 q{map.c0.x + map.c1.x * a + map.c2.x * b + map.c3.x * a * b,
                     map.c0.y + map.c1.y * a + map.c2.y * b + map.c3.y * a * b};
        add(q, g.weight[std::size_t(i)] * g.weight[std::size_t(j)] * std::abs(cross2(map.ds(b), map.dt(a))));
      }
    return count;
  }
  // A fan of triangles from the mean of the corners.
  const Vec2 v0 = centre;
  for (int i = 0; i < piece.count; ++i) {
    const Vec2 v1 = piece.vertex[std::size_t(i)], v2 = piece.vertex[std::size_t((i + 1) % piece.count)];
    const double area = 0.5 * cross2(minus(v1, v0), minus(v2, v0));
    if (!(area > tiny)) continue;
    for (int k = 0; k < rule.count; ++k) {
      const auto& l = rule.point[std::size_t(k)];
      add({l[0] * v0.x + l[1] * v1.x + l[2] * v2.x, l[0] * v0.y + l[1] * v1.y + l[2] * v2.y},
          rule.weight[std::size_t(k)] * area);
    }
  }
  return count;
}

}  // namespace exdyn::contact
