// The passes of one step of the time loop (step_passes.hpp).
#include "solver/step_passes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/parallel.hpp"
#include "common/timer.hpp"
#include "model/opened_faces.hpp"

namespace exdyn::solver {

namespace {
// f_int(u^n), and with_stress the stresses of every element; returns the strain and
// hourglass energies. The stresses are stored only when a step is written (they are
// 48 B per element, written and read back through the caches every step otherwise),
// and the velocity update sets f_int to 0 behind its read except at those steps (the
// next element pass then needs no pass of its own to clear it): whatever reads
// state.stress or state.internal_force first makes sure they are the current step's
// (forces_of_this_step).
void clear_internal_force(State& state) {
  if (!state.internal_force_zero)
    for_each_chunk(state.internal_force.size(), [&](std::size_t begin, std::size_t end, std::size_t) {
      for (int c = 0; c < 3; ++c)
        std::fill(state.internal_force.component(c).begin() + begin,
                  state.internal_force.component(c).begin() + end, 0.0);
    });
}

void internal_force_computed(State& state, bool with_stress) {
  state.internal_force_zero = false;
  state.force_step = state.step;
  if (with_stress) state.stress_step = state.step;
}

}  // namespace

// On many ranks the running sums of the shared nodes pass from rank to rank colour
// by colour (decomposition.hpp): the same bits as one rank.
element::ElementEnergies compute_internal_forces(const Model& model, Decomposition& d, State& state,
                                                 bool with_stress) {
  clear_internal_force(state);
  element::ElementEnergies total;
  if (d.comm.distributed())
    total = add_forces_across_ranks(model, d, state.displacement, state.internal_force,
                                    with_stress ? state.stress.data() : nullptr);
  else
    for (const auto& block : model.blocks) {
      const element::ElementEnergies e = element::add_internal_forces(
          block, state.displacement, state.internal_force, with_stress ? state.stress.data() : nullptr);
      total += e;
    }
  internal_force_computed(state, with_stress);
  return total;
}

// state.stress and state.internal_force at u^n: computed again (the same bits) unless
// this step's element pass left them.
void forces_of_this_step(const Model& model, Decomposition& d, State& state) {
  if (state.stress_step != state.step || state.force_step != state.step)
    compute_internal_forces(model, d, state, true);
}

namespace {

// The contact pass of every pair at x^n = x_ref + u^n with v^{n-1/2}; then the
// work done against the contact forces (trapezoidal rule):
//   E_c^n = E_c^{n-1} - 1/2 (f_c^{n-1} + f_c^n).(u^n - u^{n-1}),  u^n - u^{n-1} = dt v^{n-1/2}.
// The contact nodes' loops run on the threads, in chunks of contact_node_chunk nodes
// (a contact face has hundreds to thousands): each node is written by one thread.
constexpr std::size_t contact_node_chunk = 256;

void begin_contact_forces(ContactModel& contact, State& state) {
  std::swap(state.contact_force, state.previous_contact_force);
  const bool loads = !state.load_force.empty();
  for_each_chunk(
      contact.nodes.size(),
      [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t i = begin; i < end; ++i) {
          const std::uint32_t node = contact.nodes[i];
          for (int c = 0; c < 3; ++c)
            state.contact_force.component(c)[node] = loads ? state.load_force.component(c)[node] : 0.0;
          state.previous_gap[node] = state.gap[node];
          state.gap[node] = std::numeric_limits<double>::infinity();
        }
      },
      contact_node_chunk);
}

void run_contact_passes(const Model& model, ContactModel& contact, State& state) {
  for (auto& pair : contact.pairs) {
    for (std::size_t p = 0; p < pair.passes.size(); ++p)
      contact::run_contact_pass(pair.passes[p], pair.settings, pair.states[p], model.mesh.x_ref,
                                state.displacement, state.velocity, model.mass, state.contact_force,
                                state.gap, pair.statistics, pair.seconds);
    pair.follow_peaks();
  }
  for (auto& wall : contact.walls) {
    contact::run_wall_pass(wall.surfaces, wall.plane, wall.settings, wall.state, model.mesh.x_ref,
                           state.displacement, state.velocity, model.mass, state.time, state.contact_force,
                           state.gap, wall.statistics, wall.seconds);
    wall.max_force = std::max(wall.max_force, contact::norm(wall.state.force));
  }
}

// On many ranks (d) the power of the owned nodes, summed over the ranks with the
// contact's figures (reduce_contact_figures).
void finish_contact_forces(ContactModel& contact, State& state, double dt, Decomposition* d) {
  double power = 0.0;  // (f_c^{n-1} + f_c^n).v^{n-1/2}, W x 2
  const bool loads = !state.load_force.empty();
  // Each node's term on the threads, then their sum in node order (the bits of one loop).
  contact.node_power.resize(contact.nodes.size());
  for_each_chunk(
      contact.nodes.size(),
      [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t i = begin; i < end; ++i) {
          const std::uint32_t node = contact.nodes[i];
          if (state.gap[node] == std::numeric_limits<double>::infinity())
            state.gap[node] = 0.0;  // no candidate
          if (loads) continue;
          contact.node_power[i] =
              (state.previous_contact_force.x[node] + state.contact_force.x[node]) * state.velocity.x[node] +
              (state.previous_contact_force.y[node] + state.contact_force.y[node]) * state.velocity.y[node] +
              (state.previous_contact_force.z[node] + state.contact_force.z[node]) * state.velocity.z[node];
        }
      },
      contact_node_chunk);
  for (std::size_t i = 0; i < contact.nodes.size(); ++i) {
    const std::uint32_t node = contact.nodes[i];
    if (d != nullptr && d->owned[node] == 0) continue;
    if (!loads) {
      power += contact.node_power[i];
      continue;
    }
    for (int c = 0; c < 3; ++c)  // three terms a node, added one by one
      power += (state.previous_contact_force.component(c)[node] + state.contact_force.component(c)[node] -
                2.0 * state.load_force.component(c)[node]) *
               state.velocity.component(c)[node];
  }
  if (d != nullptr) power = reduce_contact_figures(contact, d->contact, power);
  state.contact_energy -= 0.5 * dt * power;
  // A moving wall puts work in, W = integral F.V dt (F its force on the bodies): that is
  // external work, and the contact energy is the work against the wall's force in its
  // own frame, -integral F.(v - V) dt (the same total, split as the balance reads).
  for (const RigidWall& wall : contact.walls) {
    const double work =
        0.5 * dt * contact::dot(wall.state.previous_force + wall.state.force, wall.plane.velocity);
    state.contact_energy += work;
    state.wall_work += work;
  }
}

}  // namespace

