// The setup's view of the deck's parts on many ranks (rank_setup.hpp): each part by
// numbers (a box's lattice, a cylinder's or ball's blocks) or made whole, the chunks'
// figures every rank computes, and the pieces of a rank's part built from them. Used
// by the setup's files alone (setup_*.cpp, rank_setup.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "common/mpi.hpp"
#include "common/nodal_vectors.hpp"
#include "element/element_block.hpp"
#include "input/options.hpp"
#include "mesh/mapped.hpp"
#include "mesh/mesh.hpp"
#include "model/model.hpp"
#include "ranks/decomposition.hpp"
#include "ranks/partitioning.hpp"

namespace exdyn::solver::setup {

constexpr std::uint32_t chunk_size = element::element_chunk;

// Figures as bytes: each vector and string as its length (8 bytes) and its items.
struct Packer {
  std::vector<char> bytes;
  template <class T>
  void put(const T* data, std::size_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::uint64_t n = count;
    bytes.insert(bytes.end(), reinterpret_cast<const char*>(&n), reinterpret_cast<const char*>(&n + 1));
    bytes.insert(bytes.end(), reinterpret_cast<const char*>(data),
                 reinterpret_cast<const char*>(data + count));
  }
  template <class T>
  void put(const std::vector<T>& values) {
    put(values.data(), values.size());
  }
  template <class T>
  void put_value(const T& value) {
    put(&value, 1);
  }
};
struct Unpacker {
  const std::vector<char>& bytes;
  std::size_t at = 0;
  template <class T>
  void get(std::vector<T>& out) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::uint64_t n = 0;
    std::memcpy(&n, bytes.data() + at, sizeof n);
    at += sizeof n;
    out.resize(n);
    if (n > 0) std::memcpy(out.data(), bytes.data() + at, n * sizeof(T));
    at += n * sizeof(T);
  }
  template <class T>
  T value() {
    std::vector<T> one;
    get(one);
    EXDYN_ASSERT(one.size() == 1);
    return one[0];
  }
};

// Bytes from `from` to `to` (MPI_Send and MPI_Recv, pieces of at most 1 GiB): the
// sender's `bytes` become the receiver's.
constexpr std::uint64_t piece_bytes = std::uint64_t(1) << 30;
void send_bytes(const mpi::Communicator& comm, int to, const std::vector<char>& bytes);

std::vector<char> receive_bytes(const mpi::Communicator& comm, int from);

// Rank 0's bytes on every rank (MPI_Bcast in pieces of at most 1 GiB).
void broadcast_bytes(const mpi::Communicator& comm, std::vector<char>& bytes);

// Runs `work` on rank 0 alone; an error it throws is every rank's: an InputError in
// its words (exit 2, as one process), any other error a runtime_error with its text.
// Collective over comm.
void on_rank_0(const mpi::Communicator& comm, const std::function<void()>& work);

// A part of the deck as the setup sees it, block `index`, its nodes first_node + 0, 1,
// ... and its elements first_element + 0, 1, ... of the whole mesh, in build_mesh's
// order and with its bits. Either
//  - a box, by numbers (mesh.hpp): its lattice points (I, J, K),
//    order per element along each axis (order 2: only those with at most one odd
//    index are nodes), are numbered in the order K, J, I; element (i, j, k) is
//    i + nx (j + ny k) of the part;
//  - a cylinder or ball, by numbers (`mapped`: mesh::MappedLattice, its node k is
//    first_node + k); or
//  - made whole (`built`: an imported part in one process), its mesh alone
//    (mesh::build_part_mesh: its node k is first_node + k) with the elements at each
//    node, held while the setup runs; or
//  - scattered (an imported part on many ranks): rank 0 makes it whole, every other
//    rank holds the part's figures and its faces cut to the segments of its elements
//    (`built` without nodes or elements) and its piece of it (`piece`).
// What a rank other than 0 holds of a scattered part, in part-local ids, ascending:
// the elements it needs (its own and those around their nodes: a face segment with a
// node held here is a face of one of them), their nodes' coordinates, the elements
// around the held nodes, and the owners of the part's nodes among its output rows.
struct PartPiece {
  std::vector<std::uint32_t> elements, connectivity;
  std::vector<std::uint32_t> nodes;
  std::vector<double> points;  // x, y, z of each node, m
  std::vector<std::uint32_t> around_nodes, around_start, around;
  std::uint32_t first_row = 0;  // the node of row_owner[0]
  std::vector<int> row_owner;

