// The time loop: central differences with a lumped mass matrix.
//
//   a^n       = M^-1 (f_contact(x^n, v^{n-1/2}) - f_int(u^n))   (fixed components: a = 0)
//   v^{n+1/2} = v^{n-1/2} + dt a^n                      (v^{-1/2} = v^0 - dt/2 a^0)
//   u^{n+1}   = u^n + dt v^{n+1/2}
//
// Energy at step n (docs/theory.md, "Energy"): internal energy from u^n, kinetic
// energy from the two half-step velocities around n, K^n = 1/2 sum m v^{n-1/2}.v^{n+1/2},
// the form that the central-difference scheme conserves exactly for a linear
// elastic model, so the energy balance checks the forces and the mass to round-off.
#include "solver/simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

#include "common/errors.hpp"
#include "common/isa.hpp"
#include "common/mpi.hpp"
#include "common/parallel.hpp"
#include "common/timer.hpp"
#include "common/version.hpp"
#include "output/result_writer.hpp"
#include "solver/contact_setup.hpp"
#include "solver/decomposition.hpp"
#include "solver/model.hpp"
#include "solver/nodal_update.hpp"

namespace exdyn::solver {

namespace {

struct State {
  long step = 0;
  double time = 0.0;
  NodalVectors displacement;  // u^n, m; u^{n+1} at the step's end (update_positions)
  NodalVectors velocity;      // v^{n-1/2}, then v^{n+1/2} after update_velocities, m/s
  std::array<std::vector<std::uint8_t>, 3>
      flags;  // per component: fixed_flag | contact_flag (nodal_update.hpp)
  NodalVectors
      acceleration;  // a^n, m/s^2, computed when needed (output, a non-finite step: compute_accelerations)
  NodalVectors internal_force;                 // f_int(u^n), N; 0 after update_velocities (see below)
  NodalVectors contact_force;                  // f_contact(x^n), N
  NodalVectors previous_contact_force;         // f_contact(x^{n-1}), N (for the contact work)
  std::vector<double> gap;                     // signed normal gap of each slave node, m (0: no candidate)
  std::vector<double> previous_gap;            // the gap of step n-1 (to step back after a non-finite step)
  std::vector<double> stress;                  // 6 per element: xx yy zz xy yz xz, Pa
  long stress_step = -1;                       // the step whose stresses `stress` holds (see below)
  long force_step = -1;                        // the step whose f_int `internal_force` holds, -1: none
  bool internal_force_zero = true;             // internal_force is all 0 (update_velocities zeroed it)
  double contact_energy = 0.0;                 // work done against the contact forces, J
  std::array<std::vector<double>, 4> partial;  // per-chunk sums of the nodal loops (parallel.hpp)
  std::vector<element::ElementEnergies> block_energies;  // per block, scratch of compute_forces_side_by_side
};

struct Energies {
  double kinetic = 0.0;
  double internal = 0.0;
  double hourglass = 0.0;
  double contact = 0.0;
  double external_work = 0.0;
  double total() const { return kinetic + internal + hourglass + contact - external_work; }
};

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
      total.strain += e.strain;
      total.hourglass += e.hourglass;
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

// The contact pass of every pair at x^n = x_ref + u^n with v^{n-1/2}; then the
// work done against the contact forces (trapezoidal rule):
//   E_c^n = E_c^{n-1} - 1/2 (f_c^{n-1} + f_c^n).(u^n - u^{n-1}),  u^n - u^{n-1} = dt v^{n-1/2}.
void begin_contact_forces(ContactModel& contact, State& state) {
  std::swap(state.contact_force, state.previous_contact_force);
  for (std::uint32_t node : contact.nodes) {
    state.contact_force.x[node] = state.contact_force.y[node] = state.contact_force.z[node] = 0.0;
    state.previous_gap[node] = state.gap[node];
    state.gap[node] = std::numeric_limits<double>::infinity();
  }
}

void run_contact_passes(const Model& model, ContactModel& contact, State& state) {
  for (auto& pair : contact.pairs) {
    for (std::size_t p = 0; p < pair.passes.size(); ++p)
      contact::run_contact_pass(pair.passes[p], pair.settings, pair.states[p], model.mesh.x_ref,
                                state.displacement, state.velocity, model.mass, state.contact_force,
                                state.gap, pair.statistics, pair.seconds);
    pair.max_force = std::max(pair.max_force, contact::norm(pair.slave_force()));
  }
}

void finish_contact_forces(ContactModel& contact, State& state, double dt) {
  double power = 0.0;  // (f_c^{n-1} + f_c^n).v^{n-1/2}, W x 2
  for (std::uint32_t node : contact.nodes) {
    if (state.gap[node] == std::numeric_limits<double>::infinity()) state.gap[node] = 0.0;  // no candidate
    power += (state.previous_contact_force.x[node] + state.contact_force.x[node]) * state.velocity.x[node] +
             (state.previous_contact_force.y[node] + state.contact_force.y[node]) * state.velocity.y[node] +
             (state.previous_contact_force.z[node] + state.contact_force.z[node]) * state.velocity.z[node];
  }
  state.contact_energy -= 0.5 * dt * power;
}

void compute_contact_forces(const Model& model, ContactModel& contact, State& state, double dt) {
  begin_contact_forces(contact, state);
  run_contact_passes(model, contact, state);
  finish_contact_forces(contact, state, dt);
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
  finish_contact_forces(contact, state, dt);
  internal_force_computed(state, with_stress);
  element::ElementEnergies total;
  for (const element::ElementEnergies& e : block_energies) {
    total.strain += e.strain;
    total.hourglass += e.hourglass;
  }
  return total;
}

// The figures of all pairs together (the run's), from each pair's.
contact::ContactStatistics total_statistics(const ContactModel& contact) {
  contact::ContactStatistics total;
  for (const auto& pair : contact.pairs) {
    const contact::ContactStatistics& s = pair.statistics;
    total.projections += s.projections;
    total.iterations += s.iterations;
    total.max_iterations = std::max(total.max_iterations, s.max_iterations);
    total.not_converged += s.not_converged;
    total.saddle_points += s.saddle_points;
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
    rows.push_back({{f.x, f.y, f.z}, pair.max_penetration()});
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

struct NodalUpdate {
  bool finite = true;    // every a^n finite (else the components where it is not keep v^{n-1/2})
  double kinetic = 0.0;  // K^n = 1/2 sum m v^{n-1/2}.v^{n+1/2}, J
  // 1/8 sum m |a^n|^2, J/s^2: dt^2 times it turns K^n into 1/2 sum m |v^n|^2 with
  // v^n = (v^{n-1/2} + v^{n+1/2}) / 2, which is never negative (K^n can be: in an
  // unstable run K^n + U^n stays constant while both grow without bound).
  double mass_acceleration_squared = 0.0;
  double largest_component = 0;  // max |v^{n+1/2}| over nodes and components, m/s
};

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
  });
  if (!keep_internal_force) state.internal_force_zero = true, state.force_step = -1;
  NodalUpdate update;
  update.finite = ordered_sum(state.partial[0]) == 0.0;
  if (!update.finite) return update;
  update.kinetic = 0.5 * ordered_sum(state.partial[1]);
  update.mass_acceleration_squared = 0.125 * ordered_sum(state.partial[2]);
  update.largest_component = *std::max_element(state.partial[3].begin(), state.partial[3].end());
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

// The node with the largest |v|_1 (m/s): where an instability grows fastest. On
// many ranks the fastest of every rank's owned nodes (ties: the lowest node).
std::string describe_fastest_node(const Decomposition& d, const NodalVectors& velocity) {
  std::size_t fastest = 0;
  double largest = -1.0;
  for (std::size_t i = 0; i < velocity.size(); ++i) {
    if (!d.owned.empty() && d.owned[i] == 0) continue;
    const double speed = std::abs(velocity.x[i]) + std::abs(velocity.y[i]) + std::abs(velocity.z[i]);
    if (speed > largest) largest = speed, fastest = i;
  }
  const double mine[2] = {largest, double(global_node_id(d, static_cast<std::uint32_t>(fastest)))};
  const std::vector<double> all = mpi::all_gather(d.comm, mine, 2);
  double node = all[1];
  largest = all[0];
  for (std::size_t r = 1; r < all.size() / 2; ++r)
    if (all[2 * r] > largest || (all[2 * r] == largest && all[2 * r + 1] < node))
      largest = all[2 * r], node = all[2 * r + 1];
  char text[96];
  std::snprintf(text, sizeof text, "the fastest node is %.0f, |v|_1 = %.3g m/s", node, largest);
  return text;
}

// Names the first node with a non-finite acceleration, velocity or displacement,
// else the first element with a non-finite stress, else the fastest node. Every
// rank calls it; the message is that of the lowest rank that found one.
std::string describe_non_finite(const Model& model, Decomposition& d, State& state) {
  forces_of_this_step(model, d, state);
  compute_accelerations(model, state);
  const std::pair<const char*, const NodalVectors*> fields[] = {{"acceleration", &state.acceleration},
                                                                {"velocity", &state.velocity},
                                                                {"displacement", &state.displacement}};
  std::string found;
  for (const auto& [label, field] : fields) {
    for (int c = 0; c < 3 && found.empty(); ++c) {
      const auto& values = field->component(c);
      for (std::size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i])) {
          found = std::string("non-finite ") + label + " at node " +
                  std::to_string(global_node_id(d, static_cast<std::uint32_t>(i))) + " (component " +
                  "xyz"[c] + ")";
          break;
        }
    }
    if (!found.empty()) break;
  }
  for (std::size_t k = 0; k < state.stress.size() && found.empty(); ++k)
    if (!std::isfinite(state.stress[k]))
      found = "non-finite stress in element " +
              std::to_string(global_element_id(d, static_cast<std::uint32_t>(k / 6))) + " (component " +
              std::to_string(k % 6) + " of xx yy zz xy yz xz)";
  found = mpi::first_message(d.comm, found);
  if (!found.empty()) return found;
  return "non-finite energy (" + describe_fastest_node(d, state.velocity) + ")";
}

