#include "mesh/imported.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <vector>

#include "mesh/face_sides.hpp"

namespace exdyn::mesh {

namespace {

using Point = std::array<double, 3>;

bool is_tetrahedron(int type) { return type == 4 || type == 11 || type == 29 || type == 30 || type == 31; }
bool is_prism(int type) { return type == 6 || type == 13 || type == 18 || type == 90 || type == 91; }
bool is_pyramid(int type) { return type == 7 || type == 14 || type == 19 || type == 118 || type == 119; }

std::string plural(std::size_t count, const std::string& what) {
  return std::to_string(count) + " " + what + (count == 1 ? "" : "s");
}

using Brick = std::array<std::uint32_t, 20>;

// The 24 rotations of the brick as permutations of its local nodes: a brick rotated by
// r has node v = the old node rotations[r][v]. Each is a signed permutation of the axes
// with determinant +1 acting on the offsets (brick_offsets, about the centre 1, 1, 1),
// so a rotated brick keeps its positive orientation.
std::vector<std::array<int, 20>> brick_rotations() {
  std::vector<std::array<int, 20>> rotations;
  const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const int parity[6] = {1, -1, -1, 1, 1, -1};
  for (int a = 0; a < 6; ++a)
    for (int signs = 0; signs < 8; ++signs) {
      const int sign[3] = {signs & 1 ? -1 : 1, signs & 2 ? -1 : 1, signs & 4 ? -1 : 1};
      if (parity[a] * sign[0] * sign[1] * sign[2] != 1) continue;
      std::array<int, 20> permutation{};
      for (int v = 0; v < 20; ++v) {
        std::array<int, 3> d{};
        for (int c = 0; c < 3; ++c)
          d[std::size_t(c)] = 1 + sign[c] * (brick_offsets[std::size_t(v)][std::size_t(axes[a][c])] - 1);
        for (int u = 0; u < 20; ++u)
          if (brick_offsets[std::size_t(u)] == d) permutation[std::size_t(v)] = u;
      }
      rotations.push_back(permutation);
    }
  return rotations;
}

// The opposite face of each face of brick_faces: bottom-top, front-back, right-left.
constexpr int opposite_face[6] = {1, 0, 4, 5, 2, 3};

// The elements in rows for the packed kernels (docs/performance.md): chains of
// elements joined through opposite faces, each element turned so that the chain runs
// along its xi axis (its face 5 on the previous element's face 3), as the x-rows of a
// built-in box. A chain starts from the first element not yet in one, in Hilbert order
// of the centroids, and runs both ways along that element's axis with the most
// elements (of equal ones, the axis nearest x), from its end at lower x (y, z); its
// first element is turned so that eta and zeta run as near y and z as the row allows,
// and the others follow it. On an axis-aligned box this is the built-in lattice's
// orientation, whose elements take the axis-aligned kernel. Returns the elements
// (turned) in chain order; `chains` gets each chain's first position.
std::vector<Brick> elements_in_rows(const std::vector<Brick>& elements, const std::vector<std::size_t>& seeds,
                                    int nodes_per_element, const std::function<Point(std::uint32_t)>& at,
                                    std::vector<std::size_t>& chains) {
  const std::size_t count = elements.size();
  // Each element face's neighbour across it: 6 e + f, or none.
  constexpr std::uint64_t none = ~std::uint64_t{0};
  std::vector<std::uint64_t> neighbour(6 * count, none);
  {
    std::vector<std::pair<std::array<std::uint32_t, 4>, std::uint64_t>> faces;
    faces.reserve(6 * count);
    for (std::size_t e = 0; e < count; ++e)
      for (int f = 0; f < 6; ++f) {
        std::array<std::uint32_t, 4> corners{};
        for (int k = 0; k < 4; ++k) corners[std::size_t(k)] = elements[e][std::size_t(brick_faces[f][k])];
        std::sort(corners.begin(), corners.end());
        faces.emplace_back(corners, 6 * std::uint64_t(e) + std::uint64_t(f));
      }
    std::sort(faces.begin(), faces.end());
    for (std::size_t i = 0; i + 1 < faces.size(); ++i)
      if (faces[i].first == faces[i + 1].first &&
          (i + 2 == faces.size() || faces[i + 2].first != faces[i].first) &&
          (i == 0 || faces[i - 1].first != faces[i].first)) {
        neighbour[faces[i].second] = faces[i + 1].second;
        neighbour[faces[i + 1].second] = faces[i].second;
      }
  }
  const std::vector<std::array<int, 20>> rotations = brick_rotations();
  std::vector<char> placed(count, 0);
  // The walk that last passed each element (walks are numbered from 0 up, never reused).
  std::vector<std::size_t> stamp(count, ~std::size_t{0});
  // Steps from e out through face f (then on through the opposite of each entry face)
  // over elements not placed; calls visit(element, entry face) for each.
  auto walk = [&](std::size_t e, int f, std::size_t walk_id, auto visit) {
    stamp[e] = walk_id;
    std::uint64_t across = neighbour[6 * e + std::size_t(f)];
    while (across != none) {
      const std::size_t next = std::size_t(across / 6);
      const int entry = int(across % 6);
      if (placed[next] || stamp[next] == walk_id) break;
      stamp[next] = walk_id;
      visit(next, entry);
      across = neighbour[6 * next + std::size_t(opposite_face[entry])];
    }
  };
  std::vector<Brick> result;
  result.reserve(count);
  std::size_t walks = 0;
  // The direction from an element's centroid to a face's, and its leaning towards x,
  // then y, then z.
  auto outward = [&](const Brick& nodes, int f) {
    Point d{};
    for (int k = 0; k < 8; ++k) {
      const Point p = at(nodes[std::size_t(k)]);
      for (std::size_t c = 0; c < 3; ++c) d[c] -= p[c] / 8.0;
    }
    for (int k = 0; k < 4; ++k) {
      const Point p = at(nodes[std::size_t(brick_faces[f][k])]);
      for (std::size_t c = 0; c < 3; ++c) d[c] += p[c] / 4.0;
    }
    return d;
  };
  auto unit = [](const Point& d) {
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    return Point{d[0] / length, d[1] / length, d[2] / length};
  };
  for (const std::size_t seed : seeds) {
    if (placed[seed]) continue;
    // The axis with the most elements not yet placed; of equal ones, the nearest x.
    int exit = 3;
    std::size_t longest = 0;
    double along_x = -1.0;
    for (const int f : {3, 4, 1}) {
      std::size_t length = 1;
      const std::size_t id = walks++;
      walk(seed, f, id, [&](std::size_t, int) { ++length; });
      walk(seed, opposite_face[f], id, [&](std::size_t, int) { ++length; });
      const Point d = unit(outward(elements[seed], f));
      if (length > longest || (length == longest && std::abs(d[0]) > along_x)) {
        longest = length, along_x = std::abs(d[0]);
        // Towards +x (else +y, else +z): the row runs from its lower end.
        const double lean = d[0] + 1e-3 * d[1] + 1e-6 * d[2];
        exit = lean >= 0.0 ? f : opposite_face[f];
      }
    }
    // Back to the chain's first element: its face toward the seed is its exit.
    std::size_t first = seed;
    int first_exit = exit;
    walk(seed, opposite_face[exit], walks++,
         [&](std::size_t e, int entry) { first = e, first_exit = entry; });
    // Forward, each element turned to continue the previous one's row.
    chains.push_back(result.size());
    std::size_t e = first;
    int out = first_exit;
    bool start = true;
    while (true) {
      const Brick& old = elements[e];
      const Brick* previous = start ? nullptr : &result.back();
      const std::array<int, 20>* turn = nullptr;
      double best_alignment = -1e300;
      for (const auto& r : rotations) {
        bool fits = true;
        if (previous == nullptr) {  // the exit face becomes face 3 (xi = +1): nodes 1, 2, 6, 5
          for (const int v : {1, 2, 6, 5})
            fits = fits && std::count(brick_faces[out], brick_faces[out] + 4, r[std::size_t(v)]) == 1;
          if (!fits) continue;
          // Of the four turns about xi, the one with eta nearest y and zeta nearest z.
          auto edge = [&](int from, int to) {
            const Point a = at(old[std::size_t(r[std::size_t(from)])]),
                        b = at(old[std::size_t(r[std::size_t(to)])]);
            return unit(Point{b[0] - a[0], b[1] - a[1], b[2] - a[2]});
          };
          const double alignment = edge(0, 3)[1] + edge(0, 4)[2];
          if (alignment > best_alignment) best_alignment = alignment, turn = &r;
          continue;
        }
        // nodes 0, 3, 7, 4 are the previous element's 1, 2, 6, 5
        const int here[4] = {0, 3, 7, 4}, there[4] = {1, 2, 6, 5};
        for (int k = 0; k < 4; ++k)
          fits = fits && old[std::size_t(r[std::size_t(here[k])])] == (*previous)[std::size_t(there[k])];
        if (fits) {
          turn = &r;
          break;
        }
      }
      if (turn == nullptr) break;  // no rotation continues the row: it ends here
      Brick turned{};
      for (int v = 0; v < nodes_per_element; ++v)
        turned[std::size_t(v)] = old[std::size_t((*turn)[std::size_t(v)])];
      result.push_back(turned);
      placed[e] = 1;
      start = false;
      // The next element across the new face 3, which is the old face `out`.
      const std::uint64_t across = neighbour[6 * e + std::size_t(out)];
      if (across == none || placed[std::size_t(across / 6)]) break;
      e = std::size_t(across / 6);
      out = opposite_face[across % 6];
    }
    if (chains.back() == result.size()) chains.pop_back();
    if (!placed[seed]) {  // the seed could not continue a row (an inconsistent neighbour): alone
      chains.push_back(result.size());
      result.push_back(elements[seed]);
      placed[seed] = 1;
    }
  }
  return result;
}

// The order of a face's segments, and of each segment's nodes, from the geometry alone,
// not from the numbering: segments by centroid (z, then y, then x), each segment's
// corners turned (orientation kept) to start at its corner lowest in (z, y, x). The
// contact pass gives a point on the edge between two segments to the first of them, so
// this makes the answer independent of the mesher's numbering and of the reordering;
// on an axis-aligned box it is the built-in faces' order (mesh.cpp, face_of) wherever
// those run z-major, as the faces x = const of a box one element thick in y do.
void in_geometric_order(std::vector<BoundarySegment>& boundary, const NodalVectors& x) {
  auto key = [&](std::uint32_t node) { return std::array<double, 3>{x.z[node], x.y[node], x.x[node]}; };
  std::vector<std::array<double, 3>> centroid(boundary.size());
  for (std::size_t b = 0; b < boundary.size(); ++b) {
    FaceSegment& s = boundary[b].segment;
    int lowest = 0;
    for (int k = 1; k < 4; ++k)
      if (key(s.nodes[std::size_t(k)]) < key(s.nodes[std::size_t(lowest)])) lowest = k;
    FaceSegment turned = s;
    for (int k = 0; k < 4; ++k) {
      turned.nodes[std::size_t(k)] = s.nodes[std::size_t((k + lowest) % 4)];
      if (s.node_count == 8) turned.nodes[std::size_t(4 + k)] = s.nodes[std::size_t(4 + (k + lowest) % 4)];
    }
    s = turned;
    for (int k = 0; k < 4; ++k)
      for (std::size_t c = 0; c < 3; ++c) centroid[b][c] += 0.25 * key(s.nodes[std::size_t(k)])[c];
  }
  std::vector<std::size_t> order(boundary.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return centroid[a] < centroid[b]; });
  std::vector<BoundarySegment> sorted;
  sorted.reserve(boundary.size());
  for (const std::size_t b : order) sorted.push_back(boundary[b]);
  boundary = std::move(sorted);
}

}  // namespace

