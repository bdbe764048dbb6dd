// The time loop: central differences with a lumped mass matrix.
//
//   a^n       = M^-1 (f_contact(x^n, v^{n-1/2}) - f_int(u^n))   (fixed components: a = 0)
//   v^{n+1/2} = v^{n-1/2} + dt a^n                      (v^{-1/2} = v^0 - dt/2 a^0)
//   u^{n+1}   = u^n + dt v^{n+1/2}
//
// (with unequal steps when the step follows the deformation: step_clock.hpp).
// Energy at step n (docs/theory.md, "Energy"): internal energy from u^n, kinetic
// energy from the two half-step velocities around n, K^n = 1/2 sum m v^{n-1/2}.v^{n+1/2},
// the form that the central-difference scheme conserves exactly for a linear
// elastic model, so the energy balance checks the forces and the mass to round-off.
// The passes of a step are step_passes.cpp's; what a step reports, step_report.cpp's.
#include "solver/simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>

#include "common/errors.hpp"
#include "common/isa.hpp"
#include "common/mpi.hpp"
#include "common/parallel.hpp"
#include "common/timer.hpp"
#include "common/version.hpp"
#include "element/corner_checks.hpp"
#include "model/contact_setup.hpp"
#include "model/model.hpp"
#include "output/result_writer.hpp"
#include "ranks/ranks.hpp"
#include "solver/nodal_update.hpp"
#include "solver/step_clock.hpp"
#include "solver/step_passes.hpp"
#include "solver/step_report.hpp"
#include "solver/time_loop.hpp"

