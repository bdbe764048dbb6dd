// The rules of single-surface contact (contact/single_surface.hpp): a node's normal is
// the angle-weighted pseudo-normal, an edge node takes the stiffness of the face that
// faces the contact, and a point is never checked against a segment that shares a node
// with it, even one that faces it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "contact/contact_pass.hpp"
#include "contact/single_surface.hpp"
#include "contact/slave_points.hpp"

namespace {

using namespace exdyn::contact;

exdyn::NodalVectors positions(const std::vector<Vec3>& points) {
  exdyn::NodalVectors x(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    x.x[i] = points[i].x, x.y[i] = points[i].y, x.z[i] = points[i].z;
  return x;
}

SegmentNodes quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  SegmentNodes s;
  s.nodes = {a, b, c, d, 0, 0, 0, 0};
  return s;
}

// The corner (3, 1, 1) of the brick [0, 3] x [0, 1] x [0, 1], one segment on each of its
// three faces there (x = 3, y = 1, z = 1), each a side (face) of its own with stiffness
// 1, 2 and 3 N/m.
struct BrickCorner {
  exdyn::NodalVectors x =
      positions({{3, 1, 1}, {3, 0, 1}, {3, 0, 0}, {3, 1, 0}, {0, 1, 1}, {0, 1, 0}, {0, 0, 1}});
  ContactSurfaces s;
  BrickCorner() {
    s.single_surface = true;
    s.slave_nodes = {0};
    s.segments = {quad(2, 3, 0, 1),   // x = 3, outward +x: corners (3,0,0) (3,1,0) (3,1,1) (3,0,1)
                  quad(3, 5, 4, 0),   // y = 1, outward +y
                  quad(1, 0, 4, 6)};  // z = 1, outward +z
    s.corner_begin = {0, 3};
    s.node_corners = {{0, 2, 0}, {1, 3, 1}, {2, 1, 2}};
    s.side_begin = {0, 3};
    s.side_stiffness = {1.0, 2.0, 3.0};
  }
};

TEST(SingleSurfaceRules, AnEdgeNodesNormalIsTheAngleWeightedPseudoNormal) {
  const BrickCorner brick;
  const exdyn::NodalVectors u(brick.x.size());
  for (const SegmentNodes& segment : brick.s.segments) {  // each segment faces out
    const Vec3 n = outward_normal(current_segment(segment, brick.x, u), Xi{0.0, 0.0});
    EXPECT_NEAR(norm(n), 1.0, 1e-15);
  }
  const Vec3 n = point_normal(brick.s, 0, brick.x, u);
  // Every face meets the corner at a right angle: (1, 1, 1)/sqrt 3 whatever the faces'
  // areas (an area-weighted normal leans to the large faces: (1, 3, 3)/sqrt 19).
  const double third = 1.0 / std::sqrt(3.0);
  EXPECT_NEAR(n.x, third, 1e-15);
  EXPECT_NEAR(n.y, third, 1e-15);
  EXPECT_NEAR(n.z, third, 1e-15);
}

TEST(SingleSurfaceRules, AnEdgeNodeTakesTheStiffnessOfTheFaceThatFacesTheContact) {
  const BrickCorner brick;
  const exdyn::NodalVectors u(brick.x.size());
  EXPECT_EQ(side_stiffness(brick.s, 0, {-1, 0, 0}, brick.x, u), 1.0);
  EXPECT_EQ(side_stiffness(brick.s, 0, {0, -1, 0}, brick.x, u), 2.0);
  EXPECT_EQ(side_stiffness(brick.s, 0, {-0.1, -0.2, -0.97}, brick.x, u), 3.0);
}

// A hairpin: segment A (z = 0, outward +z) and segment B hinged on A's edge x = 0, folded
// back over A with its far end 0.01 below A's plane and its outward normal down onto A:
// B faces A and passes through it, yet shares the hinge's nodes with A. Segment C, B's
// copy on nodes of its own, faces A the same way. A's Gauss points are checked against C
// (and pressed by it), never against B.
TEST(SingleSurfaceRules, ASegmentSharingANodeIsNeverChecked) {
  const exdyn::NodalVectors x = positions({{0, 0, 0},
                                           {1, 0, 0},
                                           {1, 1, 0},
                                           {0, 1, 0},  // A
                                           {0.9, 0, -0.01},
                                           {0.9, 1, -0.01},  // B's far edge
                                           {0, 0, 0},
                                           {0, 1, 0},
                                           {0.9, 0, -0.01},
                                           {0.9, 1, -0.01}});  // C
  const std::size_t n = x.size();
  auto run = [&](bool with_copy) {
    ContactSurfaces s;
    s.single_surface = s.quadrature = true;
    s.segments = {quad(0, 1, 2, 3), quad(0, 3, 5, 4)};  // B: outward a1 x a2 = -z
    if (with_copy) s.segments.push_back(quad(6, 7, 9, 8));
    s.slave_segments = {s.segments[0]};
    const double g = 1.0 / std::sqrt(3.0);
    for (double a : {-g, g})
      for (double b : {-g, g}) s.quadrature_points.push_back({0, {a, b}, 0.25});
    s.stiffness.assign(4, 1.0e6);
    s.normal_length.assign(4, 1.0);
    s.edge_neighbours.assign(s.segments.size(), {-1, -1, -1, -1});
    s.first_part_point.assign(4, 1);
    s.first_part_segment.assign(s.segments.size(), 1);
    for (std::uint32_t i = 0; i < n; ++i) s.moving_nodes.push_back(i);
    s.slave_nodes = {0, 1, 2, 3};
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
    run_contact_pass(s, settings, state, x, u, v, mass, force, gap, statistics, seconds);
    double pressed = 0.0;  // upward force on A's nodes
    for (std::uint32_t i = 0; i < 4; ++i) pressed += force.z[i];
    return std::make_pair(statistics.projections, pressed);
  };
  const auto [alone_projections, alone_force] = run(false);
  EXPECT_EQ(alone_projections, 0);
  EXPECT_EQ(alone_force, 0.0);
  const auto [copy_projections, copy_force] = run(true);
  EXPECT_EQ(copy_projections, 4);
  EXPECT_LT(copy_force, 0.0);  // C's outward normal is -z: it pushes A's points down
}

}  // namespace

