// Mortar contact in dynamics: the contact patch test of input/contact_patch_mortar.yaml
// (../shared/reference/contact-and-failure.md, section 1) on non-matching 8-node faces,
// graded faces and with friction; the plates' mirror image and energy with mortar.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../support/deck_run.hpp"

namespace {

using exdyn::input::Override;
using exdyn::testing::DeckRun;

const double plateau = 7800 * 6020.1841 * 1.0;  // rho c1 v0, Pa

struct Layer {
  double spread = 0.0, mean = 0.0;  // of sigma_zz / (rho c1 v0)
};
struct PatchRun {
  Layer lower, upper;
  double energy_error = 0.0, friction_work = 0.0;
  long not_converged = 0;
};

// The element layers on both sides of the interface at the end (half way through):
// elements of the lower block first (its top layer the last nx ny of them), then the
// upper's (its bottom layer the first).
PatchRun patch(std::array<int, 2> lower, std::array<int, 2> upper, const std::vector<Override>& more = {}) {
  std::vector<Override> overrides = {
      {"parts[0].elements", "[" + std::to_string(lower[0]) + ", " + std::to_string(lower[1]) + ", 40]"},
      {"parts[1].elements", "[" + std::to_string(upper[0]) + ", " + std::to_string(upper[1]) + ", 40]"}};
  overrides.insert(overrides.end(), more.begin(), more.end());
  const DeckRun run("contact_patch_mortar.yaml", overrides);
  const std::vector<double> s = run.final("stress");
  auto layer = [&](std::size_t first, std::size_t count) {
    Layer l;
    double lo = 1e300, hi = -1e300;
    for (std::size_t e = first; e < first + count; ++e) {
      const double v = s[6 * e + 2] / plateau;
      lo = std::min(lo, v), hi = std::max(hi, v), l.mean += v / double(count);
    }
    l.spread = hi - lo;
    return l;
  };
  const auto lower_elements = std::size_t(lower[0] * lower[1] * 40);
  PatchRun result;
  result.lower = layer(lower_elements - std::size_t(lower[0] * lower[1]), std::size_t(lower[0] * lower[1]));
  result.upper = layer(lower_elements, std::size_t(upper[0] * upper[1]));
  result.energy_error = run.summary.energy.max_relative_error;
  result.friction_work = run.history("friction_work").back();
  result.not_converged = run.summary.contact.not_converged;
  return result;
}

// Uniform layers equal to the matching run's, to round-off (the reference's measure;
// 0.2 % of rho c1 v0 is asked).
void expect_patch_passes(const PatchRun& run, const PatchRun& matching, const char* what) {
  std::printf("%s: lower layer spread %.1e mean %.15f, upper spread %.1e mean %.15f (matching %.15f)\n", what,
              run.lower.spread, run.lower.mean, run.upper.spread, run.upper.mean, matching.lower.mean);
  EXPECT_LE(run.lower.spread, 1e-12) << what;
  EXPECT_LE(run.upper.spread, 1e-12) << what;
  EXPECT_NEAR(run.lower.mean, matching.lower.mean, 1e-12) << what;
  EXPECT_NEAR(run.upper.mean, matching.upper.mean, 1e-12) << what;
  EXPECT_EQ(run.not_converged, 0) << what;
  EXPECT_LE(run.energy_error, 1e-12) << what;
}

TEST(ContactPatchMortar, NonMatchingFacesGiveTheMatchingRunsUniformLayers) {
  const PatchRun matching4 = patch({4, 4}, {4, 4});
  EXPECT_LE(matching4.lower.spread, 1e-12);
  EXPECT_NEAR(matching4.lower.mean, -0.99893, 5e-6);  // the deck's comment: the penalty rings
  expect_patch_passes(patch({4, 4}, {3, 3}), matching4, "3 x 3 on 4 x 4");
  const PatchRun matching5 = patch({5, 5}, {5, 5});
  expect_patch_passes(patch({5, 5}, {2, 2}), matching5, "2 x 2 on 5 x 5");
  const std::vector<Override> graded = {{"parts[0].grading", "[0.5, 0.5, 1]"}};
  std::vector<Override> graded_matching = graded;
  graded_matching.push_back({"parts[1].grading", "[0.5, 0.5, 1]"});
  expect_patch_passes(patch({4, 4}, {3, 3}, graded), patch({4, 4}, {4, 4}, graded_matching),
                      "3 x 3 on a graded 4 x 4");
}

TEST(ContactPatchMortar, FrictionDoesNothingInANormalImpact) {
  const PatchRun matching = patch({4, 4}, {4, 4});
  const PatchRun run = patch({4, 4}, {3, 3}, {{"contact[0].friction", "{coefficient: 0.5}"}});
  expect_patch_passes(run, matching, "3 x 3 on 4 x 4, friction 0.5");
  EXPECT_LE(std::abs(run.friction_work), 1e-20);  // J: no slip
}

TEST(ContactPatchMortar, SlaveNodesAndGaussPointsDoNotPassIt) {
  // The same mesh with the other slave points: several % across a layer, so the test
  // above measures what mortar adds.
  const PatchRun nodes = patch({4, 4}, {3, 3}, {{"contact[0].slave_points", "nodes"}});
  const PatchRun gauss = patch({4, 4}, {3, 3}, {{"contact[0].slave_points", "quadrature"}});
  std::printf("3 x 3 on 4 x 4: slave nodes spread %.2f %% / %.2f %%, Gauss points %.2f %% / %.2f %%\n",
              100 * nodes.lower.spread, 100 * nodes.upper.spread, 100 * gauss.lower.spread,
              100 * gauss.upper.spread);
  EXPECT_GT(std::max(nodes.lower.spread, nodes.upper.spread), 0.01);
  EXPECT_GT(std::max(gauss.lower.spread, gauss.upper.spread), 0.005);
}

}  // namespace

