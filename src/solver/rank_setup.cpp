// A run's setup on many ranks, each rank building only its part (rank_setup.hpp).
#include "solver/rank_setup.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>

#include "common/errors.hpp"
#include "element/corner_checks.hpp"
#include "element/element_family.hpp"
#include "material/elastic.hpp"
#include "material/material_law.hpp"
#include "mesh/mapped.hpp"
#include "mesh/mesh.hpp"
#include "solver/load_balance.hpp"
#include "solver/memory_estimate.hpp"

namespace exdyn::solver {

namespace {

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
void send_bytes(const mpi::Communicator& comm, int to, const std::vector<char>& bytes) {
  const std::uint64_t size = bytes.size();
  mpi::check(MPI_Send(&size, 1, MPI_UINT64_T, to, 0, comm.comm), "MPI_Send of a part's size");
  for (std::uint64_t at = 0; at < size; at += piece_bytes)
    mpi::check(MPI_Send(bytes.data() + at, int(std::min(piece_bytes, size - at)), MPI_CHAR, to, 0, comm.comm),
               "MPI_Send of a part");
}
std::vector<char> receive_bytes(const mpi::Communicator& comm, int from) {
  std::uint64_t size = 0;
  mpi::check(MPI_Recv(&size, 1, MPI_UINT64_T, from, 0, comm.comm, MPI_STATUS_IGNORE),
             "MPI_Recv of a part's size");
  std::vector<char> bytes(size);
  for (std::uint64_t at = 0; at < size; at += piece_bytes)
    mpi::check(MPI_Recv(bytes.data() + at, int(std::min(piece_bytes, size - at)), MPI_CHAR, from, 0,
                        comm.comm, MPI_STATUS_IGNORE),
               "MPI_Recv of a part");
  return bytes;
}
// Rank 0's bytes on every rank (MPI_Bcast in pieces of at most 1 GiB).
void broadcast_bytes(const mpi::Communicator& comm, std::vector<char>& bytes) {
  std::uint64_t size = bytes.size();
  mpi::check(MPI_Bcast(&size, 1, MPI_UINT64_T, 0, comm.comm), "MPI_Bcast of a size");
  bytes.resize(size);
  for (std::uint64_t at = 0; at < size; at += piece_bytes)
    mpi::check(MPI_Bcast(bytes.data() + at, int(std::min(piece_bytes, size - at)), MPI_CHAR, 0, comm.comm),
               "MPI_Bcast of a part");
}

// Runs `work` on rank 0 alone; an error it throws is every rank's: an InputError in
// its words (exit 2, as one process), any other error a runtime_error with its text.
// Collective over comm.
void on_rank_0(const mpi::Communicator& comm, const std::function<void()>& work) {
  std::vector<char> text;
  int status = 0;  // 0: done; 1: bad input; 2: another error
  if (comm.root()) {
    try {
      work();
    } catch (const InputError& e) {
      status = 1, text.assign(e.what(), e.what() + std::strlen(e.what()));
    } catch (const std::exception& e) {
      status = 2, text.assign(e.what(), e.what() + std::strlen(e.what()));
    }
  }
  mpi::check(MPI_Bcast(&status, 1, MPI_INT, 0, comm.comm), "MPI_Bcast of a status");
  if (status == 0) return;
  broadcast_bytes(comm, text);
  if (status == 1) throw InputError(std::string(text.begin(), text.end()));
  throw std::runtime_error(std::string(text.begin(), text.end()));
}

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
  }
  static mesh::Face unpack_face(Unpacker& in) {
    mesh::Face face;
    in.get(face.nodes);
    in.get(face.segments);
    face.normal_length = in.value<double>();
    in.get(face.segment_index);
    face.whole_segments = in.value<std::uint64_t>();
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
void walk_part(const SetupPart& part, Chunks& chunks) {
  {
    auto first_node = [&](std::size_t c) { return part.element_nodes(std::uint32_t(c * chunk_size))[0]; };
    auto last_node = [&](std::size_t c) {
      return part.element_nodes(
          std::uint32_t(std::min<std::size_t>((c + 1) * chunk_size, part.element_count) - 1))[6];
    };
    // A box keeps the masks of a window of nodes (above). A part made whole keeps a
    // mask per node (its nodes in no such order); a cylinder or ball keeps those of the
    // nodes a later chunk may touch (each with its last element, purged as the chunks
    // pass it): a few layers of its blocks and their sides.
    const bool windowed = !part.built && !part.mapped;
    std::size_t span = 1;
    for (std::size_t c = 0; c < part.chunks && windowed; ++c)
      span = std::max<std::size_t>(span, last_node(c) - first_node(c) + 1);
    std::size_t window = 1;
    while (window < span) window *= 2;
    std::vector<std::uint64_t> masks(windowed ? window : (part.built ? part.node_count : 0), 0);
    struct Live {
      std::uint64_t mask = 0;
      std::uint32_t last_element = 0;
    };
    std::unordered_map<std::uint32_t, Live> live;
    std::size_t purge_at = 1024;
    auto mask = [&](std::uint32_t g) -> std::uint64_t& {
      if (windowed) return masks[g & (window - 1)];
      if (part.built) return masks[g - part.first_node];
      const auto [it, fresh] = live.try_emplace(g);
      if (fresh) it->second.last_element = part.elements_around(g).back();
      return it->second.mask;
    };
    std::int64_t highest = std::int64_t(part.first_node) - 1;  // nodes above it have no mask yet
    std::size_t base = 0, colours = 0;
    for (std::size_t c = 0; c < part.chunks; ++c) {
      const auto begin = std::uint32_t(c * chunk_size),
                 end = std::uint32_t(std::min<std::size_t>((c + 1) * chunk_size, part.element_count));
      std::array<double, 3> sum{};
      std::uint64_t taken = 0;
      for (std::uint32_t e = begin; e < end; ++e) {
        const std::array<int, 3> ijk = windowed ? part.element_ijk(e) : std::array<int, 3>{};
        const SetupPart::ElementNodes nodes = windowed ? SetupPart::ElementNodes{} : part.element_nodes(e);
        for (int k = 0; k < 8; ++k) {
          const std::array<double, 3> x =
              windowed ? part.point(part.corner(ijk, k)) : part.point_of(nodes[k]);
          for (std::size_t a = 0; a < 3; ++a) sum[a] += x[a];
        }
      }
      const double elements = double(end - begin);
      for (double& v : sum) v /= 8.0 * elements;
      chunks.centroid.push_back(sum);
      chunks.weight.push_back(elements);
      chunks.block_of.push_back(std::uint32_t(part.index));

      if (windowed) {
        for (std::int64_t g = highest + 1; g <= std::int64_t(last_node(c)); ++g)
          masks[std::size_t(g) & (window - 1)] = 0;
        highest = std::max<std::int64_t>(highest, last_node(c));
      }
      if (live.size() >= purge_at) {  // the nodes no chunk from here on touches
        std::erase_if(live, [&](const auto& entry) { return entry.second.last_element < begin; });
        purge_at = std::max<std::size_t>(1024, 2 * live.size());
      }
      for (std::uint32_t e = begin; e < end; ++e)
        for (const std::uint32_t g : part.element_nodes(e)) taken |= mask(g);
      if (taken == ~std::uint64_t{0}) {
        base += 64;
        std::fill(masks.begin(), masks.end(), std::uint64_t{0});
        live.clear();
        taken = 0;
      }
      int colour = 0;
      while (taken & (std::uint64_t{1} << colour)) ++colour;
      for (std::uint32_t e = begin; e < end; ++e)
        for (const std::uint32_t g : part.element_nodes(e)) mask(g) |= std::uint64_t{1} << colour;
      chunks.colour.push_back(int(base) + colour);
      colours = std::max(colours, base + std::size_t(colour) + 1);
    }
    chunks.colours.push_back(colours);
  }
}

// Every part walked (walk_part); a scattered part by rank 0, which sends its chunks'
// figures to every rank. Collective over comm where a part is scattered.
Chunks walk_chunks(const SetupParts& deck_parts, const mpi::Communicator* comm = nullptr) {
  Chunks chunks;
  for (const SetupPart& part : deck_parts.list) {
    if (!part.scattered) {
      walk_part(part, chunks);
      continue;
    }
    Chunks section;
    Packer out;
    if (comm->root()) {
      walk_part(part, section);
      out.put(section.centroid);
      out.put(section.weight);
      out.put(section.colour);
      out.put(section.colours);
    }
    broadcast_bytes(*comm, out.bytes);
    Unpacker in{out.bytes};
    in.get(section.centroid);
    in.get(section.weight);
    in.get(section.colour);
    in.get(section.colours);
    chunks.centroid.insert(chunks.centroid.end(), section.centroid.begin(), section.centroid.end());
    chunks.weight.insert(chunks.weight.end(), section.weight.begin(), section.weight.end());
    chunks.block_of.insert(chunks.block_of.end(), part.chunks, std::uint32_t(part.index));
    chunks.colour.insert(chunks.colour.end(), section.colour.begin(), section.colour.end());
    chunks.colours.push_back(section.colours.at(0));
  }
  return chunks;
}

// The chunk graph of partition.cpp from the parts, part by part and chunk by chunk:
// each chunk's nodes (once each), the chunks around each of them, and how many of
// its nodes each other chunk shares. Parts share no node, so no edge joins two parts.
ChunkGraph chunk_graph_of(const SetupParts& deck_parts, const mpi::Communicator* comm);

// The partition of the chunks over `ranks` ranks: partition_chunks' on the whole model.
// comm: where a part is scattered (collective over it).
std::vector<int> partition_parts(const SetupParts& deck_parts, const Chunks& chunks, int ranks,
                                 Partitioning partitioning, const mpi::Communicator* comm = nullptr) {
  if (partitioning == Partitioning::metis) {
    check_rank_count(ranks, deck_parts.chunks, deck_parts.elements);
    if (ranks == 1) return std::vector<int>(deck_parts.chunks, 0);
    return metis_chunks(chunk_graph_of(deck_parts, comm), chunks.weight, ranks);
  }
  return bisect_chunks(chunks.centroid, chunks.weight, chunks.block_of, ranks, deck_parts.elements);
}

// The chunks (global indices) of the elements around node g, ascending.
std::vector<std::size_t> chunks_at(const SetupPart& part, std::uint32_t g) {
  std::vector<std::size_t> out;
  for (const std::uint32_t e : part.elements_around(g)) {
    const std::size_t c = part.first_chunk + e / chunk_size;
    if (out.empty() || out.back() != c) out.push_back(c);  // elements ascending: chunks too
  }
  return out;
}

// A scattered part's rows come from rank 0, which holds it.
// A node's owner: the lowest rank of the chunks around it (of a scattered part on a
// rank other than 0, among its output rows: sent with its piece).
int owner_of_node(const SetupPart& part, std::uint32_t g, const Chunks& chunks) {
  if (part.piece) return part.piece->row_owner.at(g - part.first_node - part.piece->first_row);
  int owner = std::numeric_limits<int>::max();
  for (const std::size_t c : chunks_at(part, g)) owner = std::min(owner, chunks.rank[c]);
  return owner;
}

ChunkGraph chunk_graph_of(const SetupParts& deck_parts, const mpi::Communicator* comm) {
  ChunkGraph graph;
  graph.neighbours.resize(deck_parts.chunks);
  std::vector<std::uint32_t> count(deck_parts.chunks, 0), nodes, touched;
  for (const SetupPart& part : deck_parts.list) {
    const bool here = !part.scattered || comm->root();
    for (std::size_t c = 0; c < part.chunks && here; ++c) {
      const std::size_t me = part.first_chunk + c;
      nodes.clear();
      for (auto e = std::uint32_t(c * chunk_size);
           e < std::min<std::size_t>((c + 1) * chunk_size, part.element_count); ++e)
        for (const std::uint32_t g : part.element_nodes(e)) nodes.push_back(g);
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      touched.clear();
      for (const std::uint32_t g : nodes)
        for (const std::size_t other : chunks_at(part, g))
          if (other != me && count[other]++ == 0) touched.push_back(std::uint32_t(other));
      std::sort(touched.begin(), touched.end());
      for (const std::uint32_t other : touched) {
        graph.neighbours[me].emplace_back(other, count[other]);
        count[other] = 0;
      }
    }
    if (!part.scattered) continue;
    Packer out;  // each chunk's neighbours and shared nodes, flat
    std::vector<std::uint64_t> sizes;
    std::vector<std::uint32_t> flat;  // (chunk, shared nodes) pairs
    if (comm->root())
      for (std::size_t c = 0; c < part.chunks; ++c) {
        const auto& row = graph.neighbours[part.first_chunk + c];
        sizes.push_back(row.size());
        for (const auto& [other, shared] : row) flat.push_back(other), flat.push_back(shared);
      }
    out.put(sizes);
    out.put(flat);
    broadcast_bytes(*comm, out.bytes);
    Unpacker in{out.bytes};
    in.get(sizes);
    in.get(flat);
    std::size_t at = 0;
    for (std::size_t c = 0; c < part.chunks; ++c) {
      auto& row = graph.neighbours[part.first_chunk + c];
      row.clear();
      for (std::size_t k = 0; k < sizes[c]; ++k, at += 2) row.emplace_back(flat[at], flat[at + 1]);
    }
  }
  return graph;
}

// The lumped masses of `nodes` (global ids, ascending), kg: each from the elements
// around it, in ascending order, by the family's rule (element::add_lumped_mass), so
// every node gets one process's additions in one process's order.
std::vector<double> masses_of(const input::Deck& deck, const SetupParts& deck_parts,
                              const std::vector<std::uint32_t>& nodes) {
  std::vector<std::uint32_t> elements;  // global ids
  for (const std::uint32_t g : nodes) {
    const SetupPart& part = deck_parts.part_of_node(g);
    for (const std::uint32_t e : part.elements_around(g)) elements.push_back(part.first_element + e);
  }
  std::sort(elements.begin(), elements.end());
  elements.erase(std::unique(elements.begin(), elements.end()), elements.end());
  std::vector<std::uint32_t> halo;  // the nodes of those elements, ascending
  for (const std::uint32_t e : elements) {
    const SetupPart& part = deck_parts.part_of_element(e);
    for (const std::uint32_t g : part.element_nodes(e - part.first_element)) halo.push_back(g);
  }
  std::sort(halo.begin(), halo.end());
  halo.erase(std::unique(halo.begin(), halo.end()), halo.end());
  auto index = [&](std::uint32_t g) {
    return std::uint32_t(std::lower_bound(halo.begin(), halo.end(), g) - halo.begin());
  };
  const NodalVectors x = deck_parts.points(halo);
  std::vector<double> mass(halo.size(), 0.0);
  for (std::size_t first = 0; first < elements.size();) {  // a block of each part's elements
    const SetupPart& part = deck_parts.part_of_element(elements[first]);
    std::size_t last = first;
    std::vector<std::uint32_t> connectivity;
    for (; last < elements.size() && elements[last] < part.first_element + part.element_count; ++last)
      for (const std::uint32_t g : part.element_nodes(elements[last] - part.first_element))
        connectivity.push_back(index(g));
    const input::MaterialOptions& m = deck.materials.at(std::size_t(part.options->material_index));
    element::ElementBlock block;  // what the lumping reads: the family, density and nodes
    block.formulation = part.options->formulation;
    block.family = &element::element_family(block.formulation);
    block.nodes_per_element = part.nodes_per_element;
    block.material = material::elastic_constants(m.youngs_modulus, m.poissons_ratio, m.density);
    block.count = std::uint32_t(last - first);
    block.connectivity = connectivity.data();
    element::add_lumped_mass(block, x, mass);
    first = last;
  }
  std::vector<double> result(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) result[k] = mass[index(nodes[k])];
  return result;
}

// initial_velocity's values for `nodes` (global ids) of a model of them (their
// coordinates and fixed components), node by node.
NodalVectors initial_velocities(const SetupParts& deck_parts, const std::vector<std::uint32_t>& nodes,
                                const Model& m) {
  NodalVectors v(nodes.size());
  const NodalVectors& x = m.mesh.x_ref;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::array<double, 3> vi =
        part_initial_velocity(*deck_parts.part_of_node(nodes[i]).options, {x.x[i], x.y[i], x.z[i]});
    v.x[i] = vi[0], v.y[i] = vi[1], v.z[i] = vi[2];
  }
  apply_fixed_components(m, v);
  return v;
}

// Keeps the face segments with a node among `nodes` (global ids, ascending).
mesh::KeepSegment touching(const std::vector<std::uint32_t>& nodes) {
  return [&nodes](const mesh::FaceSegment& segment) {
    for (int k = 0; k < segment.node_count; ++k)
      if (std::binary_search(nodes.begin(), nodes.end(), segment.nodes[std::size_t(k)])) return true;
    return false;
  };
}

// The fixed components of each of `nodes` (global ids, ascending): the indices into
// `nodes` of those on a face of a boundary condition fixing component c (build_model's
// rule: every node of the face, mid-side nodes included), from the faces' segments
// touching `nodes`.
std::array<std::vector<std::uint32_t>, 3> fixed_of(const input::Deck& deck, const SetupParts& deck_parts,
                                                   const std::vector<std::uint32_t>& nodes) {
  std::array<std::vector<std::uint32_t>, 3> held;  // global ids, per component
  for (const auto& bc : deck.boundary_conditions)
    for (const input::FaceRef& f : bc.faces) {
      const mesh::Face face = deck_parts.list.at(std::size_t(f.part)).face(f, touching(nodes));
      for (std::size_t c = 0; c < 3; ++c)
        if (bc.fix[c]) held[c].insert(held[c].end(), face.nodes.begin(), face.nodes.end());
    }
  std::array<std::vector<std::uint32_t>, 3> fixed;
  for (std::size_t c = 0; c < 3; ++c) {
    std::sort(held[c].begin(), held[c].end());
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (std::binary_search(held[c].begin(), held[c].end(), nodes[i])) fixed[c].push_back(std::uint32_t(i));
  }
  return fixed;
}

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
SurfaceModel surface_model(const input::Deck& deck, const SetupParts& deck_parts, const NearRank* near) {
  SurfaceModel out;
  Model& m = out.model;
  std::vector<input::FaceRef> faces;
  for (const input::ContactOptions& pair : deck.contact) {
    faces.insert(faces.end(), pair.slave.begin(), pair.slave.end());
    faces.insert(faces.end(), pair.master.begin(), pair.master.end());
  }
  for (const input::RigidWallOptions& wall : deck.rigid_walls)
    faces.insert(faces.end(), wall.slave.begin(), wall.slave.end());
  mesh::KeepSegment keep;
  if (near) keep = touching(near->nodes);
  for (const SetupPart& part : deck_parts.list) {
    // The part's faces as a mapped or imported part has them (face_of finds them by
    // name or by physical surface), first in global ids.
    mesh::PartRange& range = m.mesh.parts.emplace_back(part.range());
    range.normal_lengths = part.built    ? part.built->parts[0].normal_lengths
                           : part.mapped ? std::array<double, 6>{}  // add_mapped_part sets none
                                         : mesh::box_normal_lengths(*part.options);
    for (const input::FaceRef& f : faces) {
      if (f.part != part.index) continue;
      const bool physical = f.side == input::PartFace::physical;
      const auto surface = std::size_t(f.surface);
      if (physical ? surface < range.physical_faces.size() && range.physical_faces[surface].whole_count() > 0
                   : std::any_of(range.faces.begin(), range.faces.end(),
                                 [&](const auto& face) { return face.first == f.side; }))
        continue;
      mesh::Face face = part.face(f, keep);
      out.nodes.insert(out.nodes.end(), face.nodes.begin(), face.nodes.end());
      if (physical) {
        if (range.physical_faces.size() <= surface) range.physical_faces.resize(surface + 1);
        range.physical_faces[surface] = std::move(face);
      } else {
        range.faces.emplace_back(f.side, std::move(face));
      }
    }
  }
  std::sort(out.nodes.begin(), out.nodes.end());
  out.nodes.erase(std::unique(out.nodes.begin(), out.nodes.end()), out.nodes.end());
  auto index = [&](std::uint32_t g) {
    return std::uint32_t(std::lower_bound(out.nodes.begin(), out.nodes.end(), g) - out.nodes.begin());
  };
  auto renumber = [&](mesh::Face& face) {
    for (std::uint32_t& g : face.nodes) g = index(g);
    for (mesh::FaceSegment& segment : face.segments)
      for (int k = 0; k < segment.node_count; ++k)
        segment.nodes[std::size_t(k)] = index(segment.nodes[std::size_t(k)]);
  };
  for (mesh::PartRange& range : m.mesh.parts) {
    for (auto& named : range.faces) renumber(named.second);
    for (mesh::Face& face : range.physical_faces) renumber(face);
  }
  m.mesh.x_ref = deck_parts.points(out.nodes);
  if (!near) {
    m.mass = masses_of(deck, deck_parts, out.nodes);
    m.fixed_nodes = fixed_of(deck, deck_parts, out.nodes);
  } else {
    out.held.resize(out.nodes.size());
    m.mass.assign(out.nodes.size(), std::numeric_limits<double>::infinity());
    for (std::size_t k = 0; k < out.nodes.size(); ++k) {
      const auto at = std::lower_bound(near->nodes.begin(), near->nodes.end(), out.nodes[k]);
      if (at == near->nodes.end() || *at != out.nodes[k]) continue;
      out.held[k] = 1;
      m.mass[k] = near->model.mass[std::size_t(at - near->nodes.begin())];
    }
    for (std::size_t c = 0; c < 3; ++c)
      for (const std::uint32_t i : near->model.fixed_nodes[c])
        if (std::binary_search(out.nodes.begin(), out.nodes.end(), near->nodes[i]))
          m.fixed_nodes[c].push_back(index(near->nodes[i]));
  }
  m.inverse_mass.resize(m.mass.size());
  for (std::size_t i = 0; i < m.mass.size(); ++i) m.inverse_mass[i] = 1.0 / m.mass[i];
  return out;
}

// The whole block's groups of equal Jacobians of a 20-node part (ElementBlock::
// group_points), on every rank: each rank's own group starts (`count` elements here,
// their global ids `global`) are candidates, and the groups start at those of the
// candidates, in global order, that start one among them all; their points come with
// them from the ranks that hold them, so every rank has the whole block's bits.
// Collective over comm.
std::vector<std::array<double, 60>> whole_block_groups(const SetupPart& part, std::uint32_t count,
                                                       const std::uint32_t* connectivity,
                                                       const NodalVectors& x_ref, const std::uint32_t* global,
                                                       const mpi::Communicator& comm) {
  const input::Formulation formulation = part.options->formulation;
  // Each rank's group starts (global ids) with their nodes' coordinates, x of the 20,
  // then y, then z; every rank's, rank after rank.
  std::vector<std::uint32_t> mine;
  std::vector<double> my_points;
  for (const std::uint32_t e : element::jacobian_group_starts(formulation, count, connectivity, x_ref)) {
    mine.push_back(global[e]);
    for (int a = 0; a < 3; ++a)
      for (std::size_t k = 0; k < 20; ++k) my_points.push_back(x_ref.component(a)[connectivity[20 * e + k]]);
  }
  const std::vector<std::uint32_t> gathered = mpi::all_gather_varying(comm, mine);
  const std::vector<double> gathered_points = mpi::all_gather_varying(comm, my_points);
  // The candidates in global order, once each.
  std::vector<std::size_t> by_id(gathered.size());
  std::iota(by_id.begin(), by_id.end(), std::size_t(0));
  std::sort(by_id.begin(), by_id.end(),
            [&](std::size_t a, std::size_t b) { return gathered[a] < gathered[b]; });
  by_id.erase(std::unique(by_id.begin(), by_id.end(),
                          [&](std::size_t a, std::size_t b) { return gathered[a] == gathered[b]; }),
              by_id.end());
  NodalVectors points(20 * by_id.size());
  std::vector<std::uint32_t> order(20 * by_id.size());  // 0, 1, ... into the points
  std::iota(order.begin(), order.end(), 0u);
  for (std::size_t c = 0; c < by_id.size(); ++c)
    for (int a = 0; a < 3; ++a)
      for (std::size_t k = 0; k < 20; ++k)
        points.component(a)[20 * c + k] = gathered_points[60 * by_id[c] + 20 * std::size_t(a) + k];
  std::vector<std::array<double, 60>> groups;
  for (const std::uint32_t c :
       element::jacobian_group_starts(formulation, std::uint32_t(by_id.size()), order.data(), points)) {
    std::array<double, 60>& group = groups.emplace_back();
    for (std::size_t k = 0; k < 20; ++k)
      for (std::size_t a = 0; a < 3; ++a) group[20 * a + k] = points.component(int(a))[20 * c + k];
  }
  return groups;
}

// Each rank's piece of each scattered part (PartPiece), sent by rank 0, which holds the
// part whole, for the chunks' ranks of `chunks`. Collective over comm.
void scatter_pieces(SetupParts& deck_parts, const Chunks& chunks, const mpi::Communicator& comm) {
  if (std::none_of(deck_parts.list.begin(), deck_parts.list.end(),
                   [](const SetupPart& p) { return p.scattered; }))
    return;
  for (SetupPart& part : deck_parts.list) {
    if (!part.scattered) continue;
    if (!comm.root()) {
      part.piece = nullptr;
      const std::vector<char> bytes = receive_bytes(comm, 0);
      Unpacker in{bytes};
      auto piece = std::make_unique<PartPiece>();
      in.get(piece->elements);
      in.get(piece->connectivity);
      in.get(piece->nodes);
      in.get(piece->points);
      in.get(piece->around_nodes);
      in.get(piece->around_start);
      in.get(piece->around);
      piece->first_row = in.value<std::uint32_t>();
      in.get(piece->row_owner);
      auto figures = std::make_unique<mesh::Mesh>();
      figures->parts.push_back(SetupParts::unpack_range(in));
      part.built = std::move(figures);
      EXDYN_ASSERT(in.at == bytes.size());
      part.piece = std::move(piece);
      continue;
    }
    const mesh::Mesh& whole = *part.built;
    const auto width = std::size_t(part.nodes_per_element);
    for (int r = 1; r < comm.size; ++r) {
      PartPiece piece;
      std::vector<std::uint32_t> own;
      for (std::size_t c = 0; c < part.chunks; ++c)
        if (chunks.rank[part.first_chunk + c] == r)
          for (auto e = std::uint32_t(c * chunk_size);
               e < std::min<std::size_t>((c + 1) * chunk_size, part.element_count); ++e)
            own.push_back(e);
      for (const std::uint32_t e : own)
        piece.around_nodes.insert(piece.around_nodes.end(),
                                  whole.connectivity.begin() + std::ptrdiff_t(width * e),
                                  whole.connectivity.begin() + std::ptrdiff_t(width * (e + 1)));
      std::sort(piece.around_nodes.begin(), piece.around_nodes.end());
      piece.around_nodes.erase(std::unique(piece.around_nodes.begin(), piece.around_nodes.end()),
                               piece.around_nodes.end());
      piece.around_start.push_back(0);
      for (const std::uint32_t k : piece.around_nodes) {
        piece.around.insert(piece.around.end(), part.at_element.begin() + std::ptrdiff_t(part.at_start[k]),
                            part.at_element.begin() + std::ptrdiff_t(part.at_start[k + 1]));
        piece.around_start.push_back(std::uint32_t(piece.around.size()));
      }
      piece.elements = own;
      piece.elements.insert(piece.elements.end(), piece.around.begin(), piece.around.end());
      std::sort(piece.elements.begin(), piece.elements.end());
      piece.elements.erase(std::unique(piece.elements.begin(), piece.elements.end()), piece.elements.end());
      for (const std::uint32_t e : piece.elements)
        piece.connectivity.insert(piece.connectivity.end(),
                                  whole.connectivity.begin() + std::ptrdiff_t(width * e),
                                  whole.connectivity.begin() + std::ptrdiff_t(width * (e + 1)));
      piece.nodes = piece.connectivity;
      std::sort(piece.nodes.begin(), piece.nodes.end());
      piece.nodes.erase(std::unique(piece.nodes.begin(), piece.nodes.end()), piece.nodes.end());
      for (const std::uint32_t k : piece.nodes)
        for (int c = 0; c < 3; ++c) piece.points.push_back(whole.x_ref.component(c)[k]);
      // Rank r's output rows, [n r / p, n (r + 1) / p) of the n nodes (row_exchange),
      // within the part.
      const std::size_t n = deck_parts.nodes, p = std::size_t(comm.size);
      const std::size_t begin = std::max<std::size_t>(n * std::size_t(r) / p, part.first_node),
                        end = std::min<std::size_t>(n * std::size_t(r + 1) / p,
                                                    part.first_node + part.node_count);
      piece.first_row = begin < end ? std::uint32_t(begin - part.first_node) : 0;
      for (std::size_t g = begin; g < end; ++g)
        piece.row_owner.push_back(owner_of_node(part, std::uint32_t(g), chunks));
      Packer out;
      out.put(piece.elements);
      out.put(piece.connectivity);
      out.put(piece.nodes);
      out.put(piece.points);
      out.put(piece.around_nodes);
      out.put(piece.around_start);
      out.put(piece.around);
      out.put_value(piece.first_row);
      out.put(piece.row_owner);
      // The part's faces cut to the segments with a node of rank r's elements.
      SetupParts::pack_range(whole.parts[0], out, touching(piece.around_nodes));
      send_bytes(comm, r, out.bytes);
    }
  }
}

// This rank's part of the model, its chunks chunks.rank's.
RankSetup build_part(const input::Deck& deck, const mpi::Communicator& comm, const SetupParts& deck_parts,
                     const Chunks& chunks, Partitioning partitioning) {
  const int me = comm.rank;
  RankSetup setup;
  setup.nodes = deck_parts.nodes;
  setup.elements = deck_parts.elements;

  LocalRun& run = setup.run;
  Decomposition& d = run.decomposition;
  Model& m = run.model;
  d.comm = comm;
  d.global_nodes = deck_parts.nodes;
  d.global_elements = deck_parts.elements;
  d.partitioning = partitioning;
  d.set_up_by_rank = true;

  // This rank's chunks, elements and nodes (in ascending global order).
  std::vector<std::vector<std::uint32_t>> my_chunks(deck_parts.list.size());
  for (const SetupPart& part : deck_parts.list)
    for (std::size_t c = 0; c < part.chunks; ++c)
      if (chunks.rank[part.first_chunk + c] == me)
        my_chunks[std::size_t(part.index)].push_back(std::uint32_t(c));
  // Sized first: grown by doubling, the lists would keep up to twice their size for the
  // whole run (the node list, before its duplicates go, 8 or 20 entries an element).
  std::size_t my_elements = 0, my_entries = 0;
  for (const SetupPart& part : deck_parts.list)
    for (const std::uint32_t c : my_chunks[std::size_t(part.index)]) {
      const std::size_t count = std::min((c + 1) * chunk_size, part.element_count) - c * chunk_size;
      my_elements += count;
      my_entries += count * std::size_t(part.nodes_per_element);
    }
  d.global_element.reserve(my_elements);
  d.global_node.reserve(my_entries);
  for (const SetupPart& part : deck_parts.list)
    for (const std::uint32_t c : my_chunks[std::size_t(part.index)])
      for (std::uint32_t e = c * chunk_size; e < std::min((c + 1) * chunk_size, part.element_count); ++e) {
        d.global_element.push_back(part.first_element + e);
        for (const std::uint32_t g : part.element_nodes(e)) d.global_node.push_back(g);
      }
  std::sort(d.global_node.begin(), d.global_node.end());
  d.global_node.erase(std::unique(d.global_node.begin(), d.global_node.end()), d.global_node.end());
  d.global_node.shrink_to_fit();
  auto local_of = [&](std::uint32_t g) {
    return std::uint32_t(std::lower_bound(d.global_node.begin(), d.global_node.end(), g) -
                         d.global_node.begin());
  };
  const std::size_t local_nodes = d.global_node.size();

  // The running sums' plan from the chunks around each node; the edge cut counted at
  // the owners (each pair of chunks on different ranks, once per node they share).
  {
    std::vector<std::vector<std::pair<int, int>>> chain(local_nodes);
    std::vector<std::uint32_t> block_of(local_nodes);
    long edge_cut = 0;
    for (std::size_t i = 0; i < local_nodes; ++i) {
      const SetupPart& part = deck_parts.part_of_node(d.global_node[i]);
      const std::vector<std::size_t> around = chunks_at(part, d.global_node[i]);
      int owner = std::numeric_limits<int>::max();
      for (const std::size_t c : around) {
        chain[i].emplace_back(chunks.colour[c], chunks.rank[c]);
        owner = std::min(owner, chunks.rank[c]);
      }
      if (owner == me)
        for (std::size_t a = 0; a < around.size(); ++a)
          for (std::size_t b = a + 1; b < around.size(); ++b)
            edge_cut += chunks.rank[around[a]] != chunks.rank[around[b]];
      block_of[i] = std::uint32_t(part.index);
    }
    mpi::check(MPI_Allreduce(&edge_cut, &d.edge_cut, 1, MPI_LONG, MPI_SUM, comm.comm),
               "MPI_Allreduce of the edge cut");
    plan_force_exchange(d, me, std::move(chain), block_of, chunks.colours);
  }

  // The rank's mesh and blocks: its chunks of each part, in the whole model's order.
  m.mesh.x_ref = deck_parts.points(d.global_node);
  for (const SetupPart& part : deck_parts.list) m.mesh.parts.push_back(part.range());
  std::vector<std::size_t> first_connectivity;
  m.mesh.connectivity.reserve(my_entries);
  m.mesh.element_part.reserve(my_elements);
  for (const SetupPart& part : deck_parts.list) {
    first_connectivity.push_back(m.mesh.connectivity.size());
    for (const std::uint32_t c : my_chunks[std::size_t(part.index)])
      for (std::uint32_t e = c * chunk_size; e < std::min((c + 1) * chunk_size, part.element_count); ++e) {
        for (const std::uint32_t g : part.element_nodes(e)) m.mesh.connectivity.push_back(local_of(g));
        m.mesh.element_part.push_back(part.index);
      }
  }
  // Each block's stable step, and a 20-node block's step scale (ElementBlock::
  // step_scale: its family step over its corner-based step): the whole block's, each an
  // exact minimum over the ranks; the model's stable step is the least of them.
  std::vector<double> steps(2 * deck_parts.list.size(), std::numeric_limits<double>::infinity());
  std::vector<std::size_t> block_of_part(deck_parts.list.size(), ~std::size_t{0});  // ~0: none here
  // Each part's elements here, and the layout the whole block's elements allow: the
  // ranks' layouts together (a rank's elements may allow a faster one, such as a
  // cylinder's square core).
  std::vector<std::uint32_t> part_count(deck_parts.list.size(), 0);
  std::vector<int> layout(2 * deck_parts.list.size(), 1);
  for (const SetupPart& part : deck_parts.list) {
    const auto p = std::size_t(part.index);
    for (const std::uint32_t c : my_chunks[p])
      part_count[p] += std::min((c + 1) * chunk_size, part.element_count) - c * chunk_size;
    const element::WholeBlock own =
        element::element_layout(part.options->formulation, part_count[p],
                                m.mesh.connectivity.data() + first_connectivity[p], m.mesh.x_ref);
    layout[2 * p] = own.parallelepipeds ? 1 : 0;
    layout[2 * p + 1] = own.axis_aligned ? 1 : 0;
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, layout.data(), int(layout.size()), MPI_INT, MPI_MIN, comm.comm),
             "MPI_Allreduce of the blocks' layouts");
  std::uint32_t first_element = 0;
  for (const SetupPart& part : deck_parts.list) {
    const auto p = std::size_t(part.index);
    const auto& mine = my_chunks[p];
    const input::PartOptions& options = *part.options;
    const input::MaterialOptions& material = deck.materials.at(std::size_t(options.material_index));
    const std::uint32_t count = part_count[p];
    const material::MaterialLaw law =
        material::make_law(material, input::resolved_kinematics(options, material), options.f_bar);
    const std::uint32_t* connectivity = m.mesh.connectivity.data() + first_connectivity[p];
    element::WholeBlock whole{layout[2 * p] != 0, layout[2 * p + 1] != 0, {}};
    if (part.order == 2 && law.linear_small() && whole.parallelepipeds)  // collective: every rank
      whole.group_points = whole_block_groups(part, count, connectivity, m.mesh.x_ref,
                                              d.global_element.data() + first_element, comm);
    if (mine.empty()) continue;
    m.blocks.push_back(element::make_element_block(
        options.formulation,
        material::elastic_constants(material.youngs_modulus, material.poissons_ratio, material.density),
        options.hourglass_coefficient, first_element, count, connectivity, m.mesh.x_ref, law,
        std::move(whole)));
    element::ElementBlock& block = m.blocks.back();
    block_of_part[std::size_t(part.index)] = m.blocks.size() - 1;
    first_element += count;
    steps[2 * p] = element::critical_time_step(block, m.mesh.x_ref);
    if (block.nodes_per_element != 8)
      steps[2 * p + 1] =
          element::current_time_step(block, m.mesh.x_ref, NodalVectors(m.mesh.x_ref.size())).dt;
    // The whole block's colours, each keeping its index (possibly with no chunk here).
    EXDYN_ASSERT(block.chunk_begin.size() == mine.size() + 1);
    block.colours.assign(chunks.colours[std::size_t(part.index)], {});
    for (std::size_t local = 0; local < mine.size(); ++local)
      block.colours[std::size_t(chunks.colour[part.first_chunk + mine[local]])].push_back(
          std::uint32_t(local));
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, steps.data(), int(steps.size()), MPI_DOUBLE, MPI_MIN, comm.comm),
             "MPI_Allreduce of the blocks' stable steps");
  setup.critical_dt = std::numeric_limits<double>::infinity();  // critical_time_step of the whole model
  for (std::size_t p = 0; p < deck_parts.list.size(); ++p) {
    setup.critical_dt = std::min(setup.critical_dt, steps[2 * p]);
    if (block_of_part[p] != ~std::size_t{0} && m.blocks[block_of_part[p]].nodes_per_element != 8)
      m.blocks[block_of_part[p]].step_scale = steps[2 * p] / steps[2 * p + 1];
  }
  split_colour_steps(my_chunks, m, d);

  // Masses of the rank's nodes; the owned ones count in the energies.
  m.mass = masses_of(deck, deck_parts, d.global_node);
  m.inverse_mass.resize(local_nodes);
  m.counted_mass.resize(local_nodes);
  for (std::size_t i = 0; i < local_nodes; ++i) {
    EXDYN_ASSERT(m.mass[i] > 0.0);
    m.inverse_mass[i] = 1.0 / m.mass[i];
    m.counted_mass[i] = d.owned[i] != 0 ? m.mass[i] : 0.0;
  }
  m.fixed_nodes = fixed_of(deck, deck_parts, d.global_node);
  if (!deck.loads.empty()) {  // build_model's gravity, node by node
    m.load_acceleration.resize(local_nodes);
    for (const input::LoadOptions& load : deck.loads)
      for (std::size_t i = 0; i < local_nodes; ++i) {
        const int p = deck_parts.part_of_node(d.global_node[i]).index;
        if (!load.parts.empty() && std::find(load.parts.begin(), load.parts.end(), p) == load.parts.end())
          continue;
        for (int c = 0; c < 3; ++c) m.load_acceleration.component(c)[i] += load.gravity[std::size_t(c)];
      }
  }
  run.initial_velocity = initial_velocities(deck_parts, d.global_node, m);

  // The output rows: a node's owner is the lowest rank of the chunks around it.
  std::vector<std::uint32_t> owned, elements(d.global_element.size());
  for (std::size_t i = 0; i < local_nodes; ++i)
    if (d.owned[i] != 0) owned.push_back(std::uint32_t(i));
  std::iota(elements.begin(), elements.end(), 0u);
  d.node_rows = row_exchange(
      comm, d.global_nodes,
      [&](std::size_t g) {
        return owner_of_node(deck_parts.part_of_node(std::uint32_t(g)), std::uint32_t(g), chunks);
      },
      std::move(owned), d.global_node);
  d.element_rows = row_exchange(
      comm, d.global_elements,
      [&](std::size_t e) {
        const SetupPart& part = deck_parts.part_of_element(e);
        return chunks.rank[part.first_chunk + (e - part.first_element) / chunk_size];
      },
      std::move(elements), d.global_element);

  // The contact faces near this rank: their model, and the ranks holding each of
  // their nodes held here.
  const NearRank near{d.global_node, m};
  SurfaceModel surfaces = surface_model(deck, deck_parts, &near);
  setup.surface_nodes = std::move(surfaces.nodes);
  setup.surfaces = std::move(surfaces.model);
  setup.surface_held = std::move(surfaces.held);
  for (std::size_t k = 0; k < setup.surface_nodes.size(); ++k) {
    if (setup.surface_held[k] == 0) continue;
    const std::uint32_t g = setup.surface_nodes[k];
    setup.contact_nodes.push_back(g);
    std::vector<int>& holders = run.contact_holders.emplace_back();
    for (const std::size_t c : chunks_at(deck_parts.part_of_node(g), g)) holders.push_back(chunks.rank[c]);
    std::sort(holders.begin(), holders.end());
    holders.erase(std::unique(holders.begin(), holders.end()), holders.end());
  }
  return setup;
}