namespace exdyn::solver {

// The model, the step clock and the contact; returns the initial velocities. On many
// ranks each rank sets up only its part (rank_setup.hpp: the chunks weighed by their
// elements or their measured work) and its share of the contact
// (distributed_contact.hpp); the stable step is the whole model's (docs/parallel.md).
NodalVectors TimeLoop::set_up(const RunControls& controls, output::RunSummary& summary) {
  const mpi::Communicator& comm = controls.comm;
  d_.comm = comm;
  if (!comm.distributed()) {
    model_ = build_model(deck_);
    critical_dt_ = critical_time_step(model_);
    clock_ = std::make_unique<StepClock>(deck_.time, critical_dt_, model_);
    contact_ = build_contact(deck_, model_, clock_->next(), critical_dt_);
    summary.nodes = static_cast<long>(model_.mesh.node_count());
    summary.elements = static_cast<long>(model_.mesh.element_count());
    summary.dt = clock_->next();
    return initial_velocity(deck_, model_);
  }
  RankSetup setup = set_up_rank(deck_, comm, controls.partitioning, controls.weigh_by_work);
  critical_dt_ = setup.critical_dt;
  clock_ = std::make_unique<StepClock>(deck_.time, critical_dt_, setup.run.model, &comm);
  contact_ = rank_contact(deck_, setup, clock_->next(), critical_dt_, comm);
  local_ = std::move(setup.run);
  summary.nodes = static_cast<long>(setup.nodes);
  summary.elements = static_cast<long>(setup.elements);
  summary.dt = clock_->next();
  // From here on this rank's part only.
  d_.contact = distribute_contact(contact_, comm, d_.global_node, local_.model, setup.contact_nodes,
                                  local_.contact_holders);
  local_.contact_holders = {};
  model_ = std::move(local_.model);
  return std::move(local_.initial_velocity);
}

// NAME.h5 with the mesh. One process writes its mesh; on many ranks each writes its
// rows of it (mesh_rows), once the whole model is gone.
void TimeLoop::open_writer(const RunControls& controls) {
  output::HistoryGroups history_groups;
  for (const auto& pair : contact_.pairs) history_groups.contact_pairs.push_back(pair.name);
  for (const auto& wall : contact_.walls) history_groups.walls.push_back(wall.name);
  history_groups.boundaries = deck_.boundary_conditions.size();
  boundary_reaction_.assign(history_groups.boundaries, {0.0, 0.0, 0.0});
  output::Distribution distribution;
  MeshRows mesh;
  const bool rows = controls.comm.distributed();
  if (rows) {
    distribution.comm = controls.comm;
    distribution.nodes = d_.global_nodes;
    distribution.elements = d_.global_elements;
    distribution.node_begin = d_.node_rows.begin;
    distribution.node_end = d_.node_rows.end;
    distribution.element_begin = d_.element_rows.begin;
    distribution.element_end = d_.element_rows.end;
    mesh = mesh_rows(d_, model_.mesh);
  } else {
    mesh.element_nodes.resize(model_.mesh.element_count());
    for (std::size_t e = 0; e < mesh.element_nodes.size(); ++e)
      mesh.element_nodes[e] = static_cast<std::uint8_t>(model_.mesh.nodes_of(e));
  }
  // A restart writes on into the files of the run it goes on from.
  output::WrittenPosition resume;
  if (checkpoint_ != nullptr) resume = output::read_position(*checkpoint_);
  writer_ = std::make_unique<output::ResultWriter>(
      directory_, deck_.name,
      output::MeshView{rows ? &mesh.x_ref : &model_.mesh.x_ref,
                       rows ? &mesh.connectivity : &model_.mesh.connectivity,
                       rows ? &mesh.element_part : &model_.mesh.element_part, &mesh.element_nodes},
      deck_.output.fields, history_groups,
      // steps 0, every, 2 every, ..., the last, and one more a stop may write
      static_cast<std::size_t>(clock_->planned_steps() / std::max(deck_.output.every, 1) + 3), distribution,
      checkpoint_ != nullptr ? &resume : nullptr, first_step_);
  writer_->write_in_background(deck_.output.background);
}

// The state at step 0: u = 0, v the initial velocities, the flags of the fixed and
// contact nodes, and f_load = m g with the contact forces from the start.
void TimeLoop::set_initial_state(NodalVectors initial_velocity) {
  const std::size_t node_count = model_.mesh.node_count();
  state_.displacement.resize(node_count);
  for (std::size_t c = 0; c < 3; ++c) {
    state_.flags[c].assign(node_count, 0);
    for (const std::uint32_t node : model_.fixed_nodes[c]) state_.flags[c][node] |= fixed_flag;
    for (const std::uint32_t node : contact_.nodes) state_.flags[c][node] |= contact_flag;
  }
  state_.acceleration.resize(node_count);
  state_.internal_force.resize(node_count);
  state_.contact_force.resize(node_count);
  state_.previous_contact_force.resize(node_count);
  if (!model_.load_acceleration.empty()) {
    state_.load_force.resize(node_count);
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < node_count; ++i) {
        const double f = model_.mass[i] * model_.load_acceleration.component(c)[i];
        state_.load_force.component(c)[i] = state_.contact_force.component(c)[i] =
            state_.previous_contact_force.component(c)[i] = f;
        if (f != 0.0) state_.flags[std::size_t(c)][i] |= contact_flag;
      }
  }
  state_.gap.assign(node_count, 0.0);
  state_.previous_gap.assign(node_count, 0.0);
  state_.stress.assign(6 * model_.mesh.element_count(), 0.0);
  state_.plastic_strain.assign(model_.mesh.element_count(), 0.0);
  // The damage and status fields: arrays where a material fails or the deck asks for them
  // (16 B per element; without them the writer writes 0 and 1).
  const auto& fields = deck_.output.fields;
  const bool failing = std::any_of(model_.blocks.begin(), model_.blocks.end(),
                                   [](const element::ElementBlock& b) { return b.law.failure.active(); });
  if (failing || std::find(fields.begin(), fields.end(), input::OutputField::damage) != fields.end() ||
      std::find(fields.begin(), fields.end(), input::OutputField::status) != fields.end()) {
    state_.damage.assign(model_.mesh.element_count(), 0.0);
    state_.status.assign(model_.mesh.element_count(), 1.0);
  }
  state_.velocity = std::move(initial_velocity);
  // A failing block writes its stresses every step, and reads v^{n+1/2} for the energy of
  // its failed elements (element_block.hpp, ElementFailure).
  for (element::ElementBlock& block : model_.blocks)
    if (block.law.failure.active())
      block.failure.stress = state_.stress.data(), block.failure.velocity = &state_.velocity;
  start_jump_ = prescribed_jump_energy(model_, controls_.comm);
  for (auto& p : state_.partial) p.assign(chunk_count(node_count), 0.0);
}

