// Segmentation for mortar contact (slave_points: mortar): a slave segment cut into
// the pieces where it overlaps a master segment, with the points of a triangle rule
// on each piece (Puso and Laursen 2004; docs/contact.md, "Mortar").
//
// A slave segment and a master segment facing it are projected onto the slave's plane
// (through the mean of its corners, normal to its diagonals); the master's corner
// polygon clips the slave's (Sutherland-Hodgman); the piece is cut into a fan of
// triangles; each rule point q of the plane goes back to the slave's xi by the inverse
// of the bilinear map of its projected corners. On an 8-node segment xi is then a point
// of the curved surface: the weight makes the sum an integral over the true slave
// surface whatever its curvature,
//   w = w_rule |det dq/d(rule's coordinates)| |a1 x a2|(xi) / |det dq/dxi|      (m^2),
// and only the pieces' edges are the corners' chords. On flat faces the maps are affine
// (the mid-side nodes of a flat 8-node segment at its edges' midpoints): the pieces are
// the exact overlaps, and a rule of degree >= that of the shape functions integrates the
// consistent forces of a uniform pressure on both sides exactly.
#pragma once

#include <array>

#include "contact/segment.hpp"

namespace exdyn::contact {

// The rule of a piece: on a triangle, barycentric points and weights that sum to 1
// (times the area); a piece of four corners instead takes the n x n Gauss rule of its
// bilinear map, n = quad_side, of at least the triangle rule's degree. Both rules are
// the same under every symmetry of their shape, so a piece gets the same points
// whichever of its corners comes first (mirror-image scenes, mirror-image points).
struct PieceRule {
  int count = 0;  // points on a triangle
  std::array<std::array<double, 3>, 7> point{};
  std::array<double, 7> weight{};
  int quad_side = 1;
};

// The rule of 1, 3, 6 or 7 points a triangle: exact for polynomials of degree 1, 2, 4 and
// 5 (centroid; Strang and Fix; Dunavant; Radon); on four corners 1, 2, 3 and 3 Gauss
// points a side (degree 1, 3, 5 and 5 in each direction). Any other count is a broken
// invariant.
PieceRule piece_rule(int triangle_points);

// A point of a plane (no default value: the polygons below are made on every cut, and
// only their first `count` vertices are ever read).
struct Vec2 {
  double x, y;
};

// A polygon of the plane, counter-clockwise. Two convex quadrilaterals overlap in at
// most 8 vertices; clipping works on up to 16.
struct Polygon {
  int count = 0;
  std::array<Vec2, 16> vertex;
};

// The signed area (m^2): > 0 counter-clockwise.
double signed_area(const Polygon& polygon);

// Whether a counter-clockwise polygon is convex (every turn to the left or straight).
bool is_convex(const Polygon& polygon);

// The part of `subject` inside `clip` (convex, counter-clockwise): Sutherland-Hodgman.
Polygon clip_convex(const Polygon& subject, const Polygon& clip);

// The polygon without the vertices that do not turn it: repeats and vertices on a straight
// edge (to 1e-12 of its size), which the clipping leaves where edges meet or cross at a
// vertex. What is left depends on the region alone, not on where the clipping began.
Polygon corners_only(const Polygon& polygon);

// The plane of a slave segment: the mean of its corners, the unit normal of its
// diagonals and a basis.
struct FacetPlane {
  Vec3 origin, normal, e1, e2;
  Vec2 project(Vec3 x) const {
    const Vec3 d = x - origin;
    return {dot(d, e1), dot(d, e2)};
  }
};

// The bilinear map q(s, t) = c0 + c1 s + c2 t + c3 s t of 4 corners of a plane.
struct Bilinear {
  Vec2 c0, c1, c2, c3;
  Bilinear() = default;
  explicit Bilinear(const std::array<Vec2, 4>& corner);
  Vec2 ds(double t) const { return {c1.x + c3.x * t, c1.y + c3.y * t}; }  // dq/ds at t
  Vec2 dt(double s) const { return {c2.x + c3.x * s, c2.y + c3.y * s}; }  // dq/dt at s
  // (s, t) with q(s, t) = q by Newton from the centre (exact in one step on a
  // parallelogram); false where it does not settle.
  bool inverse(Vec2 q, double& s, double& t) const;
};

// A slave segment ready to be cut, made once a step: its plane, its corner polygon
// there, that polygon's map from xi and its monomial form (for |a1 x a2|).
struct SlaveFacet {
  bool valid = false;  // false: seen edge-on from its own plane (degenerate)
  FacetPlane plane;
  Polygon polygon;  // its corners in the plane, counter-clockwise
  Bilinear map;     // xi -> the plane
  double area = 0.0;
  Vec2 lo, hi;                   // the polygon's box
  Surface<8> surface;            // quad4: the last 4 terms zero (the same values)
  std::array<Vec3, 4> corner{};  // its corners, m
};
SlaveFacet slave_facet(const Segment& slave);

// The master's corners projected onto the slave's plane, each that lies within
// shared_point_band of its distance from a slave corner (m) put on that corner: two faces
// that meet node to node cut each slave segment into its whole self on the master
// segment opposite and nothing on its neighbours, however the two faces tilt, so that
// the pieces, and their points, do not switch between shapes with the round-off of a
// step (segment.hpp, shared_point_band).
void snap_to_slave_corners(const SlaveFacet& slave, const std::array<Vec3, 8>& master,
                           std::array<Vec2, 4>& master_corners);

// A point of a piece: where it lies on the slave segment, its weight (m^2 of the slave
// surface) and where the projection along the slave facet's normal meets the master
// segment (a starting point for the local search).
struct MortarPoint {
  Xi slave_xi;
  Xi master_xi;
  double weight;
};

// The most points one slave segment can have on one master segment: a piece of at most
// 8 corners (8 triangles), 7 points a triangle.
inline constexpr int max_mortar_points_per_pair = 8 * 7;

// The points of the pieces of the slave segment on `master` into out[0 .. count), count
// returned (at most max_mortar_points_per_pair). A master that does not face the slave
// (n_slave . n_master >= 0 of their diagonals' normals), or whose surface lies further
// than `reach` (m) from the slave's along the slave normal at the piece's centre, gives
// none.
int mortar_points(const SlaveFacet& slave, const Segment& master, const PieceRule& rule, double reach,
                  MortarPoint* out);
inline int mortar_points(const Segment& slave, const Segment& master, const PieceRule& rule, double reach,
                         MortarPoint* out) {
  return mortar_points(slave_facet(slave), master, rule, reach, out);
}

}  // namespace exdyn::contact