// Each chunk's seconds a step (chunk_costs' figures) from a first setup of the parts:
// its elements at their block's cost per element, timed on the ranks' parts (the least
// over the ranks holding one), and the slave points of its nodes at their pass's cost
// per point, timed on the contact faces near each rank (the least over the ranks with
// points). Collective over comm.
std::vector<double> measured_costs(const input::Deck& deck, const mpi::Communicator& comm,
                                   const SetupParts& deck_parts, const Chunks& chunks,
                                   const RankSetup& trial) {
  const double dt = time_stepping(deck.time, trial.critical_dt).dt;
  const Model& m = trial.run.model;
  const Decomposition& d = trial.run.decomposition;
  std::vector<double> part_cost(deck_parts.list.size(), std::numeric_limits<double>::infinity());
  const std::vector<double> block_cost = element_costs(m, dt);
  for (std::size_t b = 0; b < m.blocks.size(); ++b)
    part_cost[std::size_t(deck_parts.part_of_element(d.global_element[m.blocks[b].first_element]).index)] =
        block_cost[b];
  mpi::check(
      MPI_Allreduce(MPI_IN_PLACE, part_cost.data(), int(part_cost.size()), MPI_DOUBLE, MPI_MIN, comm.comm),
      "MPI_Allreduce of the element costs");
  const ContactModel contact =
      build_contact(deck, trial.surfaces, dt, trial.critical_dt, contact_scope(trial, comm));  // faces' ids
  std::vector<double> pass_cost = contact_costs(
      trial.surfaces, contact, initial_velocities(deck_parts, trial.surface_nodes, trial.surfaces));
  {
    std::size_t k = 0;  // a rank without points of a pass has no figure for it
    for (const ContactPair& pair : contact.pairs)
      for (const contact::ContactSurfaces& pass : pair.passes)
        if (pass.point_count() == 0)
          pass_cost[k++] = std::numeric_limits<double>::infinity();
        else
          ++k;
    for (const RigidWall& wall : contact.walls)
      if (wall.surfaces.point_count() == 0)
        pass_cost[k++] = std::numeric_limits<double>::infinity();
      else
        ++k;
  }
  if (!pass_cost.empty())
    mpi::check(
        MPI_Allreduce(MPI_IN_PLACE, pass_cost.data(), int(pass_cost.size()), MPI_DOUBLE, MPI_MIN, comm.comm),
        "MPI_Allreduce of the contact costs");
  for (double& c : pass_cost)
    if (std::isinf(c)) c = 0.0;

  // Each point counted by one rank: the rank of the first chunk holding its node, into
  // that chunk (the last slot takes the points counted elsewhere).
  std::vector<double> points(chunks.weight.size() + 1, 0.0);
  add_point_costs(
      contact, pass_cost,
      [&](std::uint32_t face_node) {
        if (trial.surface_held[face_node] == 0) return chunks.weight.size();
        const std::uint32_t g = trial.surface_nodes[face_node];
        const std::size_t c = chunks_at(deck_parts.part_of_node(g), g).front();
        return chunks.rank[c] == comm.rank ? c : chunks.weight.size();
      },
      points);
  mpi::check(
      MPI_Allreduce(MPI_IN_PLACE, points.data(), int(chunks.weight.size()), MPI_DOUBLE, MPI_SUM, comm.comm),
      "MPI_Allreduce of the contact costs of the chunks");
  std::vector<double> cost(chunks.weight.size());
  for (std::size_t c = 0; c < cost.size(); ++c)
    cost[c] = part_cost[chunks.block_of[c]] * chunks.weight[c] + points[c];
  return cost;
}

}  // namespace

