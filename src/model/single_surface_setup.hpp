// The pass of a single surface (contact `surface`, docs/contact.md "Single-surface
// contact") from its faces: each face's slave points with the stiffness a pair on that
// face would give them, merged into one pass whose master segments are the whole
// surface's.
#pragma once

#include <functional>
#include <vector>

#include "input/options.hpp"
#include "model/contact_geometry.hpp"
#include "model/model.hpp"

namespace exdyn::solver {

// The surface's options with `slave_points: auto` resolved over all its faces (quadrature
// if any face has 8-node segments), so that every face has the same kind of points; for
// `surface: all`, with the faces erosion can open (opened_faces.hpp) after the deck's.
input::ContactOptions resolved_surface_options(const Model& model, const input::ContactOptions& options);

// The segments of a single surface: all but those on a plane held normal to itself (every
// node fixed in one component and at one coordinate in it: a symmetry plane or a
// support), which nothing can reach from outside.
mesh::KeepSegment off_held_planes(const Model& model);

// The segment across each edge of each segment (ContactSurfaces::edge_neighbours): -1
// none, -2 more than one, counting only the segments `live` marks (empty: all).
std::vector<std::array<std::int32_t, 4>> edge_neighbours(const std::vector<contact::SegmentNodes>& segments,
                                                         const std::vector<std::uint8_t>& live = {});

// One pass geometry per face of the surface (its segments off held planes): the face's
// slave points against the whole surface's segments (so that the modulus, the smallest
// length and the master side of the stiffness caps are the surface's). set_stiffness
// sets each one's stiffness as it is made; then every face after the first lets its
// master side go (the first's is the surface's), so that a surface of many faces holds
// its segments once.
std::vector<PassGeometry> surface_face_geometries(const input::Deck& deck, const Model& model,
                                                  const input::ContactOptions& options,
                                                  const std::function<void(PassGeometry&)>& set_stiffness);

// The one pass of the surface from its faces' (with their stiffness): the points in
// face order (nodes: sorted, each with the stiffness of every face it lies on), the
// segments, edges and moving nodes of the whole surface, and the rules' data
// (ContactSurfaces: node corners, sides, first part).
PassGeometry merge_surface_faces(const Model& model, const input::ContactOptions& options,
                                 std::vector<PassGeometry>& faces);

}  // namespace exdyn::solver