TimeLoop::TimeLoop(const input::Deck& deck, const RunControls& controls, output::RunSummary& summary)
    : deck_(deck), controls_(controls), summary_(summary) {
  NodalVectors initial_velocity = set_up(controls, summary);
  directory_ = controls.output_directory.empty() ? deck_.output.directory : controls.output_directory;
  if (controls.restart)
    open_checkpoint(controls);    // checked before any file is touched
  else if (controls.comm.root())  // a new run: checkpoints of an earlier one are not its own
    for (const auto& [step, path] : list_checkpoints(directory_, deck_.name)) std::filesystem::remove(path);
  open_writer(controls);
  set_initial_state(std::move(initial_velocity));
  step_writer_ = std::make_unique<StepWriter>(*writer_, model_, d_);
  nodal_update_ = nodal_update_for(selected_isa());  // the element blocks' ISA
  // The element and contact passes side by side, as tasks (compute_forces_side_by_side),
  // where the element pass runs on the threads anyway (a colour of more than one chunk):
  // then one parallel region replaces several. A small model keeps its passes without
  // a region, whose barrier can cost milliseconds when another process holds a core
  // (docs/performance.md, "Threads"). (On many ranks the element pass talks to other
  // ranks between its colours, from the main thread: not as tasks.)
  const bool element_pass_threaded =
      std::any_of(model_.blocks.begin(), model_.blocks.end(), [](const auto& block) {
        return std::any_of(block.colours.begin(), block.colours.end(),
                           [](const auto& colour) { return colour.size() > 1; });
      });
  side_by_side_ =
      !contact_.empty() && max_threads() > 1 && element_pass_threaded && !controls.comm.distributed();
  if (checkpoint_ != nullptr) restore_checkpoint();
}

// One step n, in the order of the algorithm.
void TimeLoop::run() {
  loop_watch_ = Stopwatch();
  for (state_.step = first_step_;; ++state_.step) {
    step_started_ = run_watch_.seconds();
    begin_step();
    compute_forces();                // f_int(u^n), f_contact(x^n, v^{n-1/2})
    plan_time_step();                // dt^{n+1/2} from x^n
    update_velocities_and_energy();  // v^{n+1/2}, the energies of step n
    check_guards();                  // instability, penetration, inversion
    write_output();                  // history row, fields of step n
    report_progress();
    if (last_) break;
    if (stop_requested_ != 0)
      stop_on_request(stop_requested_ == stop_at_wall_limit ? "--wall-limit"
                      : stop_requested_ == SIGINT           ? "SIGINT"
                                                            : "SIGTERM");
    if (!controls_.comm.distributed() && wall_limit_near()) stop_on_request("--wall-limit");
    if (checkpoint_due()) save_checkpoint(writer_->position());  // step n, whole
    update_positions();                                          // u^{n+1}, t^{n+1}
    slowest_step_ = std::max(slowest_step_, run_watch_.seconds() - step_started_);
  }
  writer_->flush();
  summarise_ranks(d_, contact_, summary_.phase_seconds, summary_.mpi);
  const double loop_seconds = loop_watch_.seconds();
  summary_.steps = state_.step;
  summary_.element_cycles_per_second =
      loop_seconds > 0.0 ? double(summary_.elements) * double(state_.step) / loop_seconds : 0.0;
}