RankSetup set_up_rank(const input::Deck& deck, const mpi::Communicator& comm, Partitioning partitioning,
                      bool weigh_by_work) {
  // The memory check with this machine's share of the model.
  MPI_Comm here = MPI_COMM_NULL;
  mpi::check(MPI_Comm_split_type(comm.comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &here),
             "MPI_Comm_split_type of the ranks on this machine");
  int ranks_here = 1;
  MPI_Comm_size(here, &ranks_here);
  MPI_Comm_free(&here);
  check_mesh_size(deck, MachineShare{comm.size, ranks_here});

  // Rank 0 reads each Gmsh file once, for all the parts it holds.
  std::map<std::string, input::GmshMesh> files;
  auto read = [&](const std::string& file, const SourceLocation& where, const std::string& key_path) {
    auto known = files.find(file);
    if (known == files.end()) known = files.emplace(file, input::read_gmsh(file, where, key_path)).first;
    return known->second;
  };
  SetupParts deck_parts(deck, read, &comm);
  files.clear();  // the files, once the parts are made
  Chunks chunks = walk_chunks(deck_parts, &comm);
  chunks.rank = partition_parts(deck_parts, chunks, comm.size, partitioning, &comm);
  if (weigh_by_work) {  // a first setup by elements, timed, then the chunks weighed by their costs
    scatter_pieces(deck_parts, chunks, comm);
    const std::vector<double> costs = measured_costs(
        deck, comm, deck_parts, chunks, build_part(deck, comm, deck_parts, chunks, partitioning));
    weigh_by_costs(chunks.weight, costs);
    chunks.rank = partition_parts(deck_parts, chunks, comm.size, partitioning, &comm);
  }
  chunks.centroid = {};
  scatter_pieces(deck_parts, chunks, comm);
  RankSetup setup = build_part(deck, comm, deck_parts, chunks, partitioning);
  setup.run.decomposition.weighed_by_work = weigh_by_work;
  return setup;
}

