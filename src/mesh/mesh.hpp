// Structured hexahedral meshes of box parts, mapped meshes of cylinders and balls
// (mesh/mapped.hpp), and their named faces. Each part is its own body: parts share no
// nodes.
//
// A part is a lattice of grid points: (order n_x + 1) x (order n_y + 1) x (order n_z + 1)
// with order 1 for the 8-node formulations and 2 for the 20-node ones. With order 1
// every lattice point is a node; with order 2 the points with at most one odd index
// are (the corners and mid-edge points of the serendipity bricks: no face or body
// centres). Nodes are numbered along the lattice, x fastest, then y, then z, from the
// part's first_node; element (i,j,k) is first_element + i + nx (j + ny k).
// Elements use the VTK hexahedron (8) or quadratic hexahedron (20) node order.
// A part with a perturbation (parts[i].perturbation) has its corner grid points moved
// at random inside the box, each by at most fraction h, faces kept plane (mesh.cpp
// states the rule), and its mid-edge nodes at the middle of their edges.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "common/nodal_vectors.hpp"
#include "input/gmsh_file.hpp"
#include "input/options.hpp"

namespace exdyn::mesh {

inline constexpr std::uint32_t no_node = 0xffffffffu;

// A face segment: 4 corner nodes counter-clockwise seen from outside the body, so
// (y1 - y0) x (y3 - y0) points out of it; for 8 nodes then the mid-sides of the edges
// 0-1, 1-2, 2-3, 3-0 (the order of contact::Segment and `exdyn project`).
struct FaceSegment {
  std::array<std::uint32_t, 8> nodes{};
  int node_count = 4;  // 4 or 8
};

// The sides of a face that folds (mesh/face_sides.hpp): the pieces between its
// feature edges. Per segment of the whole face: its side and its index among that
// side's segments; per side: its segment count and the mean length (m) of the elements
// under it normal to it. Empty where the face is one side.
struct FaceSides {
  std::vector<std::uint32_t> side, index;
  std::vector<std::uint64_t> count;
  std::vector<double> normal_length;

  std::size_t size() const { return count.empty() ? 1 : count.size(); }
};

// A named face of a part: its nodes (a box: sorted along the face's lattice; a mapped
// part: ascending) and its segments, and the mean length (m) of the elements under it
// normal to it (for the automatic penalty stiffness); where it folds, its sides.
struct Face {
  std::vector<std::uint32_t> nodes;
  std::vector<FaceSegment> segments;
  double normal_length = 0.0;
  FaceSides sides;  // of the whole face, also when it is cut
  // A face cut to some of its segments (cut_face; a rank's contact faces,
  // ranks/rank_setup.cpp): each kept segment's index in the whole face, and the whole
  // face's segment count. Both empty for a whole face.
  std::vector<std::uint32_t> segment_index;
  std::size_t whole_segments = 0;

  bool cut() const { return whole_segments > 0; }
  // Segment k's index in the whole face, and the whole face's segment count.
  std::uint32_t index_in_whole(std::size_t k) const {
    return cut() ? segment_index[k] : static_cast<std::uint32_t>(k);
  }
  std::size_t whole_count() const { return cut() ? whole_segments : segments.size(); }
};

// Which segments of a face to keep (cut_face, lattice_face).
using KeepSegment = std::function<bool(const FaceSegment&)>;

struct PartRange {
  std::uint32_t first_node = 0;
  std::uint32_t node_count = 0;
  std::uint32_t first_element = 0;
  std::uint32_t element_count = 0;
  std::array<int, 3> elements{};       // nx, ny, nz
  int order = 1;                       // 1: 8-node elements, 2: 20-node elements
  int nodes_per_element = 8;           // 8 or 20
  std::size_t first_connectivity = 0;  // offset of the part's first element in Mesh::connectivity
  std::vector<std::uint32_t> lattice;  // node id of each lattice point (no_node: none), x fastest
  std::array<int, 3> lattice_size{};   // order n + 1 along each axis
  // A box: the element length (m) normal to each side, xmin, xmax, ... zmax.
  std::array<double, 6> normal_lengths{};
  // A mapped or imported part has no lattice: its named faces are built with it; an
  // imported part's physical surfaces, one per name of its MeshFileOptions::surfaces
  // (empty where the surface does not bound the part's volume).
  std::vector<std::pair<input::PartFace, Face>> faces;
  std::vector<Face> physical_faces;
  // The faces its bricks share, by local face (mesh/interior_faces.hpp): kept by the
  // model for a part whose faces erosion can open into a contact; else empty.
  std::vector<Face> interior_faces;

