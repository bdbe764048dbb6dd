// The nodal update (solver/nodal_update.hpp), its velocity and position passes, of
// every instruction set this CPU runs against the plain loops of the central-difference
// step, on a node count that leaves a partial pack, with fixed components, both the
// first and a later step, with and without clearing f_int; and the kinetic energy of a
// varying step (step_passes.hpp, VaryingStep) on an oscillator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "common/isa.hpp"
#include "solver/nodal_update.hpp"
#include "solver/step_passes.hpp"

namespace exdyn::solver {
namespace {

struct Nodes {
  explicit Nodes(std::size_t n) : mass(n), inverse_mass(n) {
    for (auto* field : {&f, &f_contact, &v, &u})
      for (auto& component : *field) component.assign(n, 0.0);
    for (auto& component : flags) component.assign(n, 0);
  }
  std::array<std::vector<double>, 3> f, f_contact, v, u;
  std::array<std::vector<std::uint8_t>, 3> flags;
  std::vector<double> mass, inverse_mass;

  NodalArrays arrays() {
    NodalArrays d;
    for (std::size_t c = 0; c < 3; ++c) {
      d.internal_force[c] = f[c].data();
      d.contact_force[c] = f_contact[c].data();
      d.flags[c] = flags[c].data();
      d.velocity[c] = v[c].data();
    }
    d.mass = mass.data();
    d.inverse_mass = inverse_mass.data();
    return d;
  }
  void update_positions(PositionUpdateFn position, double dt) {
    position({u[0].data(), u[1].data(), u[2].data()}, {v[0].data(), v[1].data(), v[2].data()}, 0, mass.size(),
             dt);
  }
};

Nodes random_nodes(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Nodes nodes(n);
  for (std::size_t i = 0; i < n; ++i) {
    nodes.mass[i] = 1e-6 * (1.5 + unit(rng));
    nodes.inverse_mass[i] = 1.0 / nodes.mass[i];
    for (std::size_t c = 0; c < 3; ++c) {
      nodes.f[c][i] = 1e3 * unit(rng);
      // Contact forces only at flagged nodes (the contact surfaces' nodes), as in a run.
      nodes.f_contact[c][i] = i % 7 == 0 ? 1e2 * unit(rng) : 0.0;
      nodes.v[c][i] = unit(rng);
      nodes.u[c][i] = 1e-6 * unit(rng);
      nodes.flags[c][i] = static_cast<std::uint8_t>(((i + c) % 5 == 0 ? fixed_flag : 0) |
                                                    (i % 7 == 0 || i % 11 == 0 ? contact_flag : 0));
    }
  }
  return nodes;
}

// The plain loops, node by node: the definition the packed versions must meet.
NodalSums plain_velocity_update(Nodes& d, double dt, bool first_step) {
  NodalSums sums;
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < d.mass.size(); ++i) {
      const double raw = (d.f_contact[c][i] - d.f[c][i]) * d.inverse_mass[i];
      sums.non_finite += 0.0 * raw;
      const double a = (d.flags[c][i] & fixed_flag) != 0 ? 0.0 : raw;
      const double v_old = first_step ? d.v[c][i] - 0.5 * dt * a : d.v[c][i];
      const double v_new = v_old + dt * a;
      sums.twice_kinetic += d.mass[i] * v_old * v_new;
      sums.mass_acceleration_squared += d.mass[i] * a * a;
      sums.old_power += d.mass[i] * v_old * a;
      sums.new_power += d.mass[i] * v_new * a;
      sums.largest_component = std::max(sums.largest_component, std::abs(v_new));
      d.v[c][i] = v_new;
    }
  return sums;
}

void plain_position_update(Nodes& d, double dt) {
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < d.mass.size(); ++i) d.u[c][i] = d.u[c][i] + dt * d.v[c][i];
}