std::uint64_t hilbert_index(const std::array<double, 3>& unit_point) {
  // Skilling, "Programming the Hilbert curve", AIP Conf. Proc. 707 (2004): the axes to
  // the transposed Hilbert index, then its bits interleaved, most significant first.
  constexpr int bits = 21;
  std::array<std::uint32_t, 3> x{};
  for (std::size_t c = 0; c < 3; ++c) {
    const double scaled = std::clamp(unit_point[c], 0.0, 1.0) * double((1u << bits) - 1);
    x[c] = static_cast<std::uint32_t>(scaled);
  }
  for (std::uint32_t q = 1u << (bits - 1); q > 1; q >>= 1) {
    const std::uint32_t p = q - 1;
    for (std::size_t i = 0; i < 3; ++i) {
      if (x[i] & q) {
        x[0] ^= p;  // invert
      } else {      // exchange
        const std::uint32_t t = (x[0] ^ x[i]) & p;
        x[0] ^= t;
        x[i] ^= t;
      }
    }
  }
  for (std::size_t i = 1; i < 3; ++i) x[i] ^= x[i - 1];  // Gray encode
  std::uint32_t t = 0;
  for (std::uint32_t q = 1u << (bits - 1); q > 1; q >>= 1)
    if (x[2] & q) t ^= q - 1;
  for (std::uint32_t& v : x) v ^= t;
  std::uint64_t index = 0;
  for (int bit = bits - 1; bit >= 0; --bit)
    for (std::size_t i = 0; i < 3; ++i) index = (index << 1) | ((x[i] >> bit) & 1u);
  return index;
}

