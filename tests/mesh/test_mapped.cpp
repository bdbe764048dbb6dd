// Mapped meshes of cylinders and balls (mesh/mapped.hpp): surface nodes on the true
// circle or sphere, exact cut planes, outward faces, no inverted element over a range
// of counts and gradings, and the volume converging at the order of the elements.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <set>
#include <vector>

#include "mesh/mapped.hpp"
#include "mesh/mesh.hpp"
#include "model/mesh_quality.hpp"

namespace {

using exdyn::input::Formulation;
using exdyn::input::Geometry;
using exdyn::input::PartFace;
using exdyn::input::PartOptions;

PartOptions cylinder(int around, int radius, int axial, Formulation formulation,
                     std::array<int, 3> keep = {}) {
  PartOptions p;
  p.name = "c";
  p.geometry = Geometry::cylinder;
  p.center = {0.1, -0.2, 0.3};
  p.radius = 0.01;
  p.axis = 1;  // along y: the cross-section is (z, x)
  p.length = 0.02;
  p.elements = {around, radius, axial};
  p.formulation = formulation;
  p.keep = keep;
  return p;
}

PartOptions sphere(int around, int radius, Formulation formulation, std::array<int, 3> keep = {}) {
  PartOptions p;
  p.name = "s";
  p.geometry = Geometry::sphere;
  p.center = {0.1, -0.2, 0.3};
  p.radius = 0.01;
  p.elements = {around, radius, 0};
  p.formulation = formulation;
  p.keep = keep;
  return p;
}

exdyn::mesh::Mesh build(const PartOptions& part) {
  exdyn::input::Deck deck;
  deck.parts = {part};
  return exdyn::mesh::build_mesh(deck);
}

// Distance of a node from the axis (cylinder) or the centre (sphere), m.
double radius_of(const exdyn::mesh::Mesh& mesh, const PartOptions& p, std::uint32_t node) {
  const auto x = mesh.x_ref.at(node);
  double r2 = 0.0;
  for (int c = 0; c < 3; ++c)
    if (p.geometry == Geometry::sphere || c != p.axis) r2 += (x[c] - p.center[c]) * (x[c] - p.center[c]);
  return std::sqrt(r2);
}

double exact_volume(const PartOptions& p) {
  double v = p.geometry == Geometry::cylinder ? std::numbers::pi * p.radius * p.radius * p.length
                                              : 4.0 / 3.0 * std::numbers::pi * p.radius * p.radius * p.radius;
  for (int keep : p.keep)
    if (keep != 0) v /= 2.0;
  return v;
}

const Formulation formulations[] = {Formulation::hex8, Formulation::hex20};

TEST(MappedMesh, EverySurfaceNodeLiesOnTheCircleOrSphereMidEdgeNodesIncluded) {
  for (const Formulation f : formulations)
    for (const PartOptions& p : {cylinder(4, 3, 2, f), sphere(4, 3, f), cylinder(6, 2, 1, f, {1, 0, -1}),
                                 sphere(6, 2, f, {1, 1, 0})}) {
      const auto mesh = build(p);
      const auto face = exdyn::mesh::face_of(mesh, 0, PartFace::surface);
      ASSERT_FALSE(face.nodes.empty());
      double worst = 0.0;
      for (std::uint32_t node : face.nodes) {
        // On a cylinder the surface is the curved side only, so every node there is on the circle.
        worst = std::max(worst, std::abs(radius_of(mesh, p, node) - p.radius));
      }
      // Round-off: the local point is on the circle to a few ulps of R; adding the centre
      // rounds each coordinate to an ulp of |centre| + R.
      const double round_off = 4 * std::numeric_limits<double>::epsilon() * (0.3 + p.radius);
      EXPECT_LE(worst, round_off) << exdyn::input::name(p.geometry) << " " << exdyn::input::name(f);
      // and no node of the part lies outside.
      for (std::uint32_t n = 0; n < mesh.node_count(); ++n)
        EXPECT_LE(radius_of(mesh, p, n), p.radius + round_off);
      for (const auto& segment : face.segments)
        EXPECT_EQ(segment.node_count, f == Formulation::hex20 ? 8 : 4);
    }
}

TEST(MappedMesh, CutFacesLieExactlyOnTheirPlanesAndHalveTheCounts) {
  for (const Formulation f : formulations) {
    const PartOptions whole = sphere(4, 2, f), quarter = sphere(4, 2, f, {1, -1, 0});
    const auto a = build(whole), b = build(quarter);
    EXPECT_EQ(a.element_count(), 4u * 4 * 4 + 6u * 4 * 4 * 2);
    EXPECT_EQ(b.element_count(), a.element_count() / 4);
    EXPECT_EQ(b.element_count(), exdyn::mesh::mapped_element_count(quarter));
    for (const auto& [face, axis] : {std::pair{PartFace::cut_x, 0}, std::pair{PartFace::cut_y, 1}}) {
      const auto nodes = exdyn::mesh::face_of(b, 0, face).nodes;
      ASSERT_FALSE(nodes.empty());
      for (std::uint32_t n : nodes) EXPECT_EQ(b.x_ref.at(n)[axis], quarter.center[axis]);
    }
    for (std::uint32_t n = 0; n < b.node_count(); ++n) {
      EXPECT_GE(b.x_ref.at(n)[0], quarter.center[0]);  // x+
      EXPECT_LE(b.x_ref.at(n)[1], quarter.center[1]);  // y-
    }
  }
  const PartOptions c = cylinder(4, 2, 3, Formulation::hex8, {0, 0, 1});
  const auto mesh = build(c);
  EXPECT_EQ(mesh.element_count(), (4u * 4 + 4u * 4 * 2) * 3 / 2);
  for (std::uint32_t n : exdyn::mesh::face_of(mesh, 0, PartFace::start).nodes)
    EXPECT_EQ(mesh.x_ref.at(n)[1], c.center[1]);
  for (std::uint32_t n : exdyn::mesh::face_of(mesh, 0, PartFace::end).nodes)
    EXPECT_EQ(mesh.x_ref.at(n)[1], c.center[1] + c.length);
}

TEST(MappedMesh, NodesAreDistinctAndShared) {
  for (const Formulation f : formulations)
    for (const PartOptions& p : {cylinder(3, 2, 2, f), sphere(3, 2, f)}) {
      const auto mesh = build(p);
      std::set<std::array<double, 3>> seen;
      for (std::uint32_t n = 0; n < mesh.node_count(); ++n) seen.insert(mesh.x_ref.at(n));
      EXPECT_EQ(seen.size(), mesh.node_count());
      // Every node belongs to an element (no orphan from the cuts).
      std::vector<int> used(mesh.node_count(), 0);
      for (std::uint32_t id : mesh.connectivity) used[id] = 1;
      EXPECT_EQ(std::count(used.begin(), used.end(), 1), static_cast<long>(mesh.node_count()));
    }
  // hex8 cylinder: (n_a + 1)^2 + 4 n_a n_r nodes per cross-section layer (the shells share
  // the core's sides and each other's radial lines).
  const auto mesh = build(cylinder(3, 2, 2, Formulation::hex8));
  EXPECT_EQ(mesh.node_count(), std::size_t((4 * 4 + 4 * 3 * 2) * 3));
}

TEST(MappedMesh, SurfaceSegmentsFaceOutward) {
  for (const Formulation f : formulations)
    for (const PartOptions& p : {cylinder(4, 2, 2, f, {-1, 0, 0}), sphere(4, 2, f, {0, 0, 1})}) {
      const auto mesh = build(p);
      for (const PartFace name : {PartFace::surface, PartFace::cut_x, PartFace::cut_z}) {
        if ((name == PartFace::cut_x && p.keep[0] == 0) || (name == PartFace::cut_z && p.keep[2] == 0))
          continue;
        for (const auto& s : exdyn::mesh::face_of(mesh, 0, name).segments) {
          const auto x0 = mesh.x_ref.at(s.nodes[0]), x1 = mesh.x_ref.at(s.nodes[1]),
                     x3 = mesh.x_ref.at(s.nodes[3]);
          const std::array<double, 3> a{x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
          const std::array<double, 3> b{x3[0] - x0[0], x3[1] - x0[1], x3[2] - x0[2]};
          const std::array<double, 3> normal{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                             a[0] * b[1] - a[1] * b[0]};
          // Outward: away from the centre (surface), or against the kept half-space (cut).
          std::array<double, 3> out{};
          if (name == PartFace::surface) {
            for (int c = 0; c < 3; ++c)
              out[c] = (p.geometry == Geometry::cylinder && c == p.axis) ? 0.0 : x0[c] - p.center[c];
          } else {
            const int axis = name == PartFace::cut_x ? 0 : 2;
            out[axis] = -p.keep[axis];
          }
          EXPECT_GT(normal[0] * out[0] + normal[1] * out[1] + normal[2] * out[2], 0.0);
        }
      }
    }
}

// No inverted or degenerate element for any valid counts and gradings; the smallest
// scaled Jacobian stays above a floor the layout guarantees (docs/theory.md).
TEST(MappedMesh, NoElementIsInvertedOverARangeOfCountsAndGradings) {
  double smallest = 1.0;
  int meshes = 0;
  for (const Formulation f : formulations)
    for (int around = 1; around <= 8; ++around)
      for (int radial = 1; radial <= 6; ++radial)
        for (double grading : {0.2, 1.0, 5.0}) {
          std::vector<PartOptions> parts{cylinder(around, radial, 2, f), sphere(around, radial, f)};
          if (around % 2 == 0) parts.push_back(sphere(around, radial, f, {1, 1, 1}));
          for (PartOptions& p : parts) {
            p.grading[1] = grading;
            const auto mesh = build(p);
            const auto quality = exdyn::solver::mesh_quality(mesh);
            smallest = std::min(smallest, quality[0].smallest_scaled_jacobian);
            EXPECT_GT(quality[0].smallest_scaled_jacobian, 0.5)
                << exdyn::input::name(p.geometry) << " " << around << " x " << radial << " grading "
                << grading;
            ++meshes;
          }
        }
  std::printf("%d meshes: smallest scaled Jacobian %.3f\n", meshes, smallest);
}

// The volume error falls as h^2 with 8-node elements (a polygon or polyhedron) and as
// h^4 with 20-node ones (the surface interpolated by quadratics).
TEST(MappedMesh, VolumeConvergesAtTheOrderOfTheElements) {
  for (const Geometry g : {Geometry::cylinder, Geometry::sphere})
    for (const Formulation f : formulations) {
      std::vector<double> errors;
      for (int n : {2, 4, 8, 16}) {
        const PartOptions p =
            g == Geometry::cylinder ? cylinder(n, n / 2, 1, f) : sphere(n, n / 2, f, {1, 1, 1});
        const auto mesh = build(p);
        errors.push_back(std::abs(exdyn::solver::mesh_quality(mesh)[0].volume / exact_volume(p) - 1.0));
      }
      const double order = std::log2(errors[2] / errors[3]);
      std::printf("%s %s: volume errors %.2e %.2e %.2e %.2e, order %.2f\n", exdyn::input::name(g),
                  exdyn::input::name(f), errors[0], errors[1], errors[2], errors[3], order);
      if (f == Formulation::hex8) {
        EXPECT_NEAR(order, 2.0, 0.1);
      } else {
        EXPECT_NEAR(order, 4.0, 0.3);
      }
    }
}

// `grading`: the last element's length over the first's, along a box axis and along the
// radius of a ball (towards the surface).
TEST(MappedMesh, GradingSetsTheRatioOfTheLastElementToTheFirst) {
  PartOptions box;
  box.name = "b";
  box.box_min = {0, 0, 0};
  box.box_max = {2, 1, 1};
  box.elements = {5, 1, 1};
  box.grading = {0.25, 1, 1};
  const auto mesh = build(box);
  std::vector<double> x;
  for (int i = 0; i <= 5; ++i) x.push_back(mesh.x_ref.at(std::uint32_t(i))[0]);
  EXPECT_EQ(x.front(), 0.0);
  EXPECT_EQ(x.back(), 2.0);
  EXPECT_NEAR((x[5] - x[4]) / (x[1] - x[0]), 0.25, 1e-12);
  for (int i = 1; i < 4; ++i)  // geometric: equal ratios of neighbours
    EXPECT_NEAR((x[i + 1] - x[i]) / (x[i] - x[i - 1]), (x[2] - x[1]) / (x[1] - x[0]), 1e-12);
  EXPECT_NEAR(exdyn::mesh::face_of(mesh, 0, PartFace::xmin).normal_length, x[1] - x[0], 1e-15);
  EXPECT_NEAR(exdyn::mesh::face_of(mesh, 0, PartFace::xmax).normal_length, x[5] - x[4], 1e-15);

  PartOptions ball = sphere(2, 4, Formulation::hex8);
  ball.center = {0, 0, 0};
  ball.grading = {1, 0.2, 1};
  const auto b = build(ball);
  // The nodes on the +z axis: the core's top (z = R/2), then the shell's radial grid.
  std::vector<double> z;
  for (std::uint32_t n = 0; n < b.node_count(); ++n) {
    const auto p = b.x_ref.at(n);
    if (p[0] == 0.0 && p[1] == 0.0 && p[2] >= 0.5 * ball.radius) z.push_back(p[2]);
  }
  std::sort(z.begin(), z.end());
  ASSERT_EQ(z.size(), 5u);
  EXPECT_EQ(z.front(), exdyn::mesh::core_fraction * ball.radius);
  EXPECT_NEAR(z.back(), ball.radius, 1e-18);
  EXPECT_NEAR((z[4] - z[3]) / (z[1] - z[0]), 0.2, 1e-12);
}

// A part by numbers (MappedLattice) is add_mapped_part's, bit for bit: its node and
// element counts, each element's nodes, each node's coordinates and elements, and its
// faces, over both orders, cuts along every axis and both ways, odd and even counts,
// and grading.
TEST(MappedMesh, APartByNumbersIsTheGeneratedPartBitForBit) {
  std::vector<PartOptions> parts;
  for (const Formulation f : formulations) {
    parts.push_back(cylinder(3, 2, 2, f));
    parts.push_back(sphere(3, 2, f));
    parts.push_back(cylinder(4, 3, 2, f, {1, 0, -1}));  // axis y: cuts across x and z
    parts.push_back(cylinder(4, 2, 3, f, {0, 0, 1}));
    parts.push_back(sphere(4, 3, f, {1, 1, 0}));
    parts.push_back(sphere(4, 2, f, {-1, 0, 1}));
    parts.push_back(sphere(2, 3, f, {1, 1, 1}));
  }
  parts[2].grading = {1, 0.3, 2};
  parts[4].grading = {1, 0.5, 1};
  parts[5].axis = 2;
  for (const PartOptions& p : parts) {
    SCOPED_TRACE(std::string(p.geometry == Geometry::cylinder ? "cylinder " : "ball ") +
                 std::to_string(p.elements[0]) + " " + std::to_string(p.elements[1]) + " keep " +
                 std::to_string(p.keep[0]) + std::to_string(p.keep[1]) + std::to_string(p.keep[2]) +
                 (p.formulation == Formulation::hex20 ? " hex20" : " hex8"));
    const auto mesh = build(p);
    const exdyn::mesh::MappedLattice lattice(p, 0);
    const int width = lattice.nodes_per_element();
    ASSERT_EQ(width, mesh.parts[0].nodes_per_element);
    ASSERT_EQ(lattice.node_count(), mesh.node_count());
    ASSERT_EQ(lattice.element_count(), mesh.element_count());
    std::vector<std::vector<std::uint32_t>> around(mesh.node_count());
    for (std::uint32_t e = 0; e < lattice.element_count(); ++e) {
      const auto nodes = lattice.element_nodes(e);
      for (int k = 0; k < width; ++k) {
        ASSERT_EQ(nodes[std::size_t(k)], mesh.connectivity[std::size_t(width) * e + std::size_t(k)])
            << "element " << e << " node " << k;
        around[nodes[std::size_t(k)]].push_back(e);
      }
    }
    for (std::uint32_t n = 0; n < lattice.node_count(); ++n) {
      ASSERT_EQ(lattice.point(n), mesh.x_ref.at(n)) << "node " << n;
      ASSERT_EQ(lattice.elements_around(n), around[n]) << "node " << n;
    }
    const auto& faces = mesh.parts[0].faces;
    ASSERT_EQ(lattice.faces().size(), faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const auto& [name, face] = lattice.faces()[f];
      EXPECT_EQ(name, faces[f].first);
      EXPECT_EQ(face.nodes, faces[f].second.nodes);
      EXPECT_EQ(face.normal_length, faces[f].second.normal_length);
      ASSERT_EQ(face.segments.size(), faces[f].second.segments.size());
      for (std::size_t s = 0; s < face.segments.size(); ++s)
        EXPECT_EQ(face.segments[s].nodes, faces[f].second.segments[s].nodes);
    }
  }
}

}  // namespace
