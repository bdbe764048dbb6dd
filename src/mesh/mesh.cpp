#include "mesh/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include "common/errors.hpp"
#include "mesh/face_sides.hpp"
#include "mesh/imported.hpp"
#include "mesh/mapped.hpp"

namespace exdyn::mesh {

namespace {

// splitmix64 (Steele, Lea, Flood 2014): a bijective 64-bit mix, used as a
// counter-based generator so a node's perturbation depends on its key alone.
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// The random direction r of grid point ijk, |r| <= 1, uniform in the unit ball of
// the components that move (moves[c]): drawn by rejection from the cube [-1, 1)^d,
// each draw a function of (seed, part, attempt, component) and of the node's
// indices along the axes with more than one element only, so that a part one
// element thick (plane strain) gets the same r on both of its layers.
std::array<double, 3> perturbation_direction(const input::PartOptions& options, int part_index,
                                             const std::array<int, 3>& ijk,
                                             const std::array<bool, 3>& moves) {
  std::uint64_t node_key = splitmix64(options.perturbation_seed);
  node_key = splitmix64(node_key ^ static_cast<std::uint64_t>(part_index));
  for (int axis = 0; axis < 3; ++axis)
    if (options.elements[axis] > 1) node_key = splitmix64(node_key ^ static_cast<std::uint64_t>(ijk[axis]));
  for (std::uint64_t attempt = 0;; ++attempt) {  // accepts with probability pi/4 (2 moving axes) or pi/6 (3)
    std::array<double, 3> r{};
    double length_squared = 0.0;
    for (int c = 0; c < 3; ++c) {
      if (!moves[c]) continue;
      const std::uint64_t key =
          splitmix64(splitmix64(node_key ^ attempt) ^ static_cast<std::uint64_t>(c + 1));
      r[c] = 2.0 * (static_cast<double>(key >> 11) * 0x1.0p-53) - 1.0;  // 53 random bits, in [-1, 1)
      length_squared += r[c] * r[c];
    }
    if (length_squared <= 1.0) return r;
  }
}

// Node id of corner grid point (i, j, k) of a part (lattice point order (i, j, k)).
std::uint32_t node_id(const PartRange& part, int i, int j, int k) {
  return part.node_at(part.order * i, part.order * j, part.order * k);
}

// Every element of a perturbed part checked (check_perturbed_element); `part` is part
// `part_index` of the deck, its first element in the whole mesh `first_element` (the
// error names it).
void check_perturbed_part(const PartRange& part, const NodalVectors& x, const input::Deck& deck,
                          std::size_t part_index, std::uint32_t first_element) {
  const auto& n = part.elements;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        std::array<std::array<double, 3>, 8> corners{};
        for (int corner = 0; corner < 8; ++corner)
          corners[std::size_t(corner)] =
              x.at(node_id(part, i + (corner & 1), j + ((corner >> 1) & 1), k + ((corner >> 2) & 1)));
        check_perturbed_element(corners, deck, part_index, {i, j, k},
                                first_element + static_cast<std::uint32_t>(i + n[0] * (j + n[1] * k)));
      }
}

// Nodes of a part of this order with these element counts.
std::uint64_t part_node_count(const std::array<int, 3>& n, int order) {
  const std::uint64_t nx = std::uint64_t(n[0]), ny = std::uint64_t(n[1]), nz = std::uint64_t(n[2]);
  const std::uint64_t corners = (nx + 1) * (ny + 1) * (nz + 1);
  if (order == 1) return corners;
  return corners + nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
}

void add_part(Mesh& mesh, const input::PartOptions& options, int part_index) {
  PartRange part;
  part.elements = options.elements;
  part.order = input::is_quadratic(options.formulation) ? 2 : 1;
  part.nodes_per_element = part.order == 2 ? 20 : 8;
  const auto& n = options.elements;
  const int order = part.order;
  part.first_node = static_cast<std::uint32_t>(mesh.node_count());
  part.node_count = static_cast<std::uint32_t>(part_node_count(n, order));
  part.first_element = static_cast<std::uint32_t>(mesh.element_count());
  part.element_count = static_cast<std::uint32_t>(n[0] * n[1] * n[2]);
  part.first_connectivity = mesh.connectivity.size();
  for (int axis = 0; axis < 3; ++axis) part.lattice_size[axis] = order * n[axis] + 1;
  part.normal_lengths = box_normal_lengths(options);
  const auto& size = part.lattice_size;
  part.lattice.assign(std::size_t(size[0]) * std::size_t(size[1]) * std::size_t(size[2]), no_node);
  auto corner_point = [&](const std::array<int, 3>& ijk) { return box_point(options, part_index, ijk); };
  std::uint32_t next = part.first_node;  // ids stay below no_node: at most 2^32 - 1 nodes in all
  for (int k = 0; k < size[2]; ++k)
    for (int j = 0; j < size[1]; ++j)
      for (int i = 0; i < size[0]; ++i) {
        const std::array<int, 3> lattice{i, j, k};
        int odd = 0;
        for (int c = 0; c < 3; ++c) odd += lattice[c] % order;
        if (odd > 1) continue;  // a face or body centre: no node of a serendipity brick
        std::array<double, 3> x{};
        if (odd == 0) {
          x = corner_point({i / order, j / order, k / order});
        } else {  // a mid-edge point: the middle of the (straight) edge between its corners
          std::array<int, 3> below{i / order, j / order, k / order}, above = below;
          for (int c = 0; c < 3; ++c)
            if (lattice[c] % order != 0) above[c] += 1;
          const std::array<double, 3> a = corner_point(below), b = corner_point(above);
          for (int c = 0; c < 3; ++c) x[c] = 0.5 * (a[c] + b[c]);
        }
        part.lattice[std::size_t(i) + std::size_t(size[0]) * (std::size_t(j) + std::size_t(size[1]) * k)] =
            next++;
        mesh.x_ref.x.push_back(x[0]);
        mesh.x_ref.y.push_back(x[1]);
        mesh.x_ref.z.push_back(x[2]);
      }
  EXDYN_ASSERT(next == part.first_node + part.node_count);
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        for (int local = 0; local < part.nodes_per_element; ++local) {
          // Offsets are in half elements: order 1 takes the corners at 0 and 2 as 0 and 1.
          const auto& d = brick_offsets[static_cast<std::size_t>(local)];
          const int scale = order;  // lattice points per element
          const std::uint32_t node = part.node_at(scale * i + d[0] * scale / 2, scale * j + d[1] * scale / 2,
                                                  scale * k + d[2] * scale / 2);
          EXDYN_ASSERT(node != no_node);
          mesh.connectivity.push_back(node);
        }
        mesh.element_part.push_back(part_index);
      }
  mesh.parts.push_back(std::move(part));
}

}  // namespace

