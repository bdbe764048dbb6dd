// Restart checkpoints of a run (docs/output.md, "Checkpoints"): where they are, and
// what decides when one is written. What one holds: TimeLoop::save_checkpoint
// (checkpoint.cpp) and checkpoint_state.hpp.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace exdyn::solver {

// DIRECTORY/NAME.STEP.restart, STEP the step the run goes on at, 8 digits at least.
std::string checkpoint_path(const std::string& directory, const std::string& name, long step);

// The checkpoints of run NAME in DIRECTORY, (step, path), oldest first.
std::vector<std::pair<long, std::string>> list_checkpoints(const std::string& directory,
                                                           const std::string& name);

}  // namespace exdyn::solver
