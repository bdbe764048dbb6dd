#include "mesh/mapped.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/errors.hpp"
#include "mesh/mapped_blocks.hpp"

namespace exdyn::mesh {

using namespace mapped;

namespace {

// Merges coincident points: a point within `tolerance` of one seen before gets its id.
// Only the points of the blocks' boundaries can meet (blocks meet along whole faces),
// so the points inside a block take new ids without entering the hash (`add`): it
// then holds the blocks' faces, not their volume.
class PointMerger {
 public:
  explicit PointMerger(double tolerance) : tolerance_(tolerance) {}
  std::uint32_t add(const Point& x) {
    points_.push_back(x);
    return static_cast<std::uint32_t>(points_.size() - 1);
  }
  std::uint32_t id(const Point& x) {
    const std::array<long long, 3> cell{std::llround(x[0] / tolerance_ / 8.0),
                                        std::llround(x[1] / tolerance_ / 8.0),
                                        std::llround(x[2] / tolerance_ / 8.0)};
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto found = cells_.find(key({cell[0] + dx, cell[1] + dy, cell[2] + dz}));
          if (found == cells_.end()) continue;
          for (std::uint32_t candidate : found->second) {
            const Point& y = points_[candidate];
            if (std::abs(x[0] - y[0]) <= tolerance_ && std::abs(x[1] - y[1]) <= tolerance_ &&
                std::abs(x[2] - y[2]) <= tolerance_)
              return candidate;
          }
        }
    const auto id = static_cast<std::uint32_t>(points_.size());
    points_.push_back(x);
    cells_[key(cell)].push_back(id);
    return id;
  }
  const std::vector<Point>& points() const { return points_; }

