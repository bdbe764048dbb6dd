// Bending: a cantilever's first frequency (input/cantilever.yaml) against Euler-Bernoulli
// for each brick (docs/verification.md, "Bending"). The frequency goes as the square
// root of the bending stiffness, so it shows a brick that locks (stiff) or whose
// hourglass control carries the bending (soft).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../support/deck_run.hpp"

namespace {

using exdyn::testing::DeckRun;

// Euler-Bernoulli: omega_1 = 1.875104^2 sqrt(E I / (rho A L^4)), I / A = h^2 / 12, Hz.
double beam_frequency() {
  const double e = 2.1e11, rho = 7800.0, h = 1.0e-3, length = 0.02;
  return 1.875104 * 1.875104 * std::sqrt(e * h * h / (12.0 * rho * std::pow(length, 4))) /
         (2.0 * std::numbers::pi);
}

// The tip's mean z displacement at every written step; the frequency from the first and
// the last of its zero crossings (linear between written steps), Hz.
double tip_frequency(const DeckRun& run) {
  const std::vector<double> x = exdyn::testing::read_dataset(run.h5(), "/mesh/coordinates").values;
  const std::vector<double> times = exdyn::testing::read_dataset(run.h5(), "/time").values;
  std::vector<std::size_t> tip;
  for (std::size_t i = 0; 3 * i < x.size(); ++i)
    if (std::abs(x[3 * i] - 0.02) < 1e-12) tip.push_back(i);
  std::vector<double> w;
  const long every = run.deck.output.every;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const long step = k + 1 < times.size() ? long(k) * every : run.summary.steps;
    const std::vector<double> u = run.at(step, "displacement");
    double sum = 0.0;
    for (const std::size_t i : tip) sum += u[3 * i + 2];
    w.push_back(sum / double(tip.size()));
  }
  std::vector<double> crossings;
  for (std::size_t k = 1; k + 1 < w.size(); ++k)  // from the second sample: w(0) = 0
    if (w[k] * w[k + 1] < 0.0)
      crossings.push_back(times[k] - w[k] * (times[k + 1] - times[k]) / (w[k + 1] - w[k]));
  if (crossings.size() < 3) return 0.0;
  const double half_periods = double(crossings.size() - 1);
  return half_periods / (2.0 * (crossings.back() - crossings.front()));
}

struct Case {
  std::string formulation, elements;
  double low, high;  // the ratio to Euler-Bernoulli asked
};

TEST(Cantilever, FirstBendingFrequencyOfEachBrickAgainstBeamTheory) {
  // 20-node bricks bend right; the 8-node brick with F-bar carries some shear in bending
  // (its fully integrated shear locks: stiff); the one-point brick bends through its
  // hourglass modes, whose assumed-strain stiffness is the beam's: right with one brick
  // through the thickness too.
  const std::vector<Case> cases = {{"hex20", "[20, 1, 1]", 0.995, 1.01},
                                   {"hex8", "[40, 1, 2]", 1.0, 1.10},
                                   {"hex8r", "[40, 1, 1]", 0.99, 1.01},
                                   {"hex8r", "[40, 1, 2]", 0.99, 1.02},
                                   {"hex8r", "[40, 1, 4]", 0.99, 1.01}};
  const double reference = beam_frequency();
  EXPECT_NEAR(reference, 2095.475, 1e-3);
  for (const Case& c : cases) {
    const DeckRun run("cantilever.yaml",
                      {{"parts[0].formulation", c.formulation}, {"parts[0].elements", c.elements}});
    const double ratio = tip_frequency(run) / reference;
    EXPECT_GE(ratio, c.low) << c.formulation << " " << c.elements;
    EXPECT_LE(ratio, c.high) << c.formulation << " " << c.elements;
    std::printf("cantilever %s %s: f1 / f_beam = %.4f\n", c.formulation.c_str(), c.elements.c_str(), ratio);
  }
}

}  // namespace
