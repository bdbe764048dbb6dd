// Penalty contact through whole runs: the two-plate impact against the one-plate
// reference, the bar impact, the contact patch test, the block drop, and every
// local search method on the plate case.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>

#include "../support/deck_run.hpp"
#include "../support/result_file.hpp"
#include "../support/temp_dir.hpp"
#include "input/deck_reader.hpp"
#include "material/elastic.hpp"
#include "solver/simulation.hpp"

namespace {

using exdyn::input::Override;
using exdyn::testing::read_dataset;
using exdyn::testing::step_path;

struct ContactRun : exdyn::testing::DeckRun {
  using DeckRun::DeckRun;
  std::vector<double> field(long step, const std::string& name) const { return at(step, name); }
  std::vector<long> steps() const {
    std::vector<long> result;
    const auto times = read_dataset(h5(), "/time").values;
    for (double t : times) result.push_back(std::lround(t / summary.dt));
    return result;
  }
};

exdyn::material::ElasticConstants steel() { return exdyn::material::elastic_constants(2.1e11, 0.3, 7800); }

// ---------------------------------------------------------------- plate impact

constexpr int n = 100;
constexpr long plate_steps = 448;

class PlateImpact : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    contact_ = std::make_unique<ContactRun>("plate_impact.yaml");
    reference_ = std::make_unique<ContactRun>("plate_impact_reference.yaml");
  }
  static void TearDownTestSuite() {
    contact_.reset();
    reference_.reset();
  }
  static inline std::unique_ptr<ContactRun> contact_, reference_;
};

TEST_F(PlateImpact, EachPlateAgreesWithTheReferenceCalculationAlongZZero) {
  const auto s = contact_->field(plate_steps, "stress");
  const auto r = reference_->field(plate_steps, "stress");
  const double plateau = 7800 * steel().dilatational_wave_speed() * 1.0;  // rho c1 v0
  double worst_a = 0.0, worst_b = 0.0;
  for (int i = 0; i < n; ++i) {
    const double distance = (n - i - 0.5) / n;  // x/d of the element centre from the contact plane
    if (distance >= 0.45) continue;
    // plate A: elements 0 .. 99 of the row z = 0 from its free end; plate B
    // (elements 10000 ...) is the mirror image: its element n-1-i is at the same distance.
    worst_a = std::max(worst_a, std::abs(s[6 * std::size_t(i)] - r[6 * std::size_t(i)]));
    worst_b = std::max(worst_b, std::abs(s[6 * std::size_t(n * n + n - 1 - i)] - r[6 * std::size_t(i)]));
  }
  std::printf("plate A, B against the reference, x/d < 0.45: %.4f, %.4f of the plateau\n", worst_a / plateau,
              worst_b / plateau);
  EXPECT_LE(worst_a, 0.02 * plateau);
  EXPECT_LE(worst_b, 0.02 * plateau);
  const double face = std::abs(s[6 * (n - 1)] - r[6 * (n - 1)]);
  std::printf("element at the contact face: %.5f of the plateau\n", face / plateau);
  EXPECT_LE(face, 0.02 * plateau);
}

TEST_F(PlateImpact, TwoPassContactKeepsThePlatesMirrorImages) {
  const auto s = contact_->field(plate_steps, "stress");
  const double plateau = 7800 * steel().dilatational_wave_speed() * 1.0;
  double worst = 0.0;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      for (int c : {0, 2, 5}) {
        // xz shear changes sign under the mirror x -> -x
        const double sign = c == 5 ? -1.0 : 1.0;
        worst = std::max(worst,
                         std::abs(s[6 * std::size_t(i + n * k) + std::size_t(c)] -
                                  sign * s[6 * std::size_t(n * n + (n - 1 - i) + n * k) + std::size_t(c)]));
      }
  std::printf("largest mirror difference of the two plates: %.3e of the plateau\n", worst / plateau);
  EXPECT_LE(worst, 1e-12 * plateau);  // the same contact from either side (docs/contact.md)
}