// A perturbed part must keep every element valid: at each corner of each element,
// det[e_x, e_y, e_z] > 0 with e the grid edges from the corner towards +x, +y, +z
// (the trilinear map's Jacobian there, times 8; m^3). Moves of at most fraction h
// keep a plane grid valid below fraction 1/(2 sqrt 2) = 0.354, but a 3D grid is
// certain only below 1/(2 sqrt 3) = 0.289 (sigma_min(I + E) >= 1 - ||E||_F), so every
// perturbed part is checked, where the error can name the deck key. (The mid-edge
// nodes of a 20-node part sit at the middle of straight edges, so the corner test
// covers them.)
void check_perturbed_element(const std::array<std::array<double, 3>, 8>& corners, const input::Deck& deck,
                             std::size_t part_index, const std::array<int, 3>& ijk, std::uint32_t element) {
  auto edge = [&](int from, int to) -> std::array<double, 3> {
    const auto& a = corners[std::size_t(from)];
    const auto& b = corners[std::size_t(to)];
    return {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  };
  for (int corner = 0; corner < 8; ++corner) {
    const int low = corner & ~1, front = corner & ~2, bottom = corner & ~4;  // the edges' lower ends
    const auto ex = edge(low, low | 1);
    const auto ey = edge(front, front | 2);
    const auto ez = edge(bottom, bottom | 4);
    const double det = ex[0] * (ey[1] * ez[2] - ey[2] * ez[1]) - ex[1] * (ey[0] * ez[2] - ey[2] * ez[0]) +
                       ex[2] * (ey[0] * ez[1] - ey[1] * ez[0]);
    if (det > 0.0) continue;
    throw InputError(SourceLocation{deck.source_file, 0, 0},
                     "parts[" + std::to_string(part_index) + "].perturbation",
                     "the distortion inverts element " + std::to_string(element) + " (grid cell " +
                         std::to_string(ijk[0]) + ", " + std::to_string(ijk[1]) + ", " +
                         std::to_string(ijk[2]) + " of part '" + deck.parts[part_index].name +
                         "'): its corner Jacobian is not positive; use a smaller fraction or another seed");
  }
}

void check_physical_faces(const input::Deck& deck,
                          const std::function<const PartRange&(std::size_t)>& part_of) {
  auto check = [&](const std::vector<input::FaceRef>& faces, const std::string& path) {
    for (std::size_t i = 0; i < faces.size(); ++i) {
      const input::FaceRef& f = faces[i];
      if (f.side != input::PartFace::physical) continue;
      const PartRange& part = part_of(static_cast<std::size_t>(f.part));
      if (part.physical_faces[static_cast<std::size_t>(f.surface)].whole_count() > 0) continue;
      const input::PartOptions& options = deck.parts[static_cast<std::size_t>(f.part)];
      throw InputError(SourceLocation{deck.source_file, 0, 0}, path + "[" + std::to_string(i) + "]",
                       "the face '" + input::face_name(deck, f) + "': the physical surface '" +
                           options.mesh.surfaces[static_cast<std::size_t>(f.surface)] + "' of '" +
                           options.mesh.path + "' has no quadrilateral on the boundary of the volume '" +
                           options.mesh.volume + "'");
    }
  };
  for (std::size_t b = 0; b < deck.boundary_conditions.size(); ++b)
    check(deck.boundary_conditions[b].faces, "boundary_conditions[" + std::to_string(b) + "].faces");
  for (std::size_t c = 0; c < deck.contact.size(); ++c) {
    check(deck.contact[c].slave, "contact[" + std::to_string(c) + "].slave");
    check(deck.contact[c].master, "contact[" + std::to_string(c) + "].master");
  }
  for (std::size_t w = 0; w < deck.rigid_walls.size(); ++w)
    check(deck.rigid_walls[w].slave, "rigid_walls[" + std::to_string(w) + "].slave");
}

double graded_fraction(int i, int n, double grading) {
  if (i <= 0) return 0.0;
  if (i >= n) return 1.0;
  if (grading == 1.0 || n == 1) return static_cast<double>(i) / static_cast<double>(n);
  const double r = std::pow(grading, 1.0 / static_cast<double>(n - 1));
  return (std::pow(r, i) - 1.0) / (std::pow(r, n) - 1.0);
}

std::array<double, 6> box_normal_lengths(const input::PartOptions& options) {
  std::array<double, 6> lengths{};
  const auto& n = options.elements;
  for (int axis = 0; axis < 3; ++axis) {
    const double length = options.box_max[axis] - options.box_min[axis];
    const double grading = options.grading[axis];
    lengths[std::size_t(2 * axis)] =
        grading == 1.0 ? length / n[axis] : length * graded_fraction(1, n[axis], grading);
    lengths[std::size_t(2 * axis + 1)] =
        grading == 1.0 ? length / n[axis] : length * (1.0 - graded_fraction(n[axis] - 1, n[axis], grading));
  }
  return lengths;
}

// Grid coordinates x_i = min + (max - min) i / n, written so that the last node lands
// exactly on max; graded: x_i = min + (max - min) tau_i (graded_fraction). With the
// optional distortion (parts[i].perturbation): x_c += fraction h_c r_c, with
// h_c = (max_c - min_c) / n_c the element length along c (length units) and r a random
// vector of length at most 1 (perturbation_direction) over the components along which
// the node is strictly inside the grid (0 < ijk[c] < n_c), so every face stays plane
// and in place. Each node so moves by at most fraction h: in a plane grid of squares
// no corner angle can then close before fraction = 1/(2 sqrt 2) (two neighbours each
// moved by fraction h turn an edge by at most that much).
std::array<double, 3> box_point(const input::PartOptions& options, int part_index,
                                const std::array<int, 3>& ijk) {
  const auto& n = options.elements;
  auto coordinate = [&](int axis, int index) {
    const double lo = options.box_min[axis], hi = options.box_max[axis];
    if (index == n[axis]) return hi;
    if (options.grading[axis] != 1.0)
      return lo + (hi - lo) * graded_fraction(index, n[axis], options.grading[axis]);
    return lo + (hi - lo) * static_cast<double>(index) / static_cast<double>(n[axis]);
  };
  std::array<double, 3> x{coordinate(0, ijk[0]), coordinate(1, ijk[1]), coordinate(2, ijk[2])};
  const double fraction = options.perturbation_fraction;
  if (fraction > 0.0) {
    const std::array<bool, 3> moves{0 < ijk[0] && ijk[0] < n[0], 0 < ijk[1] && ijk[1] < n[1],
                                    0 < ijk[2] && ijk[2] < n[2]};
    if (moves[0] || moves[1] || moves[2]) {
      const std::array<double, 3> r = perturbation_direction(options, part_index, ijk, moves);
      for (int c = 0; c < 3; ++c)
        x[c] += fraction * (options.box_max[c] - options.box_min[c]) / static_cast<double>(n[c]) * r[c];
    }
  }
  return x;
}

Mesh build_mesh(const input::Deck& deck) {
  std::uint64_t nodes = 0, elements = 0, connectivity = 0;
  for (const auto& part : deck.parts) {
    if (part.geometry == input::Geometry::mesh) continue;  // counted as it is read
    const auto& n = part.elements;
    const int order = input::is_quadratic(part.formulation) ? 2 : 1;
    const std::uint64_t count = part.geometry == input::Geometry::box
                                    ? std::uint64_t(n[0]) * std::uint64_t(n[1]) * std::uint64_t(n[2])
                                    : mapped_element_count(part);
    // A mapped part's nodes: at most its elements' nodes (shared ones counted again).
    nodes +=
        part.geometry == input::Geometry::box ? part_node_count(n, order) : (order == 2 ? 20 : 8) * count;
    elements += count;
    connectivity += (order == 2 ? 20 : 8) * count;
  }
  // 32-bit node ids (connectivity) and element ids.
  if (nodes > std::numeric_limits<std::uint32_t>::max() ||
      elements > std::numeric_limits<std::int32_t>::max())
    throw InputError(SourceLocation{deck.source_file, 0, 0}, "parts",
                     "the mesh has " + std::to_string(nodes) + " nodes and " + std::to_string(elements) +
                         " elements; at most 4294967295 nodes and 2147483647 elements are supported");
  Mesh mesh;
  mesh.x_ref.x.reserve(nodes);
  mesh.x_ref.y.reserve(nodes);
  mesh.x_ref.z.reserve(nodes);
  mesh.connectivity.reserve(connectivity);
  mesh.element_part.reserve(elements);
  std::map<std::string, input::GmshMesh> files;  // each file read once
  for (std::size_t p = 0; p < deck.parts.size(); ++p) {
    const std::string key_path = "parts[" + std::to_string(p) + "].mesh";
    const SourceLocation where{deck.source_file, 0, 0};
    if (deck.parts[p].geometry == input::Geometry::mesh) {
      const std::string& path = deck.parts[p].mesh.path;
      auto file = files.find(path);
      if (file == files.end())
        file = files.emplace(path, input::read_gmsh(path, where, key_path + ".file")).first;
      add_imported_part(mesh, deck.parts[p], static_cast<int>(p), file->second, where, key_path);
      continue;
    }
    if (deck.parts[p].geometry != input::Geometry::box) {
      add_mapped_part(mesh, deck.parts[p], static_cast<int>(p));
      continue;
    }
    add_part(mesh, deck.parts[p], static_cast<int>(p));
    const PartRange& part = mesh.parts.back();
    if (deck.parts[p].perturbation_fraction > 0.0)
      check_perturbed_part(part, mesh.x_ref, deck, p, part.first_element);
  }
  check_physical_faces(deck, [&](std::size_t p) -> const PartRange& { return mesh.parts[p]; });
  return mesh;
}

Mesh build_part_mesh(const input::Deck& deck, std::size_t p, std::uint32_t first_element,
                     const GmshReader& read) {
  const input::PartOptions& options = deck.parts[p];
  Mesh mesh;
  if (options.geometry == input::Geometry::mesh) {
    const std::string key_path = "parts[" + std::to_string(p) + "].mesh";
    const SourceLocation where{deck.source_file, 0, 0};
    add_imported_part(mesh, options, static_cast<int>(p), read(options.mesh.path, where, key_path + ".file"),
                      where, key_path);
  } else if (options.geometry != input::Geometry::box) {
    add_mapped_part(mesh, options, static_cast<int>(p));
  } else {
    add_part(mesh, options, static_cast<int>(p));
    if (options.perturbation_fraction > 0.0)
      check_perturbed_part(mesh.parts.back(), mesh.x_ref, deck, p, first_element);
  }
  return mesh;
}

std::vector<std::uint64_t> unshared_faces(std::vector<BrickFace> faces,
                                          std::array<std::uint32_t, 4>* non_manifold) {
  // Equal keys are neighbours. Sorting (not hashing) keeps the result independent of
  // the standard library.
  std::sort(faces.begin(), faces.end(), [](const BrickFace& a, const BrickFace& b) {
    return a.corners != b.corners ? a.corners < b.corners : a.where < b.where;
  });
  std::vector<std::uint64_t> boundary;
  if (non_manifold != nullptr) *non_manifold = {};
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].corners == faces[i].corners) ++j;
    if (j - i == 1) boundary.push_back(faces[i].where);
    if (j - i > 2 && non_manifold != nullptr && *non_manifold == std::array<std::uint32_t, 4>{})
      *non_manifold = faces[i].corners;
    i = j;
  }
  std::sort(boundary.begin(), boundary.end());
  return boundary;
}