TEST(NodalUpdate, EveryInstructionSetMatchesThePlainLoop) {
  const double dt = 1e-8;
  const std::size_t n = 1027;  // 4 x 256 + 3: a partial pack for 2, 4 and 8 lanes
  int compared = 0;
  for (const Isa isa : {Isa::x86_64_v2, Isa::x86_64_v3, Isa::x86_64_v4}) {
    if (!isa_available(isa)) continue;
    const NodalUpdateFns passes = nodal_update_for(isa);
    for (const bool first_step : {true, false})
      for (const bool zero_internal_force : {true, false}) {
        Nodes expected = random_nodes(n, 7), packed = random_nodes(n, 7);
        const NodalSums plain = plain_velocity_update(expected, dt, first_step);
        plain_position_update(expected, dt);
        const NodalSums sums = passes.velocity(packed.arrays(), 0, n, dt, first_step, zero_internal_force);
        packed.update_positions(passes.position, dt);
        // Each node's values: the same operations; x86-64-v3 and v4 may contract
        // v + dt a into one FMA, so 1e-12 relative there, the same bits on the baseline.
        const double tolerance = isa == Isa::x86_64_v2 ? 0.0 : 1e-12;
        for (std::size_t c = 0; c < 3; ++c)
          for (std::size_t i = 0; i < n; ++i) {
            ASSERT_NEAR(packed.v[c][i], expected.v[c][i], tolerance * std::abs(expected.v[c][i]))
                << isa_name(isa) << " node " << i;
            ASSERT_NEAR(packed.u[c][i], expected.u[c][i], tolerance * std::abs(expected.u[c][i]))
                << isa_name(isa) << " node " << i;
            // f_int: cleared behind the read when asked, else untouched.
            ASSERT_EQ(packed.f[c][i], zero_internal_force ? 0.0 : expected.f[c][i]) << isa_name(isa);
          }
        // The sums: the same terms, added per lane and then the lanes in order.
        EXPECT_EQ(sums.non_finite, 0.0);
        EXPECT_NEAR(sums.twice_kinetic, plain.twice_kinetic, 1e-12 * std::abs(plain.twice_kinetic));
        EXPECT_NEAR(sums.mass_acceleration_squared, plain.mass_acceleration_squared,
                    1e-12 * plain.mass_acceleration_squared);
        EXPECT_NEAR(sums.largest_component, plain.largest_component, 1e-12 * plain.largest_component);
        // The powers sum terms of either sign: to 1e-12 of the sum of their sizes,
        // sum m |v| |a| <= max |v| sqrt(sum m) sqrt(sum m a^2).
        double mass = 0.0;
        for (const double m : expected.mass) mass += 3.0 * m;
        const double power_scale =
            2.0 * plain.largest_component * std::sqrt(mass * plain.mass_acceleration_squared);
        EXPECT_NEAR(sums.old_power, plain.old_power, 1e-12 * power_scale);
        EXPECT_NEAR(sums.new_power, plain.new_power, 1e-12 * power_scale);
        ++compared;
      }
    // A non-finite force anywhere, in a pack or in the tail, is reported, and that
    // component keeps v^{n-1/2} while the others are updated.
    for (const std::size_t bad : {std::size_t{5}, n - 1}) {
      Nodes nodes = random_nodes(n, 8), expected = random_nodes(n, 8);
      nodes.f[1][bad] = std::numeric_limits<double>::infinity();
      EXPECT_NE(passes.velocity(nodes.arrays(), 0, n, dt, false, true).non_finite, 0.0) << bad;
      plain_velocity_update(expected, dt, false);
      EXPECT_EQ(nodes.v[1][bad], random_nodes(n, 8).v[1][bad]) << isa_name(isa) << " " << bad;
      EXPECT_NEAR(nodes.v[0][bad], expected.v[0][bad], 1e-12 * std::abs(expected.v[0][bad])) << bad;
      EXPECT_NEAR(nodes.v[1][bad - 1], expected.v[1][bad - 1], 1e-12 * std::abs(expected.v[1][bad - 1]))
          << bad;
    }
  }
  EXPECT_GE(compared, 4);  // the baseline runs everywhere
}

// A linear spring and mass stepped as the time loop steps it, the step drawn anew
// each time in [0.5, 1] of 0.04 / omega (so never near the stability limit 2 / omega):
// 1/2 k u^2 changes by the trapezoid of the spring's work exactly, so K^n - C^n + U^n
// must stay at its start to round-off. K^n alone (C left out) drifts by the varying
// step, which the test sees too.
TEST(VaryingStep, ASpringAndMassKeepTheirEnergyToRoundOffWhateverTheSteps) {
  const double m = 2.0, k = 5.0e3, omega = std::sqrt(k / m);  // kg, N/m, rad/s
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> fraction(0.5, 1.0);
  const auto draw = [&] { return 0.04 / omega * fraction(rng); };
  double u = 0.01, v = 0.3, previous_dt = 0.0, next_dt = draw();
  VaryingStep varying;
  double start = 0.0, worst = 0.0, worst_uncorrected = 0.0;
  for (long step = 0; step < 20000; ++step) {
    if (step == 0) previous_dt = next_dt;  // StepClock: previous() is the first step at step 0
    const double a = -k * u / m;
    const double h = step == 0 ? next_dt : 0.5 * (previous_dt + next_dt);
    const double v_old = step == 0 ? v - 0.5 * next_dt * a : v;
    const double v_new = v_old + h * a;
    varying.add(step, previous_dt, next_dt, m * v_old * a, m * v_new * a);
    const double kinetic = 0.5 * m * v_old * v_new, strain = 0.5 * k * u * u;
    const double energy = kinetic - varying.correction + strain;
    if (step == 0) start = energy;
    worst = std::max(worst, std::abs(energy - start));
    worst_uncorrected = std::max(worst_uncorrected, std::abs(kinetic + strain - start));
    v = v_new;
    u = u + next_dt * v;
    previous_dt = next_dt;
    next_dt = draw();
  }
  EXPECT_LT(worst, 1e-13 * start);
  EXPECT_GT(worst_uncorrected, 1e-4 * start);
}

TEST(VaryingStep, AFixedStepAddsExactlyNothing) {
  VaryingStep varying;
  const double dt = 1.7e-8;
  for (long step = 0; step < 100; ++step) varying.add(step, dt, dt, 3.0 + double(step), -1.0 - double(step));
  EXPECT_EQ(varying.correction, 0.0);
}

}  // namespace
}  // namespace exdyn::solver