TEST_F(PlateImpact, PenetrationStaysBelowOnePercentOfAnElementAndEnergyIsKept) {
  const auto& c = contact_->summary.contact;
  std::printf("max penetration / h %.3e, projections %ld, mean iterations %.3f, penalty k %.4e N/m\n",
              c.max_penetration_over_h, c.projections, c.mean_iterations, c.penalty_stiffness);
  EXPECT_LT(c.max_penetration_over_h, 0.01);
  EXPECT_GT(c.projections, 0);
  EXPECT_EQ(c.not_converged, 0);
  EXPECT_EQ(c.saddle_points, 0);
  EXPECT_GT(c.penalty_stiffness, 0.0);
  EXPECT_LE(contact_->summary.energy.max_relative_error, 0.01);
}

TEST_F(PlateImpact, ContactForcesConserveMomentum) {
  const auto f = contact_->field(plate_steps, "contact_force");
  double sum[3] = {0, 0, 0}, largest = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    sum[i % 3] += f[i];
    largest = std::max(largest, std::abs(f[i]));
  }
  EXPECT_GT(largest, 0.0);
  for (double s : sum) EXPECT_LE(std::abs(s), 1e-12 * largest);
}

// ---------------------------------------------------------------- bar impact

TEST(BarImpact, BarsExchangeVelocitiesAfterTwoWaveTransits) {
  const ContactRun run("bar_impact.yaml");
  const double c1 = steel().dilatational_wave_speed(), v0 = 1.0, length = 1.0e-2;
  const double duration = 2.0 * length / c1;  // 3.322e-6 s
  double first = -1.0, last = -1.0, most_tensile = 0.0;
  const std::vector<long> steps = run.steps();
  std::size_t nodes = 0;
  for (long step : steps) {
    const auto f = run.field(step, "contact_force");
    nodes = f.size() / 3;
    double left_face = 0.0;  // x force on the left bar (nodes 0 .. nodes/2 - 1): contact pushes it back (< 0)
    for (std::size_t i = 0; i < nodes / 2; ++i) left_face += f[3 * i];
    most_tensile = std::max(most_tensile, left_face);
    if (left_face < 0.0) {
      if (first < 0.0) first = static_cast<double>(step) * run.summary.dt;
      last = static_cast<double>(step) * run.summary.dt;
    }
  }
  const double measured = last - first;
  std::printf("contact duration %.5e s (2 L / c1 = %.5e s): %+.2f %%\n", measured, duration,
              100 * (measured / duration - 1));
  EXPECT_NEAR(measured, duration, 0.02 * duration);
  EXPECT_EQ(most_tensile, 0.0);  // the contact never pulls

  const auto v = run.field(steps.back(), "velocity");
  double left = 0.0, right = 0.0;
  for (std::size_t i = 0; i < nodes / 2; ++i) left += v[3 * i] / double(nodes / 2);
  for (std::size_t i = nodes / 2; i < nodes; ++i) right += v[3 * i] / double(nodes / 2);
  std::printf("after separation: left %.4f m/s, right %.4f m/s\n", left, right);
  EXPECT_NEAR(left, -v0, 0.02 * v0);
  EXPECT_NEAR(right, v0, 0.02 * v0);
  const auto f = run.field(steps.back(), "contact_force");
  for (double value : f) EXPECT_EQ(value, 0.0);  // separated at the end
  EXPECT_LE(run.summary.energy.max_relative_error, 0.01);
}

// ---------------------------------------------------------------- patch test

// Largest deviation of the nodal contact pressure (force / tributary area) from
// the face's mean pressure, over the nodes of both contact faces at the last step.
// The mean itself rings in time about rho c1 v0 (the penalty transient), so
// uniformity is measured against the mean at that instant.
double patch_deviation(bool two_pass) {
  const ContactRun run("contact_patch.yaml", {{"contact[0].two_pass", two_pass ? "true" : "false"}});
  const auto f = run.field(run.summary.steps, "contact_force");
  const auto x = read_dataset(run.h5(), "/mesh/coordinates").values;
  const double p = 7800 * steel().dilatational_wave_speed() * 0.1;
  double worst = 0.0;
  for (const bool lower : {true, false}) {
    // lower.zmax: 4 x 4 quads of 0.25 mm (nodes before 5 x 5 x 9); upper.zmin: 3 x 3 of 1/3 mm.
    const double h = lower ? 0.25e-3 : 1.0e-3 / 3;
    std::vector<double> pressure;
    double force = 0.0, total_area = 0.0;
    for (std::size_t i = 0; i < f.size() / 3; ++i) {
      if (std::abs(x[3 * i + 2]) > 1e-12 || (i < 5 * 5 * 9) != lower) continue;  // not on this face
      const double ex = x[3 * i], ey = x[3 * i + 1];
      const bool edge_x = ex < 1e-12 || ex > 1e-3 - 1e-12, edge_y = ey < 1e-12 || ey > 1e-3 - 1e-12;
      const double area = h * h * (edge_x ? 0.5 : 1.0) * (edge_y ? 0.5 : 1.0);
      const double normal_force = lower ? -f[3 * i + 2] : f[3 * i + 2];  // compressive > 0
      pressure.push_back(normal_force / area);
      force += normal_force;
      total_area += area;
    }
    const double mean = force / total_area;
    for (double value : pressure) worst = std::max(worst, std::abs(value - mean) / mean);
    std::printf("%s pass, %s face: mean pressure %.4f rho c1 v0\n", two_pass ? "two" : "one",
                lower ? "4 x 4" : "3 x 3", mean / p);
    EXPECT_NEAR(mean, p, 0.1 * p);  // ringing about the plane-wave value
  }
  std::printf("%s pass: largest deviation of the nodal contact pressure from uniform: %.2f %%\n",
              two_pass ? "two" : "one", 100 * worst);
  return worst;
}

