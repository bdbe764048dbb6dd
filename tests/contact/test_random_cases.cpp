// Random distorted segments: every method against the brute-force truth,
// robust in 100 % of cases, rigid-motion invariance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "contact/local_search.hpp"
#include "random_cases.hpp"

namespace exdyn::contact {
namespace {

using testing::Distortion;
using testing::Random;
using testing::Truth;

std::string case_text(const Segment& s, const Vec3& point) {
  std::string text = std::string(name(s.type)) + " nodes";
  char buffer[128];
  for (int i = 0; i < node_count(s.type); ++i) {
    std::snprintf(buffer, sizeof buffer, " [%.17g, %.17g, %.17g]", s.nodes[i].x, s.nodes[i].y, s.nodes[i].z);
    text += buffer;
  }
  std::snprintf(buffer, sizeof buffer, " point [%.17g, %.17g, %.17g]", point.x, point.y, point.z);
  return text + buffer;
}

// Mildly distorted segments, points near the surface over its middle: the
// minimum is unique and interior (checked on the truth); every method from
// the LSP guess must find it.
TEST(RandomCases, EveryMethodAgreesWithTheDenseGridMinimumOnMildlyDistortedSegments) {
  Random rng(20261121);
  int used = 0;
  for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
    for (int k = 0; k < 300; ++k) {
      const Segment s = testing::random_segment(rng, type, Distortion::mild);
      const Vec3 point = testing::random_point(rng, s, 0.7, 0.3);
      const Truth truth = testing::brute_force_closest_point(s, point);
      const bool unique_interior = std::fabs(truth.xi[0]) < 0.95 && std::fabs(truth.xi[1]) < 0.95 &&
                                   truth.second_distance > truth.distance + 1e-3;
      if (!unique_interior) continue;
      ++used;
      const Xi start = initial_guess_lsp(s, point);
      for (const auto& [m, method_name] : search_method_names) {
        ProjectionSettings st;
        st.method = m;
        st.tolerance = 1e-10;
        st.max_iterations = 1000;
        const ProjectionResult r = project(s, point, start, st);
        const std::string what = std::string(method_name) + " on " + case_text(s, point);
        ASSERT_TRUE(r.converged) << what << " failure " << name(r.failure);
        EXPECT_EQ(r.stationary, StationaryKind::minimum) << what;
        EXPECT_NEAR(r.xi[0], truth.xi[0], 1e-6) << what;
        EXPECT_NEAR(r.xi[1], truth.xi[1], 1e-6) << what;
        EXPECT_NEAR(r.distance, truth.distance, 1e-11) << what;
        EXPECT_TRUE(r.inside) << what;
      }
    }
  }
  EXPECT_GE(used, 500);  // most cases qualify
}

// robust: the closest point of the segment itself (interior, edge or corner)
// in every one of 2 x 3 x 2000 = 12,000 random cases, from the LSP guess.
TEST(RandomCases, RobustFindsTheClosestPointOfTheSegmentInEveryCase) {
  Random rng(77);
  int cases = 0, failures = 0, on_boundary = 0;
  ProjectionSettings st;
  st.method = SearchMethod::robust;
  for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
    for (const Distortion d : {Distortion::mild, Distortion::moderate, Distortion::strong}) {
      for (int k = 0; k < 2000; ++k) {
        const Segment s = testing::random_segment(rng, type, d);
        // Above, below and beside: xi_p in [-1.5, 1.5]^2, up to 1 along the normal.
        const Vec3 point = testing::random_point(rng, s, 1.5, 1.0);
        const Truth truth = testing::brute_force_closest_point(s, point);
        const ProjectionResult r = project(s, point, initial_guess_lsp(s, point), st);
        ++cases;
        on_boundary += r.on_boundary ? 1 : 0;
        // A point of the segment at most as far as the truth's is a closest point.
        const bool found = r.converged && std::fabs(r.xi[0]) <= 1.0 && std::fabs(r.xi[1]) <= 1.0 &&
                           r.distance <= truth.distance + 1e-10;
        if (!found) {
          ++failures;
          ADD_FAILURE() << name(type) << " " << testing::distortion_name(d) << " " << case_text(s, point)
                        << "\n robust xi (" << r.xi[0] << ", " << r.xi[1] << ") d " << r.distance
                        << " converged " << r.converged << "\n truth  xi (" << truth.xi[0] << ", "
                        << truth.xi[1] << ") d " << truth.distance;
          continue;
        }
        if (truth.second_distance > truth.distance + 1e-6) {
          EXPECT_NEAR(r.xi[0], truth.xi[0], 1e-6) << case_text(s, point);
          EXPECT_NEAR(r.xi[1], truth.xi[1], 1e-6) << case_text(s, point);
        }
        if (!r.on_boundary) {
          EXPECT_NE(r.stationary, StationaryKind::saddle) << case_text(s, point);
          EXPECT_NE(r.stationary, StationaryKind::maximum) << case_text(s, point);
        }
      }
    }
  }
  EXPECT_EQ(cases, 12000);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(on_boundary, 1000);  // edges and corners are well represented
  std::printf("robust: %d cases, %d failures, %d on an edge or a corner\n", cases, failures, on_boundary);
}

