// Contact at a fold of the master surface (contact/edge_contact.hpp): a point behind
// the bottom of a V-shaped valley projects outside both of its segments (the dead zone
// of node-to-segment contact) and takes the closest point of the shared edge, along
// the mean of the two segments' normals.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/edge_contact.hpp"
#include "contact/local_search.hpp"

namespace {

using namespace exdyn::contact;

// The valley z = s |x| over y in [0, 1]: segment A (x in [-1, 0]) and B (x in [0, 1]),
// corners counter-clockwise seen from +z (outward). A's edge xi1 = +1 and B's edge
// xi1 = -1 are the bottom line x = 0.
constexpr double s = 0.5;
Segment segment_a() {
  Segment a;
  a.nodes[0] = {-1.0, 0.0, s}, a.nodes[1] = {0.0, 0.0, 0.0}, a.nodes[2] = {0.0, 1.0, 0.0},
  a.nodes[3] = {-1.0, 1.0, s};
  return a;
}
Segment segment_b() {
  Segment b;
  b.nodes[0] = {0.0, 0.0, 0.0}, b.nodes[1] = {1.0, 0.0, s}, b.nodes[2] = {1.0, 1.0, s},
  b.nodes[3] = {0.0, 1.0, 0.0};
  return b;
}

ProjectionResult project_with(SearchMethod method, const Segment& segment, Vec3 point) {
  ProjectionSettings settings;
  settings.method = method;
  return project(segment, point, Xi{0.0, 0.0}, settings);
}

SegmentEdges continued(std::uint8_t bits) {
  SegmentEdges edges;
  edges.continued = bits;
  return edges;
}

class EdgeContactMethods : public ::testing::TestWithParam<SearchMethod> {};

TEST_P(EdgeContactMethods, PointBehindTheValleyTakesTheBottomLine) {
  const Vec3 point{0.0, 0.3, -0.02};  // 0.02 below the bottom line, in the dead zone
  Vec3 normal_sum{};
  for (const auto& [segment, edge] :
       {std::pair{segment_a(), edge_xi1_plus}, std::pair{segment_b(), edge_xi1_minus}}) {
    const ProjectionResult r = project_with(GetParam(), segment, point);
    ASSERT_TRUE(r.converged);
    // The unconstrained closest point lies across the bottom line (or, robust, on it):
    // the ordinary choice takes neither segment.
    EXPECT_FALSE(r.inside && r.stationary == StationaryKind::minimum && !r.on_boundary);
    const EdgeContact c = edge_contact(segment, point, r, continued(edge));
    ASSERT_TRUE(c.found);
    EXPECT_TRUE(c.continued);
    EXPECT_NEAR(c.y.x, 0.0, 1e-14);
    EXPECT_NEAR(c.y.y, 0.3, 1e-14);
    EXPECT_NEAR(c.y.z, 0.0, 1e-14);
    EXPECT_NEAR(c.distance, 0.02, 1e-15);
    // Each segment's own normal, tilted by atan(s) either way.
    EXPECT_NEAR(std::fabs(c.normal.x), s / std::sqrt(1.0 + s * s), 1e-14);
    EXPECT_NEAR(c.normal.z, 1.0 / std::sqrt(1.0 + s * s), 1e-14);
    normal_sum = normal_sum + c.normal;
  }
  // The pass's direction: the mean of the two, +z, and the gap -0.02.
  const Vec3 n = (1.0 / norm(normal_sum)) * normal_sum;
  EXPECT_NEAR(n.x, 0.0, 1e-14);
  EXPECT_NEAR(n.z, 1.0, 1e-14);
  EXPECT_NEAR(dot(point - Vec3{0.0, 0.3, 0.0}, n), -0.02, 1e-15);
}

INSTANTIATE_TEST_SUITE_P(Methods, EdgeContactMethods,
                         ::testing::Values(SearchMethod::newton, SearchMethod::lsp, SearchMethod::bfgs,
                                           SearchMethod::dfp, SearchMethod::simplex, SearchMethod::hybrid,
                                           SearchMethod::robust));

TEST(EdgeContact, AtASymmetryPlaneTheMirrorImageCancelsTheNormalAcrossIt) {
  // A alone, its edge x = 0 on the symmetry plane of the x axis: B is A's mirror image.
  const Vec3 point{0.0, 0.3, -0.02};
  const ProjectionResult r = project_with(SearchMethod::bfgs, segment_a(), point);
  SegmentEdges edges = continued(edge_xi1_plus);
  edges.mirror_axis[1] = 0;
  const EdgeContact c = edge_contact(segment_a(), point, r, edges);
  ASSERT_TRUE(c.found);
  EXPECT_EQ(c.normal.x, 0.0);
  EXPECT_NEAR(c.normal.z, 1.0, 1e-15);
}

TEST(EdgeContact, AnEdgeThatEndsTheSurfaceIsNotContinued) {
  const Vec3 point{0.0, 0.3, -0.02};
  const ProjectionResult r = project_with(SearchMethod::newton, segment_a(), point);
  const EdgeContact c =
      edge_contact(segment_a(), point, r, continued(edge_xi1_minus | edge_xi2_minus | edge_xi2_plus));
  ASSERT_TRUE(c.found);
  EXPECT_FALSE(c.continued);
}

TEST(EdgeContact, PastTwoEdgesTheCornerIsTheClosestPoint) {
  // Below the bottom line and past the end y = 0: the corner (0, 0, 0) of both segments.
  const Vec3 point{0.0, -0.05, -0.02};
  const ProjectionResult r = project_with(SearchMethod::newton, segment_a(), point);
  const EdgeContact c = edge_contact(segment_a(), point, r, continued(edge_xi1_plus | edge_xi2_minus));
  ASSERT_TRUE(c.found);
  EXPECT_TRUE(c.continued);
  EXPECT_EQ(c.xi[0], 1.0);
  EXPECT_EQ(c.xi[1], -1.0);
  EXPECT_NEAR(c.distance, std::hypot(0.05, 0.02), 1e-15);
}

TEST(EdgeContact, InFrontOfTheSegmentTheGapIsPositive) {
  // Past A's edge x = 0 and above the plane: no penetration.
  const Vec3 point{0.2, 0.5, 0.3};
  const ProjectionResult r = project_with(SearchMethod::newton, segment_a(), point);
  const EdgeContact c = edge_contact(segment_a(), point, r, continued(edge_xi1_plus));
  ASSERT_TRUE(c.found);
  EXPECT_GT(dot(point - c.y, c.normal), 0.0);
}

TEST(EdgeContact, AnInsideProjectionIsNotAnEdgeContact) {
  const Vec3 point{-0.5, 0.5, 0.0};
  const ProjectionResult r = project_with(SearchMethod::newton, segment_a(), point);
  ASSERT_TRUE(r.inside);
  EXPECT_FALSE(edge_contact(segment_a(), point, r, continued(15)).found);
}

}  // namespace