TEST(ContactPatch, TwoPassesTransmitAUniformPressureBetweenNonMatchingMeshes) {
  const double one = patch_deviation(false);
  const double two = patch_deviation(true);
  EXPECT_LE(two, 0.05);
  EXPECT_LT(two, one);
}

// ---------------------------------------------------------------- block drop

TEST(BlockDrop, CubeBouncesOffTheBlockWithSmallPenetration) {
  const ContactRun run("block_drop.yaml");
  const auto v = run.field(run.summary.steps, "velocity");
  const std::size_t base_nodes = 7 * 7 * 4;
  double cube_vz = 0.0;
  const std::size_t cube_nodes = v.size() / 3 - base_nodes;
  for (std::size_t i = base_nodes; i < v.size() / 3; ++i) cube_vz += v[3 * i + 2] / double(cube_nodes);
  std::printf("cube mean vz at the end: %.3f m/s (started at -5)\n", cube_vz);
  EXPECT_GT(cube_vz, 0.0);
  EXPECT_LT(run.summary.contact.max_penetration_over_h, 0.01);
  EXPECT_EQ(run.summary.contact.not_converged, 0);
  EXPECT_NEAR(run.summary.energy.initial_total, 0.5 * 7800 * 64e-9 * 25.0, 1e-9);
  EXPECT_LE(run.summary.energy.max_relative_error, 0.01);
}

// ---------------------------------------------------------------- rod on plate

// input/rod_on_plate.yaml: plate nodes under the rod's end, beside its curved side, take
// the end (the nearer edge point of a valley between its facets, or of its edge on a
// symmetry plane), not the side's facet that holds them 0.1-0.2 mm inside the rod.
TEST(RodOnPlate, TheEndTakesThePlateThroughTheTouchNotTheSide) {
  const ContactRun run("rod_on_plate.yaml");
  const auto& c = run.summary.contact;
  const auto v = run.field(run.summary.steps, "velocity");
  constexpr std::size_t rod_nodes = 1281;  // the rod's mesh comes first
  double rod_vz = 0.0;
  for (std::size_t i = 0; i < rod_nodes; ++i) rod_vz += v[3 * i + 2] / double(rod_nodes);
  std::printf("rod on plate: %ld steps, max penetration / h %.4f, energy error %.2e, rod mean vz %.1f m/s\n",
              run.summary.steps, c.max_penetration_over_h, run.summary.energy.max_relative_error, rod_vz);
  EXPECT_EQ(run.summary.status, "completed");
  EXPECT_LT(c.max_penetration_over_h, 0.03);
  EXPECT_LE(run.summary.energy.max_relative_error, 0.002);
  EXPECT_GT(rod_vz, -140.0);  // slowed from -200 m/s
  EXPECT_LT(rod_vz, -110.0);
}

// ---------------------------------------------------------------- every method

class PlateImpactMethod : public ::testing::TestWithParam<const char*> {};