  static std::size_t at(const std::vector<std::uint32_t>& list, std::uint32_t id) {
    const auto it = std::lower_bound(list.begin(), list.end(), id);
    EXDYN_ASSERT(it != list.end() && *it == id);  // sent: the setup asks for no other
    return std::size_t(it - list.begin());
  }
};

struct SetupPart {
  int index = 0;
  const input::PartOptions* options = nullptr;
  std::array<int, 3> n{};
  int order = 1, nodes_per_element = 8;
  std::uint32_t first_node = 0, node_count = 0, first_element = 0, element_count = 0;
  std::size_t first_chunk = 0, chunks = 0;            // the block's chunks among all blocks'
  std::array<std::vector<double>, 3> grid;            // grid coordinates along x, y, z (mesh::box_point), m
  std::unique_ptr<const mesh::MappedLattice> mapped;  // null: not a cylinder or ball
  std::unique_ptr<const mesh::Mesh> built;            // null: by numbers
  bool scattered = false;                             // made whole by rank 0 alone
  std::unique_ptr<const PartPiece> piece;             // a scattered part on another rank
  // Made whole: the part's elements at its node k, ascending, are
  // at_element[at_start[k] .. at_start[k + 1]).
  std::vector<std::uint32_t> at_start, at_element;

  // Order 2: the nodes of a layer of even K (rows of even J: 2 nx + 1 nodes, of odd
  // J: nx + 1) and of odd K (rows of even J only, nx + 1 nodes).
  std::size_t row() const { return std::size_t(order * n[0] + 1); }
  std::size_t short_row() const { return std::size_t(n[0] + 1); }
  std::size_t even_layer() const {
    return order == 1 ? row() * std::size_t(n[1] + 1)
                      : row() * std::size_t(n[1] + 1) + short_row() * std::size_t(n[1]);
  }
  std::size_t odd_layer() const { return short_row() * std::size_t(n[1] + 1); }

