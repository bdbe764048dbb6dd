// Coulomb friction of the contact pass (contact/friction.hpp, contact_pass.cpp): the
// law, the return to the cone, and the stick anchor that a sliding point carries
// across a segment boundary without resetting it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "contact/contact_pass.hpp"
#include "contact/friction.hpp"

namespace {

using namespace exdyn::contact;

TEST(FrictionLaw, DecaysFromStaticToDynamicWithTheSlipSpeed) {
  FrictionLaw law{true, 0.5, 0.3, 2.0};
  EXPECT_DOUBLE_EQ(law.coefficient(0.0), 0.5);
  EXPECT_DOUBLE_EQ(law.coefficient(1.0), 0.3 + 0.2 * std::exp(-2.0));
  EXPECT_NEAR(law.coefficient(1e3), 0.3, 1e-15);
  law.decay = 0.0;  // no decay: mu_s at every speed
  EXPECT_DOUBLE_EQ(law.coefficient(7.0), 0.5);
}

TEST(CoulombForce, SticksInsideTheConeAndReturnsToItOutside) {
  const TangentialForce stick = coulomb_force({1e-3, 0.0, 0.0}, 1e6, 10e3, 0.2);  // 1000 N < 2000 N
  EXPECT_FALSE(stick.slip);
  EXPECT_DOUBLE_EQ(stick.force.x, -1000.0);
  EXPECT_EQ(stick.dissipation, 0.0);
  EXPECT_EQ(norm(stick.anchor_shift), 0.0);
  const TangentialForce slip = coulomb_force({3e-3, 4e-3, 0.0}, 1e6, 10e3, 0.2);  // 5000 N > 2000 N
  EXPECT_TRUE(slip.slip);
  EXPECT_NEAR(norm(slip.force), 2000.0, 1e-9);
  EXPECT_NEAR(slip.force.x / slip.force.y, 0.75, 1e-15);  // against the tangential gap
  EXPECT_LT(slip.force.x, 0.0);
  // The anchor follows until the spring holds mu F_n: 5 mm - 2 mm = 3 mm along the gap.
  EXPECT_NEAR(norm(slip.anchor_shift), 3e-3, 1e-15);
  EXPECT_NEAR(slip.dissipation, 2000.0 * 3e-3, 1e-12);
}

// A slave node pressed 0.01 into a flat master of two segments, x in [0, 1] and [1, 2],
// slides along +x at 0.1 a step: it slips with F_t = mu F_n from its first step, and
// its anchor passes from segment 0 to segment 1 without being dropped.
TEST(FrictionPass, TheAnchorCrossesTheSegmentBoundaryWithoutReset) {
  exdyn::NodalVectors x_ref(7), u(7), v(7);
  const double xs[6] = {0, 1, 2, 0, 1, 2}, ys[6] = {0, 0, 0, 1, 1, 1};
  for (int i = 0; i < 6; ++i) x_ref.x[i] = xs[i], x_ref.y[i] = ys[i];
  x_ref.x[6] = 0.45, x_ref.y[6] = 0.5, x_ref.z[6] = -0.01;
  ContactSurfaces surfaces;
  surfaces.slave_nodes = {6};
  surfaces.stiffness = {1e6};
  surfaces.normal_length = {1.0};
  SegmentNodes left, right;
  left.nodes = {0, 1, 4, 3};
  right.nodes = {1, 2, 5, 4};
  surfaces.segments = {left, right};
  surfaces.moving_nodes = {0, 1, 2, 3, 4, 5, 6};
  ContactPassSettings settings;
  settings.project = select_method(SearchMethod::bfgs);
  settings.automatic_stiffness = false;
  settings.dt = 1e-3;
  settings.search_distance = settings.margin = 0.5;
  settings.friction = FrictionLaw{true, 0.5, 0.5, 0.0};
  ContactPassState state;
  const std::vector<double> mass(7, 1.0);
  ContactStatistics statistics;
  ContactPhaseSeconds seconds;
  v.x[6] = 100.0;  // 0.1 a step
  std::vector<std::int64_t> anchor_segments;
  for (int step = 0; step < 10; ++step) {
    u.x[6] = 0.1 * step;
    exdyn::NodalVectors force(7);
    std::vector<double> gap(7, std::numeric_limits<double>::infinity());
    run_contact_pass(surfaces, settings, state, x_ref, u, v, mass, force, gap, statistics, seconds);
    ASSERT_NEAR(force.z[6], 1e6 * 0.01, 1e-6) << step;  // the normal spring
    EXPECT_NEAR(force.x[6], -0.5 * 1e4, 1e-6) << step;  // mu F_n against the slip, from the first step
    EXPECT_NEAR(force.x[0] + force.x[1] + force.x[2] + force.x[3] + force.x[4] + force.x[5], 0.5 * 1e4, 1e-6);
    EXPECT_EQ(state.slipping, 1);
    anchor_segments.push_back(state.anchors[0].segment);
  }
  // The node passes x = 1 at step 6 (0.45 + 0.6 = 1.05); its anchor trails it by
  // mu F_n / k = 5 mm.
  EXPECT_EQ(anchor_segments.front(), 0);
  EXPECT_EQ(anchor_segments.back(), 1);
  for (const std::int64_t segment : anchor_segments) EXPECT_GE(segment, 0);  // never dropped
  // mu F_n times the slip: 0.1 a step less the 5 mm the spring holds.
  EXPECT_NEAR(state.friction_work, 0.5 * 1e4 * (10 * 0.1 - 0.5 * 1e4 / 1e6), 1e-9);
}

}  // namespace