std::vector<BoundarySegment> boundary_segments(const std::vector<std::array<std::uint32_t, 20>>& elements,
                                               int nodes_per_element, const NodalVectors& x,
                                               std::array<std::uint32_t, 4>* non_manifold) {
  std::vector<BrickFace> faces;
  faces.reserve(6 * elements.size());
  for (std::size_t e = 0; e < elements.size(); ++e)
    for (int f = 0; f < 6; ++f) {
      BrickFace face{};
      for (int k = 0; k < 4; ++k) face.corners[std::size_t(k)] = elements[e][std::size_t(brick_faces[f][k])];
      std::sort(face.corners.begin(), face.corners.end());
      face.where = 6 * std::uint64_t(e) + std::uint64_t(f);
      faces.push_back(face);
    }
  const std::vector<std::uint64_t> boundary = unshared_faces(std::move(faces), non_manifold);

  auto coordinate = [&](std::uint32_t node, int c) {
    return c == 0 ? x.x[node] : (c == 1 ? x.y[node] : x.z[node]);
  };
  std::vector<BoundarySegment> result;
  result.reserve(boundary.size());
  for (const std::uint64_t where : boundary) {
    const auto& nodes = elements[std::size_t(where / 6)];
    const int fi = static_cast<int>(where % 6);
    const int* f = brick_faces[fi];
    BoundarySegment b;
    b.segment.node_count = nodes_per_element == 20 ? 8 : 4;
    for (int k = 0; k < b.segment.node_count; ++k) b.segment.nodes[std::size_t(k)] = nodes[std::size_t(f[k])];
    for (int k = 0; k < 4; ++k) b.corners[std::size_t(k)] = nodes[std::size_t(f[k])];
    std::sort(b.corners.begin(), b.corners.end());
    std::array<std::array<double, 3>, 8> corners{};
    for (std::size_t k = 0; k < 8; ++k)
      for (int c = 0; c < 3; ++c) corners[k][std::size_t(c)] = coordinate(nodes[k], c);
    b.normal_length = brick_normal_length(fi, corners);
    result.push_back(b);
  }
  return result;
}

