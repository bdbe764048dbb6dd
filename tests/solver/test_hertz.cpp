// The Hertz impact (input/hertz_ball.yaml): a quarter ball of 20-node bricks on a
// free block, against Hertz theory with the reduced mass. The full deck runs in
// scripts (docs/verification.md); here a coarser mesh of the same deck (2.4 s).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "../support/result_file.hpp"
#include "../support/temp_dir.hpp"
#include "input/deck_reader.hpp"
#include "solver/simulation.hpp"

namespace {

using exdyn::testing::read_dataset;

struct Hertz {
  double delta = 0.0, force = 0.0, time = 0.0;  // m, N, s
};

// Hertz theory for a ball on a flat of the same material: E* = E / (2 (1 - nu^2)),
// m the reduced mass of the ball and the block (40 x 40 x 20 mm).
Hertz hertz() {
  const double E = 2.1e11, nu = 0.3, rho = 7800, R = 0.01, v = 10.0;
  const double e_star = E / (2.0 * (1.0 - nu * nu));
  const double ball = rho * 4.0 / 3.0 * std::numbers::pi * R * R * R, block = rho * 0.04 * 0.04 * 0.02;
  const double m = ball * block / (ball + block);
  Hertz h;
  h.delta = std::pow(15.0 * m * v * v / (16.0 * e_star * std::sqrt(R)), 0.4);
  h.force = 4.0 / 3.0 * e_star * std::sqrt(R) * std::pow(h.delta, 1.5);
  h.time = 2.943 * h.delta / v;
  return h;
}

TEST(HertzBall, PeakForceAndContactTimeWithinTwoPercentOfHertz) {
  const Hertz exact = hertz();
  EXPECT_NEAR(exact.force, 25670.6, 0.1);  // the deck's comment
  EXPECT_NEAR(exact.time, 41.40e-6, 0.005e-6);
  exdyn::testing::TempDir directory{"exdyn_hertz"};
  const exdyn::input::Deck deck =
      exdyn::input::read_deck(std::string(EXDYN_SOURCE_DIR) + "/input/hertz_ball.yaml",
                              {{"parts[0].elements", "[8, 2]"}, {"parts[1].elements", "[6, 6, 5]"}});
  exdyn::solver::RunControls controls;
  controls.output_directory = directory.path().string();
  const auto summary = exdyn::solver::run_simulation(deck, controls);
  const std::string h5 = directory.file(deck.name + ".h5");
  const auto time = read_dataset(h5, "/history/time").values;
  const auto force = read_dataset(h5, "/history/contact/impact/force").values;  // (H, 3) on the ball
  double peak = 0.0, first = -1.0, last = -1.0;
  for (std::size_t i = 0; i < time.size(); ++i)
    peak = std::max(peak, 4.0 * force[3 * i + 2]);  // quarter model
  for (std::size_t i = 0; i < time.size(); ++i) {
    if (4.0 * force[3 * i + 2] <= 1e-3 * peak) continue;
    if (first < 0.0) first = time[i];
    last = time[i];
  }
  std::printf("Hertz ball (8 x 2 on 6 x 6 x 5): F_max %.1f N (%+.2f %%), contact time %.2f us (%+.2f %%)\n",
              peak, 100 * (peak / exact.force - 1), 1e6 * (last - first),
              100 * ((last - first) / exact.time - 1));
  EXPECT_NEAR(peak, exact.force, 0.02 * exact.force);
  EXPECT_NEAR(last - first, exact.time, 0.02 * exact.time);
  EXPECT_LT(last, time.back());  // the ball has left the block
  EXPECT_LE(summary.energy.max_relative_error, 1e-3);
  EXPECT_EQ(summary.contact.not_converged, 0);
}

}  // namespace
