// Single-surface contact (docs/contact.md, "Single-surface contact"): one surface is
// both the slave side and the master side, so that a body can touch itself (a fold)
// and bodies touch each other without pairs being named. Two rules keep a surface
// from touching itself where it merely goes on:
//   exclusion: a slave point is never checked against a segment that shares a node with
//     it (a node: the segments at that node; a Gauss point: the segments that share a
//     node with its own segment). Those are the point's own element faces and their
//     neighbours at its nodes: they meet the point at distance zero by construction.
//   facing: a candidate counts only where the point's outward normal n_p and the
//     segment's n_m at the projection face each other, n_p . n_m < -facing_cosine, and
//     the point lies less than the search distance behind it. Two sides of one wall, a
//     face beside its neighbour across an edge, a top face beside a side face: none of
//     these face each other, so none is taken for a contact; two walls that fold onto
//     each other do (their outward normals turn to opposite directions as they close).
// A slave node's normal is the angle-weighted pseudo-normal of its segments
// (Baerentzen and Aanaes 2005): at a brick's edge (1, 0, 1)/sqrt 2 whatever the segments'
// sizes, at its corner (1, 1, 1)/sqrt 3. A Gauss point's is its segment's normal there.
#pragma once

#include <cstddef>
#include <cstdint>

#include "common/nodal_vectors.hpp"
#include "contact/contact_pass.hpp"

namespace exdyn::contact {

// The normals of a point and a segment that touch within 60 degrees of head on.
inline constexpr double facing_cosine = 0.5;

// The global search drops the segments that face the point's way, n_p . n_m >= 0.7 at
// the segment's centre (within 46 degrees of parallel; a face's own segments): before
// the next search each node moves less than margin / 2 = h / 4, so a segment turns by
// less than atan(1/2) = 27 degrees and the point's normal as much, 54 degrees together,
// and the normal across a curved segment differs from its centre's by its curvature
// (a few degrees): short of the 74 degrees from 46 to facing (120).
inline constexpr double same_way_cosine = 0.7;

// Whether `point` lies behind `segment` by more than `depth` (m) along the segment's
// centre normal n, the whole segment in front of it: x_p . n < min_i x_i . n - depth
// over its nodes, less for an 8-node segment the spread max - min of x_i . n (its
// corner shape functions go down to -1/4 each, and the surface can bulge beyond its
// nodes' hull by that much). The distance from the point to the segment is then more
// than depth (a projection onto n is 1-Lipschitz), and behind it: the global search
// drops such a pair with depth = search distance + margin, since before the next
// search the two move closer by less than the margin, and the point stays more than
// the search distance behind, where the facing rule never admits it. This is the
// other side of every wall: a thin wall's inner nodes behind its outer segments.
bool behind_beyond(const Segment& segment, Vec3 point, double depth);

// Whether slave point p of a single surface shares a node with master segment s.
bool shares_node(const ContactSurfaces& surfaces, std::size_t p, std::uint32_t segment);

// Mortar's global search on a single surface: whether a slave segment and a master segment
// are no pair, because they share a node or face the same way (their normals at the
// centres, n_s . n_m >= same_way_cosine).
bool segments_excluded(const SegmentNodes& slave, const SegmentNodes& master, const NodalVectors& x_ref,
                       const NodalVectors& u);

// The outward unit normal of slave point p at the current configuration (zero where
// its segments cancel, a sheet folded flat).
Vec3 point_normal(const ContactSurfaces& surfaces, std::size_t p, const NodalVectors& x_ref,
                  const NodalVectors& u);

// A slave node's stiffness for a contact along `normal` (N/m): that of the face the
// node lies on (its side) whose normal at the node faces `normal` most, so that an edge
// node pressed on one face takes that face's tributary area and length, as a pair on
// that face would.
double side_stiffness(const ContactSurfaces& surfaces, std::size_t p, Vec3 normal, const NodalVectors& x_ref,
                      const NodalVectors& u);

}  // namespace exdyn::contact