  std::uint32_t node(const std::array<int, 3>& ijk) const {
    const auto i = std::size_t(ijk[0]), j = std::size_t(ijk[1]), k = std::size_t(ijk[2]);
    if (order == 1)
      return first_node + static_cast<std::uint32_t>(i + row() * (j + std::size_t(n[1] + 1) * k));
    std::size_t id = ((k + 1) / 2) * even_layer() + (k / 2) * odd_layer();
    if (k % 2 == 0)
      id += ((j + 1) / 2) * row() + (j / 2) * short_row() + (j % 2 == 0 ? i : i / 2);
    else
      id += (j / 2) * short_row() + i / 2;
    return first_node + static_cast<std::uint32_t>(id);
  }
  std::array<int, 3> node_ijk(std::uint32_t g) const {
    std::size_t r = g - first_node;
    if (order == 1) {
      const int i = int(r % row());
      r /= row();
      return {i, int(r % std::size_t(n[1] + 1)), int(r / std::size_t(n[1] + 1))};
    }
    const std::size_t k2 = r / (even_layer() + odd_layer());
    r %= even_layer() + odd_layer();
    if (r >= even_layer()) {
      r -= even_layer();
      return {int(2 * (r % short_row())), int(2 * (r / short_row())), int(2 * k2 + 1)};
    }
    const std::size_t j2 = r / (row() + short_row());
    r %= row() + short_row();
    if (r < row()) return {int(r), int(2 * j2), int(2 * k2)};
    return {int(2 * (r - row())), int(2 * j2 + 1), int(2 * k2)};
  }
  std::array<int, 3> element_ijk(std::uint32_t e) const {
    const auto nx = std::uint32_t(n[0]), ny = std::uint32_t(n[1]);
    return {int(e % nx), int((e / nx) % ny), int(e / (nx * ny))};
  }
  // The lattice point of VTK node `local` of element (i, j, k) (mesh::brick_offsets:
  // half elements).
  std::array<int, 3> corner(const std::array<int, 3>& ijk, int local) const {
    const auto& d = mesh::brick_offsets[std::size_t(local)];
    return {order * ijk[0] + d[0] * order / 2, order * ijk[1] + d[1] * order / 2,
            order * ijk[2] + d[2] * order / 2};
  }
  // The element's nodes (VTK order); corner 0 is its lowest id and corner 6 its highest.
  struct ElementNodes {
    std::array<std::uint32_t, 20> ids{};
    int count = 0;
    std::uint32_t operator[](int k) const { return ids[std::size_t(k)]; }
    const std::uint32_t* begin() const { return ids.data(); }
    const std::uint32_t* end() const { return ids.data() + count; }
  };
  ElementNodes element_nodes(std::uint32_t e) const {
    ElementNodes nodes;
    nodes.count = nodes_per_element;
    if (mapped) {
      const std::array<std::uint32_t, 20> local = mapped->element_nodes(e);
      for (int k = 0; k < nodes_per_element; ++k)
        nodes.ids[std::size_t(k)] = first_node + local[std::size_t(k)];
      return nodes;
    }
    if (piece) {
      const std::uint32_t* local =
          piece->connectivity.data() + std::size_t(nodes_per_element) * PartPiece::at(piece->elements, e);
      for (int k = 0; k < nodes_per_element; ++k) nodes.ids[std::size_t(k)] = first_node + local[k];
      return nodes;
    }
    if (built) {
      const std::uint32_t* local = built->connectivity.data() + std::size_t(nodes_per_element) * e;
      for (int k = 0; k < nodes_per_element; ++k) nodes.ids[std::size_t(k)] = first_node + local[k];
      return nodes;
    }
    const std::array<int, 3> ijk = element_ijk(e);
    for (int k = 0; k < nodes_per_element; ++k) nodes.ids[std::size_t(k)] = node(corner(ijk, k));
    return nodes;
  }
  // Node g's coordinates, m.
  std::array<double, 3> point_of(std::uint32_t g) const {
    if (mapped) return mapped->point(g - first_node);
    if (piece) {
      const std::size_t i = 3 * PartPiece::at(piece->nodes, g - first_node);
      return {piece->points[i], piece->points[i + 1], piece->points[i + 2]};
    }
    if (!built) return point(node_ijk(g));
    const NodalVectors& x = built->x_ref;
    const std::size_t k = g - first_node;
    return {x.x[k], x.y[k], x.z[k]};
  }
  // The part's elements around node g, ascending.
  std::vector<std::uint32_t> elements_around(std::uint32_t g) const {
    if (mapped) return mapped->elements_around(g - first_node);
    if (piece) {
      const std::size_t i = PartPiece::at(piece->around_nodes, g - first_node);
      return {piece->around.begin() + std::ptrdiff_t(piece->around_start[i]),
              piece->around.begin() + std::ptrdiff_t(piece->around_start[i + 1])};
    }
    if (built) {
      const std::size_t k = g - first_node;
      return {at_element.begin() + std::ptrdiff_t(at_start[k]),
              at_element.begin() + std::ptrdiff_t(at_start[k + 1])};
    }
    std::array<std::uint32_t, 8> around{};
    const int count = elements_at(node_ijk(g), around);
    return {around.begin(), around.begin() + count};
  }
  // The named face f of this part (f.part == index), in global node ids: face_of's;
  // with `keep` (given global ids), cut to the segments it keeps (mesh::cut_face).
  mesh::Face face(const input::FaceRef& f, const mesh::KeepSegment& keep = {}) const {
    if (!built && !mapped)
      return mesh::lattice_face(
          n, order, f.side, mesh::box_normal_lengths(*options),
          [&](int i, int j, int k) {
            return (i % order) + (j % order) + (k % order) > 1 ? mesh::no_node : node({i, j, k});
          },
          keep);
    auto to_global = [&](mesh::FaceSegment segment) {
      for (int k = 0; k < segment.node_count; ++k) segment.nodes[std::size_t(k)] += first_node;
      return segment;
    };
    input::FaceRef own = f;
    own.part = 0;
    mesh::Face face = mapped ? mesh::named_face(mapped->faces(), index, f.side) : mesh::face_of(*built, own);
    if (keep)
      face = mesh::cut_face(face, [&](const mesh::FaceSegment& segment) { return keep(to_global(segment)); });
    for (std::uint32_t& node_id : face.nodes) node_id += first_node;
    for (mesh::FaceSegment& segment : face.segments) segment = to_global(segment);
    return face;
  }
  // build_mesh's point: a grid point, or the middle of the edge between two (of a
  // perturbed box, its corners moved: mesh::box_point).
  std::array<double, 3> point(const std::array<int, 3>& ijk) const {
    std::array<double, 3> x{};
    if (options->perturbation_fraction > 0.0) {
      std::array<int, 3> below{ijk[0] / order, ijk[1] / order, ijk[2] / order}, above = below;
      for (std::size_t a = 0; a < 3; ++a) above[a] += ijk[a] % order;
      const std::array<double, 3> low = mesh::box_point(*options, index, below);
      if (above == below) return low;
      const std::array<double, 3> high = mesh::box_point(*options, index, above);
      for (std::size_t c = 0; c < 3; ++c) x[c] = 0.5 * (low[c] + high[c]);
      return x;
    }
    for (std::size_t a = 0; a < 3; ++a) {
      const std::vector<double>& line = grid[a];
      const int at = ijk[a];
      x[a] = at % order == 0 ? line[std::size_t(at / order)]
                             : 0.5 * (line[std::size_t(at / order)] + line[std::size_t(at / order + 1)]);
    }
    return x;
  }
  // The part's elements around lattice point ijk, ascending (at most 8); returns how many.
  int elements_at(const std::array<int, 3>& ijk, std::array<std::uint32_t, 8>& out) const {
    std::array<int, 3> low{}, high{};  // the element indices along each axis whose span holds the point
    for (std::size_t a = 0; a < 3; ++a) {
      low[a] = ijk[a] % order == 0 ? std::max(0, ijk[a] / order - 1) : ijk[a] / order;
      high[a] = std::min(n[a] - 1, ijk[a] / order);
    }
    int count = 0;
    for (int k = low[2]; k <= high[2]; ++k)
      for (int j = low[1]; j <= high[1]; ++j)
        for (int i = low[0]; i <= high[0]; ++i)
          out[std::size_t(count++)] = std::uint32_t(i + n[0] * (j + n[1] * k));
    return count;
  }
  // The part's range in a mesh without its lattice (its faces, if any, added by the caller).
  mesh::PartRange range() const {
    mesh::PartRange r;
    r.first_node = first_node;
    r.node_count = node_count;
    r.first_element = first_element;
    r.element_count = element_count;
    r.elements = n;
    r.order = order;
    r.nodes_per_element = nodes_per_element;
    if (built) r.normal_lengths = built->parts[0].normal_lengths;
    return r;
  }
};

