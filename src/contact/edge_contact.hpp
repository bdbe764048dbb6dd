// Contact at the folds of a master surface. Where the surface folds convexly towards
// the slave side (two segments meeting at an angle, a segment at a symmetry plane whose
// mirror image tilts the other way), a slave point can lie behind the surface while its
// closest point on every segment's plane falls outside that segment: the "dead zone" of
// node-to-segment contact. Such a point takes the closest point of the closed segment,
// on the edge (or at the corner) that it leaves across, provided the surface goes on
// past that edge (shared with another master segment, or on a symmetry plane, where the
// mirror image goes on) and it is the closest boundary point of all the point's
// candidate segments. An edge that ends the surface never captures: a slave point beside
// a surface is not in contact with it.
//
// The direction of the contact is the mean of the outward normals of the segments
// that meet at that point, the mirror images included (a normal's component across a
// symmetry plane cancels with its image's): n = sum n_s / |sum n_s|, gap = (ys - y).n.
// It is the same whichever segment a tie goes to, and well conditioned however small
// the gap, so a symmetric scene stays symmetric.
#pragma once

#include <array>
#include <cstdint>

#include "contact/local_search.hpp"
#include "contact/segment.hpp"

namespace exdyn::contact {

// Edge bits of a segment: the edge xi1 = -1, xi1 = +1, xi2 = -1, xi2 = +1.
inline constexpr std::uint8_t edge_xi1_minus = 1, edge_xi1_plus = 2, edge_xi2_minus = 4, edge_xi2_plus = 8;

// What the surface does past each edge of a master segment (the order of the bits).
struct SegmentEdges {
  std::uint8_t continued = 0;                              // the surface goes on past the edge
  std::array<std::int8_t, 4> mirror_axis{-1, -1, -1, -1};  // on a symmetry plane x_a = const: a; else -1
};

// The corner nodes (indices into the segment's nodes, corners counter-clockwise
// from (-1,-1)) of edge e = 0..3 in the order of the bits above.
inline constexpr std::uint8_t edge_corners[4][2] = {{0, 3}, {1, 2}, {0, 1}, {3, 2}};

struct EdgeContact {
  bool found = false;
  bool continued = false;  // every edge left across goes on past the segment
  Xi xi{};                 // on the boundary of [-1,1]^2
  Vec3 y{};                // the point y(xi), m
  double distance = 0.0;   // |ys - y|, m
  Vec3 normal{};           // outward unit normal at xi, its components across the symmetry
                           // planes of the edges left across removed (renormalised)
};

// The closest point of the closed segment to `point` on the edges that a projection
// `result` left across (xi_a < -1 or > 1, or on the boundary for the robust method's
// constrained point); `edges.continued` says whether the surface goes on past every such
// edge. Along one edge a 1-D Newton on f(t) = |ys - y(t)|^2 / 2 kept in [-1, 1] (exact in
// one step on a straight quad4 edge); across two, the corner.
EdgeContact edge_contact(const Segment& segment, const Vec3& point, const ProjectionResult& result,
                         const SegmentEdges& edges);

}  // namespace exdyn::contact