void TimeLoop::begin_step() {
  state_.time = clock_->time();
  energy_ = Energies{};
  last_ = clock_->last(state_.step);
  // A step written: its element pass keeps the stresses and the velocity update keeps
  // f_int for the output (the guards may still write another step: forces_of_this_step).
  output_step_ = state_.step % deck_.output.every == 0 || last_;
  // The point states the last step wrote become the committed ones; the strain
  // increment of this pass is over dt^{n-1/2} (the rate of a rate-dependent law).
  for (const element::ElementBlock& block : model_.blocks) {
    if (state_.step > 0) element::commit_material_state(block);
    element::set_material_time_step(block, clock_->previous());
  }
  // The step of the current configuration and the inversion check (plan_time_step) ride
  // on the element pass where the block's loop runs them: no pass of their own.
  if (clock_->follows_deformation()) {
    const bool check = moved_since_check_ >= safety_radius_;  // plan_time_step's test
    for (const element::ElementBlock& block : model_.blocks)
      if (block.corners_in_pass && (block.law.finite || check))
        element::request_corner_checks(block, model_.mesh.x_ref, block.law.finite, check);
  }
  // The penalty of this step's contact pass follows the last step the mesh asked for
  // (the next one is planned after the forces; the caps' margin covers its change of a
  // fraction; a step cut short to land on end_time is not the mesh's).
  if (clock_->follows_deformation() && state_.step > 0)
    follow_time_step(contact_, clock_->uncut() / clock_->first());
}

void TimeLoop::compute_forces() {
  output::PhaseSeconds& phase = summary_.phase_seconds;
  // An element failed at the last step (on any rank) is gone from this one: its faces
  // leave the contact and the faces it exposed join it, before either pass runs.
  if (failed_everywhere_ != opened_for_eroded_) {
    follow_erosion(contact_, model_, d_);
    opened_for_eroded_ = failed_everywhere_;
  }
  element::ElementEnergies element_energy;
  if (side_by_side_) {  // each pass times itself: the two phases overlap
    element_energy = compute_forces_side_by_side(model_, contact_, state_, clock_->previous(), output_step_,
                                                 phase.element_forces);
  } else {
    ScopedTimer timer(phase.element_forces);
    element_energy = compute_internal_forces(model_, d_, state_, output_step_);
  }
  energy_.internal = element_energy.strain;
  energy_.hourglass = element_energy.hourglass;
  energy_.plastic = element_energy.plastic;
  // Damage after the pass that made this step's plastic strains and stresses; an element
  // failed now carries no force from the next step on (element_block.hpp, ElementFailure).
  state_.eroded_energy += element_energy.eroded;
  energy_.eroded = state_.eroded_energy;  // this rank's: summed over the ranks with the energies
  for (const element::ElementBlock& block : model_.blocks)
    state_.eroded_elements += element::update_damage(block, clock_->previous());
  energy_.eroded_elements = double(state_.eroded_elements);
  if (!state_.load_force.empty()) add_load_work(model_, state_, clock_->previous());
  if (!contact_.empty()) {
    if (!side_by_side_) compute_contact_forces(model_, contact_, d_, state_, clock_->previous());
    contact_statistics_ = total_statistics(contact_);
    energy_.contact = state_.contact_energy;
    energy_.friction = contact_.friction_work();
  }
  if (!model_.boundary.empty()) add_boundary_reactions(model_, d_, state_, clock_->previous());
  energy_.external_work = state_.external_work;  // this rank's: summed over the ranks with the energies
}

void TimeLoop::plan_time_step() {
  if (!clock_->follows_deformation()) return;
  ScopedTimer timer(summary_.phase_seconds.time_integration);
  const bool check = moved_since_check_ >= safety_radius_;  // check_guards' test, the same figures
  planned_inversion_.assign(model_.blocks.size(), element::InvertedElement{});
  planned_inversion_step_ = check ? state_.step : -1;
  element::CurrentStep finite{std::numeric_limits<double>::infinity(), 0};
  for (std::size_t b = 0; b < model_.blocks.size(); ++b) {
    const element::ElementBlock& block = model_.blocks[b];
    const NodalVectors& x_ref = model_.mesh.x_ref;
    element::CurrentStep current{std::numeric_limits<double>::infinity(), 0};
    if (block.corner_request.x_ref != nullptr) {  // begin_step's request, served by the element pass
      const element::CornerChecks both = element::corner_checks_of_pass(block);
      if (block.law.finite) current = both.step;
      if (check) planned_inversion_[b] = both.inverted;
    } else if (block.law.finite && check) {
      const element::CornerChecks both = element::check_corners(block, x_ref, state_.displacement);
      current = both.step, planned_inversion_[b] = both.inverted;
    } else if (block.law.finite) {
      current = element::current_time_step(block, x_ref, state_.displacement);
    } else if (check) {
      planned_inversion_[b] = element::find_inverted_element(block, x_ref, state_.displacement);
    }
    if (current.dt < finite.dt) finite = current;
  }
  const std::string collapse = clock_->plan(state_.step, d_, finite);
  if (state_.step == 0) erode_distorted_elements(model_, deck_.time, clock_->first());
  summary_.dt_min = clock_->smallest();
  if (!collapse.empty()) stop_run(collapse + when());
}