// The deck's parts, with their node, element and chunk ranges. Throws the errors
// build_mesh throws of a part made whole (a perturbed box's inverted element, an
// imported part's file, the physical surfaces the deck names).
struct SetupParts {
  std::vector<SetupPart> list;
  std::size_t nodes = 0, elements = 0, chunks = 0;

  // comm: on many ranks an imported part is scattered (made whole by rank 0 alone).
  explicit SetupParts(const input::Deck& deck, const mesh::GmshReader& read = input::read_gmsh,
                      const mpi::Communicator* comm = nullptr) {
    for (std::size_t p = 0; p < deck.parts.size(); ++p) {
      const input::PartOptions& options = deck.parts[p];
      SetupPart part;
      part.index = int(p);
      part.options = &options;
      part.n = options.elements;
      part.order = input::is_quadratic(options.formulation) ? 2 : 1;
      part.nodes_per_element = part.order == 2 ? 20 : 8;
      part.first_node = std::uint32_t(nodes);
      if (options.geometry == input::Geometry::cylinder || options.geometry == input::Geometry::sphere) {
        part.mapped = std::make_unique<mesh::MappedLattice>(options, part.index);
        part.order = part.mapped->order();
        part.nodes_per_element = part.mapped->nodes_per_element();
        part.node_count = part.mapped->node_count();
        part.first_element = std::uint32_t(elements);
        part.element_count = part.mapped->element_count();
        part.first_chunk = chunks;
        part.chunks = (part.element_count + chunk_size - 1) / chunk_size;
        add(std::move(part));
        continue;
      }
      if (options.geometry != input::Geometry::box) {
        make_whole(deck, part, read, comm);
        continue;
      }
      part.node_count = std::uint32_t(std::size_t(part.n[2] + 1) * part.even_layer() +
                                      std::size_t(part.n[2]) * (part.order == 2 ? part.odd_layer() : 0));
      part.first_element = std::uint32_t(elements);
      part.element_count =
          std::uint32_t(std::size_t(part.n[0]) * std::size_t(part.n[1]) * std::size_t(part.n[2]));
      part.first_chunk = chunks;
      part.chunks = (part.element_count + chunk_size - 1) / chunk_size;
      for (int axis = 0; axis < 3; ++axis)
        for (int i = 0; i <= part.n[std::size_t(axis)]; ++i) {
          std::array<int, 3> ijk{0, 0, 0};
          ijk[std::size_t(axis)] = i;
          part.grid[std::size_t(axis)].push_back(
              mesh::box_point(options, part.index, ijk)[std::size_t(axis)]);
        }
      if (options.perturbation_fraction > 0.0) check_perturbed(deck, part);
      add(std::move(part));
    }
    static const mesh::PartRange box;  // no physical surfaces
    mesh::check_physical_faces(deck, [&](std::size_t p) -> const mesh::PartRange& {
      return list[p].built ? list[p].built->parts[0] : box;
    });
  }
  // build_mesh's check of a perturbed box, element by element (mesh::check_perturbed_element).
  static void check_perturbed(const input::Deck& deck, const SetupPart& part) {
    for (std::uint32_t e = 0; e < part.element_count; ++e) {
      const std::array<int, 3> ijk = part.element_ijk(e);
      std::array<std::array<double, 3>, 8> corners{};
      for (int c = 0; c < 8; ++c)
        corners[std::size_t(c)] =
            part.point({part.order * (ijk[0] + (c & 1)), part.order * (ijk[1] + ((c >> 1) & 1)),
                        part.order * (ijk[2] + ((c >> 2) & 1))});
      mesh::check_perturbed_element(corners, deck, std::size_t(part.index), ijk, part.first_element + e);
    }
  }
  void add(SetupPart part) {
    nodes += part.node_count;
    elements += part.element_count;
    chunks += part.chunks;
    list.push_back(std::move(part));
  }
  // A part made whole: its mesh and the elements at each of its nodes; scattered (an
  // imported part on many ranks), by rank 0 alone, the others taking its figures and
  // faces (an error making it is every rank's).
  void make_whole(const input::Deck& deck, SetupPart& part, const mesh::GmshReader& read,
                  const mpi::Communicator* comm) {
    part.scattered =
        comm != nullptr && comm->distributed() && part.options->geometry == input::Geometry::mesh;
    if (!part.scattered) {
      build_whole(deck, part, read);
    } else {
      on_rank_0(*comm, [&] { build_whole(deck, part, read); });
      Packer out;  // the faces cut to none: their counts (each rank's come with its piece)
      if (comm->root()) pack_range(part.built->parts[0], out, [](const mesh::FaceSegment&) { return false; });
      broadcast_bytes(*comm, out.bytes);
      if (!comm->root()) {
        auto figures = std::make_unique<mesh::Mesh>();
        Unpacker in{out.bytes};
        figures->parts.push_back(unpack_range(in));
        EXDYN_ASSERT(in.at == out.bytes.size());
        part.built = std::move(figures);
      }
    }
    const mesh::PartRange& range = part.built->parts[0];
    part.order = range.order;
    part.nodes_per_element = range.nodes_per_element;
    part.node_count = range.node_count;
    part.first_element = std::uint32_t(elements);
    part.element_count = range.element_count;
    part.first_chunk = chunks;
    part.chunks = (part.element_count + chunk_size - 1) / chunk_size;
    add(std::move(part));
  }
  void build_whole(const input::Deck& deck, SetupPart& part, const mesh::GmshReader& read) {
    auto built = std::make_unique<mesh::Mesh>(
        mesh::build_part_mesh(deck, std::size_t(part.index), std::uint32_t(elements), read));
    const auto width = std::size_t(built->parts[0].nodes_per_element);
    const std::uint32_t node_count = built->parts[0].node_count;
    part.at_start.assign(std::size_t(node_count) + 1, 0);
    for (const std::uint32_t k : built->connectivity) ++part.at_start[k + 1];
    for (std::size_t k = 0; k < node_count; ++k) part.at_start[k + 1] += part.at_start[k];
    part.at_element.resize(built->connectivity.size());
    std::vector<std::uint32_t> fill(part.at_start.begin(), part.at_start.end() - 1);
    for (std::size_t i = 0; i < built->connectivity.size(); ++i)  // ascending: elements in order
      part.at_element[fill[built->connectivity[i]]++] = std::uint32_t(i / width);
    // An element uses a node once (add_imported_part refuses repeats; boxes and mapped
    // parts have none), so each list holds each element once.
    part.built = std::move(built);
  }
  // A part's figures and faces (no lattice, nodes or elements; each face cut to the
  // segments `keep` keeps) as bytes, and back.
  static void pack_face(const mesh::Face& face, Packer& out) {
    out.put(face.nodes);
    out.put(face.segments);
    out.put_value(face.normal_length);
    out.put(face.segment_index);
    out.put_value(std::uint64_t(face.whole_segments));
    out.put(face.sides.side);
    out.put(face.sides.index);
    out.put(face.sides.count);
    out.put(face.sides.normal_length);
  }
  static mesh::Face unpack_face(Unpacker& in) {
    mesh::Face face;
    in.get(face.nodes);
    in.get(face.segments);
    face.normal_length = in.value<double>();
    in.get(face.segment_index);
    face.whole_segments = in.value<std::uint64_t>();
    in.get(face.sides.side);
    in.get(face.sides.index);
    in.get(face.sides.count);
    in.get(face.sides.normal_length);
    return face;
  }
  static void pack_range(const mesh::PartRange& range, Packer& out, const mesh::KeepSegment& keep) {
    out.put_value(range.order);
    out.put_value(range.nodes_per_element);
    out.put_value(range.node_count);
    out.put_value(range.element_count);
    out.put(range.normal_lengths.data(), range.normal_lengths.size());
    out.put_value(std::uint64_t(range.faces.size()));
    for (const auto& [name, face] : range.faces) {
      out.put_value(int(name));
      pack_face(mesh::cut_face(face, keep), out);
    }
    out.put_value(std::uint64_t(range.physical_faces.size()));
    for (const mesh::Face& face : range.physical_faces) pack_face(mesh::cut_face(face, keep), out);
  }
  static mesh::PartRange unpack_range(Unpacker& in) {
    mesh::PartRange range;
    range.order = in.value<int>();
    range.nodes_per_element = in.value<int>();
    range.node_count = in.value<std::uint32_t>();
    range.element_count = in.value<std::uint32_t>();
    std::vector<double> lengths;
    in.get(lengths);
    std::copy(lengths.begin(), lengths.end(), range.normal_lengths.begin());
    for (auto faces = in.value<std::uint64_t>(); faces > 0; --faces) {
      const auto name = input::PartFace(in.value<int>());
      range.faces.emplace_back(name, unpack_face(in));
    }
    for (auto faces = in.value<std::uint64_t>(); faces > 0; --faces)
      range.physical_faces.push_back(unpack_face(in));
    return range;
  }
  const SetupPart& part_of_node(std::uint32_t g) const {
    auto it = std::upper_bound(list.begin(), list.end(), g,
                               [](std::uint32_t v, const SetupPart& p) { return v < p.first_node; });
    return *(it - 1);
  }
  // The coordinates of `ids` (global ids), m: build_mesh's bits.
  NodalVectors points(const std::vector<std::uint32_t>& ids) const {
    NodalVectors x(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const std::array<double, 3> p = part_of_node(ids[i]).point_of(ids[i]);
      for (int c = 0; c < 3; ++c) x.component(c)[i] = p[std::size_t(c)];
    }
    return x;
  }
  const SetupPart& part_of_element(std::size_t e) const {
    auto it = std::upper_bound(list.begin(), list.end(), e,
                               [](std::size_t v, const SetupPart& p) { return v < p.first_element; });
    return *(it - 1);
  }
};

