// Runs a deck: builds the model, integrates in time by central differences and
// writes the results (../shared/spec/output.md).
#pragma once

#include <chrono>
#include <csignal>
#include <functional>
#include <string>

#include "common/mpi.hpp"
#include "input/options.hpp"
#include "output/summary.hpp"
#include "ranks/ranks.hpp"

namespace exdyn::solver {

// What the caller sees of a run in progress (for a progress line).
struct Progress {
  long step = 0;
  long total_steps = 0;
  double time = 0.0;
  double dt = 0.0;
  double wall_seconds = 0.0;
};

struct RunControls {
  std::string output_directory;  // empty: the deck's output.directory
  int threads = 1;               // per rank
  // The ranks of the run (docs/parallel.md); default one process without MPI. Every
  // rank calls run_simulation with the same deck and controls.
  mpi::Communicator comm;
  // How the chunks are dealt to the ranks (decomposition.hpp), weighed by their
  // measured work (load_balance.hpp) or by their elements.
  Partitioning partitioning = Partitioning::bisection;
  bool weigh_by_work = false;
  // Set to a signal number (SIGINT, SIGTERM) by the caller's signal handler: the run
  // finishes its step, writes it and a checkpoint, and stops with a RunStopped. May be null.
  const volatile std::sig_atomic_t* stop_signal = nullptr;
  // Go on from a checkpoint (docs/output.md, "Checkpoints"): the one named, or with an
  // empty name the newest of the run in the output directory.
  bool restart = false;
  std::string restart_file;
  // Stop as on a signal before this many wall seconds have passed since the start,
  // allowing for the time a checkpoint takes (0: no limit), s.
  double wall_limit = 0.0;
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();  // the run's start
  // Called every few steps and at the end; may be empty.
  std::function<void(const Progress&)> on_progress;
};

// Runs the deck to its end time. Returns the summary (also written to NAME.json).
// A stop on request (stop_signal, wall_limit) writes a checkpoint and ends the run
// with a RunStopped that names the step and the command that goes on.
// A guard that fires (docs/stability.md: non-finite value, inverted element,
// energy growth, penetration) or a stop signal ends the run with a RunFailure
// naming what, where and when, after writing the last finite state as the final
// output step and a summary with status "failed".
output::RunSummary run_simulation(const input::Deck& deck, const RunControls& controls);

}  // namespace exdyn::solver
