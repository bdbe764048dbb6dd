// The nodal update of the central-difference step, for a range of nodes and one
// instruction set (common/isa.hpp). Two passes, each in place:
//   the velocity update, after the forces of step n:
//     a^n       = M^-1 (f_contact - f_int)       (0 on fixed components; not stored)
//     v^{n+1/2} = v^{n-1/2} + dt a^n             (first step: v^{-1/2} = v^0 - dt/2 a^0)
//   with the sums the energy and the guards need, and f_int set to 0 for the next
//   element pass (except when the step is written: the output reads f_int);
//   the position update, at the end of step n, when nothing reads u^n any more:
//     u^{n+1}   = u^n + dt v^{n+1/2}.
// Both passes are bound by memory traffic (docs/performance.md, "The nodal update"),
// so they read and write no more than they must: every array is updated where it is
// (a store to an array just read needs no read-for-ownership of its cache line), the
// masses are read once per node, not once per component, a^n is not stored (the
// output recomputes it, solver/simulation.cpp), and f_contact is read only for packs
// holding a contact node. The version for an ISA runs on packs of 2, 4 or 8 nodes (its
// vector width) with one partial sum per lane; the lanes are added in order at the end,
// so a range gives the same bits on any thread.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "common/isa.hpp"

namespace exdyn::solver {

// Flags of a node component.
inline constexpr std::uint8_t fixed_flag = 1;    // the component is fixed: a = 0
inline constexpr std::uint8_t contact_flag = 2;  // the node may carry a contact force

// The nodal arrays of one step, per component c (x, y, z), and per node.
struct NodalArrays {
  std::array<double*, 3> internal_force{};       // f_int(u^n), N; 0 after the update if asked
  std::array<const double*, 3> contact_force{};  // f_contact(x^n), N; 0 at nodes without contact_flag
  std::array<const std::uint8_t*, 3> flags{};    // fixed_flag | contact_flag
  std::array<double*, 3> velocity{};             // v^{n-1/2} in, v^{n+1/2} out, m/s
  const double* mass = nullptr;                  // lumped mass, kg
  const double* inverse_mass = nullptr;          // 1 / mass, 1/kg
};

// The sums over a range of nodes and components.
struct NodalSums {
  double non_finite = 0.0;                 // sum 0 * a_raw: 0 unless some a is inf or NaN
  double twice_kinetic = 0.0;              // sum m v^{n-1/2} v^{n+1/2}, J
  double mass_acceleration_squared = 0.0;  // sum m a^2, kg m^2/s^4
  double old_power = 0.0;                  // sum m v^{n-1/2} a^n, W
  double new_power = 0.0;                  // sum m v^{n+1/2} a^n, W
  double largest_component = 0.0;          // max |v^{n+1/2}_c|, m/s
};

// The velocity update of nodes [begin, end). A component whose a^n is not finite keeps
// v^{n-1/2} (and non_finite says so), so the caller can step back to the last finite
// state (solver/simulation.cpp). zero_internal_force: set f_int to 0 behind the read.
using VelocityUpdateFn = NodalSums (*)(const NodalArrays& arrays, std::size_t begin, std::size_t end,
                                       double dt, bool first_step, bool zero_internal_force);

// The position update u += dt v of nodes [begin, end), per component.
using PositionUpdateFn = void (*)(const std::array<double*, 3>& displacement,
                                  const std::array<const double*, 3>& velocity, std::size_t begin,
                                  std::size_t end, double dt);

struct NodalUpdateFns {
  VelocityUpdateFn velocity = nullptr;
  PositionUpdateFn position = nullptr;
};

// The two passes compiled for `isa` (which the caller has checked this CPU runs).
NodalUpdateFns nodal_update_for(Isa isa);

}  // namespace exdyn::solver