SetupChunks setup_chunks(const input::Deck& deck, int ranks, Partitioning partitioning) {
  const SetupParts deck_parts(deck);
  const Chunks chunks = walk_chunks(deck_parts);
  return {chunks.colour, partition_parts(deck_parts, chunks, ranks, partitioning)};
}

std::vector<double> setup_masses(const input::Deck& deck, const std::vector<std::uint32_t>& nodes) {
  return masses_of(deck, SetupParts(deck), nodes);
}

std::pair<std::vector<std::uint32_t>, Model> contact_faces_model(const input::Deck& deck) {
  SurfaceModel whole = surface_model(deck, SetupParts(deck), nullptr);
  return {std::move(whole.nodes), std::move(whole.model)};
}

RankSetup contact_faces_near(const input::Deck& deck, const std::vector<std::uint32_t>& nodes,
                             const Model& model) {
  const NearRank near{nodes, model};
  SurfaceModel surfaces = surface_model(deck, SetupParts(deck), &near);
  RankSetup setup;
  setup.surface_nodes = std::move(surfaces.nodes);
  setup.surfaces = std::move(surfaces.model);
  setup.surface_held = std::move(surfaces.held);
  return setup;
}

ContactScope contact_scope(const RankSetup& setup, const mpi::Communicator& comm) {
  ContactScope scope;
  scope.held = &setup.surface_held;
  scope.largest = [comm](double figure) {
    mpi::check(MPI_Allreduce(MPI_IN_PLACE, &figure, 1, MPI_DOUBLE, MPI_MAX, comm.comm),
               "MPI_Allreduce of a contact figure");
    return figure;
  };
  return scope;
}

void globalize_contact(ContactModel& contact, const std::vector<std::uint32_t>& surface_nodes) {
  auto ids = [&](std::vector<std::uint32_t>& nodes) {
    for (std::uint32_t& n : nodes) n = surface_nodes[n];
  };
  auto segments = [&](std::vector<contact::SegmentNodes>& list) {
    for (contact::SegmentNodes& s : list)
      for (int k = 0; k < contact::node_count(s.type); ++k)
        s.nodes[std::size_t(k)] = surface_nodes[s.nodes[std::size_t(k)]];
  };
  auto surfaces = [&](contact::ContactSurfaces& s) {
    ids(s.slave_nodes);
    ids(s.moving_nodes);
    segments(s.slave_segments);
    segments(s.segments);
  };
  for (ContactPair& pair : contact.pairs)
    for (contact::ContactSurfaces& s : pair.passes) surfaces(s);
  for (RigidWall& wall : contact.walls) surfaces(wall.surfaces);
  ids(contact.nodes);
}

}  // namespace exdyn::solver