void follow_erosion(ContactModel& contact, const Model& model, Decomposition& d) {
  if (d.comm.distributed())
    open_eroded_shares(contact, d.contact, model, d.global_element, d.global_elements);
  else
    open_eroded_faces(contact, model);
}

void compute_contact_forces(const Model& model, ContactModel& contact, Decomposition& d, State& state,
                            double dt) {
  begin_contact_forces(contact, state);
  if (d.comm.distributed()) {
    run_distributed_contact(contact, d.contact, model, d.global_node, state.displacement, state.velocity,
                            state.time, state.contact_force, state.gap);
    finish_contact_forces(contact, state, dt, &d);
  } else {
    run_contact_passes(model, contact, state);
    finish_contact_forces(contact, state, dt, nullptr);
  }
}

// W += dt sum m_i g_i.v_i^{n-1/2} over the counted (on many ranks: owned) nodes, in
// chunk order (the same on any number of threads).
void add_load_work(const Model& model, State& state, double dt) {
  const std::vector<double>& mass = model.counted_mass.empty() ? model.mass : model.counted_mass;
  for_each_chunk(model.mesh.node_count(), [&](std::size_t begin, std::size_t end, std::size_t k) {
    double power = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double* g = model.load_acceleration.component(c).data();
      const double* v = state.velocity.component(c).data();
      for (std::size_t i = begin; i < end; ++i) power += mass[i] * g[i] * v[i];
    }
    state.partial[0][k] = power;
  });
  state.external_work += dt * ordered_sum(state.partial[0]);
}