double brick_normal_length(int face, const std::array<std::array<double, 3>, 8>& corners) {
  constexpr int opposite[6] = {1, 0, 4, 5, 2, 3};
  const int* f = brick_faces[face];
  const int* g = brick_faces[opposite[face]];
  double distance2 = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    double here = 0.0, there = 0.0;
    for (int k = 0; k < 4; ++k) {
      here += corners[std::size_t(f[k])][c] / 4.0;
      there += corners[std::size_t(g[k])][c] / 4.0;
    }
    distance2 += (here - there) * (here - there);
  }
  return std::sqrt(distance2);
}

Face named_face(const std::vector<std::pair<input::PartFace, Face>>& faces, int part_index,
                input::PartFace side) {
  for (const auto& [name, face] : faces)
    if (name == side) return face;
  throw std::logic_error("face_of: part " + std::to_string(part_index) + " has no face " + input::name(side));
}

void nodes_of_segments(Face& face) {
  face.nodes.clear();
  for (const FaceSegment& segment : face.segments)
    face.nodes.insert(face.nodes.end(), segment.nodes.begin(), segment.nodes.begin() + segment.node_count);
  std::sort(face.nodes.begin(), face.nodes.end());
  face.nodes.erase(std::unique(face.nodes.begin(), face.nodes.end()), face.nodes.end());
}

