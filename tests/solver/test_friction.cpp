// Coulomb friction, rigid walls and gravity through whole runs, against the exact
// values of ../shared/reference/large-deformation-and-friction.md, section 4: a block
// sliding to rest (input/sliding_block.yaml), the same block on an incline, an
// oblique impact slipping throughout (input/oblique_impact.yaml), a block sliding along
// a rail of curved segments (input/block_on_rail.yaml), a bar on a wall
// against two bars meeting, a moving wall, free fall, and the mirror symmetry of a
// symmetric scene with friction.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "../support/deck_run.hpp"
#include "../support/result_file.hpp"
#include "input/deck_reader.hpp"
#include "model/model.hpp"
#include "solver/simulation.hpp"

namespace {

using exdyn::input::Override;
using exdyn::testing::read_dataset;
using exdyn::testing::step_path;

// A run with its model (the lumped masses) for the centre of mass.
struct FrictionRun : exdyn::testing::DeckRun {
  exdyn::solver::Model model;

  explicit FrictionRun(exdyn::input::Deck d)
      : DeckRun(std::move(d)), model(exdyn::solver::build_model(deck)) {}
  explicit FrictionRun(const std::string& file, const std::vector<Override>& overrides = {})
      : FrictionRun(exdyn::input::read_deck(source_path(file), overrides)) {}

  // The written steps, in order.
  std::vector<long> steps() const {
    std::vector<long> written;
    for (long s = 0; s < summary.steps; s += deck.output.every) written.push_back(s);
    written.push_back(summary.steps);
    return written;
  }
  // The mass-weighted mean of a node field over part `part`: the centre of mass's
  // displacement or velocity.
  std::array<double, 3> centre(long step, const std::string& field, int part) const {
    const std::vector<double> values = at(step, field);
    const auto& range = model.mesh.parts[std::size_t(part)];
    std::array<double, 3> sum{};
    double mass = 0.0;
    for (std::uint32_t i = range.first_node; i < range.first_node + range.node_count; ++i) {
      for (int c = 0; c < 3; ++c) sum[std::size_t(c)] += model.mass[i] * values[3 * i + std::size_t(c)];
      mass += model.mass[i];
    }
    for (double& s : sum) s /= mass;
    return sum;
  }
};

// Least-squares slope of y(t).
double slope(const std::vector<double>& t, const std::vector<double>& y) {
  const double n = double(t.size());
  double st = 0, sy = 0, stt = 0, sty = 0;
  for (std::size_t i = 0; i < t.size(); ++i) st += t[i], sy += y[i], stt += t[i] * t[i], sty += t[i] * y[i];
  return (n * sty - st * sy) / (n * stt - st * st);
}

// The centre of mass's velocity component c over the written steps with t in [t0, t1]:
// its least-squares slope (the mean acceleration, m/s^2).
double mean_acceleration(const FrictionRun& run, int part, int c, double t0, double t1) {
  std::vector<double> t, v;
  const std::vector<double> times = read_dataset(run.h5(), "/time").values;
  const std::vector<long> steps = run.steps();
  for (std::size_t k = 0; k < steps.size(); ++k)
    if (times[k] >= t0 && times[k] <= t1) {
      t.push_back(times[k]);
      v.push_back(run.centre(steps[k], "velocity", part)[std::size_t(c)]);
    }
  return slope(t, v);
}

constexpr double g = 1.0e5, mu = 0.3, v0 = 3.0;

// --- sliding to rest: a block on a plate through a two-pass pair with friction

class SlidingBlock : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { run_ = new FrictionRun("sliding_block.yaml"); }
  static void TearDownTestSuite() { delete run_; }
  static inline FrictionRun* run_ = nullptr;
};

