// The cases of ../shared/reference/local-search-tests.md, for every method
// where the answer is defined, with the documented failures detected.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "contact/local_search.hpp"

namespace exdyn::contact {
namespace {

Segment flat_q8() {
  Segment s;
  s.type = SegmentType::quad8;
  for (int i = 0; i < 8; ++i) s.nodes[i] = {node_xi[i][0], node_xi[i][1], 0.0};
  return s;
}
Segment t2_segment() {  // z = 0.5 x^2 + 0.1 y^2 at the nodes
  Segment s = flat_q8();
  for (int i = 0; i < 8; ++i)
    s.nodes[i].z = 0.5 * s.nodes[i].x * s.nodes[i].x + 0.1 * s.nodes[i].y * s.nodes[i].y;
  return s;
}
Segment t3_segment() {
  Segment s;
  s.type = SegmentType::quad4;
  s.nodes[0] = {-1, -1, 0};
  s.nodes[1] = {1, -1, 0.5};
  s.nodes[2] = {1, 1, 0};
  s.nodes[3] = {-1, 1, 0.5};
  return s;
}
Segment t5_segment() {
  Segment s = flat_q8();
  s.nodes[4] = {-0.5, -1, 0};
  s.nodes[7] = {-1, -0.5, 0};
  return s;
}

struct Start {
  std::string label;
  Xi xi;
};
// The paper's six starting points: one LSP step, the centre, the four corners.
std::vector<Start> six_starts(const Segment& s, const Vec3& point) {
  return {{"lsp", initial_guess_lsp(s, point)},
          {"center", {0, 0}},
          {"corner1", {-1, -1}},
          {"corner2", {1, -1}},
          {"corner3", {1, 1}},
          {"corner4", {-1, 1}}};
}

ProjectionSettings settings_for(SearchMethod m) {
  ProjectionSettings st;
  st.method = m;
  st.tolerance = 1e-10;
  st.max_iterations = 500;  // LSP converges only linearly on curved segments (T2b: 95 iterations)
  return st;
}

constexpr std::array gradient_methods{
    SearchMethod::newton,  SearchMethod::lsp,  SearchMethod::steepest_descent,
    SearchMethod::broyden, SearchMethod::bfgs, SearchMethod::dfp};

std::string describe(SearchMethod m, const std::string& start, const ProjectionResult& r) {
  return std::string(name(m)) + " from " + start + ": xi (" + std::to_string(r.xi[0]) + ", " +
         std::to_string(r.xi[1]) + ") it " + std::to_string(r.iterations) + " " +
         std::string(name(r.stationary)) + " " + std::string(name(r.failure));
}

TEST(ReferenceCases, T1FlatEveryGradientMethodInAtMostTwoIterationsFromAnywhere) {
  const Segment s = flat_q8();
  const Vec3 point{0.3, -0.2, 0.5};
  std::vector<Start> starts = six_starts(s, point);
  for (const Xi far : {Xi{3, -4}, Xi{-2.5, 0.7}, Xi{0.31, -0.19}}) starts.push_back({"far", far});
  for (const SearchMethod m : gradient_methods) {
    for (const Start& start : starts) {
      const ProjectionResult r = project(s, point, start.xi, settings_for(m));
      const std::string what = describe(m, start.label, r);
      EXPECT_TRUE(r.converged) << what;
      EXPECT_LE(r.iterations, 2) << what;
      EXPECT_NEAR(r.xi[0], 0.3, 1e-14) << what;
      EXPECT_NEAR(r.xi[1], -0.2, 1e-14) << what;
      EXPECT_NEAR(r.distance, 0.5, 1e-14) << what;
      EXPECT_NEAR(r.gap, 0.5, 1e-14) << what;
      EXPECT_EQ(r.stationary, StationaryKind::minimum) << what;
      EXPECT_TRUE(r.inside) << what;
    }
  }
  for (const SearchMethod m : {SearchMethod::simplex, SearchMethod::hybrid, SearchMethod::robust}) {
    for (const Start& start : six_starts(s, point)) {
      const ProjectionResult r = project(s, point, start.xi, settings_for(m));
      const std::string what = describe(m, start.label, r);
      EXPECT_TRUE(r.converged) << what;
      EXPECT_NEAR(r.xi[0], 0.3, 1e-8) << what;
      EXPECT_NEAR(r.xi[1], -0.2, 1e-8) << what;
      EXPECT_NEAR(r.distance, 0.5, 1e-14) << what;
    }
  }
}

TEST(ReferenceCases, T2FromTheCentreEveryGradientMethodStopsOnASaddleAndSaysSo) {
  const Segment s = t2_segment();
  const Vec3 point{0, 0, 1.25};
  for (const SearchMethod m : gradient_methods) {
    const ProjectionResult r = project(s, point, {0, 0}, settings_for(m));
    const std::string what = describe(m, "center", r);
    EXPECT_TRUE(r.converged) << what;
    EXPECT_EQ(r.iterations, 1) << what;
    EXPECT_EQ(r.stationary, StationaryKind::saddle) << what;
    EXPECT_NEAR(r.distance, 1.25, 1e-15) << what;
  }
}

TEST(ReferenceCases, T2SimplexHybridAndRobustEscapeTheSaddle) {
  const Segment s = t2_segment();
  const Vec3 point{0, 0, 1.25};
  for (const SearchMethod m : {SearchMethod::simplex, SearchMethod::hybrid, SearchMethod::robust}) {
    for (const Start& start : six_starts(s, point)) {
      const ProjectionResult r = project(s, point, start.xi, settings_for(m));
      const std::string what = describe(m, start.label, r);
      EXPECT_TRUE(r.converged) << what;
      EXPECT_EQ(r.stationary, StationaryKind::minimum) << what;
      EXPECT_NEAR(std::fabs(r.xi[0]), 0.7071068, 1e-7) << what;
      EXPECT_NEAR(r.xi[1], 0.0, 1e-7) << what;
      EXPECT_NEAR(r.distance, std::sqrt(1.5), 1e-12) << what;
    }
  }
}

TEST(ReferenceCases, T2FromTheCornersEveryGradientMethodFindsTheMinimum) {
  const Segment s = t2_segment();
  const Vec3 point{0, 0, 1.25};
  for (const SearchMethod m : gradient_methods) {
    for (const Start& start : six_starts(s, point)) {
      if (start.label == "lsp" || start.label == "center") continue;  // the saddle, above
      const ProjectionResult r = project(s, point, start.xi, settings_for(m));
      const std::string what = describe(m, start.label, r);
      EXPECT_TRUE(r.converged) << what;
      EXPECT_EQ(r.stationary, StationaryKind::minimum) << what;
      EXPECT_NEAR(std::fabs(r.xi[0]), 0.7071068, 1e-7) << what;
      EXPECT_NEAR(r.distance, std::sqrt(1.5), 1e-12) << what;
    }
  }
}

TEST(ReferenceCases, T2bEveryMethodFindsTheCentreFromEveryStart) {
  const Segment s = t2_segment();
  const Vec3 point{0, 0, 0.8};
  for (const auto& [m, method_name] : search_method_names) {
    for (const Start& start : six_starts(s, point)) {
      const ProjectionResult r = project(s, point, start.xi, settings_for(m));
      const std::string what = describe(m, start.label, r);
      EXPECT_TRUE(r.converged) << what;
      EXPECT_EQ(r.stationary, StationaryKind::minimum) << what;
      EXPECT_NEAR(r.xi[0], 0.0, 1e-7) << what;
      EXPECT_NEAR(r.xi[1], 0.0, 1e-7) << what;
      EXPECT_NEAR(r.distance, 0.8, 1e-12) << what;
    }
  }
}

TEST(ReferenceCases, T2cTheCentreIsAMaximumAndRobustFindsACorner) {
  const Segment s = t2_segment();
  const Vec3 point{0, 0, 6};
  for (const SearchMethod m : gradient_methods) {
    const ProjectionResult r = project(s, point, {0, 0}, settings_for(m));
    const std::string what = describe(m, "center", r);
    EXPECT_EQ(r.stationary, StationaryKind::maximum) << what;
    EXPECT_NEAR(r.distance, 6.0, 1e-15) << what;
  }
  // Newton from a corner: the unconstrained minimum, outside the segment.
  const ProjectionResult newton = project(s, point, {1, 1}, settings_for(SearchMethod::newton));
  EXPECT_EQ(newton.stationary, StationaryKind::minimum);
  EXPECT_NEAR(std::fabs(newton.xi[0]), std::sqrt(10.0), 1e-9);
  EXPECT_FALSE(newton.inside);
  // Steepest descent from a corner: g.H.g <= 0, the step of eq. 19 is undefined.
  const ProjectionResult sd = project(s, point, {1, 1}, settings_for(SearchMethod::steepest_descent));
  EXPECT_FALSE(sd.converged);
  EXPECT_EQ(sd.failure, FailureReason::non_positive_curvature);
  for (const Start& start : six_starts(s, point)) {
    const ProjectionResult r = project(s, point, start.xi, settings_for(SearchMethod::robust));
    const std::string what = describe(SearchMethod::robust, start.label, r);
    EXPECT_TRUE(r.converged) << what;
    EXPECT_EQ(std::fabs(r.xi[0]), 1.0) << what;
    EXPECT_EQ(std::fabs(r.xi[1]), 1.0) << what;
    EXPECT_NEAR(r.distance, 5.5821143, 1e-7) << what;
    EXPECT_TRUE(r.on_boundary) << what;
    EXPECT_TRUE(r.inside) << what;
    EXPECT_EQ(r.stationary, StationaryKind::none) << what;  // not a stationary point of f
  }
}

TEST(ReferenceCases, T3TwistedQuad4EveryMethodFromEveryStart) {
  const Segment s = t3_segment();
  const Vec3 point{0.2, 0.3, 0.8};
  for (const auto& [m, method_name] : search_method_names) {
    for (const Start& start : six_starts(s, point)) {
      const ProjectionResult r = project(s, point, start.xi, settings_for(m));
      const std::string what = describe(m, start.label, r);
      EXPECT_TRUE(r.converged) << what;
      EXPECT_EQ(r.stationary, StationaryKind::minimum) << what;
      EXPECT_NEAR(r.xi[0], 0.1610826, 5e-8) << what;
      EXPECT_NEAR(r.xi[1], 0.2774013, 5e-8) << what;
      EXPECT_NEAR(r.distance, 0.5629727, 5e-8) << what;
      EXPECT_TRUE(r.inside) << what;
    }
  }
}

TEST(ReferenceCases, T4OutsideUnconstrainedMethodsSayOutsideRobustFindsTheEdge) {
  const Segment s = flat_q8();
  const Vec3 point{1.5, 0.2, 0.3};
  for (const auto& [m, method_name] : search_method_names) {
    if (m == SearchMethod::robust) continue;
    for (const Start& start : six_starts(s, point)) {
      const ProjectionResult r = project(s, point, start.xi, settings_for(m));
      const std::string what = describe(m, start.label, r);
      EXPECT_TRUE(r.converged) << what;
      EXPECT_NEAR(r.xi[0], 1.5, 1e-8) << what;
      EXPECT_NEAR(r.xi[1], 0.2, 1e-8) << what;
      EXPECT_FALSE(r.inside) << what;
      EXPECT_NEAR(r.distance, 0.3, 1e-12) << what;
    }
  }
  for (const Start& start : six_starts(s, point)) {
    const ProjectionResult r = project(s, point, start.xi, settings_for(SearchMethod::robust));
    const std::string what = describe(SearchMethod::robust, start.label, r);
    EXPECT_TRUE(r.converged) << what;
    EXPECT_EQ(r.xi[0], 1.0) << what;
    EXPECT_NEAR(r.xi[1], 0.2, 1e-12) << what;
    EXPECT_NEAR(r.distance, 0.5830952, 1e-7) << what;
    EXPECT_TRUE(r.inside) << what;
    EXPECT_TRUE(r.on_boundary) << what;
  }
}

TEST(ReferenceCases, T4bRobustFindsTheCorner) {
  const Segment s = flat_q8();
  const Vec3 point{1.4, 1.3, 0.2};
  for (const Start& start : six_starts(s, point)) {
    const ProjectionResult r = project(s, point, start.xi, settings_for(SearchMethod::robust));
    const std::string what = describe(SearchMethod::robust, start.label, r);
    EXPECT_TRUE(r.converged) << what;
    EXPECT_EQ(r.xi[0], 1.0) << what;
    EXPECT_EQ(r.xi[1], 1.0) << what;
    EXPECT_NEAR(r.distance, 0.5385165, 1e-7) << what;
    EXPECT_TRUE(r.on_boundary) << what;
  }
}

TEST(ReferenceCases, T5QuarterPointFromTheLspGuessAndTheCentre) {
  const Segment s = t5_segment();
  const Vec3 point{-0.9, -0.95, 0.2};
  for (const auto& [m, method_name] : search_method_names) {
    for (const Start& start : six_starts(s, point)) {
      if (start.label != "lsp" && start.label != "center") continue;
      const ProjectionResult r = project(s, point, start.xi, settings_for(m));
      const std::string what = describe(m, start.label, r);
      EXPECT_TRUE(r.converged) << what;
      EXPECT_EQ(r.stationary, StationaryKind::minimum) << what;
      EXPECT_NEAR(r.xi[0], -0.6228027, 5e-8) << what;
      EXPECT_NEAR(r.xi[1], -0.8114014, 5e-8) << what;
      EXPECT_NEAR(r.distance, 0.2, 1e-12) << what;
      EXPECT_NEAR(r.gap, 0.2, 1e-12) << what;
    }
  }
}

TEST(ReferenceCases, T5FromTheSingularCornerEveryGradientMethodReportsTheSingularity) {
  const Segment s = t5_segment();
  const Vec3 point{-0.9, -0.95, 0.2};
  // LSP: A = a_a.a_b = 0 at the corner: its step is undefined.
  const ProjectionResult lsp = project(s, point, {-1, -1}, settings_for(SearchMethod::lsp));
  EXPECT_FALSE(lsp.converged);
  EXPECT_EQ(lsp.failure, FailureReason::singular_matrix);
  EXPECT_EQ(lsp.iterations, 0);
  // The others: g = -2 r.a = 0 there, so they stop at once on the corner,
  // where a_1 x a_2 = 0: no normal, and the result says so.
  for (const SearchMethod m : {SearchMethod::newton, SearchMethod::steepest_descent, SearchMethod::broyden,
                               SearchMethod::bfgs, SearchMethod::dfp}) {
    const ProjectionResult r = project(s, point, {-1, -1}, settings_for(m));
    const std::string what = describe(m, "corner1", r);
    EXPECT_EQ(r.failure, FailureReason::singular_jacobian) << what;
    EXPECT_EQ(r.xi[0], -1.0) << what;
    EXPECT_EQ(r.xi[1], -1.0) << what;
    EXPECT_EQ(r.gap, 0.0) << what;
    EXPECT_GT(r.distance, 0.2) << what;
  }
  // robust is not fooled.
  const ProjectionResult r = project(s, point, {-1, -1}, settings_for(SearchMethod::robust));
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.failure, FailureReason::none);
  EXPECT_NEAR(r.xi[0], -0.6228027, 5e-8);
  EXPECT_NEAR(r.xi[1], -0.8114014, 5e-8);
  EXPECT_NEAR(r.distance, 0.2, 1e-12);
}

TEST(ReferenceCases, T5OtherPointsOutsideTheSegmentAreAtTheSameDistance) {
  // The map is not one-to-one: Newton from the fourth corner lands outside.
  const Segment s = t5_segment();
  const Vec3 point{-0.9, -0.95, 0.2};
  const ProjectionResult r = project(s, point, {-1, 1}, settings_for(SearchMethod::newton));
  EXPECT_TRUE(r.converged);
  EXPECT_FALSE(r.inside);
  EXPECT_NEAR(r.distance, 0.2, 1e-12);
  EXPECT_NEAR(r.xi[0], 4.978, 1e-3);
  EXPECT_NEAR(r.xi[1], 1.989, 1e-3);
}

// A master block x <= 0, z <= 0: top face z = 0 and side face x = 0 meet at a
// convex edge along y. Both faces' nodes counter-clockwise seen from outside.
Segment block_face(bool top, SegmentType type) {
  Segment s;
  s.type = type;
  const auto map = [top](Xi xi) -> Vec3 {
    return top ? Vec3{0.5 * (xi[0] - 1.0), 0.5 * xi[1], 0.0} : Vec3{0.0, 0.5 * xi[0], 0.5 * (xi[1] - 1.0)};
  };
  for (int i = 0; i < node_count(type); ++i) s.nodes[i] = map(node_xi[i]);
  return s;
}

TEST(ReferenceCases, DeadZoneOutsideBothFacesTheClosestPointIsTheEdge) {
  const Vec3 point{0.3, 0, 0.4};
  for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
    for (const bool top : {true, false}) {
      const Segment s = block_face(top, type);
      // Unconstrained: the projection lies outside the face.
      const ProjectionResult newton = project(s, point, {0, 0}, settings_for(SearchMethod::newton));
      EXPECT_TRUE(newton.converged);
      EXPECT_FALSE(newton.inside);
      // robust: the edge point (0, 0, 0), distance 0.5, direction (0.6, 0, 0.8).
      const ProjectionResult r =
          project(s, point, initial_guess_lsp(s, point), settings_for(SearchMethod::robust));
      EXPECT_TRUE(r.on_boundary);
      EXPECT_NEAR(r.distance, 0.5, 1e-12);
      const Vec3 y = position(s, r.xi);
      EXPECT_NEAR(y.x, 0.0, 1e-12);
      EXPECT_NEAR(y.y, 0.0, 1e-12);
      EXPECT_NEAR(y.z, 0.0, 1e-12);
      const Vec3 direction = (1.0 / r.distance) * (point - y);
      EXPECT_NEAR(direction.x, 0.6, 1e-12);
      EXPECT_NEAR(direction.z, 0.8, 1e-12);
    }
  }
}