std::string format_time(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g s", seconds);
  return text;
}

std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

// Writes the fields of step n: v^n = v^{n+1/2} - dt/2 a^n (the velocity update is done).
// On many ranks every rank calls it: the owners' values travel to the ranks that
// write their rows (decomposition.hpp, rows_of), which write them together.
class StepWriter {
 public:
  StepWriter(output::ResultWriter& writer, const Model& model, Decomposition& d)
      : writer_(writer), model_(model), d_(d) {
    velocity_.resize(model.mesh.node_count());
    von_mises_.resize(model.mesh.element_count());
  }
  void write(State& state, double dt) {
    forces_of_this_step(model_, d_, state);  // f_int and sigma at u^n
    compute_accelerations(model_, state);    // a^n: the nodal update does not store it
    for_each_chunk(velocity_.size(), [&](std::size_t begin, std::size_t end, std::size_t) {
      for (int c = 0; c < 3; ++c) {
        const double* v = state.velocity.component(c).data();
        const double* a = state.acceleration.component(c).data();
        double* out = velocity_.component(c).data();
        for (std::size_t i = begin; i < end; ++i) out[i] = v[i] - 0.5 * dt * a[i];
      }
    });
    for_each_chunk(von_mises_.size(), [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t e = begin; e < end; ++e) {
        material::SymTensor s;
        std::copy_n(state.stress.data() + 6 * e, 6, s.begin());
        von_mises_[e] = material::von_mises(s);
      }
    });
    output::StepData data;
    data.step = state.step;
    data.time = state.time;
    if (!d_.comm.distributed()) {
      data.displacement = &state.displacement;
      data.velocity = &velocity_;
      data.acceleration = &state.acceleration;
      data.contact_force = &state.contact_force;
      data.gap = state.gap.data();
      data.stress = state.stress.data();
      data.von_mises = von_mises_.data();
    } else {
      const std::pair<const NodalVectors*, NodalVectors*> vectors[] = {{&state.displacement, &rows_[0]},
                                                                       {&velocity_, &rows_[1]},
                                                                       {&state.acceleration, &rows_[2]},
                                                                       {&state.contact_force, &rows_[3]}};
      for (const auto& [local, rows] : vectors) rows_of(d_, *local, *rows);
      rows_of(d_, state.gap.data(), 1, true, gap_rows_);
      rows_of(d_, state.stress.data(), 6, false, stress_rows_);
      rows_of(d_, von_mises_.data(), 1, false, von_mises_rows_);
      data.displacement = &rows_[0];
      data.velocity = &rows_[1];
      data.acceleration = &rows_[2];
      data.contact_force = &rows_[3];
      data.gap = gap_rows_.data();
      data.stress = stress_rows_.data();
      data.von_mises = von_mises_rows_.data();
    }
    writer_.write_step(data);
  }

 private:
  output::ResultWriter& writer_;
  const Model& model_;
  Decomposition& d_;
  NodalVectors velocity_;
  std::vector<double> von_mises_;
  std::array<NodalVectors, 4> rows_;  // many ranks: this rank's rows of u, v, a, f_contact
  std::vector<double> gap_rows_, stress_rows_, von_mises_rows_;
};

