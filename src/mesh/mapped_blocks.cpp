#include "mesh/mapped_blocks.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "mesh/mapped.hpp"

namespace exdyn::mesh::mapped {

namespace {

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

}  // namespace

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

// Local to global coordinates, m: a cylinder's (p, q, s) go to the axes after its
// axis, cyclically, a ball's are x, y, z; both about the centre.
Point to_global(const input::PartOptions& options, const Point& local) {
  const int ax = options.axis;
  const std::array<int, 3> global_axis = options.geometry == input::Geometry::cylinder
                                             ? std::array<int, 3>{(ax + 1) % 3, (ax + 2) % 3, ax}
                                             : std::array<int, 3>{0, 1, 2};
  Point x{};
  for (int c = 0; c < 3; ++c)
    x[std::size_t(global_axis[std::size_t(c)])] =
        options.center[std::size_t(global_axis[std::size_t(c)])] + local[std::size_t(c)];
  return x;
}

// The named faces of a mapped part from its boundary segments (in order of element and
// local face), each named by where it lies: on a cut plane (every corner exactly on
// it), on a cylinder's end planes, or else on the curved surface.
std::vector<std::pair<input::PartFace, Face>> named_faces(const input::PartOptions& options, int part_index,
                                                          const std::vector<OuterSegment>& boundary) {
  const bool cylinder = options.geometry == input::Geometry::cylinder;
  const int ax = options.axis;
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
  for (const OuterSegment& outer : boundary) {
    auto all_at = [&](int c, double value) {
      for (const Point& corner : outer.corners)
        if (corner[std::size_t(c)] != value) return false;
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
    faces[f].second.segments.push_back(outer.segment);
    normal_length_sum[f] += outer.normal_length;
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    auto& [name, face] = faces[f];
    if (face.segments.empty())
      throw std::logic_error(std::string("add_mapped_part: the face ") + input::name(name) + " of part " +
                             std::to_string(part_index) + " has no segment");
    finish_face(face, normal_length_sum[f]);
  }
  return faces;
}

}  // namespace exdyn::mesh::mapped
