// Damage and erosion (docs/verification.md, "Damage and erosion"): a brick pulled apart
// in uniaxial strain (input/tension_failure.yaml), every node prescribed, so that its
// state is homogeneous and known exactly at every step; and a bar of 1,536 bricks
// pulled until every layer has failed, on 1, 2 and 3 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "../support/deck_run.hpp"

namespace {

using exdyn::testing::DeckRun;

// The deck's brick: steel, linear hardening, small strain, 1 us steps, V = 10 m/s on L = 10 mm.
constexpr double youngs = 2.0e11, nu = 0.3, yield = 4.0e8, hardening = 1.0e9;
constexpr double dt = 1.0e-6, speed = 10.0, length = 0.01, area = 1.0e-4;
constexpr double shear = youngs / (2.0 * (1.0 + nu)), bulk = youngs / (3.0 * (1.0 - 2.0 * nu));

// The exact state at step n: eps_zz, eps_p, q (von Mises) and sigma_zz.
struct Exact {
  double strain, plastic, q, sigma_zz, mean;
};
Exact exact(long n) {
  Exact s;
  s.strain = double(n) * dt * speed / length;
  s.plastic = std::max((2.0 * shear * s.strain - yield) / (3.0 * shear + hardening), 0.0);
  s.q = s.plastic > 0.0 ? yield + hardening * s.plastic : 2.0 * shear * s.strain;
  s.mean = bulk * s.strain;
  s.sigma_zz = s.mean + 2.0 / 3.0 * s.q;
  return s;
}

// The last step whose reaction at the moving end is not zero: the step the brick failed at
// (it carries its force at that step, none from the next).
long failure_step(const DeckRun& run) {
  const std::vector<double> force = run.history("boundary/3/force");
  long last = -1;
  for (std::size_t n = 0; 3 * n < force.size(); ++n)
    if (force[3 * n + 2] != 0.0) last = long(n);
  return last;
}

class TensionFailure : public ::testing::TestWithParam<std::string> {};

// The one-point brick too: a homogeneous state has no hourglass mode.
INSTANTIATE_TEST_SUITE_P(Bricks, TensionFailure, ::testing::Values("hex8", "hex8r"));

TEST_P(TensionFailure, FailsAtTheExactStepCarryingTheHardeningLawsForceUntilThen) {
  const DeckRun run("tension_failure.yaml",
                    {exdyn::input::parse_override("parts[0].formulation=" + GetParam())});
  ASSERT_EQ(run.summary.status, "completed");
  long analytical = 0;
  while (exact(analytical).plastic < 0.05) ++analytical;
  EXPECT_EQ(analytical, 78);
  EXPECT_EQ(failure_step(run), analytical);
  const std::vector<double> force = run.history("boundary/3/force");
  const std::vector<double> held = run.history("boundary/2/force");
  const long steps = long(force.size() / 3);
  for (long n = 1; n <= analytical; ++n) {
    EXPECT_NEAR(force[3 * n + 2] / (area * exact(n).sigma_zz), 1.0, 1e-12) << n;
    EXPECT_NEAR(held[3 * n + 2] / (area * exact(n).sigma_zz), -1.0, 1e-12) << n;
  }
  for (long n = analytical + 1; n < steps; ++n) EXPECT_EQ(force[3 * n + 2], 0.0) << n;
  // The fields: eroded, damage 1, no stress.
  EXPECT_EQ(run.final("status"), std::vector<double>{0.0});
  EXPECT_EQ(run.final("damage"), std::vector<double>{1.0});
  EXPECT_EQ(run.final("stress"), std::vector<double>(6, 0.0));
  EXPECT_EQ(run.at(70, "status"), std::vector<double>{1.0});
  EXPECT_NEAR(run.at(70, "damage")[0], exact(70).plastic / 0.05, 1e-12);
  // The energy left with the element: the internal energy gone, the eroded energy up by
  // as much, and the balance closed to round-off at every step, the failure step too
  // (the plastic work by the trapezoid is the work the prescribed motion did).
  const std::vector<double> internal = run.history("internal_energy");
  const std::vector<double> eroded = run.history("eroded_energy");
  const std::vector<double> total = run.history("total_energy");
  EXPECT_EQ(eroded[std::size_t(analytical)], 0.0);
  EXPECT_EQ(internal[std::size_t(analytical) + 1], 0.0);
  EXPECT_GT(eroded[std::size_t(analytical) + 1], internal[std::size_t(analytical)]);
  for (std::size_t n = 0; n < total.size(); ++n) EXPECT_NEAR(total[n], total[0], 1e-12 * eroded.back()) << n;
  EXPECT_LT(run.summary.energy.max_relative_error, 1e-13);
  EXPECT_EQ(run.history("eroded_mass").back(), 0.0);  // the mass stays on the nodes
  EXPECT_EQ(run.summary.energy.eroded_elements, 1);
  EXPECT_EQ(run.summary.energy.eroded, eroded.back());
}

TEST(TensionFailureJohnsonCook, FailsWithinAStepOfItsDamageSummedOverTheExactPath) {
  // D = sum d eps_p / eps_f(sigma*, eps_dot_p), over the exact path, step by step.
  const double d1 = 0.01, d2 = 0.3, d3 = -1.5, d4 = 0.01;
  const DeckRun run("tension_failure.yaml", {exdyn::input::parse_override(
                                                "materials.steel.failure={johnson_cook: {D1: 0.01, D2: 0.3, "
                                                "D3: -1.5, D4: 0.01}}")});
  double damage = 0.0;
  long predicted = 0;
  for (long n = 1; damage < 1.0; ++n) {
    const Exact now = exact(n), before = exact(n - 1);
    const double increment = now.plastic - before.plastic;
    if (increment > 0.0) {
      const double triaxiality = std::min(now.mean / now.q, 1.5);
      const double rate = std::max(increment / dt, 1.0);  // eps_dot_0 = 1 /s
      damage += increment / ((d1 + d2 * std::exp(d3 * triaxiality)) * (1.0 + d4 * std::log(rate)));
    }
    predicted = n;
  }
  EXPECT_LE(std::abs(failure_step(run) - predicted), 1) << failure_step(run) << " against " << predicted;
  EXPECT_GT(predicted, 20);  // past yield by many steps
}

}  // namespace
