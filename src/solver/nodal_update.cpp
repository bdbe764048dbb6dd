#include "solver/nodal_update.hpp"

#include <algorithm>
#include <cmath>

#include "common/simd_pack.hpp"

namespace exdyn::solver {
namespace {

// The velocity update of one node component, scalar: the tail of the pack loop below.
struct ScalarSums {
  double non_finite = 0.0, twice_kinetic = 0.0, m_a2 = 0.0, old_power = 0.0, new_power = 0.0, largest = 0.0;
};

// Nodes [begin, end) in packs of Lanes (the rest one by one), the three components of
// a pack together so that the masses are read once. The operations of each node are
// those of the scalar loop; only the sums are split over the lanes.
template <int Lanes>
NodalSums velocity_range(const NodalArrays& d, std::size_t begin, std::size_t end, double dt, bool first_step,
                         bool zero_internal_force) {
  using Real = Pack<Lanes>;
  using Mask = IntPack<Lanes>;
  const double half_step_back = -0.5 * dt;
  Real non_finite{}, twice_kinetic{}, m_a2{}, old_power{}, new_power{}, largest{};
  std::size_t i = begin;
  for (; i + Lanes <= end; i += Lanes) {
    const Real m = load<Real>(d.mass + i, 0);
    const Real inverse_m = load<Real>(d.inverse_mass + i, 0);
    for (std::size_t c = 0; c < 3; ++c) {
      double* f = d.internal_force[c] + i;
      const std::uint8_t* flags = d.flags[c] + i;
      double* v = d.velocity[c] + i;
      Mask is_fixed;
      int contact = 0;
      for (int lane = 0; lane < Lanes; ++lane) {
        is_fixed[lane] = flags[lane] & fixed_flag;
        contact |= flags[lane] & contact_flag;
      }
      // 0 - f_int where no node of the pack has contact: the same bits as f_contact - f_int.
      const Real f_c = contact != 0 ? load<Real>(d.contact_force[c] + i, 0) : Real{};
      const Real raw = (f_c - load<Real>(f, 0)) * inverse_m;
      if (zero_internal_force) store(f, Real{});
      const Real zero_if_finite = 0.0 * raw;  // NaN where a is inf or NaN
      non_finite += zero_if_finite;
      const Real a_i = is_fixed != 0 ? Real{} : raw;
      const Real v_i = load<Real>(v, 0);
      const Real v_old = first_step ? v_i + half_step_back * a_i : v_i;
      const Real v_new = v_old + dt * a_i;
      twice_kinetic += m * v_old * v_new;
      m_a2 += m * a_i * a_i;
      old_power += m * v_old * a_i;
      new_power += m * v_new * a_i;
      const Real speed = v_new < 0.0 ? -v_new : v_new;
      largest = speed > largest ? speed : largest;
      store(v, zero_if_finite == 0.0 ? v_new : v_i);  // a non-finite a leaves v^{n-1/2}
    }
  }
  ScalarSums tail;
  for (; i < end; ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      double& f = d.internal_force[c][i];
      double& v = d.velocity[c][i];
      const double raw = (d.contact_force[c][i] - f) * d.inverse_mass[i];
      if (zero_internal_force) f = 0.0;
      const double zero_if_finite = 0.0 * raw;
      tail.non_finite += zero_if_finite;
      const double a_i = (d.flags[c][i] & fixed_flag) != 0 ? 0.0 : raw;
      const double v_old = first_step ? v + half_step_back * a_i : v;
      const double v_new = v_old + dt * a_i;
      tail.twice_kinetic += d.mass[i] * v_old * v_new;
      tail.m_a2 += d.mass[i] * a_i * a_i;
      tail.old_power += d.mass[i] * v_old * a_i;
      tail.new_power += d.mass[i] * v_new * a_i;
      tail.largest = std::max(tail.largest, std::abs(v_new));
      if (zero_if_finite == 0.0) v = v_new;
    }
  }
  NodalSums sums;
  for (int lane = 0; lane < Lanes; ++lane) {
    sums.non_finite += non_finite[lane];
    sums.twice_kinetic += twice_kinetic[lane];
    sums.mass_acceleration_squared += m_a2[lane];
    sums.old_power += old_power[lane];
    sums.new_power += new_power[lane];
    sums.largest_component = std::max(sums.largest_component, largest[lane]);
  }
  sums.non_finite += tail.non_finite;
  sums.twice_kinetic += tail.twice_kinetic;
  sums.mass_acceleration_squared += tail.m_a2;
  sums.old_power += tail.old_power;
  sums.new_power += tail.new_power;
  sums.largest_component = std::max(sums.largest_component, tail.largest);
  return sums;
}

// u += dt v on [begin, end), per component, in packs of Lanes.
template <int Lanes>
void position_range(const std::array<double*, 3>& u, const std::array<const double*, 3>& v, std::size_t begin,
                    std::size_t end, double dt) {
  using Real = Pack<Lanes>;
  for (std::size_t c = 0; c < 3; ++c) {
    std::size_t i = begin;
    for (; i + Lanes <= end; i += Lanes)
      store(u[c] + i, load<Real>(u[c] + i, 0) + dt * load<Real>(v[c] + i, 0));
    for (; i < end; ++i) u[c][i] = u[c][i] + dt * v[c][i];
  }
}

// The versions per ISA, as the element loops (element/element_isa.hpp).
[[gnu::flatten]] NodalSums velocity_x86_64_v2(const NodalArrays& d, std::size_t begin, std::size_t end,
                                              double dt, bool first_step, bool zero_internal_force) {
  return velocity_range<2>(d, begin, end, dt, first_step, zero_internal_force);
}
[[gnu::target("arch=x86-64-v3"), gnu::flatten]] NodalSums velocity_x86_64_v3(const NodalArrays& d,
                                                                             std::size_t begin,
                                                                             std::size_t end, double dt,
                                                                             bool first_step,
                                                                             bool zero_internal_force) {
  return velocity_range<4>(d, begin, end, dt, first_step, zero_internal_force);
}
[[gnu::target("arch=x86-64-v4"), gnu::flatten]] NodalSums velocity_x86_64_v4(const NodalArrays& d,
                                                                             std::size_t begin,
                                                                             std::size_t end, double dt,
                                                                             bool first_step,
                                                                             bool zero_internal_force) {
  return velocity_range<8>(d, begin, end, dt, first_step, zero_internal_force);
}

[[gnu::flatten]] void position_x86_64_v2(const std::array<double*, 3>& u,
                                         const std::array<const double*, 3>& v, std::size_t begin,
                                         std::size_t end, double dt) {
  position_range<2>(u, v, begin, end, dt);
}
[[gnu::target("arch=x86-64-v3"), gnu::flatten]] void position_x86_64_v3(const std::array<double*, 3>& u,
                                                                        const std::array<const double*, 3>& v,
                                                                        std::size_t begin, std::size_t end,
                                                                        double dt) {
  position_range<4>(u, v, begin, end, dt);
}
[[gnu::target("arch=x86-64-v4"), gnu::flatten]] void position_x86_64_v4(const std::array<double*, 3>& u,
                                                                        const std::array<const double*, 3>& v,
                                                                        std::size_t begin, std::size_t end,
                                                                        double dt) {
  position_range<8>(u, v, begin, end, dt);
}

}  // namespace

NodalUpdateFns nodal_update_for(Isa isa) {
  switch (isa) {
    case Isa::x86_64_v4:
      return {velocity_x86_64_v4, position_x86_64_v4};
    case Isa::x86_64_v3:
      return {velocity_x86_64_v3, position_x86_64_v3};
    case Isa::x86_64_v2:
      break;
  }
  return {velocity_x86_64_v2, position_x86_64_v2};
}

}  // namespace exdyn::solver