// What every rank computes of every chunk: its centroid (partition_chunks' rule),
// its colour (element_block.cpp's greedy colouring) and then its rank.
struct Chunks {
  std::vector<std::array<double, 3>> centroid;
  std::vector<double> weight;
  std::vector<std::uint32_t> block_of;
  std::vector<int> colour, rank;
  std::vector<std::size_t> colours;  // per block
};

// One pass over every element of every part, a chunk at a time. The colouring is
// build_schedule's: a chunk takes the lowest colour that no earlier chunk sharing a
// node has, with 64 colours per bit mask (past them, a new set of 64). Its masks are
// kept for a window of node ids only: a chunk's nodes lie within [its first element's
// corner 0, its last element's corner 6], both ascending with the chunk, so no later
// chunk comes back below the current one's lowest node.
void walk_part(const SetupPart& part, Chunks& chunks);

// Every part walked (walk_part); a scattered part by rank 0, which sends its chunks'
// figures to every rank. Collective over comm where a part is scattered.
Chunks walk_chunks(const SetupParts& deck_parts, const mpi::Communicator* comm = nullptr);

// The chunk graph of partition.cpp from the parts, part by part and chunk by chunk:
// each chunk's nodes (once each), the chunks around each of them, and how many of
// its nodes each other chunk shares. Parts share no node, so no edge joins two parts.
ChunkGraph chunk_graph_of(const SetupParts& deck_parts, const mpi::Communicator* comm);

