#include "solver/nodal_update.hpp"

#include <algorithm>
#include <cmath>

#include "common/simd_pack.hpp"

namespace exdyn::solver {
namespace {

// One node component: the scalar form of the pack loop below (its tail).
struct ScalarSums {
  double non_finite = 0.0, twice_kinetic = 0.0, m_a2 = 0.0, largest = 0.0;
};

// Nodes [begin, end) in packs of Lanes (the rest one by one). The operations of each
// node are those of the scalar loop; only the sums are split over the lanes.
template <int Lanes>
NodalSums update_range(const NodalArrays& d, std::size_t begin, std::size_t end, double dt, bool first_step) {
  using Real = Pack<Lanes>;
  using Mask = IntPack<Lanes>;
  const double half_step_back = -0.5 * dt;
  Real non_finite{}, twice_kinetic{}, m_a2{}, largest{};
  ScalarSums tail;
  for (int c = 0; c < 3; ++c) {
    const double* f = d.internal_force[std::size_t(c)];
    const double* f_contact = d.contact_force[std::size_t(c)];
    const std::uint8_t* flags = d.flags[std::size_t(c)];
    const double* v = d.velocity[std::size_t(c)];
    const double* u = d.displacement[std::size_t(c)];
    double* v_next = d.next_velocity[std::size_t(c)];
    double* u_next = d.next_displacement[std::size_t(c)];
    std::size_t i = begin;
    for (; i + Lanes <= end; i += Lanes) {
      Mask is_fixed;
      int contact = 0;
      for (int lane = 0; lane < Lanes; ++lane) {
        is_fixed[lane] = flags[i + std::size_t(lane)] & fixed_flag;
        contact |= flags[i + std::size_t(lane)] & contact_flag;
      }
      // 0 - f_int where no node of the pack has contact: the same bits as f_contact - f_int.
      const Real f_c = contact != 0 ? load<Real>(f_contact + i, 0) : Real{};
      const Real raw = (f_c - load<Real>(f + i, 0)) * load<Real>(d.inverse_mass + i, 0);
      non_finite += 0.0 * raw;
      const Real a_i = is_fixed != 0 ? Real{} : raw;
      const Real v_i = load<Real>(v + i, 0);
      const Real v_old = first_step ? v_i + half_step_back * a_i : v_i;
      const Real v_new = v_old + dt * a_i;
      const Real m = load<Real>(d.mass + i, 0);
      twice_kinetic += m * v_old * v_new;
      m_a2 += m * a_i * a_i;
      const Real speed = v_new < 0.0 ? -v_new : v_new;
      largest = speed > largest ? speed : largest;
      store(v_next + i, v_new);
      store(u_next + i, load<Real>(u + i, 0) + dt * v_new);
    }
    for (; i < end; ++i) {
      const double raw = (f_contact[i] - f[i]) * d.inverse_mass[i];
      tail.non_finite += 0.0 * raw;
      const double a_i = (flags[i] & fixed_flag) != 0 ? 0.0 : raw;
      const double v_old = first_step ? v[i] + half_step_back * a_i : v[i];
      const double v_new = v_old + dt * a_i;
      tail.twice_kinetic += d.mass[i] * v_old * v_new;
      tail.m_a2 += d.mass[i] * a_i * a_i;
      tail.largest = std::max(tail.largest, std::abs(v_new));
      v_next[i] = v_new;
      u_next[i] = u[i] + dt * v_new;
    }
  }
  NodalSums sums;
  for (int lane = 0; lane < Lanes; ++lane) {
    sums.non_finite += non_finite[lane];
    sums.twice_kinetic += twice_kinetic[lane];
    sums.mass_acceleration_squared += m_a2[lane];
    sums.largest_component = std::max(sums.largest_component, largest[lane]);
  }
  sums.non_finite += tail.non_finite;
  sums.twice_kinetic += tail.twice_kinetic;
  sums.mass_acceleration_squared += tail.m_a2;
  sums.largest_component = std::max(sums.largest_component, tail.largest);
  return sums;
}

// The versions per ISA, as the element loops (element/element_isa.hpp).
[[gnu::flatten]] NodalSums update_x86_64_v2(const NodalArrays& d, std::size_t begin, std::size_t end,
                                            double dt, bool first_step) {
  return update_range<2>(d, begin, end, dt, first_step);
}

[[gnu::target("arch=x86-64-v3"), gnu::flatten]] NodalSums update_x86_64_v3(const NodalArrays& d,
                                                                           std::size_t begin, std::size_t end,
                                                                           double dt, bool first_step) {
  return update_range<4>(d, begin, end, dt, first_step);
}

[[gnu::target("arch=x86-64-v4"), gnu::flatten]] NodalSums update_x86_64_v4(const NodalArrays& d,
                                                                           std::size_t begin, std::size_t end,
                                                                           double dt, bool first_step) {
  return update_range<8>(d, begin, end, dt, first_step);
}

}  // namespace

NodalUpdateFn nodal_update_for(Isa isa) {
  switch (isa) {
    case Isa::x86_64_v4:
      return update_x86_64_v4;
    case Isa::x86_64_v3:
      return update_x86_64_v3;
    case Isa::x86_64_v2:
      break;
  }
  return update_x86_64_v2;
}

}  // namespace exdyn::solver