namespace {

// The paper's plates (input/plate_impact.yaml, hex8, and input/plate_impact_hex20.yaml) with
// mortar: two passes, one the mirror image of the other, so the plates stay mirror images
// (element i of plate A and element n - 1 - i of plate B; xz changes sign), and energy
// is kept to round-off with the contact energy.
void expect_mirror_images(const char* deck_file, int n) {
  const DeckRun run(deck_file, {{"contact[0].slave_points", "mortar"}});
  const std::vector<double> s = run.final("stress");
  double worst = 0.0;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      for (int c : {0, 1, 2, 5}) {
        const double sign = c == 5 ? -1.0 : 1.0;
        const std::size_t a = 6 * std::size_t(i + n * k) + std::size_t(c);
        const std::size_t b = 6 * std::size_t(n * n + (n - 1 - i) + n * k) + std::size_t(c);
        worst = std::max(worst, std::abs(s[a] - sign * s[b]));
      }
  std::printf("%s with mortar: largest mirror difference %.1e of rho c1 v0, energy error %.1e\n", deck_file,
              worst / plateau, run.summary.energy.max_relative_error);
  EXPECT_LE(worst, 1e-12 * plateau) << deck_file;
  EXPECT_LE(run.summary.energy.max_relative_error, 1e-13) << deck_file;
  EXPECT_EQ(run.summary.contact.not_converged, 0) << deck_file;
  EXPECT_EQ(run.summary.contact.pairs.at(0).slave_points, "mortar");
}

TEST(PlateImpactMortar, TwoPassesKeepThePlatesMirrorImagesAndTheEnergy) {
  expect_mirror_images("plate_impact.yaml", 100);
  expect_mirror_images("plate_impact_hex20.yaml", 50);
}

// The Hertz ball's coarse mesh (as tests/solver/test_hertz.cpp) with mortar at its default
// penalty: within 2 % of Hertz in F_max and contact time, as the Gauss points there.
TEST(HertzBallMortar, PeakForceAndContactTimeWithinTwoPercentOfHertz) {
  const double E = 2.1e11, nu = 0.3, rho = 7800, R = 0.01, v = 10.0;
  const double e_star = E / (2.0 * (1.0 - nu * nu));
  const double ball = rho * 4.0 / 3.0 * 3.14159265358979323846 * R * R * R, block = rho * 0.04 * 0.04 * 0.02;
  const double m = ball * block / (ball + block);
  const double delta = std::pow(15.0 * m * v * v / (16.0 * e_star * std::sqrt(R)), 0.4);
  const double force = 4.0 / 3.0 * e_star * std::sqrt(R) * std::pow(delta, 1.5), time = 2.943 * delta / v;
  const DeckRun run("hertz_ball.yaml", {{"parts[0].elements", "[8, 2]"},
                                        {"parts[1].elements", "[6, 6, 5]"},
                                        {"contact[0].slave_points", "mortar"},
                                        {"contact[0].penalty", "{scale: 1.0}"}});
  const std::vector<double> t = run.history("time"), f = run.history("contact/impact/force");
  double peak = 0.0, first = -1.0, last = -1.0;
  for (std::size_t i = 0; i < t.size(); ++i) peak = std::max(peak, 4.0 * f[3 * i + 2]);
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (4.0 * f[3 * i + 2] <= 1e-3 * peak) continue;
    if (first < 0.0) first = t[i];
    last = t[i];
  }
  std::printf("Hertz ball (8 x 2 on 6 x 6 x 5), mortar: F_max %+.2f %%, contact time %+.2f %%\n",
              100 * (peak / force - 1), 100 * ((last - first) / time - 1));
  EXPECT_NEAR(peak, force, 0.02 * force);
  EXPECT_NEAR(last - first, time, 0.02 * time);
  EXPECT_LT(last, t.back());
  EXPECT_LE(run.summary.energy.max_relative_error, 1e-13);
  EXPECT_EQ(run.summary.contact.not_converged, 0);
  EXPECT_EQ(run.summary.contact.saddle_points, 0);
}

}  // namespace