// The partition of the chunks over `ranks` ranks: partition_chunks' on the whole model.
// comm: where a part is scattered (collective over it).
std::vector<int> partition_parts(const SetupParts& deck_parts, const Chunks& chunks, int ranks,
                                 Partitioning partitioning, const mpi::Communicator* comm = nullptr);

// The chunks (global indices) of the elements around node g, ascending.
std::vector<std::size_t> chunks_at(const SetupPart& part, std::uint32_t g);

// A scattered part's rows come from rank 0, which holds it.
// A node's owner: the lowest rank of the chunks around it (of a scattered part on a
// rank other than 0, among its output rows: sent with its piece).
int owner_of_node(const SetupPart& part, std::uint32_t g, const Chunks& chunks);

ChunkGraph chunk_graph_of(const SetupParts& deck_parts, const mpi::Communicator* comm);

// The lumped masses of `nodes` (global ids, ascending), kg: each from the elements
// around it, in ascending order, by the family's rule (element::add_lumped_mass), so
// every node gets one process's additions in one process's order.
std::vector<double> masses_of(const input::Deck& deck, const SetupParts& deck_parts,
                              const std::vector<std::uint32_t>& nodes);

// initial_velocity's values for `nodes` (global ids) of a model of them (their
// coordinates and fixed components), node by node.
NodalVectors initial_velocities(const SetupParts& deck_parts, const std::vector<std::uint32_t>& nodes,
                                const Model& m);

