// Master contact segments: the bilinear quad4 and the quadratic serendipity
// quad8, their position y(xi), first derivatives a_a = dy/dxi_a, second
// derivatives y_,ab and outward normal, for any node coordinates.
//
// Nodes: corners counter-clockwise (-1,-1) (1,-1) (1,1) (-1,1), then mid-sides
// (0,-1) (1,0) (0,1) (-1,0). Seen from outside the body the corners run
// counter-clockwise, so n = a_1 x a_2 / |a_1 x a_2| points out of the body.
//
// A segment is converted once per projection to its monomial form
//   y(xi) = c0 + c1 xi1 + c2 xi2 + c3 xi1 xi2                        (quad4)
//         + c4 xi1^2 + c5 xi2^2 + c6 xi1^2 xi2 + c7 xi1 xi2^2        (quad8)
// which interpolates exactly as the shape functions do (same polynomial
// space) and makes every evaluation a handful of multiply-adds.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "contact/search_names.hpp"

namespace exdyn::contact {

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
constexpr double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }

// Where two faces meet node to node (every node of one exactly opposite a node of the
// other, as two equal meshes start), a point's projections onto the segments around the
// node opposite spread around it by |g| tan(alpha), |g| the distance between the two and
// alpha the tilt of each segment from the line joining them. Within this fraction of that
// distance a projection is taken to be at the corner or edge it is near (contact_choice.hpp),
// and a mortar master corner at the slave corner (mortar.hpp): while the faces turn by less
// than atan(0.1) = 5.7 degrees, a point that stays opposite a node never sits on the band's
// boundary, where the round-off of the two sides of a mirror would choose differently.
inline constexpr double shared_point_band = 0.1;

// Parametric coordinates (xi1, xi2) on [-1,1]^2.
using Xi = std::array<double, 2>;

// A master segment: its type and up to 8 nodes (quad4 uses the first 4).
struct Segment {
  SegmentType type = SegmentType::quad4;
  std::array<Vec3, 8> nodes{};
};

constexpr int node_count(SegmentType type) { return type == SegmentType::quad4 ? 4 : 8; }

// Parametric coordinates of node i (corners then mid-sides).
constexpr std::array<Xi, 8> node_xi{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}}};

// The position and its derivatives at one xi.
struct SurfacePoint {
  Vec3 y;              // position
  Vec3 a1, a2;         // dy/dxi1, dy/dxi2 (tangents)
  Vec3 y11, y12, y22;  // second derivatives d2y/dxi_a dxi_b
};

// Monomial form of a segment with Terms = 4 (quad4) or 8 (quad8) coefficients.
template <int Terms>
struct Surface {
  static_assert(Terms == 4 || Terms == 8);
  std::array<Vec3, Terms> c{};
};
using Quad4Surface = Surface<4>;
using Quad8Surface = Surface<8>;

// Monomial coefficients from the nodes (exact: same polynomial space).
template <int Terms>
constexpr Surface<Terms> make_surface(const Segment& s) {
  const auto& Y = s.nodes;
  Surface<Terms> out;
  auto& c = out.c;
  if constexpr (Terms == 4) {
    // N_i = (1 + xi1_i xi1)(1 + xi2_i xi2) / 4
    c[0] = 0.25 * (Y[0] + Y[1] + Y[2] + Y[3]);
    c[1] = 0.25 * ((Y[1] + Y[2]) - (Y[0] + Y[3]));
    c[2] = 0.25 * ((Y[2] + Y[3]) - (Y[0] + Y[1]));
    c[3] = 0.25 * ((Y[0] + Y[2]) - (Y[1] + Y[3]));
  } else {
    // Corner: N = (-1 + xi1^2 + xi2^2 + s1 s2 xi1 xi2 + s2 xi1^2 xi2 + s1 xi1 xi2^2) / 4,
    // mid-side (0, s2): N = (1 + s2 xi2 - xi1^2 - s2 xi1^2 xi2) / 2,
    // mid-side (s1, 0): N = (1 + s1 xi1 - xi2^2 - s1 xi1 xi2^2) / 2.
    const Vec3 corners = Y[0] + Y[1] + Y[2] + Y[3];
    c[0] = 0.5 * (Y[4] + Y[5] + Y[6] + Y[7]) - 0.25 * corners;
    c[1] = 0.5 * (Y[5] - Y[7]);
    c[2] = 0.5 * (Y[6] - Y[4]);
    c[3] = 0.25 * ((Y[0] + Y[2]) - (Y[1] + Y[3]));
    c[4] = 0.25 * corners - 0.5 * (Y[4] + Y[6]);
    c[5] = 0.25 * corners - 0.5 * (Y[5] + Y[7]);
    c[6] = 0.25 * ((Y[2] + Y[3]) - (Y[0] + Y[1])) - 0.5 * (Y[6] - Y[4]);
    c[7] = 0.25 * ((Y[1] + Y[2]) - (Y[0] + Y[3])) - 0.5 * (Y[5] - Y[7]);
  }
  return out;
}