// behind_beyond: a point lies behind a segment by more than a depth along its centre
// normal only where every point of the segment is that far in front of it; an 8-node
// segment whose corners are raised bulges below its nodes at its centre, by their spread.
TEST(SingleSurfaceRules, APointFarBehindASegmentIsBehindEveryPointOfIt) {
  Segment flat;  // the unit square z = 0, outward +z
  flat.nodes = {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0}};
  EXPECT_TRUE(behind_beyond(flat, Vec3{0.5, 0.5, -0.31}, 0.3));
  EXPECT_FALSE(behind_beyond(flat, Vec3{0.5, 0.5, -0.29}, 0.3));
  EXPECT_FALSE(behind_beyond(flat, Vec3{0.5, 0.5, 2.0}, 0.3));   // in front
  EXPECT_TRUE(behind_beyond(flat, Vec3{5.0, 5.0, -0.31}, 0.3));  // beside and behind

  Segment bowl;  // corners at z = 0.4, mid-sides at 0: the centre at -0.4
  bowl.type = SegmentType::quad8;
  bowl.nodes = {Vec3{0, 0, 0.4}, Vec3{1, 0, 0.4}, Vec3{1, 1, 0.4}, Vec3{0, 1, 0.4},
                Vec3{0.5, 0, 0}, Vec3{1, 0.5, 0}, Vec3{0.5, 1, 0}, Vec3{0, 0.5, 0}};
  EXPECT_NEAR(evaluate(bowl, Xi{0.0, 0.0}).y.z, -0.4, 1e-15);
  // 0.2 below every node, yet 0.2 in front of the centre: not behind.
  EXPECT_FALSE(behind_beyond(bowl, Vec3{0.5, 0.5, -0.2}, 0.1));
  EXPECT_TRUE(behind_beyond(bowl, Vec3{0.5, 0.5, -0.51}, 0.1));

  // Warped and curved segments, points around them: wherever the rule says behind, every
  // point of a 41 x 41 grid on the segment is further than the depth along the normal.
  std::uint64_t state = 12345;
  auto random = [&state] {  // in [-1, 1)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) * 0x1.0p-52 - 1.0;
  };
  int behind = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Segment s;
    s.type = trial % 2 == 0 ? SegmentType::quad4 : SegmentType::quad8;
    for (int i = 0; i < node_count(s.type); ++i) {
      const Xi xi = node_xi[std::size_t(i)];
      s.nodes[std::size_t(i)] = Vec3{xi[0] + 0.2 * random(), xi[1] + 0.2 * random(), 0.3 * random()};
    }
    const Vec3 n = outward_normal(evaluate(s, Xi{0.0, 0.0}));
    const Vec3 point{2.0 * random(), 2.0 * random(), 1.5 * random()};
    const double depth = 0.2;
    if (!behind_beyond(s, point, depth)) continue;
    ++behind;
    for (int a = 0; a <= 40; ++a)
      for (int b = 0; b <= 40; ++b) {
        const Vec3 y = evaluate(s, Xi{-1.0 + a / 20.0, -1.0 + b / 20.0}).y;
        ASSERT_GT(dot(y - point, n), depth) << "trial " << trial;
      }
  }
  EXPECT_GT(behind, 50);  // the rule was put to the test
}