 private:
  static std::uint64_t key(const std::array<long long, 3>& c) {
    return (static_cast<std::uint64_t>(c[0]) * 0x9e3779b97f4a7c15ULL) ^
           (static_cast<std::uint64_t>(c[1]) * 0xc2b2ae3d27d4eb4fULL) ^
           (static_cast<std::uint64_t>(c[2]) * 0x165667b19e3779f9ULL);
  }
  double tolerance_;
  std::vector<Point> points_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace

std::uint64_t mapped_element_count(const input::PartOptions& o) {
  const std::uint64_t na = std::uint64_t(o.elements[0]), nr = std::uint64_t(o.elements[1]);
  std::uint64_t count = o.geometry == input::Geometry::cylinder
                            ? (na * na + 4 * na * nr) * std::uint64_t(o.elements[2])
                            : na * na * na + 6 * na * na * nr;
  for (const int keep : o.keep)
    if (keep != 0) count /= 2;  // each cut runs through the middle of the symmetric layout
  return count;
}

void add_mapped_part(Mesh& mesh, const input::PartOptions& options, int part_index) {
  const bool cylinder = options.geometry == input::Geometry::cylinder;
  const int order = input::is_quadratic(options.formulation) ? 2 : 1;
  const int nodes_per_element = order == 2 ? 20 : 8;
  auto to_global = [&](const Point& local) { return mapped::to_global(options, local); };
  const std::vector<Block> blocks = cylinder ? cylinder_blocks(options) : sphere_blocks(options);

  // Every lattice point of every block (order 2: those with at most one odd index),
  // merged across the blocks' shared faces; then the elements.
  PointMerger merger(1e-9 * options.radius);
  std::vector<std::array<std::uint32_t, 20>> elements;
  const std::array<int, 20> mirror = mirror_xi();
  for (const Block& block : blocks) {
    std::array<int, 3> size{};
    for (int c = 0; c < 3; ++c) size[std::size_t(c)] = order * block.n[std::size_t(c)] + 1;
    std::vector<std::uint32_t> lattice(static_cast<std::size_t>(size[0]) * static_cast<std::size_t>(size[1]) *
                                           static_cast<std::size_t>(size[2]),
                                       no_node);
    auto at = [&](int i, int j, int k) -> std::uint32_t& {
      return lattice[std::size_t(i) +
                     std::size_t(size[0]) * (std::size_t(j) + std::size_t(size[1]) * std::size_t(k))];
    };
    for (int k = 0; k < size[2]; ++k)
      for (int j = 0; j < size[1]; ++j)
        for (int i = 0; i < size[0]; ++i) {
          if ((i % order) + (j % order) + (k % order) > 1) continue;
          const Point x = to_global(block.at(double(i) / order, double(j) / order, double(k) / order));
          const bool boundary =
              i == 0 || j == 0 || k == 0 || i == size[0] - 1 || j == size[1] - 1 || k == size[2] - 1;
          at(i, j, k) = boundary ? merger.id(x) : merger.add(x);
        }
    for (int k = 0; k < block.n[2]; ++k)
      for (int j = 0; j < block.n[1]; ++j)
        for (int i = 0; i < block.n[0]; ++i) {
          std::array<std::uint32_t, 20> nodes{};
          for (int l = 0; l < nodes_per_element; ++l) {
            const auto& d = brick_offsets[std::size_t(l)];
            nodes[std::size_t(l)] =
                at(order * i + d[0] * order / 2, order * j + d[1] * order / 2, order * k + d[2] * order / 2);
          }
          // A left-handed block map gives a negative Jacobian: mirror the element.
          const auto& x = merger.points();
          auto edge = [&](int from, int to) {
            const Point& a = x[nodes[std::size_t(from)]];
            const Point& b = x[nodes[std::size_t(to)]];
            return Point{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
          };
          const Point e1 = edge(0, 1), e2 = edge(0, 3), e3 = edge(0, 4);
          const double det = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) -
                             e1[1] * (e2[0] * e3[2] - e2[2] * e3[0]) +
                             e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
          if (det < 0.0) {
            std::array<std::uint32_t, 20> mirrored{};
            for (int l = 0; l < nodes_per_element; ++l)
              mirrored[std::size_t(l)] = nodes[std::size_t(mirror[std::size_t(l)])];
            nodes = mirrored;
          }
          elements.push_back(nodes);
        }
  }

  // `keep`: the elements whose centroid lies in every kept half-space (the cuts run
  // along grid planes through the centre, so no centroid lies on a cut).
  const auto& points = merger.points();
  std::vector<std::array<std::uint32_t, 20>> kept;
  for (const auto& nodes : elements) {
    Point centroid{};
    for (int l = 0; l < 8; ++l)
      for (int c = 0; c < 3; ++c)
        centroid[std::size_t(c)] += points[nodes[std::size_t(l)]][std::size_t(c)] / 8.0;
    bool inside = true;
    for (int c = 0; c < 3; ++c)
      if (options.keep[std::size_t(c)] != 0 &&
          options.keep[std::size_t(c)] * (centroid[std::size_t(c)] - options.center[std::size_t(c)]) <= 0.0)
        inside = false;
    if (inside) kept.push_back(nodes);
  }
  EXDYN_ASSERT(kept.size() == mapped_element_count(options));

  // The nodes the kept elements use, numbered in the order they were made.
  std::vector<std::uint32_t> new_id(points.size(), no_node);
  for (const auto& nodes : kept)
    for (int l = 0; l < nodes_per_element; ++l) new_id[nodes[std::size_t(l)]] = 0;
  PartRange part;
  part.elements = options.elements;
  part.order = order;
  part.nodes_per_element = nodes_per_element;
  part.first_node = static_cast<std::uint32_t>(mesh.node_count());
  part.first_element = static_cast<std::uint32_t>(mesh.element_count());
  part.first_connectivity = mesh.connectivity.size();
  std::uint32_t next = part.first_node;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (new_id[i] == no_node) continue;
    new_id[i] = next++;
    mesh.x_ref.x.push_back(points[i][0]);
    mesh.x_ref.y.push_back(points[i][1]);
    mesh.x_ref.z.push_back(points[i][2]);
  }
  part.node_count = next - part.first_node;
  part.element_count = static_cast<std::uint32_t>(kept.size());
  for (auto& nodes : kept) {
    for (int l = 0; l < nodes_per_element; ++l) {
      nodes[std::size_t(l)] = new_id[nodes[std::size_t(l)]];
      mesh.connectivity.push_back(nodes[std::size_t(l)]);
    }
    mesh.element_part.push_back(part_index);
  }

  // The boundary faces (element faces no other element shares), named by where they lie.
  const NodalVectors& x = mesh.x_ref;
  std::vector<OuterSegment> boundary;
  for (const BoundarySegment& b : boundary_segments(kept, nodes_per_element, x)) {
    OuterSegment& outer = boundary.emplace_back();
    outer.segment = b.segment;
    for (std::size_t k = 0; k < 4; ++k) outer.corners[k] = x.at(b.segment.nodes[k]);
    outer.normal_length = b.normal_length;
  }
  std::vector<std::pair<input::PartFace, Face>> faces = named_faces(options, part_index, boundary);
  part.faces = std::move(faces);
  mesh.parts.push_back(std::move(part));
}

}  // namespace exdyn::mesh