// y(xi) only (the cheapest evaluation, for derivative-free methods).
template <int Terms>
inline Vec3 position(const Surface<Terms>& s, Xi xi) {
  const auto& c = s.c;
  const double u = xi[0], v = xi[1];
  Vec3 y = c[0] + u * (c[1] + v * c[3]) + v * c[2];
  if constexpr (Terms == 8) y = y + u * u * (c[4] + v * c[6]) + v * v * (c[5] + u * c[7]);
  return y;
}

// y, its first and its second derivatives at xi.
template <int Terms>
inline SurfacePoint evaluate(const Surface<Terms>& s, Xi xi) {
  const auto& c = s.c;
  const double u = xi[0], v = xi[1];
  SurfacePoint p;
  p.y = c[0] + u * (c[1] + v * c[3]) + v * c[2];
  p.a1 = c[1] + v * c[3];
  p.a2 = c[2] + u * c[3];
  p.y12 = c[3];
  if constexpr (Terms == 8) {
    p.y = p.y + u * u * (c[4] + v * c[6]) + v * v * (c[5] + u * c[7]);
    p.a1 = p.a1 + (2.0 * u) * (c[4] + v * c[6]) + (v * v) * c[7];
    p.a2 = p.a2 + (2.0 * v) * (c[5] + u * c[7]) + (u * u) * c[6];
    p.y11 = 2.0 * (c[4] + v * c[6]);
    p.y22 = 2.0 * (c[5] + u * c[7]);
    p.y12 = p.y12 + (2.0 * u) * c[6] + (2.0 * v) * c[7];
  }
  return p;
}

// The same from a Segment (converts to the monomial form each call: for
// tests and occasional use; kernels convert once per projection).
SurfacePoint evaluate(const Segment& segment, Xi xi);
Vec3 position(const Segment& segment, Xi xi);

// Outward unit normal a_1 x a_2 / |a_1 x a_2| at xi; the zero vector where the
// map is singular (a_1 x a_2 = 0, e.g. the corner of a quarter-point segment).
Vec3 outward_normal(const Segment& segment, Xi xi);
inline Vec3 outward_normal(const SurfacePoint& p) {
  const Vec3 n = cross(p.a1, p.a2);
  const double length = norm(n);
  return length > 0.0 ? (1.0 / length) * n : Vec3{};
}

// Reference shape functions N_i(xi) (the textbook form, used to check the
// monomial form). Entries beyond node_count(type) are zero.
std::array<double, 8> shape_functions(SegmentType type, Xi xi);

// The node ids of a segment of a contact face (global node numbers), in the order
// of Segment: corners, then for quad8 the mid-sides.
struct SegmentNodes {
  SegmentType type = SegmentType::quad4;
  std::array<std::uint32_t, 8> nodes{};
};

// An axis-aligned box that holds the whole segment: for quad4 the box of its nodes
// (a bilinear patch lies in the convex hull of its corners); for quad8 the box of
// the 9 control points of the same surface written as a biquadratic Bezier patch,
// which can reach beyond the nodes where the segment bulges. lo and hi, m.
struct SegmentBox {
  Vec3 lo, hi;
};
SegmentBox segment_box(const Segment& segment);

// Length of the diagonal of the nodes' bounding box: the segment's size, the
// scale of the relative tolerances of the local search.
double segment_size(const Segment& segment);

}  // namespace exdyn::contact
