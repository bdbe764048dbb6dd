// Prescribed velocity (boundary_conditions[].velocity): a bar in uniaxial strain whose
// end moves at V from the start. Exact figures of central differences: the energy
// balance with the work of the motion, W = sum dt/2 (R^{n-1} + R^n).V, closes to
// round-off; the front crosses one brick a step at most, so the held end feels
// nothing before it; and the driven end's reaction is rho c1 A V, the impedance of the
// bar, while the front runs (docs/verification.md, "Prescribed motion").
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "../support/deck_run.hpp"
#include "common/errors.hpp"

namespace {

using exdyn::testing::DeckRun;

// A steel bar 0.2 m long, 1 cm square, 40 bricks along z; every lateral face held
// normal to itself (uniaxial strain: the exact wave speed is c1); zmin held, zmax
// moving at +1 m/s.
std::string bar_deck(const std::string& formulation) {
  return "name: pulled\n"
         "materials:\n"
         "  steel: {model: linear_elastic, density: 7800, youngs_modulus: 2.0e11, poissons_ratio: 0.3}\n"
         "parts:\n"
         "  - {name: bar, box: {min: [0, 0, 0], max: [0.01, 0.01, 0.2]}, elements: [1, 1, 40],\n"
         "     material: steel, formulation: " +
         formulation +
         "}\n"
         "boundary_conditions:\n"
         "  - {faces: [bar.xmin, bar.xmax], fix: [x]}\n"
         "  - {faces: [bar.ymin, bar.ymax], fix: [y]}\n"
         "  - {faces: [bar.zmin], fix: [z]}\n"
         "  - {faces: [bar.zmax], velocity: {z: 1.0}}\n"
         "time: {end_time: 3.0e-5}\n"
         "output: {every: 1000}\n";
}

TEST(PrescribedVelocity, PulledBarClosesTheEnergyBalanceAndCarriesItsImpedance) {
  for (const std::string formulation : {"hex8", "hex8r", "hex20"}) {
    SCOPED_TRACE(formulation);
    const DeckRun run(exdyn::input::parse_deck(bar_deck(formulation), "pulled.yaml"));
    EXPECT_EQ(run.summary.status, "completed");
    EXPECT_LT(run.summary.energy.max_relative_error, 1e-12);
    const std::vector<double> time = run.history("time");
    const std::vector<double> held = run.history("boundary/2/force");
    const std::vector<double> driven = run.history("boundary/3/force");
    const std::vector<double> work = run.history("external_work");
    ASSERT_EQ(driven.size(), 3 * time.size());
    // The front crosses at most one element a step (a brick couples its own nodes
    // alone): the held end feels nothing for the first 39 steps of 40 bricks.
    for (std::size_t n = 0; n < 39; ++n) EXPECT_EQ(held[3 * n + 2], 0.0) << n;
    EXPECT_NE(held[3 * (time.size() - 1) + 2], 0.0);
    const double rho = 7800.0, e = 2.0e11, nu = 0.3, area = 1.0e-4, v = 1.0;
    const double c1 = std::sqrt(e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu) * rho));
    const double transit = 0.2 / c1;
    // The mean reaction while the front runs, from t = transit / 4 to 3 transit / 4:
    // the work of the motion over that time is R V dt (R constant), J.
    std::size_t a = 0, b = 0;
    while (time[a] < 0.25 * transit) ++a;
    while (time[b] < 0.75 * transit) ++b;
    const double mean = (work[b] - work[a]) / (v * (time[b] - time[a]));
    EXPECT_NEAR(mean / (rho * c1 * area * v), 1.0, 0.01);
    // The x and y reactions of the driven face: none (its x and y are free).
    for (std::size_t n = 0; n < time.size(); ++n) {
      EXPECT_EQ(driven[3 * n], 0.0);
      EXPECT_EQ(driven[3 * n + 1], 0.0);
    }
  }
}

TEST(PrescribedVelocity, TwoValuesAtASharedNodeAreBadInputAndNothingIsWritten) {
  std::string text = bar_deck("hex8");
  text.replace(text.find("  - {faces: [bar.zmin], fix: [z]}"), 33,
               "  - {faces: [bar.zmin, bar.zmax], fix: [z]}");
  const exdyn::input::Deck deck = exdyn::input::parse_deck(text, "pulled.yaml");
  exdyn::testing::TempDir directory{"exdyn_conflict"};
  exdyn::solver::RunControls controls;
  controls.output_directory = directory.path().string();
  try {
    exdyn::solver::run_simulation(deck, controls);
    ADD_FAILURE() << "a node held at rest and moved at 1 m/s was accepted";
  } catch (const exdyn::InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("boundary_conditions[2] and boundary_conditions[3] prescribe different z "
                                   "velocities (0 and 1 m/s)"),
        std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(directory.file("pulled.h5")));
}

}  // namespace