void add_imported_part(Mesh& mesh, const input::PartOptions& options, int part_index,
                       const input::GmshMesh& file, const SourceLocation& where,
                       const std::string& key_path) {
  auto fail = [&](const std::string& message) { throw InputError(where, key_path, message); };
  const std::string in_file = " of '" + file.file + "'";
  const input::GmshGroup* volume = nullptr;
  for (const input::GmshGroup& group : file.volumes)
    if (group.name == options.mesh.volume) volume = &group;
  if (volume == nullptr) fail("no physical volume '" + options.mesh.volume + "'" + in_file);
  const std::string volume_text = "the physical volume '" + volume->name + "'" + in_file;

  // Only hexahedra of the formulation's node count.
  const bool quadratic = input::is_quadratic(options.formulation);
  const int wanted = quadratic ? input::gmsh_type::hex20 : input::gmsh_type::hex8;
  std::vector<std::string> others;
  std::size_t hex8 = 0, hex20 = 0;
  for (const input::GmshElements& block : volume->elements) {
    if (block.type == input::gmsh_type::hex8) hex8 += block.tags.size();
    if (block.type == input::gmsh_type::hex20) hex20 += block.tags.size();
    if (block.type == input::gmsh_type::hex8 || block.type == input::gmsh_type::hex20) continue;
    std::string kind = "elements";
    if (is_tetrahedron(block.type)) kind = "tetrahedra";
    if (is_prism(block.type)) kind = "prisms";
    if (is_pyramid(block.type)) kind = "pyramids";
    if (block.type == 12) kind = "27-node hexahedra";
    others.push_back(std::to_string(block.tags.size()) + " " + kind + " ('" + block.name + "', Gmsh type " +
                     std::to_string(block.type) + ")");
  }
  if (!others.empty()) {
    std::string list;
    for (const std::string& other : others) list += (list.empty() ? "" : ", ") + other;
    fail(volume_text + " has " + list +
         ": a part takes only 8-node hexahedra (hex8, hex8r) or 20-node ones (hex20, hex20r); mesh it with "
         "hexahedra (Recombine, Transfinite), and for 20 nodes with Mesh.SecondOrderIncomplete = 1");
  }
  if (hex8 > 0 && hex20 > 0)
    fail(volume_text + " mixes " + plural(hex8, "8-node hexahedron") + " and " +
         plural(hex20, "20-node hexahedron") + ": a part's elements all have the same nodes");
  if (hex8 + hex20 == 0) fail(volume_text + " has no elements");
  if ((quadratic && hex8 > 0) || (!quadratic && hex20 > 0))
    fail(volume_text + " has " + (hex8 > 0 ? "8" : "20") + "-node hexahedra, but the part's formulation " +
         input::name(options.formulation) + " takes " + (quadratic ? "20" : "8") + "-node ones" +
         (quadratic ? " (gmsh -3 -order 2 with Mesh.SecondOrderIncomplete = 1)" : " (gmsh -3 -order 1)"));

  // The file's nodes by tag.
  const std::size_t file_nodes = file.node_tags.size();
  if (file.coordinates.size() != 3 * file_nodes)
    fail("'" + file.file + "' gives " + std::to_string(file.coordinates.size()) + " coordinates for " +
         plural(file_nodes, "node"));
  std::unordered_map<std::size_t, std::uint32_t> index_of_tag;
  index_of_tag.reserve(file_nodes);
  for (std::size_t i = 0; i < file_nodes; ++i)
    if (!index_of_tag.emplace(file.node_tags[i], static_cast<std::uint32_t>(i)).second)
      fail("'" + file.file + "' has node tag " + std::to_string(file.node_tags[i]) + " twice");
  auto file_point = [&](std::uint32_t i) {
    return Point{file.coordinates[3 * std::size_t(i)], file.coordinates[3 * std::size_t(i) + 1],
                 file.coordinates[3 * std::size_t(i) + 2]};
  };

  // Elements in VTK order (file node indices), each checked.
  const int nodes_per_element = quadratic ? 20 : 8;
  std::vector<Brick> elements;
  std::vector<std::size_t> element_tags;  // Gmsh's, for messages
  for (const input::GmshElements& block : volume->elements) {
    if (block.type != wanted) continue;
    if (block.nodes.size() != std::size_t(nodes_per_element) * block.tags.size())
      fail(volume_text + ": " + plural(block.tags.size(), "element") + " with " +
           std::to_string(block.nodes.size()) + " node tags");
    for (std::size_t e = 0; e < block.tags.size(); ++e) {
      const std::string element_text = "element " + std::to_string(block.tags[e]) + " of " + volume_text;
      std::array<std::uint32_t, 20> nodes{};
      for (int v = 0; v < nodes_per_element; ++v) {
        const int g = quadratic ? gmsh_hex20_node[std::size_t(v)] : v;
        const std::size_t tag = block.nodes[std::size_t(nodes_per_element) * e + std::size_t(g)];
        const auto found = index_of_tag.find(tag);
        if (found == index_of_tag.end())
          fail(element_text + " names node " + std::to_string(tag) + ", which the file does not have");
        nodes[std::size_t(v)] = found->second;
      }
      std::array<std::uint32_t, 20> sorted = nodes;
      std::sort(sorted.begin(), sorted.begin() + nodes_per_element);
      if (const auto twice = std::adjacent_find(sorted.begin(), sorted.begin() + nodes_per_element);
          twice != sorted.begin() + nodes_per_element)
        fail(element_text + " is degenerate: node " + std::to_string(file.node_tags[*twice]) +
             " is two of its nodes");
      for (int v = 0; v < nodes_per_element; ++v)
        for (const double c : file_point(nodes[std::size_t(v)]))
          if (!std::isfinite(c))
            fail(element_text + " has node " + std::to_string(file.node_tags[nodes[std::size_t(v)]]) +
                 " at a coordinate that is not a finite number");
      // The trilinear corner map's Jacobian at each corner: det[e_xi, e_eta, e_zeta] of
      // the edges from the corner towards the next corner along each direction (m^3).
      // Not positive: the element is inverted or flat there.
      constexpr int along[8][3] = {{1, 3, 4}, {0, 2, 5}, {3, 1, 6}, {2, 0, 7},
                                   {5, 7, 0}, {4, 6, 1}, {7, 5, 2}, {6, 4, 3}};
      constexpr double sign[8] = {1, -1, 1, -1, -1, 1, -1, 1};  // the edges' handedness at each corner
      for (int corner = 0; corner < 8; ++corner) {
        const Point o = file_point(nodes[std::size_t(corner)]);
        Point edge[3];
        for (int a = 0; a < 3; ++a) {
          const Point p = file_point(nodes[std::size_t(along[corner][a])]);
          for (std::size_t c = 0; c < 3; ++c) edge[a][c] = p[c] - o[c];
        }
        const double det = sign[corner] * (edge[0][0] * (edge[1][1] * edge[2][2] - edge[1][2] * edge[2][1]) -
                                           edge[0][1] * (edge[1][0] * edge[2][2] - edge[1][2] * edge[2][0]) +
                                           edge[0][2] * (edge[1][0] * edge[2][1] - edge[1][1] * edge[2][0]));
        if (!(det > 0.0))
          fail(element_text + " is " + (det < 0.0 ? "inverted" : "degenerate") +
               ": the Jacobian at its corner node " +
               std::to_string(file.node_tags[nodes[std::size_t(corner)]]) + " is " +
               (det < 0.0 ? "negative" : "zero") +
               " (Gmsh's hexahedron numbers its bottom corners counter-clockwise seen from the top)");
      }
      elements.push_back(nodes);
      element_tags.push_back(block.tags[e]);
    }
  }

  // Two elements on the same nodes overlap (a mesh merged twice): each face of one
  // would be shared with the other and the body would have no boundary.
  {
    std::vector<std::pair<Brick, std::size_t>> sorted;
    sorted.reserve(elements.size());
    for (std::size_t e = 0; e < elements.size(); ++e) {
      Brick key = elements[e];
      std::sort(key.begin(), key.begin() + nodes_per_element);
      sorted.emplace_back(key, e);
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i + 1 < sorted.size(); ++i)
      if (sorted[i].first == sorted[i + 1].first)
        fail("elements " + std::to_string(element_tags[sorted[i].second]) + " and " +
             std::to_string(element_tags[sorted[i + 1].second]) + " of " + volume_text +
             " have the same nodes: they overlap (is the mesh in the file twice?)");
  }

  // Element order: in rows seeded along a Hilbert curve through the centroids (in the
  // volume's bounding box, one scale for the three axes so that the curve's cells are
  // cubes), or the file's.
  std::vector<Brick> ordered = elements;
  std::vector<std::size_t> chains;
  if (options.mesh.reorder) {
    Point low{}, high{};
    low.fill(std::numeric_limits<double>::infinity());
    high.fill(-std::numeric_limits<double>::infinity());
    std::vector<Point> centroid(elements.size());
    for (std::size_t e = 0; e < elements.size(); ++e) {
      for (int v = 0; v < 8; ++v) {
        const Point p = file_point(elements[e][std::size_t(v)]);
        for (std::size_t c = 0; c < 3; ++c) centroid[e][c] += p[c] / 8.0;
      }
      for (std::size_t c = 0; c < 3; ++c) {
        low[c] = std::min(low[c], centroid[e][c]);
        high[c] = std::max(high[c], centroid[e][c]);
      }
    }
    const double extent = std::max({high[0] - low[0], high[1] - low[1], high[2] - low[2], 0.0});
    std::vector<std::uint64_t> key(elements.size());
    for (std::size_t e = 0; e < elements.size(); ++e) {
      Point unit{};
      for (std::size_t c = 0; c < 3; ++c) unit[c] = extent > 0.0 ? (centroid[e][c] - low[c]) / extent : 0.0;
      key[e] = hilbert_index(unit);
    }
    std::vector<std::size_t> seeds(elements.size());
    std::iota(seeds.begin(), seeds.end(), std::size_t(0));
    std::stable_sort(seeds.begin(), seeds.end(),
                     [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
    ordered = elements_in_rows(elements, seeds, nodes_per_element, file_point, chains);
  }

  // Part node ids: along each row's four lines of corners (0-1-..., 3-2-..., 4-5-...,
  // 7-6-...), each line's nodes consecutive as in a built-in box (so a row's packs
  // load their nodes as vectors), then any other node by first use.
  const std::size_t total_nodes = mesh.node_count() + file_nodes;
  if (total_nodes > std::numeric_limits<std::uint32_t>::max() ||
      mesh.element_count() + elements.size() > std::size_t(std::numeric_limits<std::int32_t>::max()))
    fail("the mesh would pass 4294967295 nodes or 2147483647 elements");
  PartRange part;
  part.order = quadratic ? 2 : 1;
  part.nodes_per_element = nodes_per_element;
  part.first_node = static_cast<std::uint32_t>(mesh.node_count());
  part.first_element = static_cast<std::uint32_t>(mesh.element_count());
  part.first_connectivity = mesh.connectivity.size();
  part.element_count = static_cast<std::uint32_t>(elements.size());
  std::vector<std::uint32_t> part_node(file_nodes, no_node);
  std::uint32_t next = part.first_node;
  auto number = [&](std::uint32_t file_index) {
    std::uint32_t& id = part_node[file_index];
    if (id != no_node) return;
    id = next++;
    const Point p = file_point(file_index);
    mesh.x_ref.x.push_back(p[0]);
    mesh.x_ref.y.push_back(p[1]);
    mesh.x_ref.z.push_back(p[2]);
  };
  chains.push_back(ordered.size());
  for (std::size_t c = 0; c + 1 < chains.size(); ++c)
    for (const auto& [start, along] : {std::pair{0, 1}, std::pair{3, 2}, std::pair{4, 5}, std::pair{7, 6}}) {
      number(ordered[chains[c]][std::size_t(start)]);
      for (std::size_t e = chains[c]; e < chains[c + 1]; ++e) number(ordered[e][std::size_t(along)]);
    }
  std::vector<std::array<std::uint32_t, 20>> numbered;
  numbered.reserve(ordered.size());
  for (const Brick& old : ordered) {
    std::array<std::uint32_t, 20> nodes{};
    for (int v = 0; v < nodes_per_element; ++v) {
      number(old[std::size_t(v)]);
      nodes[std::size_t(v)] = part_node[old[std::size_t(v)]];
      mesh.connectivity.push_back(nodes[std::size_t(v)]);
    }
    mesh.element_part.push_back(part_index);
    numbered.push_back(nodes);
  }
  part.node_count = next - part.first_node;

  // The boundary, whole (surface) and by physical surface.
  std::array<std::uint32_t, 4> non_manifold{};
  std::vector<BoundarySegment> boundary =
      boundary_segments(numbered, nodes_per_element, mesh.x_ref, &non_manifold);
  in_geometric_order(boundary, mesh.x_ref);
  if (non_manifold != std::array<std::uint32_t, 4>{}) {
    std::vector<std::uint32_t> file_index_of(part.node_count);
    for (std::size_t i = 0; i < file_nodes; ++i)
      if (part_node[i] != no_node)
        file_index_of[part_node[i] - part.first_node] = static_cast<std::uint32_t>(i);
    std::string corners;
    for (const std::uint32_t node : non_manifold)
      corners += (corners.empty() ? "" : ", ") +
                 std::to_string(file.node_tags[file_index_of[node - part.first_node]]);
    fail(volume_text + " has a face (corner nodes " + corners +
         ") shared by more than two elements: elements overlap or the mesh is not a manifold");
  }
  if (boundary.empty())  // every face shared by exactly two elements: a closed body
    fail(volume_text + " has no boundary: every face of its " + plural(elements.size(), "element") +
         " is shared by two of them (a mesh that closes on itself, as when its nodes are repeated "
         "periodically)");
  Face whole;
  double whole_length = 0.0;
  std::vector<double> lengths;
  for (const BoundarySegment& b : boundary) {
    whole.segments.push_back(b.segment);
    whole_length += b.normal_length;
    lengths.push_back(b.normal_length);
  }
  finish_face(whole, whole_length);
  whole.sides = fold_sides(whole.segments, lengths, mesh.x_ref);
  part.faces.emplace_back(input::PartFace::surface, std::move(whole));

  std::vector<std::size_t> by_corners(boundary.size());
  std::iota(by_corners.begin(), by_corners.end(), std::size_t(0));
  std::sort(by_corners.begin(), by_corners.end(),
            [&](std::size_t a, std::size_t b) { return boundary[a].corners < boundary[b].corners; });
  for (const std::string& surface_name : options.mesh.surfaces) {
    const input::GmshGroup* surface = nullptr;
    for (const input::GmshGroup& group : file.surfaces)
      if (group.name == surface_name) surface = &group;
    // Which boundary faces the surface's quadrilaterals are, in boundary order.
    std::vector<std::size_t> matched;
    if (surface != nullptr)
      for (const input::GmshElements& block : surface->elements) {
        const int n = block.nodes_per_element;
        if ((block.type != input::gmsh_type::quad4 && block.type != input::gmsh_type::quad8) ||
            block.nodes.size() != std::size_t(n) * block.tags.size())
          continue;  // triangles and the like bound no hexahedron
        for (std::size_t q = 0; q < block.tags.size(); ++q) {
          std::array<std::uint32_t, 4> corners{};
          bool in_part = true;
          for (std::size_t k = 0; k < 4; ++k) {
            const auto found = index_of_tag.find(block.nodes[std::size_t(n) * q + k]);
            in_part = in_part && found != index_of_tag.end() && part_node[found->second] != no_node;
            if (in_part) corners[k] = part_node[found->second];
          }
          if (!in_part) continue;
          std::sort(corners.begin(), corners.end());
          const auto hit = std::lower_bound(by_corners.begin(), by_corners.end(), corners,
                                            [&](std::size_t b, const std::array<std::uint32_t, 4>& key) {
                                              return boundary[b].corners < key;
                                            });
          if (hit != by_corners.end() && boundary[*hit].corners == corners) matched.push_back(*hit);
        }
      }
    std::sort(matched.begin(), matched.end());
    matched.erase(std::unique(matched.begin(), matched.end()), matched.end());
    Face face;
    double length = 0.0;
    lengths.clear();
    for (const std::size_t b : matched) {
      face.segments.push_back(boundary[b].segment);
      length += boundary[b].normal_length;
      lengths.push_back(boundary[b].normal_length);
    }
    if (!face.segments.empty()) finish_face(face, length);
    face.sides = fold_sides(face.segments, lengths, mesh.x_ref);
    part.physical_faces.push_back(std::move(face));
  }
  mesh.parts.push_back(std::move(part));
}

}  // namespace exdyn::mesh
