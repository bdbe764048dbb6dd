// The faces that erosion can open (docs/contact.md, "Faces that erosion opens"): the
// faces two bricks of a part share. Each is kept twice, outward of either brick, and
// grouped by the brick's local face (brick_faces), so that each group is one oriented
// sheet per direction of a structured part (a box's local face 3 is its +x side).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/mesh.hpp"

namespace exdyn::mesh {

// Every face of part `part`'s bricks, keyed by its sorted corners, where = 6 e + local
// face (e: the global element), sorted by corners and then where: the faces two bricks
// share are neighbours in it.
std::vector<BrickFace> part_brick_faces(const Mesh& mesh, int part);

// The shared faces of part `part` by the local face of the brick they are outward of
// (0..5), each in element order: 4 or 8 nodes as the part's order; empty where the part
// is one brick thick that way. The normal length is the bricks' (brick_normal_length).
// The model keeps them for the parts that need them (PartRange::interior_faces).
std::vector<Face> interior_faces(const Mesh& mesh, int part);

// Whether segment corners `corners` (counter-clockwise, the first four of a segment's
// nodes) run the way brick face `where` of the mesh runs, i.e. the segment is outward
// of that brick.
bool outward_of(const Mesh& mesh, std::uint64_t where, const std::uint32_t* corners);

}  // namespace exdyn::mesh
