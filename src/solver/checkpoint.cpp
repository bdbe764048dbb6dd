// Restart checkpoints (docs/output.md, "Checkpoints"). A checkpoint is taken between
// two steps: once step n is whole (its forces, v^{n+1/2}, its history row and fields
// written), before u^{n+1} = u^n + dt v^{n+1/2}. It holds the state (checkpoint_state.hpp),
// the time loop's own accumulators (energy balance, guards, varying step), the step
// clock, and where the run stands in NAME.h5. A restart builds the model from the deck
// as any run does, puts that state back, makes u^{n+1} as the run did and goes on at
// step n+1: every step after it computes what the run that never stopped computed,
// from the same bits.
#include "solver/checkpoint.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>

#include "common/errors.hpp"
#include "common/isa.hpp"
#include "common/version.hpp"
#include "input/deck_reader.hpp"
#include "ranks/contact_checkpoint.hpp"
#include "ranks/rank_checkpoint.hpp"
#include "solver/checkpoint_ranks.hpp"
#include "solver/checkpoint_state.hpp"
#include "solver/time_loop.hpp"

namespace exdyn::solver {

namespace fs = std::filesystem;

namespace {

constexpr const char* suffix = ".restart";

std::string join_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + '\x1f';
  return text;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t begin = 0;
  for (std::size_t end; (end = text.find('\x1f', begin)) != std::string::npos; begin = end + 1)
    lines.push_back(text.substr(begin, end - begin));
  return lines;
}

}  // namespace

std::string checkpoint_path(const std::string& directory, const std::string& name, long step) {
  char number[32];
  std::snprintf(number, sizeof number, "%08ld", step);
  return (fs::path(directory) / (name + "." + number + suffix)).string();
}