TEST_F(SlidingBlock, DeceleratesAtMuGAndStopsAtTheCoulombDistance) {
  const FrictionRun& run = *run_;
  ASSERT_EQ(run.summary.status, "completed");
  const double stop_time = v0 / (mu * g), distance = v0 * v0 / (2 * mu * g);  // 100 us, 0.15 mm
  // Over the slide, after the first 10 us of settling onto the plate.
  const double a = mean_acceleration(run, 0, 0, 0.1 * stop_time, 0.9 * stop_time);
  const double u_end = run.centre(run.summary.steps, "displacement", 0)[0];
  std::printf("deceleration %.6g m/s^2 (mu g = %.6g, %.4f %% off), stopped at %.6g mm (%.6g, %.4f %% off)\n",
              -a, mu * g, 100 * std::abs(-a / (mu * g) - 1), 1e3 * u_end, 1e3 * distance,
              100 * std::abs(u_end / distance - 1));
  EXPECT_NEAR(-a, mu * g, 0.01 * mu * g);
  EXPECT_NEAR(u_end, distance, 0.01 * distance);
  // At rest after stopping: from 1.2 t_stop on the block moves less than 1e-3 of its slide.
  double largest_move = 0.0;
  const std::vector<long> steps = run.steps();
  const std::vector<double> times = read_dataset(run.h5(), "/time").values;
  for (std::size_t k = 0; k < steps.size(); ++k)
    if (times[k] >= 1.2 * stop_time)
      largest_move = std::max(largest_move, std::abs(run.centre(steps[k], "displacement", 0)[0] - u_end));
  std::printf("largest move after 1.2 t_stop: %.3g m (%.3g of the slide)\n", largest_move,
              largest_move / distance);
  EXPECT_LT(largest_move, 1e-3 * distance);
}

// Friction dissipates the kinetic energy: the friction work is the initial kinetic
// energy less what the elastic bodies still hold; kinetic + internal + contact energy
// (the friction work is a part of contact_energy) - the work of gravity is constant.
TEST_F(SlidingBlock, FrictionWorkTakesTheKineticEnergyAndTheBalanceHolds) {
  const FrictionRun& run = *run_;
  const double kinetic = 0.5 * 7800 * 0.01 * 0.01 * 0.005 * v0 * v0;  // J
  const double friction = run.history("friction_work").back();
  std::printf("friction work %.6g J of the initial kinetic energy %.6g J; energy error %.3g\n", friction,
              kinetic, run.summary.energy.max_relative_error);
  EXPECT_NEAR(friction, kinetic, 0.01 * kinetic);
  EXPECT_LT(run.summary.energy.max_relative_error, 1e-3);
  // The contact energy holds the friction work, the contact dashpot's and what the
  // springs still store.
  const double contact = run.history("contact_energy").back();
  std::printf("contact energy %.6g J: friction %.6g J, dashpots and springs %.3g J\n", contact, friction,
              contact - friction);
  EXPECT_GE(contact, friction);
}

// Two passes: the friction and normal forces on the block are those on the plate,
// reversed, at every written step; and the pair's history has |F_t| = mu F_n while
// the block slides.
TEST_F(SlidingBlock, TwoPassesGiveEqualAndOppositeForces) {
  const FrictionRun& run = *run_;
  for (const long step : run.steps()) {
    const std::vector<double> f = run.at(step, "contact_force");
    std::array<std::array<double, 3>, 2> total{};
    double largest = 0.0;
    for (int part = 0; part < 2; ++part) {
      const auto& range = run.model.mesh.parts[std::size_t(part)];
      for (std::uint32_t i = range.first_node; i < range.first_node + range.node_count; ++i)
        for (int c = 0; c < 3; ++c) {
          total[std::size_t(part)][std::size_t(c)] += f[3 * i + std::size_t(c)];
          largest = std::max(largest, std::abs(f[3 * i + std::size_t(c)]));
        }
    }
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(total[0][std::size_t(c)], -total[1][std::size_t(c)], 1e-12 * largest);
  }
  const auto normal = run.history("contact/sliding/normal_force");
  const auto tangential = run.history("contact/sliding/tangential_force");
  const auto time = run.history("time");
  double mean_ratio = 0.0;
  int rows = 0;
  for (std::size_t i = 0; i < time.size(); ++i)
    if (time[i] > 0.1e-4 && time[i] < 0.9e-4 && normal[i] > 0.0)
      mean_ratio += tangential[i] / normal[i], ++rows;
  mean_ratio /= rows;
  std::printf("mean |F_t| / F_n while sliding: %.6f\n", mean_ratio);
  EXPECT_NEAR(mean_ratio, mu, 0.01 * mu);
}

