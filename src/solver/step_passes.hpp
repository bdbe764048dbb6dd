// The passes of one step of the time loop (solver/simulation.cpp): the state they
// work on, the internal and contact forces, the accelerations and the nodal update.
// Each pass runs on the threads in chunks and gives the same bits on any number of
// them (docs/performance.md).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "common/nodal_vectors.hpp"
#include "contact/contact_pass.hpp"
#include "element/element_block.hpp"
#include "model/contact_setup.hpp"
#include "model/model.hpp"
#include "output/result_writer.hpp"
#include "ranks/ranks.hpp"
#include "solver/nodal_update.hpp"

namespace exdyn::solver {

struct State {
  long step = 0;
  double time = 0.0;
  NodalVectors displacement;  // u^n, m; u^{n+1} at the step's end (update_positions)
  NodalVectors velocity;      // v^{n-1/2}, then v^{n+1/2} after update_velocities, m/s
  std::array<std::vector<std::uint8_t>, 3>
      flags;  // per component: fixed_flag | contact_flag (nodal_update.hpp)
  NodalVectors
      acceleration;  // a^n, m/s^2, computed when needed (output, a non-finite step: compute_accelerations)
  NodalVectors internal_force;  // f_int(u^n), N; 0 after update_velocities (see below)
  // f_contact(x^n) + f_load, N: the loads' constant m g rides with the contact forces
  // (the velocity update reads one array of external forces); contact_nodes and
  // loaded nodes carry contact_flag.
  NodalVectors contact_force;
  NodalVectors previous_contact_force;  // f_contact(x^{n-1}) + f_load, N (for the contact work)
  NodalVectors load_force;              // f_load = m g, N; empty without loads
  std::vector<double> gap;              // signed normal gap of each slave node, m (0: no candidate)
  std::vector<double> previous_gap;     // the gap of step n-1 (to step back after a non-finite step)
  std::vector<double> stress;           // 6 per element: xx yy zz xy yz xz, Pa
  std::vector<double> plastic_strain;   // per element, for the output (gather_plastic_strain)
  std::vector<double> damage, status;   // per element, for the output (gather_plastic_strain)
  double eroded_energy = 0.0;           // energy that left with eroded elements, J (this rank's)
  long eroded_elements = 0;             // elements failed so far (this rank's)
  long stress_step = -1;                // the step whose stresses `stress` holds (see below)
  long force_step = -1;                 // the step whose f_int `internal_force` holds, -1: none
  bool internal_force_zero = true;      // internal_force is all 0 (update_velocities zeroed it)
  double contact_energy = 0.0;          // work done against the contact forces, J
  double external_work = 0.0;           // work of the loads, J (on many ranks: the owned nodes')
  double wall_work = 0.0;               // work of the moving walls, J (every rank: the whole)
  // The reaction force of each boundary condition on the bodies at step n and n-1, N
  // (this rank's owned nodes), and the compensation of its sum (see add_boundary_reactions).
  std::vector<std::array<double, 3>> reaction, previous_reaction, reaction_error;
  std::array<std::vector<double>, 6> partial;            // per-chunk sums of the nodal loops (parallel.hpp)
  std::vector<element::ElementEnergies> block_energies;  // per block, scratch of compute_forces_side_by_side
};

struct Energies {
  double kinetic = 0.0;
  double internal = 0.0;
  double hourglass = 0.0;
  double contact = 0.0;
  double external_work = 0.0;
  double plastic = 0.0;   // plastic work so far, J: a part of `internal`
  double friction = 0.0;  // friction work so far, J: a part of `contact`
  // The internal and hourglass energy that left the model with eroded elements so far, J
  // (their mass stays on the nodes: no kinetic energy leaves).
  double eroded = 0.0;
  double eroded_elements = 0.0;  // failed so far (a count)
  double total() const { return kinetic + internal + hourglass + contact - external_work + eroded; }
};

struct NodalUpdate {
  bool finite = true;    // every a^n finite (else the components where it is not keep v^{n-1/2})
  double kinetic = 0.0;  // K^n = 1/2 sum m v^{n-1/2}.v^{n+1/2}, J
  // 1/8 sum m |a^n|^2, J/s^2: dt^2 times it turns K^n into 1/2 sum m |v^n|^2 with
  // v^n = (v^{n-1/2} + v^{n+1/2}) / 2, which is never negative (K^n can be: in an
  // unstable run K^n + U^n stays constant while both grow without bound).
  double mass_acceleration_squared = 0.0;
  double largest_component = 0;  // max |v^{n+1/2}| over nodes and components, m/s
  double old_power = 0.0;        // sum m v^{n-1/2}.a^n, W
  double new_power = 0.0;        // sum m v^{n+1/2}.a^n, W
};

// What a varying step adds to K^n (docs/theory.md, "Energy"). The velocity update
// weighs a^n by h^n = (dt^{n-1/2} + dt^{n+1/2}) / 2, so
//   K^n - K^{n-1} = 1/2 v^{n-1/2}.(h^{n-1} F^{n-1} + h^n F^n)      (F = M a),
// while the internal, contact and external terms take the trapezoid over
// u^n - u^{n-1} = dt^{n-1/2} v^{n-1/2}. The reported kinetic energy is K^n - C^n with
//   C^n - C^{n-1} = 1/4 [(dt^{n+1/2} - dt^{n-1/2}) v^{n-1/2}.F^n
//                      + (dt^{n-3/2} - dt^{n-1/2}) v^{n-1/2}.F^{n-1}],   C^0 = 0,
// so that its change is the trapezoid's too; with a fixed step C stays exactly 0.
struct VaryingStep {
  double correction = 0.0;  // C^n, J
  void add(long step, double previous_dt, double next_dt, double old_power, double new_power) {
    if (step > 0)
      correction +=
          0.25 * ((next_dt - previous_dt) * old_power + (step_before_ - previous_dt) * previous_new_power_);
    // dt^{n-1/2} for the next step; at step 0 the step of v^{-1/2} = v^0 - dt^{1/2} a^0 / 2.
    step_before_ = step > 0 ? previous_dt : next_dt;
    previous_new_power_ = new_power;
  }