void add_boundary_reactions(const Model& model, const Decomposition& d, State& state, double dt) {
  const std::size_t conditions = model.boundary.size();
  state.previous_reaction.assign(conditions, {0.0, 0.0, 0.0});  // R^{n-1}, compensated
  for (std::size_t b = 0; b < state.reaction.size(); ++b)
    for (std::size_t c = 0; c < 3; ++c)
      state.previous_reaction[b][c] = state.reaction[b][c] + state.reaction_error[b][c];
  state.reaction.assign(conditions, {0.0, 0.0, 0.0});
  state.reaction_error.assign(conditions, {0.0, 0.0, 0.0});
  double work = 0.0;
  for (std::size_t b = 0; b < conditions; ++b) {
    const BoundaryNodes& condition = model.boundary[b];
    for (int c = 0; c < 3; ++c) {
      const double* f_int = state.internal_force.component(c).data();
      const double* f_ext = state.contact_force.component(c).data();
      double sum = 0.0, error = 0.0;
      for (const std::uint32_t node : condition.nodes[std::size_t(c)])
        if (d.owned.empty() || d.owned[node] != 0) add_compensated(sum, error, f_int[node] - f_ext[node]);
      state.reaction[b][std::size_t(c)] = sum;
      state.reaction_error[b][std::size_t(c)] = error;
      work += 0.5 * dt * (state.previous_reaction[b][std::size_t(c)] + (sum + error)) *
              condition.velocity[std::size_t(c)];
    }
  }
  state.external_work += work;
}

// f_int (compute_internal_forces) and the contact forces (compute_contact_forces) of
// step n, side by side on the threads. The two are independent: the element pass reads
// u^n and writes f_int and the stresses, the contact pass reads u^n and v^{n-1/2} and
// writes f_contact, the gaps and its own state. So the contact pass runs as one task
// (its loops on one thread) while the team runs the element chunks as tasks, and
// whoever is free takes the next chunk. On a small model the serial parts of the
// contact pass (the bucket rebuild, the scatter) are then hidden behind element work,
// and there is one parallel region where there were one per colour and per contact
// loop (docs/performance.md, "Two threads"). The same operations in the same order
// on every array: the same bits as the passes one after the other.
// element_seconds: the element pass's own time is added to it (its task's, from start
// to end); the contact pass times itself (pair.seconds), so the phases of the run
// summary overlap in this mode.
element::ElementEnergies compute_forces_side_by_side(const Model& model, ContactModel& contact, State& state,
                                                     double dt, bool with_stress, double& element_seconds) {
  clear_internal_force(state);
  begin_contact_forces(contact, state);
  std::vector<element::ElementEnergies>& block_energies = state.block_energies;
  block_energies.resize(model.blocks.size());
  double* stress = with_stress ? state.stress.data() : nullptr;

  // Two tasks: the element pass, which makes a task of each chunk and waits for each
  // colour's, and the contact pass. Each thread takes one; the element chunks are
  // taken by whichever thread is free, so the thread that finishes the contact pass
  // goes on with them.
#pragma omp parallel
#pragma omp single
  {
#pragma omp task shared(model, state, block_energies, element_seconds)
    {
      const ScopedTimer timer(element_seconds);
      for (std::size_t b = 0; b < model.blocks.size(); ++b)
        block_energies[b] = element::add_internal_forces_as_tasks(model.blocks[b], state.displacement,
                                                                  state.internal_force, stress);
    }
#pragma omp task shared(model, contact, state)
    run_contact_passes(model, contact, state);
  }  // the barrier: every task is done
  finish_contact_forces(contact, state, dt, nullptr);
  internal_force_computed(state, with_stress);
  element::ElementEnergies total;
  for (const element::ElementEnergies& e : block_energies) total += e;
  return total;
}