std::vector<std::pair<long, std::string>> list_checkpoints(const std::string& directory,
                                                           const std::string& name) {
  std::vector<std::pair<long, std::string>> found;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory, error)) {
    const std::string file = entry.path().filename().string();
    const std::size_t length = file.size(), head = name.size() + 1,
                      tail = std::char_traits<char>::length(suffix);
    if (length <= head + tail || file.compare(0, name.size(), name) != 0 || file[name.size()] != '.' ||
        file.compare(length - tail, tail, suffix) != 0)
      continue;
    const std::string digits = file.substr(head, length - head - tail);
    long step = 0;
    const auto [end, status] = std::from_chars(digits.data(), digits.data() + digits.size(), step);
    if (status != std::errc() || end != digits.data() + digits.size() ||
        !std::all_of(digits.begin(), digits.end(),
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
      continue;
    found.emplace_back(step, entry.path().string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

// The time loop's own values that carry from step to step (time_loop.hpp), and the
// run summary's figures that accumulate. The clock goes through StepClock::Saved.
template <class Archive>
void TimeLoop::visit_loop(Archive& a) {
  a("loop/boundary_reaction", boundary_reaction_);
  a("loop/varying_step", varying_step_);
  a("loop/initial_total", initial_total_);
  a("loop/largest_energy", largest_energy_);
  a("loop/max_energy_error", max_energy_error_);
  a("loop/initial_mean_energy", initial_mean_energy_);
  a("loop/largest_mean_energy", largest_mean_energy_);
  a("loop/mean_energy", mean_energy_);
  a("loop/moved_since_check", moved_since_check_);
  a("loop/safety_radius", safety_radius_);
  a("loop/largest_speed", largest_speed_);
  a("loop/small_strain_warned", small_strain_warned_);
  a("loop/failed_everywhere", failed_everywhere_);
  a("loop/opened_for_eroded", opened_for_eroded_);
  a("loop/last_written", last_written_);
  a("summary/guard_checks", summary_.guard_checks);
  a("summary/phase_seconds", summary_.phase_seconds);
  a("summary/checkpoints_written", summary_.checkpoints.written);
  a("summary/checkpoint_seconds", summary_.checkpoints.seconds);
  a("summary/largest_checkpoint_seconds", summary_.checkpoints.largest_seconds);
}

void TimeLoop::open_checkpoint(const RunControls& controls) {
  std::string path = controls.restart_file;
  if (path.empty()) {
    const auto found = list_checkpoints(directory_, deck_.name);
    if (found.empty())
      throw InputError("--restart: no checkpoint of " + deck_.name + " in " + directory_ + " (" +
                       fs::path(checkpoint_path(directory_, deck_.name, 0)).filename().string() +
                       " and on) to go on from");
    path = found.back().second;
  } else if (!fs::exists(path)) {
    throw InputError("--restart: the checkpoint " + path + " does not exist");
  }
  checkpoint_ = std::make_unique<output::CheckpointReader>(path);
  const output::CheckpointReader& file = *checkpoint_;
  const std::string refused = "--restart: the checkpoint " + path + " ";
  if (const std::string written_by = file.text("exdyn_version"); written_by != exdyn::version)
    throw InputError(refused + "was written by exdyn " + written_by + "; this is exdyn " + exdyn::version +
                     ", which cannot go on from it");
  if (const std::string isa = file.text("isa"); isa != isa_name(selected_isa()))
    throw InputError(refused + "was written with the element kernels of " + isa + ", this run uses " +
                     isa_name(selected_isa()) + ": give --isa " + isa + " for the same bits");
  std::string difference;
  try {
    difference = input::restart_difference(file.text("deck"), deck_);
  } catch (const std::exception&) {
    throw InputError(refused + "holds a deck that cannot be read");
  }
  if (!difference.empty())
    throw InputError(refused + "is of another deck: " + difference +
                     "; a restart may change time.end_time, output and checkpoint only");
  if (file.value<std::uint64_t>("mesh") != whole_mesh_hash(model_, d_))
    throw InputError(refused + "is of another mesh (a mesh file changed since it was written)");
  const fs::path h5 = fs::path(directory_) / (deck_.name + ".h5");
  if (!fs::exists(h5))
    throw InputError(refused + "goes on writing " + h5.string() + ", which does not exist");
  first_step_ = file.value<long>("next_step");
  if (first_step_ < 1) throw InputError(refused + "names step " + std::to_string(first_step_));
}

void TimeLoop::restore_checkpoint() {
  const output::CheckpointReader& file = *checkpoint_;
  const StateLoader loader{file};
  if (controls_.comm.distributed()) {
    load_whole_state(file, state_, model_, d_, contact_);
  } else {
    visit_state(loader, state_, contact_.nodes);
    visit_blocks(loader, model_.blocks);
    visit_contact(loader, contact_);
    finish_loading_contact(contact_);
  }
  visit_loop(loader);
  clock_->restore(file.value<StepClock::Saved>("loop/clock"));
  summary_.dt_min = clock_->smallest();
  summary_.warnings = split_lines(file.text("summary/warnings"));
  summary_.restart = {first_step_, file.path()};
  last_checkpoint_wall_ = run_watch_.seconds();
  checkpoint_.reset();
  update_positions();  // u^{n+1}, t^{n+1}: where step n ended
}

bool TimeLoop::checkpoint_due() const {
  const input::CheckpointOptions& c = deck_.checkpoint;
  if (!c.enabled()) return false;
  if (c.every > 0 && (state_.step + 1) % c.every == 0) return true;
  // On many ranks the clock's rule is agreed by all (update_velocities_and_energy).
  return controls_.comm.distributed() ? checkpoint_by_clock_ : checkpoint_clock_due();
}

bool TimeLoop::checkpoint_clock_due() const {
  const double every = deck_.checkpoint.every_seconds;
  return every > 0.0 && run_watch_.seconds() - last_checkpoint_wall_ >= every;
}

// Near the limit: less time left than the slowest checkpoint, two of the slowest steps
// and the slowest field output (the stop writes its step) would take, with half as much
// again to spare (before the first checkpoint, one estimated at 200 MB/s of the state's
// size), and half a second for the end of the process (the summary, freeing the model).
bool TimeLoop::wall_limit_near() const {
  if (controls_.wall_limit <= 0.0) return false;
  const double estimate =
      double(model_.mesh.node_count() * 200 + model_.mesh.element_count() * 120) / 200.0e6;
  const double needed =
      1.5 * (std::max(slowest_checkpoint_, estimate) + 2.0 * slowest_step_ + slowest_output_) + 0.5;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - controls_.started).count();
  return elapsed + needed >= controls_.wall_limit;
}

void TimeLoop::save_checkpoint(const output::WrittenPosition& position) {
  Stopwatch watch;
  const long next_step = state_.step + 1;
  const std::string path = checkpoint_path(directory_, deck_.name, next_step);
  ++summary_.checkpoints.written;
  if (mesh_hash_ == 0) mesh_hash_ = whole_mesh_hash(model_, d_);
  // On many ranks the file one process writes, written by all: each rank its rows of the
  // nodal and element arrays and its chunks' point states, rank 0 the rest, made whole.
  const bool ranks = controls_.comm.distributed();
  output::CheckpointWriter file(path, controls_.comm);
  std::set<std::string> pieced;
  WholeState whole;
  if (ranks) {
    add_state_pieces(file, state_, d_, pieced);
    add_block_pieces(file, d_, model_, pieced);
    whole = gather_whole_state(state_, model_, d_, contact_);
  }
  if (controls_.comm.root()) {
    file.add("exdyn_version", std::string_view(exdyn::version));
    file.add("isa", std::string_view(isa_name(selected_isa())));
    file.add("deck", input::to_yaml(deck_));
    file.add_value("mesh", mesh_hash_);
    file.add_value("next_step", next_step);
    StateSaver saver{file, ranks ? &pieced : nullptr};
    if (ranks) {
      visit_state(saver, whole.state, whole.contact_nodes, &whole.contact_rows);
      visit_blocks(saver, whole.blocks);
      visit_contact(saver, whole.contact, &whole.keys);
    } else {
      visit_state(saver, state_, contact_.nodes);
      visit_blocks(saver, model_.blocks);
      visit_contact(saver, contact_);
    }
    visit_loop(saver);
    file.add_value("loop/clock", clock_->saved());
    file.add("summary/warnings", join_lines(summary_.warnings));
    output::add_position(file, position);
  }
  file.commit();  // on many ranks every rank's part on disk before the name
  summary_.checkpoints.bytes = double(file.bytes_written());
  if (controls_.comm.root()) {
    // The oldest beyond `keep` go once the new one is whole.
    const auto found = list_checkpoints(directory_, deck_.name);
    const std::size_t keep = std::size_t(std::max(deck_.checkpoint.keep, 1));
    for (std::size_t k = 0; k + keep < found.size(); ++k)
      if (found[k].second != path) std::remove(found[k].second.c_str());
  }
  const double seconds = watch.seconds();
  summary_.checkpoints.seconds += seconds;
  summary_.checkpoints.largest_seconds = std::max(summary_.checkpoints.largest_seconds, seconds);
  summary_.checkpoints.last = path;
  slowest_checkpoint_ = std::max(slowest_checkpoint_, seconds);
  last_checkpoint_wall_ = run_watch_.seconds();
}

// Step n is done and its history row added: the checkpoint is written, then the step's
// fields too where the schedule would not write them (the checkpoint's position leaves
// them out, so a restart removes them; writing them runs the element pass again, which
// the checkpoint must not see).
void TimeLoop::stop_on_request(const std::string& why) {
  const long step = state_.step;
  const double time = state_.time;
  save_checkpoint(writer_->position());
  if (!output_step_) {
    ScopedTimer timer(summary_.phase_seconds.output);
    if (step % deck_.output.history_every != 0)
      writer_->add_history(history_row(), contact_history(contact_), force_rows());
    step_writer_->write(state_, clock_->next());
    writer_->flush();
  }
  std::string command = "exdyn run " + deck_.source_file;
  if (!controls_.output_directory.empty()) command += " --output " + controls_.output_directory;
  command += " --restart";
  throw RunStopped("stopped by " + why + " after step " + std::to_string(step) + ", time " +
                       format_time(time) + "; the checkpoint " + summary_.checkpoints.last +
                       " is written: go on with `" + command + "`",
                   step);
}

}  // namespace exdyn::solver