// The scene is symmetric about y = 0: node (x, y, z) and node (x, -y, z) move as
// mirror images. (The plate has an odd number of elements across y. With an even one,
// the block's nodes on y = 0 lie on the edge between two plate segments that the
// block's weight warps as mirror images, and the tie goes to the first segment, whose
// normal leans by the warp: the halves then drift apart by 1e-6 of the slide,
// docs/verification.md.)
TEST_F(SlidingBlock, StaysAMirrorImageAboutItsMidPlane) {
  const FrictionRun& run = *run_;
  const exdyn::NodalVectors& x = run.model.mesh.x_ref;
  const std::vector<double> u = run.at(run.summary.steps, "displacement");
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    largest = std::max(largest, std::abs(u[3 * i]));
    const int body_i = i < run.model.mesh.parts[1].first_node ? 0 : 1;
    for (std::size_t j = 0; j < x.size(); ++j) {
      if ((j < run.model.mesh.parts[1].first_node ? 0 : 1) != body_i) continue;
      if (std::abs(x.x[j] - x.x[i]) > 1e-12 || std::abs(x.y[j] + x.y[i]) > 1e-12 ||
          std::abs(x.z[j] - x.z[i]) > 1e-12)
        continue;
      worst = std::max({worst, std::abs(u[3 * i] - u[3 * j]), std::abs(u[3 * i + 1] + u[3 * j + 1]),
                        std::abs(u[3 * i + 2] - u[3 * j + 2])});
    }
  }
  std::printf("largest mirror difference %.3g of the largest displacement\n", worst / largest);
  EXPECT_LE(worst, 1e-12 * largest);
}

// The same slide with 20-node parts: the default slave points are then the Gauss
// points of the 8-node slave segments.
TEST(SlidingBlockHex20, QuadraturePointsDecelerateAtMuG) {
  const FrictionRun run("sliding_block.yaml",
                        {{"parts[0].formulation", "hex20"}, {"parts[1].formulation", "hex20"}});
  ASSERT_EQ(run.summary.status, "completed");
  ASSERT_EQ(run.summary.contact.pairs.at(0).slave_points, "quadrature");
  const double stop_time = v0 / (mu * g), distance = v0 * v0 / (2 * mu * g);
  const double a = mean_acceleration(run, 0, 0, 0.1 * stop_time, 0.9 * stop_time);
  const double u_end = run.centre(run.summary.steps, "displacement", 0)[0];
  std::printf("hex20: deceleration %.6g m/s^2 (%.4f %% off), stopped at %.6g mm (%.4f %% off)\n", -a,
              100 * std::abs(-a / (mu * g) - 1), 1e3 * u_end, 100 * std::abs(u_end / distance - 1));
  EXPECT_NEAR(-a, mu * g, 0.01 * mu * g);
  EXPECT_NEAR(u_end, distance, 0.01 * distance);
}

// --- the incline: gravity at theta from the plate's normal, the block at rest

std::vector<Override> incline(double degrees) {
  const double theta = degrees * std::numbers::pi / 180.0;
  char gravity[96];
  std::snprintf(gravity, sizeof gravity, "[%.17g, 0, %.17g]", g * std::sin(theta), -g * std::cos(theta));
  return {{"loads[0].gravity", gravity}, {"parts[0].initial_velocity", "[0, 0, 0]"}};
}

// tan 10 deg = 0.176 < mu: the block sticks. It slips only while the normal force
// builds from zero in its first microseconds (no cone holds it then); after that it
// creeps by no more than the penalty's elastic stick, tan theta times the penetration.
TEST(Incline, SticksBelowTheFrictionAngle) {
  const FrictionRun run("sliding_block.yaml", incline(10.0));
  ASSERT_EQ(run.summary.status, "completed");
  const auto steps = run.steps();
  const double half = run.centre(steps[steps.size() / 2], "displacement", 0)[0];
  const double end = run.centre(steps.back(), "displacement", 0)[0];
  const auto penetration = run.history("contact/sliding/max_penetration");
  const double stick =
      std::tan(10.0 * std::numbers::pi / 180.0) * *std::max_element(penetration.begin(), penetration.end());
  std::printf(
      "incline 10 deg: settled by %.3g m, then moved %.3g m in the second half (elastic stick %.3g m)\n",
      half, end - half, stick);
  EXPECT_LT(std::abs(end - half), stick);
  EXPECT_LT(std::abs(end), 1e-6);  // under a micrometre: against 0.48 mm sliding at 30 deg
}

