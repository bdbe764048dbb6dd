// Segmentation for mortar contact (slave_points: mortar): a slave segment cut into
// the pieces where it overlaps a master segment, with the points of a triangle rule
// on each piece (Puso and Laursen 2004; docs/contact.md, "Mortar").
//
// Each segment is one flat facet (quad4: its corners) or four (quad8: the corners of
// the quarters xi in [-1,0]^2 ... [0,1]^2, points of the curved surface). A slave
// facet and a master facet facing it are projected onto the slave facet's plane (its
// centre, the normal of its diagonals); the master polygon clips the slave polygon
// (Sutherland-Hodgman); the piece is cut into a fan of triangles; each rule point q of
// the plane goes back to the slave facet by the inverse of its bilinear map, and so to
// the segment's xi. Its weight makes the sum an integral over the true slave surface:
//   w = w_rule A_triangle |a1 x a2|(xi) h^2 / |det dq/d(s,t)|      (m^2)
// (h = 1 on quad4, 1/2 on a quad8 quarter). On flat faces both maps are affine: the
// pieces are the exact overlaps, and a rule of degree >= that of N_slave N_master
// integrates the consistent forces of a uniform pressure exactly.
#pragma once

#include <array>

#include "contact/segment.hpp"

namespace exdyn::contact {

// A rule on a triangle: barycentric points and weights that sum to 1 (times the area).
struct TriangleRule {
  int count = 0;
  std::array<std::array<double, 3>, 7> point{};
  std::array<double, 7> weight{};
};

// The rule of 1, 3, 6 or 7 points: exact for polynomials of degree 1, 2, 4 and 5
// (centroid; Strang and Fix; Dunavant; Radon). Any other count is a broken invariant.
TriangleRule triangle_rule(int points);

struct Vec2 {
  double x = 0.0, y = 0.0;
};

// A polygon of the plane, counter-clockwise. Two convex quadrilaterals overlap in at
// most 8 vertices; clipping works on up to 16.
struct Polygon {
  int count = 0;
  std::array<Vec2, 16> vertex{};
};

// The signed area (m^2): > 0 counter-clockwise.
double signed_area(const Polygon& polygon);

// Whether a counter-clockwise polygon is convex (every turn to the left or straight).
bool is_convex(const Polygon& polygon);

// The part of `subject` inside `clip` (convex, counter-clockwise): Sutherland-Hodgman.
Polygon clip_convex(const Polygon& subject, const Polygon& clip);

// A flat facet of a segment: its 4 corners (counter-clockwise seen from outside) and
// the part of the segment's xi it stands for, xi = center + half (s, t), (s,t) in [-1,1]^2.
struct Facet {
  std::array<Vec3, 4> corner{};
  Xi center{};
  double half = 1.0;
};
constexpr int facet_count(SegmentType type) { return type == SegmentType::quad4 ? 1 : 4; }
Facet segment_facet(const Segment& segment, int k);

// A point of a piece: where it lies on the slave segment, its weight (m^2 of the slave
// surface) and where the projection along the slave facet's normal meets the master
// segment (a starting point for the local search).
struct MortarPoint {
  Xi slave_xi{};
  Xi master_xi{};
  double weight = 0.0;
};

// The most points one slave segment can have on one master segment: 4 x 4 facet pairs,
// each piece at most 8 vertices (6 triangles), 7 points a triangle.
inline constexpr int max_mortar_points_per_pair = 16 * 6 * 7;

// The points of the pieces of `slave` on `master` into out[0 .. count), count returned
// (at most max_mortar_points_per_pair). Facet pairs that do not face each other
// (n_slave . n_master >= 0), or whose planes lie further apart than `capture` (m) at the
// piece's centre, give none.
int mortar_points(const Segment& slave, const Segment& master, const TriangleRule& rule, double capture,
                  MortarPoint* out);

}  // namespace exdyn::contact
