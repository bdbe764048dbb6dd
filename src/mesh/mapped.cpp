#include "mesh/mapped.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/errors.hpp"

namespace exdyn::mesh {

namespace {

using Point = std::array<double, 3>;

// A structured block of the layout: n elements along its three lattice directions,
// and the map from lattice coordinates (element units; halves for mid-edge points) to
// a point, m. Blocks meet along whole faces; their shared points are merged.
struct Block {
  std::array<int, 3> n{};
  std::function<Point(double, double, double)> at;
};

// cos and sin of (pi / 4) u for u in [-1, 1], odd in u and exact at the ends and the
// middle: u = 0 gives (1, 0) and u = +-1 gives (sqrt(1/2), +-sqrt(1/2)), so the
// diagonals and the symmetry lines of the layout are exact.
std::array<double, 2> quarter_angle(double u) {
  const double a = std::abs(u);
  double c = std::sqrt(0.5), s = c;
  if (a != 1.0) {
    c = std::cos(0.25 * std::numbers::pi * a);
    s = std::sin(0.25 * std::numbers::pi * a);
  }
  return {c, u < 0.0 ? -s : s};
}

// tan((pi / 4) u) for u in [-1, 1], odd in u, exact at 0 and +-1.
double quarter_tan(double u) {
  const double a = std::abs(u);
  const double t = a == 1.0 ? 1.0 : std::tan(0.25 * std::numbers::pi * a);
  return u < 0.0 ? -t : t;
}

// The graded fraction at lattice coordinate t (element units, halves between grid
// points): linear inside an element, so a mid-edge point lies halfway along it.
double fraction_at(double t, int n, double grading) {
  const int k = static_cast<int>(std::floor(t));
  const double a = graded_fraction(k, n, grading);
  if (t == static_cast<double>(k)) return a;
  return a + (t - k) * (graded_fraction(k + 1, n, grading) - a);
}

// (1 - tau) p + tau s, component by component.
std::array<double, 3> blend(const std::array<double, 3>& p, const std::array<double, 3>& s, double tau) {
  return {(1.0 - tau) * p[0] + tau * s[0], (1.0 - tau) * p[1] + tau * s[1], (1.0 - tau) * p[2] + tau * s[2]};
}

// Cylinder layout in local coordinates (p, q) of the cross-section and s along the
// axis; Point = {p, q, s}.
std::vector<Block> cylinder_blocks(const input::PartOptions& o) {
  const int na = o.elements[0], nr = o.elements[1], nz = o.elements[2];
  const double R = o.radius, a = core_fraction * R, L = o.length;
  const double radial_grading = o.grading[1], axial_grading = o.grading[2];
  auto axial = [=](double k) { return L * fraction_at(k, nz, axial_grading); };
  std::vector<Block> blocks;
  blocks.push_back({{na, na, nz}, [=](double i, double j, double k) -> Point {
                      return {a * (2.0 * i / na - 1.0), a * (2.0 * j / na - 1.0), axial(k)};
                    }});
  for (int quarter = 0; quarter < 4; ++quarter)
    blocks.push_back({{na, nr, nz}, [=](double u, double t, double k) -> Point {
                        const double v = 2.0 * u / na - 1.0;  // [-1, 1] along the core's side
                        const auto [c, s] = quarter_angle(v);
                        const std::array<double, 3> x =
                            blend({a, a * v, 0.0}, {R * c, R * s, 0.0}, fraction_at(t, nr, radial_grading));
                        double p = x[0], q = x[1];
                        for (int turn = 0; turn < quarter; ++turn) {  // a quarter turn: (p, q) -> (-q, p)
                          const double old_p = p;
                          p = -q;
                          q = old_p;
                        }
                        return {p, q, axial(k)};
                      }});
  return blocks;
}

// Ball layout in coordinates relative to the centre.
std::vector<Block> sphere_blocks(const input::PartOptions& o) {
  const int na = o.elements[0], nr = o.elements[1];
  const double R = o.radius, a = core_fraction * R, radial_grading = o.grading[1];
  std::vector<Block> blocks;
  blocks.push_back({{na, na, na}, [=](double i, double j, double k) -> Point {
                      return {a * (2.0 * i / na - 1.0), a * (2.0 * j / na - 1.0), a * (2.0 * k / na - 1.0)};
                    }});
  // The six faces of the cube: the face's local frame (u, v, outward) as signed axes.
  struct Frame {
    int axis[3];
    double sign[3];
  };
  const Frame frames[6] = {{{0, 1, 2}, {1, 1, 1}},  {{1, 0, 2}, {1, 1, -1}}, {{1, 2, 0}, {1, 1, 1}},
                           {{2, 1, 0}, {1, 1, -1}}, {{2, 0, 1}, {1, 1, 1}},  {{0, 2, 1}, {1, 1, -1}}};
  for (const Frame& frame : frames)
    blocks.push_back({{na, na, nr}, [=](double i, double j, double t) -> Point {
                        const double u = 2.0 * i / na - 1.0, v = 2.0 * j / na - 1.0;
                        // The point of the sphere along the grid lines of equal angle.
                        const double du = quarter_tan(u), dv = quarter_tan(v);
                        const double scale = R / std::sqrt(du * du + dv * dv + 1.0);
                        const std::array<double, 3> x =
                            blend({a * u, a * v, a}, {scale * du, scale * dv, scale},
                                  fraction_at(t, nr, radial_grading));
                        Point result{};
                        for (int c = 0; c < 3; ++c)
                          result[std::size_t(frame.axis[c])] = frame.sign[c] * x[std::size_t(c)];
                        return result;
                      }});
  return blocks;
}

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

// The local node that mirrors each node of a brick across xi = 0 (offsets (2 - d0, d1, d2)):
// applied to an element whose block map is left-handed, it makes the element right-handed.
std::array<int, 20> mirror_xi() {
  std::array<int, 20> mirror{};
  for (int l = 0; l < 20; ++l) {
    const auto& d = brick_offsets[std::size_t(l)];
    for (int m = 0; m < 20; ++m) {
      const auto& e = brick_offsets[std::size_t(m)];
      if (e[0] == 2 - d[0] && e[1] == d[1] && e[2] == d[2]) mirror[std::size_t(l)] = m;
    }
  }
  return mirror;
}

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
  // Local to global: a cylinder's (p, q, s) go to the axes after its axis, cyclically.
  const int ax = options.axis;
  const std::array<int, 3> global_axis =
      cylinder ? std::array<int, 3>{(ax + 1) % 3, (ax + 2) % 3, ax} : std::array<int, 3>{0, 1, 2};
  auto to_global = [&](const Point& local) {
    Point x{};
    for (int c = 0; c < 3; ++c)
      x[std::size_t(global_axis[std::size_t(c)])] =
          options.center[std::size_t(global_axis[std::size_t(c)])] + local[std::size_t(c)];
    return x;
  };
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