TEST(ReferenceCases, PenetratedPointTheNearestFaceIsTheSideFace) {
  const Vec3 point{-0.1, 0, -0.3};
  for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
    for (const auto& [m, method_name] : search_method_names) {
      const ProjectionSettings st = settings_for(m);
      const Segment top = block_face(true, type), side = block_face(false, type);
      const ProjectionResult rt = project(top, point, initial_guess_lsp(top, point), st);
      const ProjectionResult rs = project(side, point, initial_guess_lsp(side, point), st);
      EXPECT_TRUE(rt.inside && rs.inside) << method_name;
      EXPECT_NEAR(rt.gap, -0.3, 1e-9) << method_name;
      EXPECT_NEAR(rs.gap, -0.1, 1e-9) << method_name;
      EXPECT_LT(rs.distance, rt.distance) << method_name;
      const Vec3 y = position(side, rs.xi);
      EXPECT_NEAR(y.x, 0.0, 1e-9);
      EXPECT_NEAR(y.y, 0.0, 1e-8);
      EXPECT_NEAR(y.z, -0.3, 1e-8);
    }
  }
}

TEST(ReferenceCases, SelectMethodReturnsTheKernelOfEveryName) {
  for (const auto& [m, method_name] : search_method_names) {
    EXPECT_NE(select_method(m), nullptr) << method_name;
    const Segment s = t3_segment();
    const Vec3 point{0.2, 0.3, 0.8};
    ProjectionSettings st = settings_for(m);
    const ProjectionResult a = select_method(m)(s, point, {0, 0}, st);
    const ProjectionResult b = project(s, point, {0, 0}, st);
    EXPECT_EQ(a.xi, b.xi) << method_name;
    EXPECT_EQ(a.iterations, b.iterations) << method_name;
  }
}

TEST(ReferenceCases, MaxIterationsIsReportedWhenTheStoppingTestIsNotMet) {
  const Segment s = t2_segment();
  ProjectionSettings st = settings_for(SearchMethod::lsp);
  st.max_iterations = 5;
  const ProjectionResult r = project(s, {0, 0, 0.8}, {1, 1}, st);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.failure, FailureReason::max_iterations);
  EXPECT_EQ(r.iterations, 5);
}

}  // namespace
}  // namespace exdyn::contact