void finish_face(Face& face, double normal_length_sum) {
  face.normal_length = normal_length_sum / static_cast<double>(face.segments.size());
  nodes_of_segments(face);
}

Face cut_face(const Face& whole, const KeepSegment& keep) {
  Face face;
  face.normal_length = whole.normal_length;
  face.sides = whole.sides;
  face.whole_segments = whole.whole_count();
  for (std::size_t k = 0; k < whole.segments.size(); ++k)
    if (keep(whole.segments[k])) {
      face.segments.push_back(whole.segments[k]);
      face.segment_index.push_back(whole.index_in_whole(k));
    }
  nodes_of_segments(face);
  return face;
}

namespace {

Face whole_face_of(const Mesh& mesh, const input::FaceRef& reference) {
  const int part_index = reference.part;
  const input::PartFace side = reference.side;
  const PartRange& part = mesh.parts.at(static_cast<std::size_t>(part_index));
  if (side == input::PartFace::physical) {
    const Face& face = part.physical_faces.at(static_cast<std::size_t>(reference.surface));
    if (face.whole_count() == 0)
      throw std::logic_error("face_of: physical surface " + std::to_string(reference.surface) + " of part " +
                             std::to_string(part_index) + " has no segment");
    return face;
  }
  if (side == input::PartFace::interior) {
    if (part.interior_faces.empty())
      throw std::logic_error("face_of: part " + std::to_string(part_index) + " keeps no interior faces");
    return part.interior_faces.at(static_cast<std::size_t>(reference.surface));
  }
  if (part.lattice.empty()) return named_face(part.faces, part_index, side);  // a mapped or imported part
  return lattice_face(part.elements, part.order, side, part.normal_lengths,
                      [&](int i, int j, int k) { return part.node_at(i, j, k); });
}

}  // namespace

