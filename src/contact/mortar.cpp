#include "contact/mortar.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"

namespace exdyn::contact {

TriangleRule triangle_rule(int points) {
  TriangleRule rule;
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
      break;
    case 3:
      orbit(1.0 / 6.0, third);
      break;
    case 6:
      orbit(0.44594849091596488632, 0.22338158967801146570);
      orbit(0.091576213509770743460, 0.10995174365532186764);
      break;
    case 7:
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

Facet segment_facet(const Segment& segment, int k) {
  Facet facet;
  const auto& y = segment.nodes;
  if (segment.type == SegmentType::quad4) {
    facet.corner = {y[0], y[1], y[2], y[3]};
    return facet;
  }
  // The quarters of a quad8 through its nodes and its centre y(0, 0), counter-clockwise.
  const Vec3 centre = 0.5 * (y[4] + y[5] + y[6] + y[7]) - 0.25 * (y[0] + y[1] + y[2] + y[3]);
  facet.half = 0.5;
  switch (k) {
    case 0:
      facet.corner = {y[0], y[4], centre, y[7]}, facet.center = {-0.5, -0.5};
      break;
    case 1:
      facet.corner = {y[4], y[1], y[5], centre}, facet.center = {0.5, -0.5};
      break;
    case 2:
      facet.corner = {centre, y[5], y[2], y[6]}, facet.center = {0.5, 0.5};
      break;
    default:
      facet.corner = {y[7], centre, y[6], y[3]}, facet.center = {-0.5, 0.5};
  }
  return facet;
}

namespace {

// The plane of a facet: its centre, the unit normal of its diagonals and a basis of it.
struct Plane {
  Vec3 origin, normal, e1, e2;
  Vec2 project(Vec3 x) const {
    const Vec3 d = x - origin;
    return {dot(d, e1), dot(d, e2)};
  }
};

Plane facet_plane(const Facet& f) {
  Plane plane;
  const auto& p = f.corner;
  plane.origin = 0.25 * (p[0] + p[1] + p[2] + p[3]);
  const Vec3 n = cross(p[2] - p[0], p[3] - p[1]);
  plane.normal = (1.0 / norm(n)) * n;
  const Vec3 side = p[1] - p[0];
  const Vec3 along = side - dot(side, plane.normal) * plane.normal;
  plane.e1 = (1.0 / norm(along)) * along;
  plane.e2 = cross(plane.normal, plane.e1);
  return plane;
}

// The bilinear map q(s, t) = c0 + c1 s + c2 t + c3 s t of 4 corners of the plane.
struct Bilinear {
  Vec2 c0, c1, c2, c3;
  explicit Bilinear(const std::array<Vec2, 4>& p)
      : c0{0.25 * (p[0].x + p[1].x + p[2].x + p[3].x), 0.25 * (p[0].y + p[1].y + p[2].y + p[3].y)},
        c1{0.25 * (p[1].x + p[2].x - p[0].x - p[3].x), 0.25 * (p[1].y + p[2].y - p[0].y - p[3].y)},
        c2{0.25 * (p[2].x + p[3].x - p[0].x - p[1].x), 0.25 * (p[2].y + p[3].y - p[0].y - p[1].y)},
        c3{0.25 * (p[0].x + p[2].x - p[1].x - p[3].x), 0.25 * (p[0].y + p[2].y - p[1].y - p[3].y)} {}
  // dq/ds and dq/dt at (s, t).
  Vec2 ds(double t) const { return {c1.x + c3.x * t, c1.y + c3.y * t}; }
  Vec2 dt(double s) const { return {c2.x + c3.x * s, c2.y + c3.y * s}; }
  // (s, t) with q(s, t) = q by Newton from the centre (exact in one step on a
  // parallelogram); false where it does not settle.
  bool inverse(Vec2 q, double& s, double& t) const {
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
};

Vec3 bilinear_point(const Facet& f, double s, double t) {
  const auto& p = f.corner;
  return 0.25 * ((1 - s) * (1 - t) * p[0] + (1 + s) * (1 - t) * p[1] + (1 + s) * (1 + t) * p[2] +
                 (1 - s) * (1 + t) * p[3]);
}

struct Box2 {
  Vec2 lo, hi;
};
Box2 box_of(const Polygon& polygon) {
  Box2 box{polygon.vertex[0], polygon.vertex[0]};
  for (int i = 1; i < polygon.count; ++i) {
    const Vec2 v = polygon.vertex[std::size_t(i)];
    box.lo = {std::min(box.lo.x, v.x), std::min(box.lo.y, v.y)};
    box.hi = {std::max(box.hi.x, v.x), std::max(box.hi.y, v.y)};
  }
  return box;
}

// |a1 x a2| at xi of the slave segment, m^2 per unit xi1 xi2.
template <int Terms>
double area_element(const Surface<Terms>& surface, Xi xi) {
  const SurfacePoint p = evaluate(surface, xi);
  return norm(cross(p.a1, p.a2));
}

template <int SlaveTerms>
int pair_points(const Segment& slave, const Segment& master, const TriangleRule& rule, double capture,
                MortarPoint* out) {
  const Surface<SlaveTerms> surface = make_surface<SlaveTerms>(slave);
  int count = 0;
  for (int fs = 0; fs < facet_count(slave.type); ++fs) {
    const Facet sf = segment_facet(slave, fs);
    const Plane plane = facet_plane(sf);
    Polygon slave_polygon;
    slave_polygon.count = 4;
    std::array<Vec2, 4> slave_corners;
    for (int i = 0; i < 4; ++i)
      slave_corners[std::size_t(i)] = slave_polygon.vertex[std::size_t(i)] =
          plane.project(sf.corner[std::size_t(i)]);
    const Bilinear slave_map(slave_corners);
    const double slave_area = signed_area(slave_polygon);
    if (!(slave_area > 0.0)) continue;
    const Box2 slave_box = box_of(slave_polygon);
    for (int fm = 0; fm < facet_count(master.type); ++fm) {
      const Facet mf = segment_facet(master, fm);
      const auto& m = mf.corner;
      if (!(dot(cross(m[2] - m[0], m[3] - m[1]), plane.normal) < 0.0)) continue;  // not facing
      // Seen along the slave normal the master's corners run clockwise: reversed.
      std::array<Vec2, 4> master_corners;
      for (int i = 0; i < 4; ++i) master_corners[std::size_t(i)] = plane.project(m[std::size_t(i)]);
      Polygon master_polygon;
      master_polygon.count = 4;
      for (int i = 0; i < 4; ++i)
        master_polygon.vertex[std::size_t(i)] = master_corners[std::size_t((4 - i) % 4)];
      const Box2 master_box = box_of(master_polygon);
      if (master_box.hi.x < slave_box.lo.x || slave_box.hi.x < master_box.lo.x ||
          master_box.hi.y < slave_box.lo.y || slave_box.hi.y < master_box.lo.y)
        continue;
      Polygon piece;
      if (is_convex(master_polygon))
        piece = clip_convex(slave_polygon, master_polygon);
      else if (is_convex(slave_polygon))
        piece = clip_convex(master_polygon, slave_polygon);
      else
        continue;
      const double tiny = 1.0e-12 * slave_area;
      if (piece.count < 3 || !(signed_area(piece) > tiny)) continue;
      const Bilinear master_map(master_corners);
      // The planes' distance along the slave normal at the piece's centre: beyond the
      // capture distance the piece is not a contact (and not looked for).
      Vec2 centre{};
      for (int i = 0; i < piece.count; ++i)
        centre = {centre.x + piece.vertex[std::size_t(i)].x / piece.count,
                  centre.y + piece.vertex[std::size_t(i)].y / piece.count};
      double s = 0, t = 0, sm = 0, tm = 0;
      if (!slave_map.inverse(centre, s, t) || !master_map.inverse(centre, sm, tm)) continue;
      if (std::abs(dot(bilinear_point(mf, sm, tm) - bilinear_point(sf, s, t), plane.normal)) > capture)
        continue;
      const Vec2 v0 = piece.vertex[0];
      for (int i = 1; i + 1 < piece.count; ++i) {
        const Vec2 v1 = piece.vertex[std::size_t(i)], v2 = piece.vertex[std::size_t(i + 1)];
        const double area = 0.5 * cross2(minus(v1, v0), minus(v2, v0));
        if (!(area > tiny)) continue;
        for (int g = 0; g < rule.count; ++g) {
          const auto& l = rule.point[std::size_t(g)];
          const Vec2 q{l[0] * v0.x + l[1] * v1.x + l[2] * v2.x, l[0] * v0.y + l[1] * v1.y + l[2] * v2.y};
          if (!slave_map.inverse(q, s, t) || !master_map.inverse(q, sm, tm)) continue;
          const double plane_jacobian = std::abs(cross2(slave_map.ds(t), slave_map.dt(s)));
          MortarPoint point;
          point.slave_xi = {sf.center[0] + sf.half * s, sf.center[1] + sf.half * t};
          point.master_xi = {mf.center[0] + mf.half * sm, mf.center[1] + mf.half * tm};
          point.weight = rule.weight[std::size_t(g)] * area * area_element(surface, point.slave_xi) *
                         sf.half * sf.half / plane_jacobian;
          EXDYN_ASSERT(count < max_mortar_points_per_pair);
          out[count++] = point;
        }
      }
    }
  }
  return count;
}

}  // namespace

int mortar_points(const Segment& slave, const Segment& master, const TriangleRule& rule, double capture,
                  MortarPoint* out) {
  return slave.type == SegmentType::quad4 ? pair_points<4>(slave, master, rule, capture, out)
                                          : pair_points<8>(slave, master, rule, capture, out);
}

}  // namespace exdyn::contact
