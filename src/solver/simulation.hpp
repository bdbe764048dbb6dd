// Runs a deck: builds the model, integrates in time by central differences and
// writes the results (../shared/spec/output.md).
#pragma once

#include <functional>
#include <string>

#include "input/options.hpp"
#include "output/summary.hpp"

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
  int threads = 1;
  // Called every few steps and at the end; may be empty.
  std::function<void(const Progress&)> on_progress;
};

// Runs the deck to its end time. Returns the summary (also written to NAME.json).
// A physical failure writes the last good state, a summary with status "failed"
// and rethrows the RunFailure.
output::RunSummary run_simulation(const input::Deck& deck, const RunControls& controls);

}  // namespace exdyn::solver