output::ContactFigures contact_figures(const contact::ContactStatistics& statistics) {
  output::ContactFigures c;
  c.projections = statistics.projections;
  c.mean_iterations = statistics.projections > 0 ? static_cast<double>(statistics.iterations) /
                                                       static_cast<double>(statistics.projections)
                                                 : 0.0;
  c.max_iterations = statistics.max_iterations;
  c.not_converged = statistics.not_converged;
  c.saddle_points = statistics.saddle_points;
  c.max_penetration_over_h = statistics.max_penetration_over_h;
  c.penalty_stiffness = statistics.max_pair_stiffness;
  return c;
}

void summarise_contact(const ContactModel& contact, const contact::ContactStatistics& statistics,
                       output::RunSummary& summary) {
  static_cast<output::ContactFigures&>(summary.contact) = contact_figures(statistics);
  summary.contact.pairs.resize(contact.pairs.size());
  double global_search = 0.0, local_search = 0.0, forces = 0.0;
  for (std::size_t k = 0; k < contact.pairs.size(); ++k) {
    const ContactPair& pair = contact.pairs[k];
    output::ContactPairSummary& out = summary.contact.pairs[k];
    out.name = pair.name;
    out.slave_points = input::name(pair.slave_points);
    out.method = std::string(contact::name(pair.settings.projection.method));
    out.figures = contact_figures(pair.statistics);
    out.local_search_seconds = pair.seconds.local_search;
    out.max_force = pair.max_force;
    global_search += pair.seconds.global_search;
    local_search += pair.seconds.local_search;
    forces += pair.seconds.forces;
  }
  summary.phase_seconds.contact_global_search = global_search;
  summary.phase_seconds.contact_local_search = local_search;
  summary.phase_seconds.contact_forces = forces;
}