void TimeLoop::update_velocities_and_energy() {
  {
    ScopedTimer timer(summary_.phase_seconds.time_integration);
    const NodalUpdate mine = update_velocities(model_, state_, clock_->velocity_step(state_.step),
                                               state_.step == 0, output_step_, nodal_update_);
    if (!state_.reaction.empty()) boundary_reaction_ = state_.reaction;
    // On many ranks the wall limit is agreed with the signals: every rank stops at one step.
    // So is a checkpoint by every_seconds: every rank writes it at the same step.
    int signal = controls_.stop_signal != nullptr ? int(*controls_.stop_signal) : 0;
    if (controls_.comm.distributed()) {
      if (signal == 0 && wall_limit_near()) signal = stop_at_wall_limit;
      if (signal == 0 && checkpoint_clock_due()) signal = checkpoint_by_clock;
    }
    update_ = reduce_over_ranks(controls_.comm, mine, energy_, boundary_reaction_, state_.reaction_error,
                                signal, stop_requested_);
    checkpoint_by_clock_ = stop_requested_ == checkpoint_by_clock;
    if (checkpoint_by_clock_) stop_requested_ = 0;
    if (!update_.finite) step_back_and_stop(describe_non_finite(model_, d_, state_) + when());
    varying_step_.add(state_.step, clock_->previous(), clock_->next(), update_.old_power, update_.new_power);
    energy_.kinetic = update_.kinetic - varying_step_.correction;
    failed_everywhere_ = long(energy_.eroded_elements);
    energy_.external_work += state_.wall_work;
    const double dt = clock_->next();
    mean_energy_ = energy_.total() + dt * dt * update_.mass_acceleration_squared;
    largest_speed_ = std::sqrt(3.0) * update_.largest_component;  // >= |v^{n+1/2}|_2 of every node
  }
  const double total = energy_.total();
  if (!std::isfinite(total)) step_back_and_stop(describe_non_finite(model_, d_, state_) + when());
  if (state_.step == 0) initial_total_ = total, initial_mean_energy_ = mean_energy_;
  largest_mean_energy_ = std::max(largest_mean_energy_, std::abs(mean_energy_));
  // The scale counts what loads and moving walls put in: a run driven from outside
  // starts from nothing.
  largest_energy_ =
      std::max({largest_energy_, std::abs(total), energy_.kinetic, energy_.internal + energy_.hourglass,
                std::abs(energy_.external_work) + std::abs(energy_.contact)});
  if (largest_energy_ > 0.0)
    max_energy_error_ = std::max(max_energy_error_, std::abs(total - initial_total_) / largest_energy_);
  summary_.energy = {initial_total_, total, max_energy_error_};
  summary_.energy.plastic_work = energy_.plastic;
  summary_.energy.hourglass = energy_.hourglass;
  summary_.energy.internal = energy_.internal;
  summary_.energy.eroded = energy_.eroded;
  summary_.energy.eroded_elements = long(energy_.eroded_elements);
  summarise_contact(contact_, contact_statistics_, summary_);
}