// tan 30 deg = 0.577 > mu: it slides at g (sin theta - mu cos theta).
TEST(Incline, SlidesAboveTheFrictionAngleAtTheCoulombAcceleration) {
  const FrictionRun run("sliding_block.yaml", incline(30.0));
  ASSERT_EQ(run.summary.status, "completed");
  const double theta = std::numbers::pi / 6.0;
  const double exact = g * (std::sin(theta) - mu * std::cos(theta));  // 24019 m/s^2
  const double a = mean_acceleration(run, 0, 0, 2e-5, 2e-4);
  std::printf("incline 30 deg: acceleration %.6g m/s^2 (exact %.6g, %.4f %% off)\n", a, exact,
              100 * std::abs(a / exact - 1));
  EXPECT_NEAR(a, exact, 0.01 * exact);
}

// --- the oblique impact on a rigid wall, slipping throughout

void expect_slipping_impact(const FrictionRun& run, double mu_wall, double vt0, double vn0) {
  ASSERT_EQ(run.summary.status, "completed");
  const auto force = run.history("wall/floor/force");
  int rows = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < force.size() / 3; ++i) {
    const double normal = std::abs(force[3 * i + 2]), tangential = std::hypot(force[3 * i], force[3 * i + 1]);
    if (!(normal > 0.0)) continue;
    ++rows;
    worst = std::max(worst, std::abs(tangential / normal - mu_wall));
  }
  const auto v = run.centre(run.summary.steps, "velocity", 0);
  const double exact = vt0 - mu_wall * (v[2] + vn0);
  std::printf(
      "%s: %d rows in contact, largest | |F_t| / F_n - mu | %.3g; exit v_t %.6g (exact %.6g from v_n,out "
      "%.6g, %.4f %% off); energy error %.3g\n",
      run.deck.name.c_str(), rows, worst, v[0], exact, v[2], 100 * std::abs(v[0] / exact - 1),
      run.summary.energy.max_relative_error);
  EXPECT_GT(rows, 10);
  EXPECT_LE(worst, 1e-6 * mu_wall);
  EXPECT_GT(v[2], 0.0);  // it bounced
  EXPECT_NEAR(v[0], exact, 0.01 * exact);
  EXPECT_LT(run.summary.energy.max_relative_error, 1e-3);
}

TEST(ObliqueImpact, SlipsThroughoutWithTheCoulombRatioAndExitSpeed) {
  const FrictionRun run("oblique_impact.yaml");
  expect_slipping_impact(run, 0.2, 10.0, 5.0);
  // The wall's figures in the summary: its largest force is the history's, its
  // friction work the run's.
  ASSERT_EQ(run.summary.contact.walls.size(), 1u);
  const exdyn::output::WallSummary& wall = run.summary.contact.walls[0];
  EXPECT_EQ(wall.name, "floor");
  EXPECT_EQ(wall.slave_points, "nodes");
  const auto force = run.history("wall/floor/force");
  double largest = 0.0;
  for (std::size_t i = 0; i < force.size() / 3; ++i)
    largest = std::max(largest, std::hypot(force[3 * i], force[3 * i + 1], force[3 * i + 2]));
  EXPECT_DOUBLE_EQ(wall.max_force, largest);
  EXPECT_DOUBLE_EQ(wall.friction_work, run.history("friction_work").back());
  EXPECT_GT(wall.penalty_stiffness, 0.0);
}

TEST(ObliqueImpact, QuadraturePointsOfA20NodeBlockToo) {
  expect_slipping_impact(FrictionRun("oblique_impact.yaml", {{"parts[0].formulation", "hex20"}}), 0.2, 10.0,
                         5.0);
}

// --- long sliding on a curved surface: a block along a rail of curved 8-node segments