// The figures of a step summed over the ranks, in rank order (the same bits on every
// rank, so all take the same decisions): the nodal update's sums, the element
// energies (in `energy`) and the stop signal any rank has seen. Identity on one rank.
NodalUpdate reduce_over_ranks(const mpi::Communicator& comm, NodalUpdate update, Energies& energy,
                              const volatile std::sig_atomic_t* stop_signal, int& stop_requested) {
  const int signal = stop_signal != nullptr ? int(*stop_signal) : 0;
  if (!comm.distributed()) {
    stop_requested = signal;
    return update;
  }
  const double mine[7] = {update.finite ? 0.0 : 1.0,
                          update.kinetic,
                          update.mass_acceleration_squared,
                          update.largest_component,
                          energy.internal,
                          energy.hourglass,
                          double(signal)};
  const std::vector<double> all = mpi::all_gather(comm, mine, 7);
  NodalUpdate total;
  total.finite = all[0] == 0.0;
  total.kinetic = all[1];
  total.mass_acceleration_squared = all[2];
  total.largest_component = all[3];
  energy.internal = all[4];
  energy.hourglass = all[5];
  stop_requested = int(all[6]);
  for (std::size_t r = 1; r < std::size_t(comm.size); ++r) {
    const double* f = all.data() + 7 * r;
    total.finite = total.finite && f[0] == 0.0;
    total.kinetic += f[1];
    total.mass_acceleration_squared += f[2];
    total.largest_component = std::max(total.largest_component, f[3]);
    energy.internal += f[4];
    energy.hourglass += f[5];
    stop_requested = std::max(stop_requested, int(f[6]));
  }
  return total;
}