// The guards of docs/stability.md; the state of step n is finite here.
void TimeLoop::check_guards() {
  ScopedTimer timer(summary_.phase_seconds.guards);
  const double growth = mean_energy_ - initial_mean_energy_;
  const double scale = std::max(largest_energy_, largest_mean_energy_) + start_jump_;  // J
  summary_.guard_checks.largest_energy_growth =
      std::max(summary_.guard_checks.largest_energy_growth, scale > 0.0 ? growth / scale : 0.0);
  if (growth > deck_.guards.energy_growth * scale) {
    char detail[200];
    std::snprintf(detail, sizeof detail,
                  "the energy grew by %.3g %% of the largest energy seen (guards.energy_growth = %.3g %%): "
                  "an instability; ",
                  100.0 * growth / scale, 100.0 * deck_.guards.energy_growth);
    std::string advice =
        "; time.courant is " + format_number(clock_->next() / critical_dt_) + " of the stable step";
    if (!contact_.empty())
      advice += ", the stiffest contact node pair " + format_number(contact_statistics_.max_pair_stiffness) +
                " N/m";
    stop_run(detail + describe_fastest_node(d_, state_.velocity) + when() + advice);
  }
  if (contact_statistics_.max_penetration_over_h > deck_.guards.max_penetration) {
    char detail[200];
    std::snprintf(detail, sizeof detail, " penetrates by %.3g h (guards.max_penetration = %.3g h)",
                  contact_statistics_.max_penetration_over_h, deck_.guards.max_penetration);
    // (the statistics name nodes by their global ids, on any number of ranks)
    stop_run(contact_.deepest_contact() + ": slave node " + std::to_string(contact_statistics_.deepest_node) +
             detail + when());
  }
  if (moved_since_check_ >= safety_radius_) check_inversion();
  moved_since_check_ += clock_->next() * largest_speed_;  // u^{n+1} - u^n = dt v^{n+1/2}
}

// Every rank checks its elements; the lowest element found is named (on many ranks:
// by the lowest rank that found one).
void TimeLoop::check_inversion() {
  safety_radius_ = std::numeric_limits<double>::infinity();
  std::string message;
  std::uint32_t inverted_element = std::numeric_limits<std::uint32_t>::max();
  for (std::size_t b = 0; b < model_.blocks.size(); ++b) {
    const element::ElementBlock& block = model_.blocks[b];
    const element::InvertedElement inverted =
        planned_inversion_step_ == state_.step
            ? planned_inversion_[b]
            : element::find_inverted_element(block, model_.mesh.x_ref, state_.displacement);
    safety_radius_ = std::min(safety_radius_, inverted.safety_radius);
    if (!inverted.found) continue;
    const std::uint32_t element = global_element_id(d_, inverted.element);
    if (element >= inverted_element) continue;
    inverted_element = element;
    const std::uint32_t node =
        block.connectivity[std::size_t(block.nodes_per_element) * (inverted.element - block.first_element) +
                           std::size_t(inverted.corner)];
    char detail[160];
    std::snprintf(detail, sizeof detail, " (det J = %.3g m^3 at its corner node %u)", inverted.det_jacobian,
                  global_node_id(d_, node));
    message = "element " + std::to_string(element) + " is inverted" + detail + when();
  }
  message = mpi::first_message(controls_.comm, message);
  if (!message.empty()) stop_run(message);
  safety_radius_ = mpi::min(controls_.comm, safety_radius_);
  moved_since_check_ = 0.0;
  ++summary_.guard_checks.inversion_passes;
}

void TimeLoop::warn_small_strain() {
  if (small_strain_warned_) return;
  const std::string text = small_strain_warning(deck_, model_, state_, controls_.comm, when());
  if (text.empty()) return;
  summary_.warnings.push_back(text);
  small_strain_warned_ = true;
}

void TimeLoop::write_output() {
  ScopedTimer timer(summary_.phase_seconds.output);
  if (state_.step % deck_.output.history_every == 0 || last_)
    writer_->add_history(history_row(), contact_history(contact_), force_rows());
  if (output_step_) {
    const Stopwatch watch;
    step_writer_->write(state_, clock_->next());
    last_written_ = state_.step;
    warn_small_strain();
    slowest_output_ = std::max(slowest_output_, watch.seconds());
  }
}

void TimeLoop::report_progress() {
  if (!controls_.on_progress || (!last_ && loop_watch_.seconds() - last_progress_ < 0.25)) return;
  last_progress_ = loop_watch_.seconds();
  controls_.on_progress({state_.step, clock_->planned_steps(), state_.time, clock_->next(), last_progress_});
}