// While the block slips, its centre decelerates at mu g whatever it spins at; it
// crosses 23 of the rail's 1 mm segments, its anchor carried from one to the next.
TEST(BlockOnRail, SlidesAcrossTwentyCurvedSegmentsDeceleratingAtMuG) {
  const FrictionRun run("block_on_rail.yaml");
  ASSERT_EQ(run.summary.status, "completed");
  const double mu_rail = 0.1, v_start = 50.0, t_end = run.deck.time.end_time;
  const double a = mean_acceleration(run, 1, 0, 0.1 * t_end, 0.9 * t_end);
  const double slid = run.centre(run.summary.steps, "displacement", 1)[0];
  const double exact = v_start * t_end - 0.5 * mu_rail * g * t_end * t_end;  // 23.75 mm
  std::printf(
      "block on rail: deceleration %.6g m/s^2 (mu g = %.6g, %.3f %% off), slid %.4f mm (%.4f exact) "
      "across %d segments of 1 mm; %ld projections, %ld failed; energy error %.3g\n",
      -a, mu_rail * g, 100 * std::abs(-a / (mu_rail * g) - 1), 1e3 * slid, 1e3 * exact, int(slid / 1e-3),
      run.summary.contact.projections, run.summary.contact.not_converged + run.summary.contact.saddle_points,
      run.summary.energy.max_relative_error);
  EXPECT_NEAR(-a, mu_rail * g, 0.01 * mu_rail * g);
  EXPECT_NEAR(slid, exact, 0.01 * exact);
  EXPECT_GE(slid, 20e-3);
  EXPECT_EQ(run.summary.contact.not_converged + run.summary.contact.saddle_points, 0);
  EXPECT_LT(run.summary.energy.max_relative_error, 1e-3);
  // In contact throughout, once it has settled: the pair pushes in every history row.
  const auto normal = run.history("contact/slide/normal_force"), time = run.history("time");
  int apart = 0;
  for (std::size_t i = 0; i < time.size(); ++i) apart += time[i] > 0.1 * t_end && !(normal[i] > 0.0);
  std::printf("rows without contact after settling: %d of %zu\n", apart, time.size());
  EXPECT_LT(apart, int(time.size() / 100));
}

// --- walls against contact, a moving wall, gravity

// A bar on a rigid wall moves as each of two equal bars meeting at the plane between
// them (the wall pushes as the mirror image would: rigid_wall.hpp). The bars are in
// uniaxial strain (lateral faces held), so that their faces stay flat: a face that
// bulges meets its image's facets off the plane, and node-to-segment contact then
// differs from the flat wall by the order of the penetration (docs/verification.md).
exdyn::input::Deck bars(bool wall, const std::string& formulation) {
  std::string text = R"(name: bars
materials:
  steel: {model: linear_elastic, density: 7800, youngs_modulus: 2.1e11, poissons_ratio: 0.3}
parts:
  - {name: a, box: {min: [-0.004, 0, 0], max: [0, 0.001, 0.002]}, elements: [8, 1, 4], material: steel,
     formulation: F, initial_velocity: [5, 0, 0]}
)";
  if (wall)
    text += R"(rigid_walls:
  - {name: plane, point: [0, 0, 0], normal: [-1, 0, 0], slave: [a.xmax]}
)";
  else
    text +=
        R"(  - {name: b, box: {min: [0, 0, 0], max: [0.004, 0.001, 0.002]}, elements: [8, 1, 4], material: steel,
     formulation: F, initial_velocity: [-5, 0, 0]}
contact:
  - {name: meet, slave: [a.xmax], master: [b.xmin]}
)";
  text += R"(boundary_conditions:
  - {faces: [a.ymin, a.ymax], fix: [y]}
  - {faces: [a.zmin, a.zmax], fix: [z]}
time: {end_time: 2.0e-6, courant: 0.5}
output: {every: 1000, fields: [displacement, velocity]}
)";
  text.replace(text.find("formulation: F"), 14, "formulation: " + formulation);
  if (!wall) text.replace(text.find("formulation: F"), 14, "formulation: " + formulation);
  if (!wall) text.replace(text.find("[a.ymin, a.ymax]"), 16, "[a.ymin, a.ymax, b.ymin, b.ymax]");
  if (!wall) text.replace(text.find("[a.zmin, a.zmax]"), 16, "[a.zmin, a.zmax, b.zmin, b.zmax]");
  return exdyn::input::parse_deck(text, "bars.yaml");
}

