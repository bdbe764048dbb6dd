// The sides of a face: the pieces between its feature edges. A Gmsh part's boundary is
// one face (`<part>.surface`), and a physical surface may wrap a corner too; a single
// surface takes each side as a face of its own, as it takes each side of a box: a node
// on two sides has a stiffness on each, from that side's own segments, and a point's
// penalty comes from its side's element length, not from the whole boundary's mean
// (docs/contact.md, "Single surface").
#pragma once

#include <cstddef>
#include <vector>

#include "common/nodal_vectors.hpp"
#include "mesh/mesh.hpp"

namespace exdyn::mesh {

// Two segments that share an edge lie on one side unless their normals (at the
// centres, from the corners) are more than this far apart, rad: 60 degrees. A right
// angle is a fold; a curved face meshed with at least 3 segments per right angle
// (30 degrees each) is not.
inline constexpr double feature_angle = 1.0471975511965976;

// The sides of a face of `segments` (a whole face, outward) on coordinates x, each
// segment's normal length given: the segments connected across edges that are no fold,
// each side numbered by its first segment in face order. Empty where the face is one
// side.
FaceSides fold_sides(const std::vector<FaceSegment>& segments, const std::vector<double>& normal_length,
                     const NodalVectors& x);

// Side k of `face` (whole or cut; face.sides of the whole face) as a face cut to it:
// its segments in face order, each with its index among the whole side's segments, the
// whole side's segment count and mean normal length, and its nodes. A face of one side
// is itself.
Face side_of(const Face& face, std::size_t k);

}  // namespace exdyn::mesh
