// Which master face a slave point is matched to near edges and corners (contact_pass.cpp,
// the choice of each point's contact): the face it really touches, never a neighbouring
// face's extension nor a face further away across the body.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "contact/contact_pass.hpp"

namespace {

using namespace exdyn::contact;

constexpr double stiffness = 1.0e6;  // N/m

// One contact pass of the slave node `slave` (the last node) against `segments` at rest;
// returns its gap (m) and the force on it (N).
struct Outcome {
  double gap = 0.0;
  Vec3 force{};
};

Outcome one_pass(const exdyn::NodalVectors& x_ref, const std::vector<SegmentNodes>& segments,
                 const std::vector<SegmentEdges>& edges) {
  const std::size_t n = x_ref.size();
  const auto slave = static_cast<std::uint32_t>(n - 1);
  ContactSurfaces surfaces;
  surfaces.slave_nodes = {slave};
  surfaces.stiffness = {stiffness};
  surfaces.normal_length = {1.0};
  surfaces.segments = segments;
  surfaces.edges = edges;
  for (std::uint32_t i = 0; i < n; ++i) surfaces.moving_nodes.push_back(i);
  ContactPassSettings settings;
  settings.project = select_method(SearchMethod::bfgs);
  settings.automatic_stiffness = false;
  settings.dt = 1e-3;
  settings.search_distance = settings.margin = 0.5;
  ContactPassState state;
  const exdyn::NodalVectors u(n), v(n);
  const std::vector<double> mass(n, 1.0);
  ContactStatistics statistics;
  ContactPhaseSeconds seconds;
  exdyn::NodalVectors force(n);
  std::vector<double> gap(n, std::numeric_limits<double>::infinity());
  run_contact_pass(surfaces, settings, state, x_ref, u, v, mass, force, gap, statistics, seconds);
  return {gap[slave], {force.x[slave], force.y[slave], force.z[slave]}};
}

// The unit cube [0, 1]^3 as a closed master surface: its 8 corners (VTK order), its six
// faces outward (hex8's face order: z = 0, z = 1, y = 0, x = 1, y = 1, x = 0), every edge
// shared with the next face.
const std::array<Vec3, 8> cube_corners{
    {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
const std::array<std::array<std::uint32_t, 4>, 6> cube_faces{
    {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};
const std::array<Vec3, 6> cube_normals{{{0, 0, -1}, {0, 0, 1}, {0, -1, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}}};

Outcome cube_pass(const Vec3& point) {
  exdyn::NodalVectors x_ref(9);
  for (std::size_t i = 0; i < 8; ++i)
    x_ref.x[i] = cube_corners[i].x, x_ref.y[i] = cube_corners[i].y, x_ref.z[i] = cube_corners[i].z;
  x_ref.x[8] = point.x, x_ref.y[8] = point.y, x_ref.z[8] = point.z;
  std::vector<SegmentNodes> segments(6);
  for (std::size_t f = 0; f < 6; ++f)
    for (int k = 0; k < 4; ++k) segments[f].nodes[std::size_t(k)] = cube_faces[f][std::size_t(k)];
  SegmentEdges closed;
  closed.continued = edge_xi1_minus | edge_xi1_plus | edge_xi2_minus | edge_xi2_plus;
  return one_pass(x_ref, segments, std::vector<SegmentEdges>(6, closed));
}

std::string text(const Vec3& p) {
  return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
}

// Points just inside a face, 0.1 from a neighbouring face (an edge) or from two (a
// corner), 0.02 deep, from every face towards every edge and corner: each is pushed
// back out through the face it is under, by k times its depth; the same places just
// outside the cube, and diagonally off every edge and corner, feel nothing.
TEST(FaceChoice, AtACubesEdgesAndCornersFromEverySideThePointTakesTheFaceItIsUnder) {
  constexpr double depth = 0.02, offset = 0.1;
  int inside = 0;
  for (std::size_t f = 0; f < 6; ++f) {
    const Vec3 n = cube_normals[f];
    // The face's centre, and its two in-plane axes.
    const Vec3 centre{0.5 + 0.5 * n.x, 0.5 + 0.5 * n.y, 0.5 + 0.5 * n.z};
    const Vec3 s = std::abs(n.x) > 0.5 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    const Vec3 t = cross(n, s);
    for (const double a : {-1.0, 0.0, 1.0})
      for (const double b : {-1.0, 0.0, 1.0}) {
        if (a == 0.0 && b == 0.0) continue;  // the middle of the face: no edge near
        // 0.1 from the edges that a and b point to (the face spans +-0.5 about its centre).
        const Vec3 near_edges = centre + (a * (0.5 - offset)) * s + (b * (0.5 - offset)) * t;
        const Vec3 under = near_edges - depth * n;
        const Outcome in = cube_pass(under);
        EXPECT_NEAR(in.gap, -depth, 1e-9) << "face " << f << " at " << text(under);
        const Vec3 expected = (stiffness * depth) * n;
        EXPECT_NEAR(in.force.x, expected.x, 1e-6) << "face " << f << " at " << text(under);
        EXPECT_NEAR(in.force.y, expected.y, 1e-6) << "face " << f << " at " << text(under);
        EXPECT_NEAR(in.force.z, expected.z, 1e-6) << "face " << f << " at " << text(under);
        ++inside;
        const Outcome out = cube_pass(near_edges + depth * n);
        EXPECT_EQ(norm(out.force), 0.0) << "face " << f << " in front at " << text(near_edges + depth * n);
        // Diagonally off the edge (or corner) itself.
        const Vec3 edge_point = centre + (0.5 * a) * s + (0.5 * b) * t;
        const Vec3 off = edge_point + 0.05 * (n + a * s + b * t);
        EXPECT_EQ(norm(cube_pass(off).force), 0.0) << "off the edge or corner at " << text(off);
      }
  }
  EXPECT_EQ(inside, 48);  // 6 faces x (4 edges + 4 corners)
}

// A shallow valley (two segments meeting at x = 1, z = s |x - 1|) ends at a rim, x = 1.2,
// where a side face goes down. A point just under the valley's bottom line is in the
// dead zone of both valley segments (each projection falls just past the shared edge),
// while the side face, 0.2 away, takes it inside: it touches the valley, and is pushed
// up out of it by its depth, not out through the side by 0.2.
TEST(FaceChoice, UnderAShallowValleyBesideARimThePointTakesTheValleyNotTheFarSide) {
  constexpr double s = 0.05, depth = 1.0e-3;
  exdyn::NodalVectors x_ref(9);
  const std::array<Vec3, 9> nodes{{{0, 0, s},
                                   {1, 0, 0},
                                   {1.2, 0, 0.2 * s},
                                   {0, 1, s},
                                   {1, 1, 0},
                                   {1.2, 1, 0.2 * s},
                                   {1.2, 0, -1},
                                   {1.2, 1, -1},
                                   {1, 0.5, -depth}}};
  for (std::size_t i = 0; i < 9; ++i)
    x_ref.x[i] = nodes[i].x, x_ref.y[i] = nodes[i].y, x_ref.z[i] = nodes[i].z;
  std::vector<SegmentNodes> segments(3);
  segments[0].nodes = {0, 1, 4, 3};  // the valley's left side, outward up
  segments[1].nodes = {1, 2, 5, 4};  // its right side
  segments[2].nodes = {6, 7, 5, 2};  // the side face x = 1.2, outward +x
  std::vector<SegmentEdges> edges(3);
  edges[0].continued = edge_xi1_plus;
  edges[1].continued = edge_xi1_minus | edge_xi1_plus;
  edges[2].continued = edge_xi2_plus;
  const Outcome o = one_pass(x_ref, segments, edges);
  EXPECT_NEAR(o.gap, -depth, 1e-12);
  EXPECT_NEAR(o.force.z, stiffness * depth, 1e-6);  // along the valley's mean normal, +z
  EXPECT_NEAR(o.force.x, 0.0, 1e-6);
  EXPECT_NEAR(o.force.y, 0.0, 1e-6);
}

// A body above z = 0 (a rod's end, seen from below): its end face z = 0, outward -z,
// whose edge y = 0 lies on a symmetry plane (its mirror image goes on past it), and its
// side x = 1 going up, bulged a hair past both planes (as a deforming side is). A point
// a hair below the end face and a hair past its edge on the plane (its projection just
// past xi1 = 1) is outside the body: no contact, although the side's plane takes it
// inside, 0.13 deep.
TEST(FaceChoice, InFrontOfAFacesEdgeOnASymmetryPlaneAFarFaceDoesNotTakeThePoint) {
  exdyn::NodalVectors x_ref(9);
  const std::array<Vec3, 9> nodes{{{0, -1, 0},
                                   {1, -1, 0},
                                   {1, 0, 0},
                                   {0, 0, 0},
                                   {1, -1, -1e-6},
                                   {1, 1e-6, -1e-6},
                                   {1, 1e-6, 1},
                                   {1, -1, 1},
                                   {0.87, 1e-7, -1e-8}}};
  for (std::size_t i = 0; i < 9; ++i)
    x_ref.x[i] = nodes[i].x, x_ref.y[i] = nodes[i].y, x_ref.z[i] = nodes[i].z;
  std::vector<SegmentNodes> segments(2);
  segments[0].nodes = {0, 3, 2, 1};  // the end z = 0, outward -z: xi1 along +y, xi2 along +x
  segments[1].nodes = {4, 5, 6, 7};  // the side x = 1, outward +x
  std::vector<SegmentEdges> edges(2);
  edges[0].continued = edge_xi1_plus | edge_xi2_plus;  // y = 0 (the mirror), x = 1 (the side)
  edges[0].mirror_axis[1] = 1;
  edges[1].continued = edge_xi1_plus | edge_xi2_minus;  // y = 0 (the mirror), z = 0 (the end)
  edges[1].mirror_axis[1] = 1;
  const Outcome o = one_pass(x_ref, segments, edges);
  EXPECT_EQ(norm(o.force), 0.0);
  EXPECT_GE(o.gap, 0.0);
}

}  // namespace