void expect_wall_equals_mirror_image(const std::string& formulation) {
  const FrictionRun on_wall(bars(true, formulation)), meeting(bars(false, formulation));
  ASSERT_EQ(on_wall.summary.status, "completed");
  ASSERT_EQ(meeting.summary.status, "completed");
  ASSERT_EQ(on_wall.summary.steps, meeting.summary.steps);
  const auto a = on_wall.at(on_wall.summary.steps, "displacement");
  const auto b = meeting.at(meeting.summary.steps, "displacement");
  double worst = 0.0, largest = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {  // bar a's nodes come first in both
    worst = std::max(worst, std::abs(a[k] - b[k]));
    largest = std::max(largest, std::abs(a[k]));
  }
  // How far bar a's contact face is from flat (x = 0 at the start) on the wall: the
  // spread of its nodes' x displacements.
  double low = 1e300, high = -1e300;
  for (std::size_t i = 0; i < a.size() / 3; ++i)
    if (on_wall.model.mesh.x_ref.x[i] == 0.0) low = std::min(low, a[3 * i]), high = std::max(high, a[3 * i]);
  std::printf(
      "%s: bar on the wall against two bars: largest difference %.3g of the largest displacement %.3g m; "
      "the face's warp %.3g of it\n",
      formulation.c_str(), worst / largest, largest, (high - low) / largest);
  EXPECT_GT(largest, 1e-6);  // the bar has hit and come back
  // A flat face (hex8 in uniaxial strain): the wall is the mirror image. The face of a
  // 20-node bar does not stay flat (its lumped mid-side and corner nodes move apart),
  // and the image's facets then lie off the plane, by far less than the warp.
  if (high - low <= 1e-12 * largest)
    EXPECT_LE(worst, 1e-9 * largest);
  else
    EXPECT_LE(worst, 1e-4 * (high - low));
}

TEST(RigidWall, ABarOnTheWallMovesAsTwoBarsMeeting) { expect_wall_equals_mirror_image("hex8"); }
TEST(RigidWall, ABarOnTheWallMovesAsTwoBarsMeetingWithQuadraturePoints) {
  expect_wall_equals_mirror_image("hex20");
}

// Galilean invariance: a wall moving at V into a bar at rest is the bar moving at -V
// onto a fixed wall, seen from the wall.
TEST(RigidWall, AMovingWallIsTheFixedWallSeenFromIt) {
  exdyn::input::Deck fixed = bars(true, "hex8");
  exdyn::input::Deck moving = fixed;
  moving.parts[0].initial_velocity = {0, 0, 0};
  moving.rigid_walls[0].velocity = {-5, 0, 0};
  const FrictionRun a(fixed), b(moving);
  ASSERT_EQ(a.summary.steps, b.summary.steps);
  const double t = read_dataset(a.h5(), "/time").values.back();
  const auto ua = a.at(a.summary.steps, "displacement"), ub = b.at(b.summary.steps, "displacement");
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < ua.size() / 3; ++i) {
    worst = std::max(worst, std::abs((ua[3 * i] - 5.0 * t) - ub[3 * i]));
    largest = std::max(largest, std::abs(ub[3 * i]));
  }
  std::printf("moving wall against the fixed wall: largest difference %.3g of %.3g m\n", worst / largest,
              largest);
  EXPECT_GT(largest, 1e-6);
  EXPECT_LE(worst, 1e-9 * largest);
  const auto force = a.history("wall/plane/force");
  EXPECT_LT(*std::min_element(force.begin(), force.end()), 0.0);  // pushes the bar back along -x
}

// Free fall: u = g t^2 / 2 exactly (central differences integrate a constant
// acceleration exactly), and the work of gravity is the kinetic energy gained.
TEST(Gravity, FreeFallIsExactAndItsWorkIsTheKineticEnergy) {
  exdyn::input::Deck deck = bars(true, "hex8");
  deck.rigid_walls.clear();
  deck.parts[0].initial_velocity = {0, 0, 0};
  deck.loads.push_back({{-9.81e4, 0, 0}, {}});
  const FrictionRun run(deck);
  const double t = read_dataset(run.h5(), "/time").values.back();
  const auto u = run.at(run.summary.steps, "displacement");
  const double fall = 0.5 * 9.81e4 * t * t;
  for (std::size_t i = 0; i < u.size() / 3; ++i) EXPECT_NEAR(u[3 * i], -fall, 1e-12 * fall);
  // K^n = 1/2 m v^{n-1/2}.v^{n+1/2} = 1/2 m g^2 (t^2 - dt^2 / 4): the gain since K^0 is
  // 1/2 m g^2 t^2, the work.
  const auto kinetic = run.history("kinetic_energy");
  const double gained = kinetic.back() - kinetic.front(), work = run.history("external_work").back();
  std::printf("free fall: external work %.9g J, kinetic energy gained %.9g J\n", work, gained);
  EXPECT_NEAR(work, gained, 1e-9 * gained);
  EXPECT_LT(run.summary.energy.max_relative_error, 1e-9);
}

}  // namespace