  // Node id at lattice point (I, J, K); no_node where the lattice has no node.
  std::uint32_t node_at(int i, int j, int k) const {
    return lattice[static_cast<std::size_t>(i) +
                   static_cast<std::size_t>(lattice_size[0]) *
                       (static_cast<std::size_t>(j) + static_cast<std::size_t>(lattice_size[1]) * k)];
  }
};

struct Mesh {
  NodalVectors x_ref;                       // reference coordinates, m
  std::vector<std::uint32_t> connectivity;  // nodes_per_element ids per element, part after part
  std::vector<std::int32_t> element_part;   // part index of each element
  std::vector<PartRange> parts;             // in deck order

  std::size_t node_count() const { return x_ref.size(); }
  std::size_t element_count() const { return element_part.size(); }
  // The nodes of element e (global index) and how many there are.
  int nodes_of(std::size_t e) const {
    return parts[static_cast<std::size_t>(element_part[e])].nodes_per_element;
  }
  const std::uint32_t* element_nodes(std::size_t e) const {
    const PartRange& part = parts[static_cast<std::size_t>(element_part[e])];
    return connectivity.data() + part.first_connectivity +
           static_cast<std::size_t>(part.nodes_per_element) * (e - part.first_element);
  }
  // True when every part has elements of `nodes` nodes.
  bool all_elements_have(int nodes) const {
    for (const PartRange& part : parts)
      if (part.nodes_per_element != nodes) return false;
    return true;
  }
};

// Builds every part of the deck (checks the node count fits 32-bit indices, and that
// a perturbed part has no element with a non-positive corner Jacobian).
Mesh build_mesh(const input::Deck& deck);

// Part p of the deck alone, as build_mesh makes it (the same nodes in the same order
// with the same bits, numbered from 0; its faces; the same checks of a perturbed or
// imported part, an error naming element first_element + e for its element e): for a
// rank that builds only its own elements of a part it cannot make piece by piece
// (ranks/rank_setup.hpp). An imported part's file comes from `read` (input::read_gmsh's
// arguments and result: on many ranks, read once and sent to every rank).
using GmshReader = std::function<input::GmshMesh(const std::string& file, const SourceLocation& where,
                                                 const std::string& key_path)>;
Mesh build_part_mesh(const input::Deck& deck, std::size_t p, std::uint32_t first_element,
                     const GmshReader& read = input::read_gmsh);

// Every physical surface the deck names bounds its part's volume (part_of(p): part p's
// range), else an InputError naming the deck key; build_mesh checks it.
void check_physical_faces(const input::Deck& deck,
                          const std::function<const PartRange&(std::size_t)>& part_of);

// The nodes and outward-oriented segments of one named face.
Face face_of(const Mesh& mesh, const input::FaceRef& face);
inline Face face_of(const Mesh& mesh, int part, input::PartFace side) {
  return face_of(mesh, input::FaceRef{part, side});
}

// The six faces of a VTK brick, outward: corners (counter-clockwise seen from
// outside), then the mid-edge nodes of the edges 0-1, 1-2, 2-3, 3-0 of the face.
inline constexpr int brick_faces[6][8] = {{0, 3, 2, 1, 11, 10, 9, 8},   {4, 5, 6, 7, 12, 13, 14, 15},
                                          {0, 1, 5, 4, 8, 17, 12, 16},  {1, 2, 6, 5, 9, 18, 13, 17},
                                          {2, 3, 7, 6, 10, 19, 14, 18}, {3, 0, 4, 7, 11, 16, 15, 19}};

// A face of a brick that no other brick of its part shares.
struct BoundarySegment {
  FaceSegment segment;                   // outward, 4 or 8 nodes
  std::array<std::uint32_t, 4> corners;  // the corner node ids, ascending (a key to match faces by)
  double normal_length = 0.0;            // centroid of this face to the opposite face's, m
};

// A brick face by its sorted corner nodes (a key to match faces by) and where it is:
// 6 element + local face.
struct BrickFace {
  std::array<std::uint32_t, 4> corners;
  std::uint64_t where;
};
// The `where` of the faces no other face of the list matches, ascending. A face matched
// by more than one other is no manifold's: its corners go to `non_manifold` (left
// empty when none is).
std::vector<std::uint64_t> unshared_faces(std::vector<BrickFace> faces,
                                          std::array<std::uint32_t, 4>* non_manifold = nullptr);

// The boundary faces of bricks of `nodes_per_element` (8 or 20) nodes each, in order of
// element and then local face. A face shared by more than two bricks is no manifold's:
// its sorted corners are returned in `non_manifold` (left empty when none is).
std::vector<BoundarySegment> boundary_segments(const std::vector<std::array<std::uint32_t, 20>>& elements,
                                               int nodes_per_element, const NodalVectors& x,
                                               std::array<std::uint32_t, 4>* non_manifold = nullptr);

// The length of a brick normal to its local face `face` (brick_faces), m: from the
// face's centroid to the opposite face's, corner k at corners[k].
double brick_normal_length(int face, const std::array<std::array<double, 3>, 8>& corners);

// The face named `side` among a mapped or imported part's faces (PartRange::faces);
// a logic_error naming part_index where it has none.
Face named_face(const std::vector<std::pair<input::PartFace, Face>>& faces, int part_index,
                input::PartFace side);

// A face's nodes (every node of its segments, ascending, once) and its mean normal
// length, from its segments and the sum of their normal lengths.
void finish_face(Face& face, double normal_length_sum);
// The first half of it: face.nodes from its segments.
void nodes_of_segments(Face& face);

// The segments of `whole` that `keep` keeps, in its order, with their places in it
// (Face::segment_index), its normal length and sides and the nodes of the kept segments.
Face cut_face(const Face& whole, const KeepSegment& keep);

// Lattice offsets (along x, y, z, in units of half an element) of the nodes of a brick
// from its lowest corner, in VTK order: the 8 corners, then for 20 nodes the mid-edge
// points of the bottom, the top and the vertical edges.
inline constexpr std::array<std::array<int, 3>, 20> brick_offsets{
    {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {2, 2, 2},
     {0, 2, 2}, {1, 0, 0}, {2, 1, 0}, {1, 2, 0}, {0, 1, 0}, {1, 0, 2}, {2, 1, 2},
     {1, 2, 2}, {0, 1, 2}, {0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}}};

// The box part's pieces as functions of the lattice, for a rank that builds only its
// own elements (ranks/rank_setup.hpp) and must get the bits build_mesh gives:
// the corner grid point (i, j, k) of part `part_index` (m, with its perturbation),
// and the element lengths normal to its sides xmin, xmax, ..., zmax (m).
std::array<double, 3> box_point(const input::PartOptions& options, int part_index,
                                const std::array<int, 3>& ijk);
std::array<double, 6> box_normal_lengths(const input::PartOptions& options);
// Element ijk of perturbed box part `part_index` (element `element` of the whole mesh),
// its corner grid points corners[a + 2 b + 4 c] at (i + a, j + b, k + c): an InputError
// naming it and the deck key where a corner Jacobian is not positive (build_mesh's
// check of a perturbed part, element by element in (k, j, i) order).
void check_perturbed_element(const std::array<std::array<double, 3>, 8>& corners, const input::Deck& deck,
                             std::size_t part_index, const std::array<int, 3>& ijk, std::uint32_t element);
// A side of a box part of n elements of this order (1 or 2), with node_at(i, j, k) the
// node at lattice point (i, j, k) (no_node where none is): face_of's box faces. With
// `keep`, the face cut to the segments it keeps (cut_face's), made one segment at a time.
Face lattice_face(const std::array<int, 3>& n, int order, input::PartFace side,
                  const std::array<double, 6>& normal_lengths,
                  const std::function<std::uint32_t(int, int, int)>& node_at, const KeepSegment& keep = {});

// Grid fraction tau_i in [0, 1] of grid point i of n elements whose lengths change
// geometrically from the first to the last by the ratio `grading` (last / first):
// lengths r^k, r = grading^(1 / (n - 1)), so tau_i = (r^i - 1) / (r^n - 1).
double graded_fraction(int i, int n, double grading);

}  // namespace exdyn::mesh