// Newton from the centre on the same kind of cases: not robust (for the record).
TEST(RandomCases, NewtonFromTheCentreIsNotRobust) {
  Random rng(78);
  ProjectionSettings st;
  st.method = SearchMethod::newton;
  for (const Distortion d : {Distortion::mild, Distortion::moderate, Distortion::strong}) {
    int hits = 0;
    const int n = 1000;
    for (int k = 0; k < n; ++k) {
      const Segment s = testing::random_segment(rng, SegmentType::quad8, d);
      const Vec3 point = testing::random_point(rng, s, 1.5, 1.0);
      const Truth truth = testing::brute_force_closest_point(s, point);
      const ProjectionResult r = project(s, point, {0, 0}, st);
      if (r.converged && r.inside && std::fabs(r.distance - truth.distance) <= 1e-10) ++hits;
    }
    std::printf("newton from the centre, quad8 %s: %.1f %% on the closest point of the segment\n",
                testing::distortion_name(d), 100.0 * hits / n);
    EXPECT_LT(hits, n);
  }
}

// The answer does not change under a rigid rotation and translation.
TEST(RandomCases, RobustIsInvariantUnderRigidMotions) {
  Random rng(99);
  ProjectionSettings st;
  st.method = SearchMethod::robust;
  for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
    for (const Distortion d : {Distortion::mild, Distortion::moderate, Distortion::strong}) {
      for (int k = 0; k < 300; ++k) {
        const Segment s = testing::random_segment(rng, type, d);
        const Vec3 point = testing::random_point(rng, s, 1.5, 1.0);
        const testing::RigidMotion motion = testing::random_motion(rng, 10.0);
        const Segment moved = testing::transformed(s, motion);
        const Vec3 moved_point = motion.apply(point);
        const ProjectionResult a = project(s, point, initial_guess_lsp(s, point), st);
        const ProjectionResult b = project(moved, moved_point, initial_guess_lsp(moved, moved_point), st);
        const std::string what = case_text(s, point);
        EXPECT_NEAR(a.distance, b.distance, 1e-12) << what;
        EXPECT_NEAR(a.gap, b.gap, 1e-9) << what;
        EXPECT_EQ(a.on_boundary, b.on_boundary) << what;
        const Truth truth = testing::brute_force_closest_point(s, point);
        if (truth.second_distance > truth.distance + 1e-6) {  // xi is unique
          EXPECT_NEAR(a.xi[0], b.xi[0], 1e-8) << what;
          EXPECT_NEAR(a.xi[1], b.xi[1], 1e-8) << what;
        }
      }
    }
  }
}

}  // namespace
}  // namespace exdyn::contact