// The figures of all pairs together (the run's), from each pair's.
contact::ContactStatistics total_statistics(const ContactModel& contact) {
  contact::ContactStatistics total;
  std::vector<const contact::ContactStatistics*> all;
  for (const auto& pair : contact.pairs) all.push_back(&pair.statistics);
  for (const auto& wall : contact.walls) all.push_back(&wall.statistics);
  for (const contact::ContactStatistics* each : all) {
    const contact::ContactStatistics& s = *each;
    total.projections += s.projections;
    total.iterations += s.iterations;
    total.max_iterations = std::max(total.max_iterations, s.max_iterations);
    total.not_converged += s.not_converged;
    total.saddle_points += s.saddle_points;
    total.fallbacks += s.fallbacks;
    if (s.max_penetration_over_h > total.max_penetration_over_h) {
      total.max_penetration_over_h = s.max_penetration_over_h;
      total.deepest_node = s.deepest_node;
    }
    total.max_pair_stiffness = std::max(total.max_pair_stiffness, s.max_pair_stiffness);
  }
  return total;
}

// This step's row of each pair's history.
std::vector<output::ContactHistoryRow> contact_history(const ContactModel& contact) {
  std::vector<output::ContactHistoryRow> rows;
  rows.reserve(contact.pairs.size());
  for (const auto& pair : contact.pairs) {
    const contact::Vec3 f = pair.slave_force();
    rows.push_back({{f.x, f.y, f.z},
                    pair.max_penetration(),
                    contact::norm(pair.normal_force()),
                    contact::norm(pair.tangential_force()),
                    pair.normal_force_sum(),
                    pair.tangential_force_sum()});
  }
  return rows;
}

std::vector<output::WallHistoryRow> wall_history(const ContactModel& contact) {
  std::vector<output::WallHistoryRow> rows;
  rows.reserve(contact.walls.size());
  for (const auto& wall : contact.walls) {
    const contact::Vec3 f = wall.state.force;
    rows.push_back({{f.x, f.y, f.z}});
  }
  return rows;
}

// a^n = (f_contact - f_int) / m, 0 on fixed components: the accelerations alone (to
// step back to the last finite state). False when some a is not finite.
bool compute_accelerations(const Model& model, State& state) {
  for_each_chunk(model.mesh.node_count(), [&](std::size_t begin, std::size_t end, std::size_t k) {
    double non_finite = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double* f = state.internal_force.component(c).data();
      const double* f_contact = state.contact_force.component(c).data();
      double* a = state.acceleration.component(c).data();
      const double* inverse_mass = model.inverse_mass.data();
      for (std::size_t i = begin; i < end; ++i) {
        a[i] = (f_contact[i] - f[i]) * inverse_mass[i];
        non_finite += 0.0 * a[i];
      }
    }
    state.partial[0][k] = non_finite;
  });
  apply_fixed_components(model, state.acceleration);
  return ordered_sum(state.partial[0]) == 0.0;
}

