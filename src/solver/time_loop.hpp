// The time loop of a run (simulation.cpp) and what it keeps from step to step, which
// a checkpoint saves and a restart puts back (checkpoint.cpp). Not for use outside
// src/solver.
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "common/timer.hpp"
#include "element/corner_checks.hpp"
#include "model/contact_setup.hpp"
#include "model/model.hpp"
#include "output/checkpoint_file.hpp"
#include "output/result_writer.hpp"
#include "ranks/ranks.hpp"
#include "solver/checkpoint.hpp"
#include "solver/nodal_update.hpp"
#include "solver/simulation.hpp"
#include "solver/step_clock.hpp"
#include "solver/step_passes.hpp"
#include "solver/step_report.hpp"

namespace exdyn::solver {

// A run in progress: the model, its state and everything the loop reports to.
class TimeLoop {
 public:
  TimeLoop(const input::Deck& deck, const RunControls& controls, output::RunSummary& summary);
  void run();
  void flush() { writer_->flush(); }

 private:
  NodalVectors set_up(const RunControls& controls, output::RunSummary& summary);
  void open_writer(const RunControls& controls);
  void set_initial_state(NodalVectors initial_velocity);
  void begin_step();
  void compute_forces();
  void plan_time_step();
  void update_velocities_and_energy();
  void check_guards();
  void check_inversion();
  void warn_small_strain();
  void write_output();
  void update_positions();
  void report_progress();
  [[noreturn]] void stop_run(const std::string& message);
  // Restart checkpoints (checkpoint.cpp): the one a restart goes on from, checked
  // against this deck and program before any file is touched; the state put back from
  // it; when the next is due; writing one of the state at the start of this step (u^n,
  // v^{n-1/2}) with the files' position; and stopping on request after one.
  void open_checkpoint(const RunControls& controls);
  void restore_checkpoint();
  bool checkpoint_due() const;
  bool checkpoint_clock_due() const;
  bool wall_limit_near() const;
  void save_checkpoint(const output::WrittenPosition& position);
  [[noreturn]] void stop_on_request(const std::string& why);
  template <class Archive>
  void visit_loop(Archive& archive);
  [[noreturn]] void step_back_and_stop(const std::string& message);
  std::string when() const {
    return " at step " + std::to_string(state_.step) + ", time " + format_time(state_.time);
  }
  output::HistoryRow history_row() const {
    return {state_.time,
            energy_.kinetic,
            energy_.internal,
            energy_.contact,
            energy_.hourglass,
            energy_.external_work,
            energy_.total(),
            energy_.plastic,
            energy_.friction,
            energy_.eroded,
            0.0};
  }
  // The rigid walls' forces, then the boundary conditions' reactions.
  std::vector<output::WallHistoryRow> force_rows() const {
    std::vector<output::WallHistoryRow> rows = wall_history(contact_);
    for (const auto& r : boundary_reaction_) rows.push_back({r});
    return rows;
  }

  const input::Deck& deck_;
  const RunControls& controls_;
  output::RunSummary& summary_;
  Model model_;
  LocalRun local_;
  Decomposition& d_ = local_.decomposition;
  ContactModel contact_;
  double critical_dt_ = 0.0;
  std::unique_ptr<StepClock> clock_;
  std::unique_ptr<output::ResultWriter> writer_;
  std::unique_ptr<StepWriter> step_writer_;
  State state_;
  NodalUpdateFns nodal_update_{};
  bool side_by_side_ = false;
  bool output_step_ = false, last_ = false;
  contact::ContactStatistics contact_statistics_;         // all pairs together, updated every step
  std::vector<std::array<double, 3>> boundary_reaction_;  // each condition's, over all ranks, N
  Energies energy_;
  NodalUpdate update_;
  VaryingStep varying_step_;
  Stopwatch loop_watch_;
  double last_progress_ = -1.0;
  double initial_total_ = 0.0, largest_energy_ = 0.0, max_energy_error_ = 0.0;
  long last_written_ = -1;  // the last step written to NAME.h5
  // The inversion guard runs its element pass only when some element could have
  // inverted: when the nodes may have moved (bound: sum of dt max|v|) as far as the
  // safety radius of the last configuration checked (element_block.hpp). A stable
  // run checks rarely (the plate case: once in about 4600 steps), a blowing-up one
  // every step.
  // The energy guard watches E_mean^n = 1/2 sum m |v^n|^2 + U^n + H^n + contact - work:
  // bounded in a stable run, exponential in an unstable one (docs/stability.md).
  double initial_mean_energy_ = 0.0, largest_mean_energy_ = 0.0, mean_energy_ = 0.0;
  double moved_since_check_ = std::numeric_limits<double>::infinity(), safety_radius_ = 0.0,
         largest_speed_ = 0.0;
  // Following the deformation, the step's plan reads every element's corners: when the
  // inversion check falls on that step it rides along (element::check_corners), each
  // block's result kept here for check_inversion, stamped with the step.
  std::vector<element::InvertedElement> planned_inversion_;
  long planned_inversion_step_ = -1;
  // What a prescribed velocity's start can show in E_mean (prescribed_jump_energy), J.
  double start_jump_ = 0.0;
  bool small_strain_warned_ = false;
  // The elements failed on all ranks by the last step, and when the contact last
  // followed erosion (opened_faces.hpp).
  long failed_everywhere_ = 0, opened_for_eroded_ = 0;
  int stop_requested_ = 0;  // the signal a rank has seen (SIGINT, SIGTERM), agreed by all every step
  // Checkpoints: the output directory; the checkpoint a restart goes on from (until its
  // state is put back); the step the loop starts at; the wall clock since the start and
  // at the last checkpoint, and the slowest checkpoint, step and field output so far (s), for
  // every_seconds and --wall-limit.
  std::string directory_;
  // On many ranks, whether the ranks agreed that every_seconds has passed; the whole
  // mesh's hash, once computed.
  bool checkpoint_by_clock_ = false;
  std::uint64_t mesh_hash_ = 0;
  std::unique_ptr<output::CheckpointReader> checkpoint_;
  long first_step_ = 0;
  Stopwatch run_watch_;
  double last_checkpoint_wall_ = 0.0, slowest_checkpoint_ = 0.0, slowest_step_ = 0.0, step_started_ = 0.0,
         slowest_output_ = 0.0;
};

}  // namespace exdyn::solver