void TimeLoop::update_positions() {
  ScopedTimer timer(summary_.phase_seconds.time_integration);
  solver::update_positions(state_, clock_->next(), nodal_update_);  // u^{n+1}
  clock_->advance(state_.step);
}

// Writes the current step (if it is not written yet) as the final output step and
// stops the run: run_simulation writes the summary with status "failed".
void TimeLoop::stop_run(const std::string& message) {
  ScopedTimer timer(summary_.phase_seconds.output);
  if (state_.step > last_written_) {
    writer_->add_history(history_row(), contact_history(contact_), force_rows());
    step_writer_->write(state_, clock_->next());
    last_written_ = state_.step;
  }
  throw RunFailure(message, state_.step, state_.time);
}

// Step n produced a non-finite value: go back to step n-1, the last finite state,
// from u^{n-1} = u^n - dt v^{n-1/2}, with that step's contact forces and gaps, and
// stop there. The velocity update has made v^{n+1/2} = v^{n-1/2} + dt a^n in place
// wherever a^n is finite (and left v^{n-1/2} where it is not): v^{n-1/2} is taken
// back as v^{n+1/2} - dt a^n, to round-off (state.acceleration holds a^n:
// describe_non_finite computed it). The point states go back to step n-1's.
void TimeLoop::step_back_and_stop(const std::string& message) {
  if (state_.step == 0) throw RunFailure(message, state_.step, state_.time);
  const double dv = clock_->velocity_step(state_.step), du = clock_->previous();
  for_each_chunk(model_.mesh.node_count(), [&](std::size_t begin, std::size_t end, std::size_t) {
    for (int c = 0; c < 3; ++c) {
      double* v = state_.velocity.component(c).data();
      const double* a = state_.acceleration.component(c).data();
      for (std::size_t i = begin; i < end; ++i)
        if (std::isfinite(a[i])) v[i] -= dv * a[i];
    }
  });
  add_scaled(state_.displacement, -du, state_.velocity);  // u^{n-1} = u^n - dt v^{n-1/2}
  for (const element::ElementBlock& block : model_.blocks) element::commit_material_state(block);
  compute_internal_forces(model_, d_, state_, true);
  std::swap(state_.contact_force, state_.previous_contact_force);
  std::swap(state_.gap, state_.previous_gap);
  compute_accelerations(model_, state_);
  --state_.step;
  state_.stress_step = state_.force_step = state_.step;  // computed above, at u^{n-1}
  state_.time = clock_->follows_deformation() ? state_.time - du : static_cast<double>(state_.step) * du;
  stop_run(message + " (the last finite state, step " + std::to_string(state_.step) + ", is written)");
}

output::RunSummary run_simulation(const input::Deck& deck, const RunControls& controls) {
  Stopwatch total_watch;
  output::RunSummary summary;
  summary.name = deck.name;
  summary.exdyn_version = exdyn::version;
  summary.threads = set_threads(controls.threads);
  summary.isa = isa_name(selected_isa());
  summary.end_time = deck.time.end_time;
  summary.ranks = controls.comm.size;
  const std::string directory =
      controls.output_directory.empty() ? deck.output.directory : controls.output_directory;
  const std::string summary_path = (std::filesystem::path(directory) / (deck.name + ".json")).string();
  // Only the root rank writes the summary (the figures are the same on every rank).
  const auto write_summary = [&] {
    if (controls.comm.root()) output::write_summary(summary_path, summary);
  };
  summary.warnings = input::deck_warnings(deck);
  TimeLoop loop(deck, controls, summary);
  // A run that ends early: its files flushed, then the summary that says why.
  const auto end_early = [&](const char* status, const std::exception& why, long step) {
    loop.flush();
    summary.status = status;
    summary.message = why.what();
    summary.steps = step;
    summary.wall_seconds = total_watch.seconds();
    write_summary();
  };
  try {
    loop.run();
  } catch (const RunStopped& stopped) {
    end_early("stopped", stopped, stopped.step());
    throw;
  } catch (const RunFailure& failure) {
    end_early("failed", failure, failure.step());
    throw;
  }
  summary.wall_seconds = total_watch.seconds();
  write_summary();
  return summary;
}

}  // namespace exdyn::solver