// The exchanges' figures of all ranks (summary mpi: sums, and the longest wait).
void summarise_ranks(const Decomposition& d, output::MpiSummary& out) {
  if (!d.comm.distributed()) return;
  const HaloFigures h = halo_figures(d);
  const double mine[4] = {double(h.shared_nodes), double(h.messages_sent), double(h.bytes_sent),
                          d.exchange_seconds};
  const std::vector<double> all = mpi::all_gather(d.comm, mine, 4);
  for (std::size_t r = 0; r < all.size() / 4; ++r) {
    out.shared_nodes += long(all[4 * r]);
    out.messages_per_step += long(all[4 * r + 1]);
    out.bytes_per_step += all[4 * r + 2];
    out.exchange_seconds = std::max(out.exchange_seconds, all[4 * r + 3]);
  }
  out.contact_nodes = long(d.contact_received.size());
}

}  // namespace

output::RunSummary run_simulation(const input::Deck& deck, const RunControls& controls) {
  Stopwatch total_watch;
  output::RunSummary summary;
  summary.name = deck.name;
  summary.exdyn_version = exdyn::version;
  summary.threads = set_threads(controls.threads);
  summary.isa = isa_name(selected_isa());
  summary.end_time = deck.time.end_time;

  // On many ranks every rank builds the whole model, cuts out its part (with every
  // contact node) and keeps only that (decomposition.hpp). The stable step comes from
  // the whole model on every rank: the 20-node rule takes one element per group of
  // equal Jacobians, the group's first in the whole block, so a rank's part could
  // give another last bit (docs/parallel.md).
  const mpi::Communicator& comm = controls.comm;
  summary.ranks = comm.size;
  Model model = build_model(deck);
  NodalVectors initial_v = initial_velocity(deck, model);
  LocalRun local;
  if (comm.distributed()) local = localize(model, contact_face_nodes(deck, model.mesh), initial_v, comm);
  const double critical_dt = critical_time_step(model);
  const TimeStepping stepping = time_stepping(deck.time, critical_dt);
  const double dt = stepping.dt;
  ContactModel contact = build_contact(deck, model, dt, critical_dt);
  summary.nodes = static_cast<long>(model.mesh.node_count());
  summary.elements = static_cast<long>(model.mesh.element_count());
  summary.dt = dt;

  const std::string directory =
      controls.output_directory.empty() ? deck.output.directory : controls.output_directory;
  std::vector<std::uint8_t> element_nodes(model.mesh.element_count());
  for (std::size_t e = 0; e < element_nodes.size(); ++e)
    element_nodes[e] = static_cast<std::uint8_t>(model.mesh.nodes_of(e));
  std::vector<std::string> pair_names;
  for (const auto& pair : contact.pairs) pair_names.push_back(pair.name);
  output::Distribution distribution;
  if (comm.distributed()) {
    distribution.comm = comm;
    distribution.node_begin = local.decomposition.node_rows.begin;
    distribution.node_end = local.decomposition.node_rows.end;
    distribution.element_begin = local.decomposition.element_rows.begin;
    distribution.element_end = local.decomposition.element_rows.end;
  }
  output::ResultWriter writer(
      directory, deck.name,
      output::MeshView{&model.mesh.x_ref, &model.mesh.connectivity, &model.mesh.element_part, &element_nodes},
      deck.output.fields, pair_names,
      // steps 0, every, 2 every, ..., the last, and one more a stop may write
      static_cast<std::size_t>(stepping.steps / std::max(deck.output.every, 1) + 3), distribution);
  writer.write_in_background(deck.output.background);
  const std::string summary_path = (std::filesystem::path(directory) / (deck.name + ".json")).string();
  // Only the root rank writes the summary (the figures are the same on every rank).
  const auto write_summary = [&] {
    if (comm.root()) output::write_summary(summary_path, summary);
  };
  // From here on this rank's part only.
  Decomposition& decomposition = local.decomposition;
  decomposition.comm = comm;
  if (comm.distributed()) {
    contact = localize_contact(contact, decomposition);
    for (ContactPair& pair : contact.pairs) pair.settings.share = share_projections(decomposition);
    model = std::move(local.model);
    initial_v = std::move(local.initial_velocity);
  }

  State state;
  const std::size_t node_count = model.mesh.node_count();
  state.displacement.resize(node_count);
  for (std::size_t c = 0; c < 3; ++c) {
    state.flags[c].assign(node_count, 0);
    for (const std::uint32_t node : model.fixed_nodes[c]) state.flags[c][node] |= fixed_flag;
    for (const std::uint32_t node : contact.nodes) state.flags[c][node] |= contact_flag;
  }
  state.acceleration.resize(node_count);
  state.internal_force.resize(node_count);
  state.contact_force.resize(node_count);
  state.previous_contact_force.resize(node_count);
  state.gap.assign(node_count, 0.0);
  state.previous_gap.assign(node_count, 0.0);
  state.stress.assign(6 * model.mesh.element_count(), 0.0);
  state.velocity = std::move(initial_v);
  for (auto& p : state.partial) p.assign(chunk_count(node_count), 0.0);
  StepWriter step_writer(writer, model, decomposition);
  const NodalUpdateFns nodal_update = nodal_update_for(selected_isa());  // the element blocks' ISA
  // The element and contact passes side by side, as tasks (compute_forces_side_by_side),
  // where the element pass runs on the threads anyway (a colour of more than one chunk):
  // then one parallel region replaces several. A small model keeps its passes without
  // a region, whose barrier can cost milliseconds when another process holds a core
  // (docs/performance.md, "Threads").
  const bool element_pass_threaded =
      std::any_of(model.blocks.begin(), model.blocks.end(), [](const auto& block) {
        return std::any_of(block.colours.begin(), block.colours.end(),
                           [](const auto& colour) { return colour.size() > 1; });
      });
  // (On many ranks the element pass talks to other ranks between its colours, from
  // the main thread: not as tasks.)
  const bool side_by_side =
      !contact.pairs.empty() && max_threads() > 1 && element_pass_threaded && !comm.distributed();

  output::PhaseSeconds& phase = summary.phase_seconds;
  contact::ContactStatistics contact_statistics;  // all pairs together, updated every step
  Stopwatch loop_watch;
  double last_progress = -1.0;
  double initial_total = 0.0, largest_energy = 0.0, max_energy_error = 0.0;
  long last_written = -1;  // the last step written to NAME.h5
  // The inversion guard runs its element pass only when some element could have
  // inverted: when the nodes may have moved (bound: sum of dt max|v|) as far as the
  // safety radius of the last configuration checked (element_block.hpp). A stable
  // run checks rarely (the plate case: once in about 4600 steps), a blowing-up one
  // every step.
  // The energy guard watches E_mean^n = 1/2 sum m |v^n|^2 + U^n + H^n + contact - work:
  // bounded in a stable run, exponential in an unstable one (docs/stability.md).
  double initial_mean_energy = 0.0, largest_mean_energy = 0.0, mean_energy = 0.0;
  double moved_since_check = std::numeric_limits<double>::infinity(), safety_radius = 0.0,
         largest_speed = 0.0;
  Energies energy;
  int stop_requested = 0;  // the signal a rank has seen (SIGINT, SIGTERM), agreed by all every step

  // "..., at step n, time t s"
  const auto when = [&] {
    return " at step " + std::to_string(state.step) + ", time " + format_time(state.time);
  };
  // Writes the current step (if it is not written yet) as the final output step and
  // stops the run: the catch below writes the summary with status "failed".
  const auto stop_run = [&](const std::string& message) {
    ScopedTimer timer(phase.output);
    if (state.step > last_written) {
      writer.add_history({state.time, energy.kinetic, energy.internal, energy.contact, energy.hourglass,
                          energy.external_work, energy.total()},
                         contact_history(contact));
      step_writer.write(state, dt);
      last_written = state.step;
    }
    throw RunFailure(message, state.step, state.time);
  };
  // Step n produced a non-finite value: go back to step n-1, the last finite state,
  // from u^{n-1} = u^n - dt v^{n-1/2}, with that step's contact forces and gaps, and
  // stop there. The velocity update has made v^{n+1/2} = v^{n-1/2} + dt a^n in place
  // wherever a^n is finite (and left v^{n-1/2} where it is not): v^{n-1/2} is taken
  // back as v^{n+1/2} - dt a^n, to round-off (state.acceleration holds a^n:
  // describe_non_finite computed it).
  const auto step_back_and_stop = [&](const std::string& message) {
    if (state.step == 0) throw RunFailure(message, state.step, state.time);
    for_each_chunk(node_count, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (int c = 0; c < 3; ++c) {
        double* v = state.velocity.component(c).data();
        const double* a = state.acceleration.component(c).data();
        for (std::size_t i = begin; i < end; ++i)
          if (std::isfinite(a[i])) v[i] -= dt * a[i];
      }
    });
    add_scaled(state.displacement, -dt, state.velocity);  // u^{n-1} = u^n - dt v^{n-1/2}
    compute_internal_forces(model, decomposition, state, true);
    std::swap(state.contact_force, state.previous_contact_force);
    std::swap(state.gap, state.previous_gap);
    compute_accelerations(model, state);
    --state.step;
    state.stress_step = state.force_step = state.step;  // computed above, at u^{n-1}
    state.time = static_cast<double>(state.step) * dt;
    stop_run(message + " (the last finite state, step " + std::to_string(state.step) + ", is written)");
  };

  try {
    for (state.step = 0;; ++state.step) {
      state.time = static_cast<double>(state.step) * dt;
      energy = Energies{};
      // A step written: its element pass keeps the stresses and the velocity update keeps
      // f_int for the output (the guards may still write another step:
      // forces_of_this_step).
      const bool output_step = state.step % deck.output.every == 0 || state.step == stepping.steps;
      if (side_by_side) {  // each pass times itself: the two phases overlap
        const element::ElementEnergies element_energy =
            compute_forces_side_by_side(model, contact, state, dt, output_step, phase.element_forces);
        energy.internal = element_energy.strain;
        energy.hourglass = element_energy.hourglass;
      } else {
        ScopedTimer timer(phase.element_forces);
        const element::ElementEnergies element_energy =
            compute_internal_forces(model, decomposition, state, output_step);
        energy.internal = element_energy.strain;
        energy.hourglass = element_energy.hourglass;
      }
      if (!contact.pairs.empty()) {
        if (!side_by_side) compute_contact_forces(model, contact, state, dt);
        contact_statistics = total_statistics(contact);
        energy.contact = state.contact_energy;
      }
      {
        ScopedTimer timer(phase.time_integration);
        const NodalUpdate update = reduce_over_ranks(
            comm, update_velocities(model, state, dt, state.step == 0, output_step, nodal_update), energy,
            controls.stop_signal, stop_requested);
        if (!update.finite) step_back_and_stop(describe_non_finite(model, decomposition, state) + when());
        energy.kinetic = update.kinetic;
        mean_energy = energy.total() + dt * dt * update.mass_acceleration_squared;
        largest_speed = std::sqrt(3.0) * update.largest_component;  // >= |v^{n+1/2}|_2 of every node
      }
      const double total = energy.total();
      if (!std::isfinite(total)) {
        step_back_and_stop(describe_non_finite(model, decomposition, state) + when());
      }
      if (state.step == 0) initial_total = total, initial_mean_energy = mean_energy;
      largest_mean_energy = std::max(largest_mean_energy, std::abs(mean_energy));
      largest_energy =
          std::max({largest_energy, std::abs(total), energy.kinetic, energy.internal + energy.hourglass});
      if (largest_energy > 0.0)
        max_energy_error = std::max(max_energy_error, std::abs(total - initial_total) / largest_energy);
      summary.energy = {initial_total, total, max_energy_error};
      summarise_contact(contact, contact_statistics, summary);

      {  // the guards of docs/stability.md; the state of step n is finite here
        ScopedTimer timer(phase.guards);
        const double growth = mean_energy - initial_mean_energy;
        const double scale = std::max(largest_energy, largest_mean_energy);  // J
        summary.guard_checks.largest_energy_growth =
            std::max(summary.guard_checks.largest_energy_growth, scale > 0.0 ? growth / scale : 0.0);
        if (growth > deck.guards.energy_growth * scale) {
          char detail[200];
          std::snprintf(
              detail, sizeof detail,
              "the energy grew by %.3g %% of the largest energy seen (guards.energy_growth = %.3g %%): "
              "an instability; ",
              100.0 * growth / scale, 100.0 * deck.guards.energy_growth);
          std::string advice = "; time.courant is " + format_number(dt / critical_dt) + " of the stable step";
          if (!contact.pairs.empty())
            advice += ", the stiffest contact node pair " +
                      format_number(contact_statistics.max_pair_stiffness) + " N/m";
          stop_run(detail + describe_fastest_node(decomposition, state.velocity) + when() + advice);
        }
        if (contact_statistics.max_penetration_over_h > deck.guards.max_penetration) {
          char detail[200];
          std::snprintf(detail, sizeof detail, " penetrates by %.3g h (guards.max_penetration = %.3g h)",
                        contact_statistics.max_penetration_over_h, deck.guards.max_penetration);
          stop_run("contact pair " + contact.pair_of(contact_statistics.deepest_node) + ": slave node " +
                   std::to_string(global_node_id(decomposition, contact_statistics.deepest_node)) + detail +
                   when());
        }
        if (moved_since_check >= safety_radius) {
          // Every rank checks its elements; the lowest element found is named (on
          // many ranks: by the lowest rank that found one).
          safety_radius = std::numeric_limits<double>::infinity();
          std::string inverted_message;
          std::uint32_t inverted_element = std::numeric_limits<std::uint32_t>::max();
          for (const auto& block : model.blocks) {
            const element::InvertedElement inverted =
                element::find_inverted_element(block, model.mesh.x_ref, state.displacement);
            safety_radius = std::min(safety_radius, inverted.safety_radius);
            if (!inverted.found) continue;
            const std::uint32_t element = global_element_id(decomposition, inverted.element);
            if (element >= inverted_element) continue;
            inverted_element = element;
            const std::uint32_t node = block.connectivity[std::size_t(block.nodes_per_element) *
                                                              (inverted.element - block.first_element) +
                                                          std::size_t(inverted.corner)];
            char detail[160];
            std::snprintf(detail, sizeof detail, " (det J = %.3g m^3 at its corner node %u)",
                          inverted.det_jacobian, global_node_id(decomposition, node));
            inverted_message = "element " + std::to_string(element) + " is inverted" + detail + when();
          }
          inverted_message = mpi::first_message(comm, inverted_message);
          if (!inverted_message.empty()) stop_run(inverted_message);
          safety_radius = mpi::min(comm, safety_radius);
          moved_since_check = 0.0;
          ++summary.guard_checks.inversion_passes;
        }
        moved_since_check += dt * largest_speed;  // u^{n+1} - u^n = dt v^{n+1/2}
      }

      const bool last = state.step == stepping.steps;
      {
        ScopedTimer timer(phase.output);
        if (state.step % deck.output.history_every == 0 || last)
          writer.add_history({state.time, energy.kinetic, energy.internal, energy.contact, energy.hourglass,
                              energy.external_work, total},
                             contact_history(contact));
        if (state.step % deck.output.every == 0 || last) {
          step_writer.write(state, dt);
          last_written = state.step;
        }
      }
      if (controls.on_progress && (last || loop_watch.seconds() - last_progress >= 0.25)) {
        last_progress = loop_watch.seconds();
        controls.on_progress({state.step, stepping.steps, state.time, dt, last_progress});
      }
      if (last) break;
      if (stop_requested != 0)
        stop_run(std::string("interrupted by ") + (stop_requested == SIGINT ? "SIGINT" : "SIGTERM") + when() +
                 "; the results up to this step are written");
      {
        ScopedTimer timer(phase.time_integration);
        update_positions(state, dt, nodal_update);                                // u^{n+1}
        gather_contact_nodes(decomposition, state.displacement, state.velocity);  // many ranks
      }
    }
  } catch (const RunFailure& failure) {
    writer.flush();
    summary.status = "failed";
    summary.message = failure.what();
    summary.steps = state.step;
    summary.wall_seconds = total_watch.seconds();
    write_summary();
    throw;
  }
  writer.flush();
  summarise_ranks(decomposition, summary.mpi);
  const double loop_seconds = loop_watch.seconds();
  summary.steps = stepping.steps;
  summary.wall_seconds = total_watch.seconds();
  summary.element_cycles_per_second =
      loop_seconds > 0.0
          ? static_cast<double>(summary.elements) * static_cast<double>(stepping.steps) / loop_seconds
          : 0.0;
  write_summary();
  return summary;
}

}  // namespace exdyn::solver