// The velocity update of central differences, in one pass over the nodes
// (docs/performance.md, "The nodal update"): per node and component
//   a^n = (f_contact - f_int) / m, 0 where the component is fixed,
//   v^{n+1/2} = v^{n-1/2} + dt a^n (at step 0 from v^{-1/2} = v^0 - dt/2 a^0),
// in place, with the energy sums, each per chunk of nodes and added in chunk order (the
// same bits on any number of threads); f_int is set to 0 behind the read unless the
// step is written (keep_internal_force: the output recomputes a^n from it). u^n stays
// for the guards and the output; update_positions makes u^{n+1} at the step's end.
// A component whose a^n is not finite keeps v^{n-1/2} (step_back_and_stop).
// The passes are the versions of the selected ISA (nodal_update.hpp): packs of nodes,
// one partial sum per lane.
NodalUpdate update_velocities(const Model& model, State& state, double dt, bool first_step,
                              bool keep_internal_force, const NodalUpdateFns& passes) {
  NodalArrays arrays;
  for (std::size_t c = 0; c < 3; ++c) {
    const int component = static_cast<int>(c);
    arrays.internal_force[c] = state.internal_force.component(component).data();
    arrays.contact_force[c] = state.contact_force.component(component).data();
    arrays.flags[c] = state.flags[c].data();
    arrays.velocity[c] = state.velocity.component(component).data();
  }
  // The energy sums count each node once: on many ranks only the owned nodes' mass.
  arrays.mass = model.counted_mass.empty() ? model.mass.data() : model.counted_mass.data();
  arrays.inverse_mass = model.inverse_mass.data();
  for_each_chunk(model.mesh.node_count(), [&](std::size_t begin, std::size_t end, std::size_t k) {
    const NodalSums sums = passes.velocity(arrays, begin, end, dt, first_step, !keep_internal_force);
    state.partial[0][k] = sums.non_finite;
    state.partial[1][k] = sums.twice_kinetic;
    state.partial[2][k] = sums.mass_acceleration_squared;
    state.partial[3][k] = sums.largest_component;
    state.partial[4][k] = sums.old_power;
    state.partial[5][k] = sums.new_power;
  });
  if (!keep_internal_force) state.internal_force_zero = true, state.force_step = -1;
  NodalUpdate update;
  update.finite = ordered_sum(state.partial[0]) == 0.0;
  if (!update.finite) return update;
  update.kinetic = 0.5 * ordered_sum(state.partial[1]);
  update.mass_acceleration_squared = 0.125 * ordered_sum(state.partial[2]);
  update.largest_component = *std::max_element(state.partial[3].begin(), state.partial[3].end());
  update.old_power = ordered_sum(state.partial[4]);
  update.new_power = ordered_sum(state.partial[5]);
  return update;
}

// u^{n+1} = u^n + dt v^{n+1/2}, in place: the last thing of step n.
void update_positions(State& state, double dt, const NodalUpdateFns& passes) {
  std::array<double*, 3> u;
  std::array<const double*, 3> v;
  for (int c = 0; c < 3; ++c) {
    u[std::size_t(c)] = state.displacement.component(c).data();
    v[std::size_t(c)] = state.velocity.component(c).data();
  }
  for_each_chunk(state.displacement.size(), [&](std::size_t begin, std::size_t end, std::size_t) {
    passes.position(u, v, begin, end, dt);
  });
}

// y += scale x, componentwise over the nodes: u^{n+1} = u^n + dt v^{n+1/2};
// v^{-1/2} = v^0 - dt/2 a^0 at the start; v^{n-1/2} = v^{n+1/2} - dt a^n to step back.
void add_scaled(NodalVectors& y, double scale, const NodalVectors& x) {
  for_each_chunk(y.size(), [&](std::size_t begin, std::size_t end, std::size_t) {
    for (int c = 0; c < 3; ++c) {
      double* out = y.component(c).data();
      const double* in = x.component(c).data();
      for (std::size_t i = begin; i < end; ++i) out[i] += scale * in[i];
    }
  });
}

void gather_plastic_strain(const Model& model, State& state) {
  for (const element::ElementBlock& block : model.blocks) {
    std::copy(block.material_state.plastic_strain.begin(), block.material_state.plastic_strain.end(),
              state.plastic_strain.begin() + block.first_element);
    const element::ElementFailure& f = block.failure;
    for (std::size_t e = 0; e < f.status.size() && !state.status.empty(); ++e) {
      state.damage[block.first_element + e] = f.damage[e];
      state.status[block.first_element + e] = f.status[e] == element::ElementStatus::alive ? 1.0 : 0.0;
    }
  }
}

void erode_distorted_elements(const Model& model, const input::TimeOptions& time, double first_dt) {
  if (!time.erode) return;
  const double erode_step = time.min_dt_ratio * first_dt / time.courant;  // s
  for (const element::ElementBlock& block : model.blocks) {
    if (block.failure.status.empty()) continue;
    block.failure.erode_step = erode_step;
    block.failure.distorted.assign(block.count, 0);
    block.failure.held.assign(
        std::size_t(block.count) * element::ElementFailure::held_size(block.nodes_per_element),
        std::numeric_limits<double>::quiet_NaN());
  }
}

}  // namespace exdyn::solver
