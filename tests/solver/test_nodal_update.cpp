// The fused nodal update (solver/nodal_update.hpp) of every instruction set this CPU
// runs against the plain loop of the central-difference step, on a node count that
// leaves a partial pack, with fixed components, both the first and a later step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "common/isa.hpp"
#include "solver/nodal_update.hpp"

namespace exdyn::solver {
namespace {

struct Nodes {
  explicit Nodes(std::size_t n) : mass(n), inverse_mass(n) {
    for (auto* field : {&f, &f_contact, &v, &u, &v_next, &u_next})
      for (auto& component : *field) component.assign(n, 0.0);
    for (auto& component : flags) component.assign(n, 0);
  }
  std::array<std::vector<double>, 3> f, f_contact, v, u, v_next, u_next;
  std::array<std::vector<std::uint8_t>, 3> flags;
  std::vector<double> mass, inverse_mass;

  NodalArrays arrays() {
    NodalArrays d;
    for (std::size_t c = 0; c < 3; ++c) {
      d.internal_force[c] = f[c].data();
      d.contact_force[c] = f_contact[c].data();
      d.flags[c] = flags[c].data();
      d.velocity[c] = v[c].data();
      d.displacement[c] = u[c].data();
      d.next_velocity[c] = v_next[c].data();
      d.next_displacement[c] = u_next[c].data();
    }
    d.mass = mass.data();
    d.inverse_mass = inverse_mass.data();
    return d;
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

// The plain loop, node by node: the definition the packed versions must meet.
NodalSums plain_update(Nodes& d, double dt, bool first_step) {
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
      sums.largest_component = std::max(sums.largest_component, std::abs(v_new));
      d.v_next[c][i] = v_new;
      d.u_next[c][i] = d.u[c][i] + dt * v_new;
    }
  return sums;
}

TEST(NodalUpdate, EveryInstructionSetMatchesThePlainLoop) {
  const double dt = 1e-8;
  const std::size_t n = 1027;  // 4 x 256 + 3: a partial pack for 2, 4 and 8 lanes
  int compared = 0;
  for (const Isa isa : {Isa::x86_64_v2, Isa::x86_64_v3, Isa::x86_64_v4}) {
    if (!isa_available(isa)) continue;
    for (const bool first_step : {true, false}) {
      Nodes expected = random_nodes(n, 7), packed = random_nodes(n, 7);
      const NodalSums plain = plain_update(expected, dt, first_step);
      const NodalSums sums = nodal_update_for(isa)(packed.arrays(), 0, n, dt, first_step);
      // Each node's values: the same operations; x86-64-v3 and v4 may contract
      // v + dt a into one FMA, so 1e-12 relative there, the same bits on the baseline.
      const double tolerance = isa == Isa::x86_64_v2 ? 0.0 : 1e-12;
      for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < n; ++i) {
          ASSERT_NEAR(packed.v_next[c][i], expected.v_next[c][i], tolerance * std::abs(expected.v_next[c][i]))
              << isa_name(isa) << " node " << i;
          ASSERT_NEAR(packed.u_next[c][i], expected.u_next[c][i], tolerance * std::abs(expected.u_next[c][i]))
              << isa_name(isa) << " node " << i;
        }
      // The sums: the same terms, added per lane and then the lanes in order.
      EXPECT_EQ(sums.non_finite, 0.0);
      EXPECT_NEAR(sums.twice_kinetic, plain.twice_kinetic, 1e-12 * std::abs(plain.twice_kinetic));
      EXPECT_NEAR(sums.mass_acceleration_squared, plain.mass_acceleration_squared,
                  1e-12 * plain.mass_acceleration_squared);
      EXPECT_NEAR(sums.largest_component, plain.largest_component, 1e-12 * plain.largest_component);
      ++compared;
    }
    // A non-finite force anywhere, in a pack or in the tail, is reported.
    for (const std::size_t bad : {std::size_t{5}, n - 1}) {
      Nodes nodes = random_nodes(n, 8);
      nodes.f[1][bad] = std::numeric_limits<double>::infinity();
      EXPECT_NE(nodal_update_for(isa)(nodes.arrays(), 0, n, dt, false).non_finite, 0.0) << bad;
    }
  }
  EXPECT_GE(compared, 2);  // the baseline runs everywhere
}

}  // namespace
}  // namespace exdyn::solver