  // The boundary faces (element faces no other element shares), named by where they lie:
  // on a cut plane (every corner exactly on it), on a cylinder's end planes, or else on
  // the curved surface.
  const NodalVectors& x = mesh.x_ref;
  auto coordinate = [&](std::uint32_t node, int c) {
    return c == 0 ? x.x[node] : (c == 1 ? x.y[node] : x.z[node]);
  };
  const double start = options.center[std::size_t(ax)];
  const double end = options.center[std::size_t(ax)] + options.length * 1.0;  // as the last grid point
  const std::array<input::PartFace, 3> cut_names{input::PartFace::cut_x, input::PartFace::cut_y,
                                                 input::PartFace::cut_z};
  std::vector<std::pair<input::PartFace, Face>> faces;
  auto face_named = [&](input::PartFace name) -> Face& {
    for (auto& [n, face] : faces)
      if (n == name) return face;
    faces.emplace_back(name, Face{});
    return faces.back().second;
  };
  face_named(input::PartFace::surface);
  if (cylinder) {
    face_named(input::PartFace::start);
    face_named(input::PartFace::end);
  }
  for (int c = 0; c < 3; ++c)
    if (options.keep[std::size_t(c)] != 0) face_named(cut_names[std::size_t(c)]);
  std::vector<double> normal_length_sum(faces.size(), 0.0);
  auto face_index = [&](input::PartFace name) {  // every name the loop can meet is made above
    std::size_t i = 0;
    while (faces[i].first != name) ++i;
    return i;
  };
  for (const BoundarySegment& boundary : boundary_segments(kept, nodes_per_element, x)) {
    const FaceSegment& segment = boundary.segment;
    auto all_at = [&](int c, double value) {
      for (int k = 0; k < 4; ++k)
        if (coordinate(segment.nodes[std::size_t(k)], c) != value) return false;
      return true;
    };
    input::PartFace name = input::PartFace::surface;
    for (int c = 0; c < 3; ++c)
      if (options.keep[std::size_t(c)] != 0 && all_at(c, options.center[std::size_t(c)]))
        name = cut_names[std::size_t(c)];
    if (cylinder && name == input::PartFace::surface) {
      if (all_at(ax, start)) name = input::PartFace::start;
      if (all_at(ax, end)) name = input::PartFace::end;
    }
    const std::size_t f = face_index(name);
    faces[f].second.segments.push_back(segment);
    normal_length_sum[f] += boundary.normal_length;
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    auto& [name, face] = faces[f];
    if (face.segments.empty())
      throw std::logic_error(std::string("add_mapped_part: the face ") + input::name(name) + " of part " +
                             std::to_string(part_index) + " has no segment");
    finish_face(face, normal_length_sum[f]);
  }
  part.faces = std::move(faces);
  mesh.parts.push_back(std::move(part));
}

}  // namespace exdyn::mesh