TEST_P(PlateImpactMethod, RunsThePlateCaseToTheEnd) {
  const ContactRun run("plate_impact.yaml", {{"contact[0].local_search.method", GetParam()}});
  const auto& c = run.summary.contact;
  std::printf(
      "%-17s projections %ld, mean iterations %.3f, max %ld, not converged %ld, saddles %ld, "
      "max penetration / h %.2e\n",
      GetParam(), c.projections, c.mean_iterations, c.max_iterations, c.not_converged, c.saddle_points,
      c.max_penetration_over_h);
  EXPECT_EQ(run.summary.status, "completed");
  EXPECT_EQ(run.summary.steps, plate_steps);
  EXPECT_LT(c.max_penetration_over_h, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Methods, PlateImpactMethod,
                         ::testing::Values("newton", "lsp", "steepest_descent", "broyden", "bfgs", "dfp",
                                           "simplex", "hybrid", "robust"));

// ---------------------------------------------------------------- failed searches

std::vector<Override> coarse_plates(const char* local_search) {
  return {{"parts[0].elements", "[20, 1, 20]"},
          {"parts[1].elements", "[20, 1, 20]"},
          {"contact[0].local_search", local_search}};
}

// A method that fails on every projection (the simplex stopped after 20 iterations, short
// of its 1e-10 tolerance): bare, no contact force at all; with the default fallback,
// every projection settled again by the robust method from the same start, counted, and
// the run the robust method's own, bit for bit.
TEST(FailedSearch, IsSettledByTheFallbackAndCounted) {
  const ContactRun bare(
      "plate_impact.yaml",
      coarse_plates("{method: simplex, max_iterations: 20, initial_guess: center, fallback: none}"));
  const ContactRun settled("plate_impact.yaml",
                           coarse_plates("{method: simplex, max_iterations: 20, initial_guess: center}"));
  const ContactRun robust("plate_impact.yaml",
                          coarse_plates("{method: robust, max_iterations: 20, initial_guess: center}"));
  const auto& b = bare.summary.contact;
  const auto& s = settled.summary.contact;
  std::printf("bare: %ld of %ld not converged; with the fallback: %ld settled, %ld not converged\n",
              b.not_converged, b.projections, s.fallbacks, s.not_converged);
  EXPECT_GT(b.projections, 0);
  EXPECT_EQ(b.not_converged, b.projections);
  EXPECT_EQ(b.fallbacks, 0);
  double largest = 0.0;
  for (const double f : bare.final("contact_force")) largest = std::max(largest, std::abs(f));
  EXPECT_EQ(largest, 0.0);  // a failed projection never gives a force
  EXPECT_EQ(s.projections, b.projections);
  EXPECT_EQ(s.fallbacks, s.projections);
  EXPECT_EQ(s.not_converged + s.saddle_points, 0);
  EXPECT_EQ(robust.summary.contact.fallbacks, 0);  // (the method is its own fallback: not run twice)
  for (const char* field : {"displacement", "velocity", "stress", "contact_force"})
    EXPECT_EQ(settled.final(field), robust.final(field)) << field;
}

// The sums of the points' force magnitudes (/history/contact/NAME/normal_force_sum): two
// plates pressed flat, every normal along x, the two passes' points pressing in opposite
// directions: row by row the magnitude of the pair's normal force; no friction, no
// tangential sum; at the peak every node of both faces pressed (21 x 2 a face).
TEST(ContactHistory, TheSumOfMagnitudesIsTheNormalForceOfTwoFlatFaces) {
  const ContactRun run("plate_impact.yaml",
                       {{"parts[0].elements", "[20, 1, 20]"}, {"parts[1].elements", "[20, 1, 20]"}});
  const std::vector<double> sum = run.history("contact/interface/normal_force_sum");
  const std::vector<double> normal = run.history("contact/interface/normal_force");
  const std::vector<double> tangential = run.history("contact/interface/tangential_force_sum");
  ASSERT_EQ(sum.size(), normal.size());
  double peak = 0.0;
  for (std::size_t r = 0; r < sum.size(); ++r) {
    EXPECT_NEAR(sum[r], normal[r], 1e-12 * normal[r]) << "row " << r;
    EXPECT_EQ(tangential[r], 0.0);
    peak = std::max(peak, sum[r]);
  }
  const auto& pair = run.summary.contact.pairs.front();
  EXPECT_GT(peak, 0.0);
  EXPECT_GE(pair.peak_normal_force_sum, peak);
  EXPECT_EQ(pair.points_in_contact_at_peak, 2 * 21 * 2);
}

}  // namespace
