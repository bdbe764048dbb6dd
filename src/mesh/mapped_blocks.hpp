// The block layouts of the mapped meshes (docs/input.md, "cylinder" and "sphere"): a
// cylinder is a square core and four quarters around it, a ball a cube and six faces
// around it, each block a structured lattice with a map to space. add_mapped_part
// (mapped.cpp) meshes them into a part; MappedLattice (mapped_lattice.cpp) numbers the
// same lattice without storing it. Both take from here the layouts, the node mirror of
// left-handed blocks, the local-to-global map and the naming of the boundary.
#pragma once

#include <array>
#include <functional>
#include <utility>
#include <vector>

#include "input/options.hpp"
#include "mesh/mesh.hpp"

namespace exdyn::mesh::mapped {

using Point = std::array<double, 3>;

// A structured block of the layout: n elements along its three lattice directions,
// and the map from lattice coordinates (element units; halves for mid-edge points) to
// a point, m. Blocks meet along whole faces; their shared points are merged.
struct Block {
  std::array<int, 3> n{};
  std::function<Point(double, double, double)> at;
};

// Cylinder layout in local coordinates (p, q) of the cross-section and s along the
// axis; Point = {p, q, s}.
std::vector<Block> cylinder_blocks(const input::PartOptions& o);

// Ball layout in coordinates relative to the centre.
std::vector<Block> sphere_blocks(const input::PartOptions& o);

// The local node that mirrors each node of a brick across xi = 0 (offsets (2 - d0, d1, d2)):
// applied to an element whose block map is left-handed, it makes the element right-handed.
std::array<int, 20> mirror_xi();

// Local to global coordinates, m: a cylinder's (p, q, s) go to the axes after its
// axis, cyclically, a ball's are x, y, z; both about the centre.
Point to_global(const input::PartOptions& options, const Point& local);

// A boundary segment of a mapped part, its corners' coordinates (m) and the length of
// its element normal to it (m).
struct OuterSegment {
  FaceSegment segment;
  std::array<Point, 4> corners{};
  double normal_length = 0.0;
};

// The named faces of a mapped part from its boundary segments (in order of element and
// local face), each named by where it lies: on a cut plane (every corner exactly on
// it), on a cylinder's end planes, or else on the curved surface.
std::vector<std::pair<input::PartFace, Face>> named_faces(const input::PartOptions& options, int part_index,
                                                          const std::vector<OuterSegment>& boundary);

}  // namespace exdyn::mesh::mapped