Face face_of(const Mesh& mesh, const input::FaceRef& reference) {
  Face face = whole_face_of(mesh, reference);
  return reference.fold_side < 0 ? face : side_of(face, std::size_t(reference.fold_side));
}

Face lattice_face(const std::array<int, 3>& n, int order, input::PartFace side,
                  const std::array<double, 6>& normal_lengths,
                  const std::function<std::uint32_t(int, int, int)>& node_at_lattice,
                  const KeepSegment& keep) {
  // The face is the grid plane axis = fixed; (p, q) are its in-plane axes,
  // ordered so that e_p x e_q is the outward normal.
  int axis = 0, p = 0, q = 0, fixed = 0;
  switch (side) {
    case input::PartFace::xmin:
      axis = 0, p = 2, q = 1, fixed = 0;
      break;
    case input::PartFace::xmax:
      axis = 0, p = 1, q = 2, fixed = n[0];
      break;
    case input::PartFace::ymin:
      axis = 1, p = 0, q = 2, fixed = 0;
      break;
    case input::PartFace::ymax:
      axis = 1, p = 2, q = 0, fixed = n[1];
      break;
    case input::PartFace::zmin:
      axis = 2, p = 1, q = 0, fixed = 0;
      break;
    case input::PartFace::zmax:
      axis = 2, p = 0, q = 1, fixed = n[2];
      break;
    case input::PartFace::surface:
    case input::PartFace::start:
    case input::PartFace::end:
    case input::PartFace::cut_x:
    case input::PartFace::cut_y:
    case input::PartFace::cut_z:
    case input::PartFace::physical:
    case input::PartFace::interior:
      throw std::logic_error(std::string("face_of: a box part has no face ") + input::name(side));
  }
  // Lattice point (a, b) of the face plane, in lattice units along p and q.
  auto node_at = [&](int a, int b) {
    std::array<int, 3> ijk{};
    ijk[axis] = order * fixed;
    ijk[p] = a;
    ijk[q] = b;
    return node_at_lattice(ijk[0], ijk[1], ijk[2]);
  };
  Face face;
  // The element length normal to the face: (max - min) / n, or the graded first or last one.
  face.normal_length = normal_lengths[static_cast<std::size_t>(2 * axis + (fixed == 0 ? 0 : 1))];
  if (!keep)
    for (int b = 0; b <= order * n[q]; ++b)
      for (int a = 0; a <= order * n[p]; ++a)
        if (const std::uint32_t node = node_at(a, b); node != no_node) face.nodes.push_back(node);
  for (int b = 0; b < n[q]; ++b)
    for (int a = 0; a < n[p]; ++a) {
      const int a0 = order * a, b0 = order * b, a1 = a0 + order, b1 = b0 + order;
      FaceSegment segment;
      segment.node_count = order == 2 ? 8 : 4;
      segment.nodes[0] = node_at(a0, b0);
      segment.nodes[1] = node_at(a1, b0);
      segment.nodes[2] = node_at(a1, b1);
      segment.nodes[3] = node_at(a0, b1);
      if (order == 2) {  // mid-sides of the edges 0-1, 1-2, 2-3, 3-0
        segment.nodes[4] = node_at(a0 + 1, b0);
        segment.nodes[5] = node_at(a1, b0 + 1);
        segment.nodes[6] = node_at(a0 + 1, b1);
        segment.nodes[7] = node_at(a0, b0 + 1);
      }
      const auto index = static_cast<std::uint32_t>(a + n[p] * b);
      if (keep && !keep(segment)) continue;
      face.segments.push_back(segment);
      if (keep) face.segment_index.push_back(index);
    }
  if (keep) {
    face.whole_segments = std::size_t(n[p]) * std::size_t(n[q]);
    nodes_of_segments(face);
  }
  return face;
}

}  // namespace exdyn::mesh