 private:
  double step_before_ = 0.0;         // dt^{n-3/2} at step n, s
  double previous_new_power_ = 0.0;  // v^{n-1/2}.F^{n-1}, W
};

// f_int(u^n) of every block (on many ranks with the running sums of the shared
// nodes), with_stress the element stresses too; returns the blocks' energies.
element::ElementEnergies compute_internal_forces(const Model& model, Decomposition& d, State& state,
                                                 bool with_stress);
// state.stress and state.internal_force at u^n (computed again unless this step's are there).
void forces_of_this_step(const Model& model, Decomposition& d, State& state);
// The contact's surfaces brought to the elements' life after an element failed
// (opened_faces.hpp; on many ranks, every rank together: open_eroded_shares).
void follow_erosion(ContactModel& contact, const Model& model, Decomposition& d);
// The contact forces of every pair at x^n with v^{n-1/2}, and the contact work over
// the last step dt = t^n - t^{n-1} (on many ranks: distributed_contact.hpp).
void compute_contact_forces(const Model& model, ContactModel& contact, Decomposition& d, State& state,
                            double dt);
// The work of the loads over the last step dt, added to state.external_work (before
// the velocity update: v^{n-1/2}).
void add_load_work(const Model& model, State& state, double dt);
// The reaction of each boundary condition at step n, R = f_int - f_contact - f_load
// summed over its node components (on many ranks the owned ones), into state.reaction
// with the compensation of the sum in state.reaction_error (Neumaier's: a symmetry
// plane's net reaction is a sum of forces that cancel, and compensated it comes out the
// same on any number of ranks, reduce_over_ranks),
// and the work of the prescribed motion over the last step dt, added to
// state.external_work: W += dt/2 (R^{n-1} + R^n).V, the trapezoidal rule of the contact
// work (with u^n - u^{n-1} = dt V on those nodes; exact for a linear elastic body).
// Call after the forces of step n, before the velocity update (it clears f_int).
void add_boundary_reactions(const Model& model, const Decomposition& d, State& state, double dt);
// The two above side by side as OpenMP tasks (the same bits).
element::ElementEnergies compute_forces_side_by_side(const Model& model, ContactModel& contact, State& state,
                                                     double dt, bool with_stress, double& element_seconds);
contact::ContactStatistics total_statistics(const ContactModel& contact);
std::vector<output::ContactHistoryRow> contact_history(const ContactModel& contact);
std::vector<output::WallHistoryRow> wall_history(const ContactModel& contact);
// a^n = (f_contact - f_int) / m (0 on fixed components); false where some a is not finite.
bool compute_accelerations(const Model& model, State& state);
// v^{n+1/2} = v^{n-1/2} + dt a^n in place, with the energy sums.
NodalUpdate update_velocities(const Model& model, State& state, double dt, bool first_step,
                              bool keep_internal_force, const NodalUpdateFns& passes);
// u^{n+1} = u^n + dt v^{n+1/2}.
void update_positions(State& state, double dt, const NodalUpdateFns& passes);
// y += scale x.
void add_scaled(NodalVectors& y, double scale, const NodalVectors& x);
// The blocks' per-element equivalent plastic strains into state.plastic_strain, and
// their damage and status (1 alive, 0 failed or eroded) into state.damage and state.status.
void gather_plastic_strain(const Model& model, State& state);
// time.erode, from the first step dt (s) on: each block that can fail marks, in its
// corner checks, the live elements whose own stable step (without the Courant factor)
// is below min_dt_ratio dt / courant or that invert, and its damage pass fails them.
void erode_distorted_elements(const Model& model, const input::TimeOptions& time, double first_dt);

}  // namespace exdyn::solver