// Keeps the face segments with a node among `nodes` (global ids, ascending).
mesh::KeepSegment touching(const std::vector<std::uint32_t>& nodes);

// The prescribed components of `nodes` (global ids, ascending), as indices into
// `nodes` (build_model's rule: every node of a condition's faces, mid-side nodes
// included), from the faces' segments touching `nodes`; a conflict names a global id.
PrescribedMotion fixed_of(const input::Deck& deck, const SetupParts& deck_parts,
                          const std::vector<std::uint32_t>& nodes);

// A rank's nodes (global ids, ascending) and its model.
struct NearRank {
  const std::vector<std::uint32_t>& nodes;
  const Model& model;
};

// The contact faces alone (RankSetup::surfaces): every face the contact pairs and
// walls name, whole, or near one rank (`near`): cut to the segments with a node the
// rank holds (mesh::Face::segment_index), the held nodes' masses and fixed components
// the rank's, the other nodes of those segments (a halo) at infinite mass and free.
struct SurfaceModel {
  std::vector<std::uint32_t> nodes;  // of the faces (global ids, ascending): node k of the model
  Model model;
  std::vector<std::uint8_t> held;  // near a rank: whether it holds node k
};

SurfaceModel surface_model(const input::Deck& deck, const SetupParts& deck_parts, const NearRank* near);

// The whole block's groups of equal Jacobians of a 20-node part (ElementBlock::
// group_points), on every rank: each rank's own group starts (`count` elements here,
// their global ids `global`) are candidates, and the groups start at those of the
// candidates, in global order, that start one among them all; their points come with
// them from the ranks that hold them, so every rank has the whole block's bits.
// Collective over comm.
std::vector<std::array<double, 60>> whole_block_groups(const SetupPart& part, std::uint32_t count,
                                                       const std::uint32_t* connectivity,
                                                       const NodalVectors& x_ref, const std::uint32_t* global,
                                                       const mpi::Communicator& comm);

// Each rank's piece of each scattered part (PartPiece), sent by rank 0, which holds the
// part whole, for the chunks' ranks of `chunks`. Collective over comm.
void scatter_pieces(SetupParts& deck_parts, const Chunks& chunks, const mpi::Communicator& comm);

}  // namespace exdyn::solver::setup
