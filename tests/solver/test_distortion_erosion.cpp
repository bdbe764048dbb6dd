// time.erode (docs/theory.md, "Damage and erosion"): an element of a part that can fail
// whose own step falls below min_dt_ratio of the first, or that inverts, is eroded
// instead of stopping the run. The scene is input/perforation.yaml on a coarse plate
// (16 x 16 x 4 bricks, 3 mm through the thickness), where the bricks crushed beside the
// projectile's rim invert at 29 us.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "../support/deck_run.hpp"
#include "common/errors.hpp"
#include "input/deck_reader.hpp"
#include "solver/simulation.hpp"

namespace {

using exdyn::testing::DeckRun;

std::vector<exdyn::input::Override> coarse(bool erode, double end_time) {
  return {exdyn::input::parse_override("parts[1].elements=[16, 16, 4]"),
          exdyn::input::parse_override("parts[0].elements=[4, 2, 16]"),
          exdyn::input::parse_override("time.end_time=" + std::to_string(end_time)),
          exdyn::input::parse_override(std::string("time.erode=") + (erode ? "true" : "false")),
          exdyn::input::parse_override("output.every=5")};
}

TEST(DistortionErosion, AnElementThatWouldStopTheRunInvertedErodesInstead) {
  // Without the rule the inversion guard stops the run (exit 1), naming the element.
  exdyn::testing::TempDir directory{"exdyn_stopped"};
  const exdyn::input::Deck deck =
      exdyn::input::read_deck(DeckRun::source_path("perforation.yaml"), coarse(false, 4.0e-5));
  std::string message;
  long inverted_step = -1;
  try {
    exdyn::solver::RunControls controls;
    controls.output_directory = directory.path().string();
    exdyn::solver::run_simulation(deck, controls);
  } catch (const exdyn::RunFailure& failure) {
    message = failure.what(), inverted_step = failure.step();
  }
  ASSERT_NE(message.find(" is inverted"), std::string::npos) << message;
  const std::size_t begin = message.find("element ") + 8;
  const std::size_t inverted = std::stoul(message.substr(begin, message.find(' ', begin) - begin));

  const DeckRun eroding("perforation.yaml", coarse(true, 4.0e-5));
  ASSERT_EQ(eroding.summary.status, "completed") << eroding.summary.message;
  // The element that inverted without the rule fails at that step (the runs are the same
  // run until then) and is gone at the next written step, with its damage below 1: the
  // rule, not the damage, failed it.
  const long written = (inverted_step + 4) / 5 * 5;
  EXPECT_EQ(eroding.at(written - 5, "status")[inverted], 1.0);
  EXPECT_EQ(eroding.at(written, "status")[inverted], 0.0);
  EXPECT_LT(eroding.at(written, "damage")[inverted], 1.0);
  // Before the rule takes an element, both runs are the same run.
  EXPECT_EQ(
      exdyn::testing::read_dataset(directory.file("perforation.h5"), "/steps/000005/displacement").values,
      eroding.at(5, "displacement"));
  const std::vector<double> status = eroding.final("status"), damage = eroding.final("damage");
  long distorted = 0;
  for (std::size_t e = 0; e < status.size(); ++e) distorted += status[e] == 0.0 && damage[e] < 1.0;
  EXPECT_GE(distorted, 2);
  EXPECT_EQ(eroding.summary.energy.eroded_elements, std::count(status.begin(), status.end(), 0.0));
  // The step stays above min_dt_ratio (0.1) of the first: a marked element sets none.
  EXPECT_GT(eroding.summary.dt_min, 0.1 * eroding.summary.dt);
  // The balance with the energy the eroded elements took along.
  EXPECT_LT(eroding.summary.energy.max_relative_error, 2.0e-3);
}

}  // namespace

namespace {

// input/perforation_fine.yaml: the same scene on the round plate of
// input/meshes/weldox_plate.geo. The mesh is the quarter disc (every node within R of
// the axis, the clamped rim's at R), and the projectile, 0.2 mm above the plate at 300
// m/s, touches it when the gap closes at 0.2 mm / 300 m/s = 0.667 us, not before.
TEST(PerforationFine, TheRoundPlateIsTheQuarterDiscTouchedWhenTheGapCloses) {
  const DeckRun run("perforation_fine.yaml", {exdyn::input::parse_override("time.end_time=1.5e-6"),
                                              exdyn::input::parse_override("output.history_every=1"),
                                              exdyn::input::parse_override("output.every=1000")});
  ASSERT_EQ(run.summary.status, "completed") << run.summary.message;
  const std::vector<double> x = exdyn::testing::read_dataset(run.h5(), "/mesh/coordinates").values;
  const std::vector<double> part = exdyn::testing::read_dataset(run.h5(), "/mesh/part").values;
  const std::vector<double> cells = exdyn::testing::read_dataset(run.h5(), "/mesh/connectivity").values;
  constexpr double radius = 50e-3, thickness = 12e-3;
  double largest = 0.0, lowest = 0.0;
  for (std::size_t e = 0; e < part.size(); ++e) {
    if (part[e] != 1.0) continue;
    for (std::size_t k = 0; k < 8; ++k) {
      const std::size_t n = std::size_t(cells[8 * e + k]);
      largest = std::max(largest, std::hypot(x[3 * n], x[3 * n + 1]));
      lowest = std::min(lowest, x[3 * n + 2]);
    }
  }
  EXPECT_NEAR(largest, radius, 1e-12 * radius);
  EXPECT_NEAR(lowest, -thickness, 1e-12 * thickness);
  const std::vector<double> time = run.history("time");
  const std::vector<double> force = run.history("contact/all/force");
  const double touch = 0.2e-3 / 300.0, dt = run.summary.dt;
  long touched = 0;
  for (std::size_t n = 0; n < time.size(); ++n) {
    if (time[n] < touch - dt) {
      EXPECT_EQ(force[3 * n + 2], 0.0) << time[n];
    } else if (time[n] > touch + dt) {
      EXPECT_GT(std::abs(force[3 * n + 2]), 0.0) << time[n];
      ++touched;
    }
  }
  EXPECT_GT(touched, 10);
  EXPECT_LT(run.summary.energy.max_relative_error, 1e-3);
}

}  // namespace
