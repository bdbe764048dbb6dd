// exdyn: the command line (../shared/spec/cli.md). The one try/catch of the
// program: bad input or usage -> exit 2; a failed run -> exit 1; a run stopped on
// request after writing a checkpoint -> exit 3.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "app/project_command.hpp"
#include "common/errors.hpp"
#include "common/isa.hpp"
#include "common/mpi.hpp"
#include "common/version.hpp"
#include "input/deck_reader.hpp"
#include "mesh/mesh.hpp"
#include "model/mesh_quality.hpp"
#include "solver/simulation.hpp"

namespace {

constexpr int exit_success = 0;
constexpr int exit_run_failed = 1;
constexpr int exit_bad_input = 2;
constexpr int exit_stopped = 3;

std::vector<exdyn::input::Override> parse_overrides(const std::vector<std::string>& arguments) {
  std::vector<exdyn::input::Override> overrides;
  for (const auto& argument : arguments) overrides.push_back(exdyn::input::parse_override(argument));
  return overrides;
}

std::string format_duration(double seconds) {
  char text[32];
  if (seconds < 60.0)
    std::snprintf(text, sizeof text, "%.1fs", seconds);
  else if (seconds < 3600.0)
    std::snprintf(text, sizeof text, "%dm%02ds", int(seconds) / 60, int(seconds) % 60);
  else
    std::snprintf(text, sizeof text, "%dh%02dm", int(seconds) / 3600, (int(seconds) / 60) % 60);
  return text;
}

// One line, rewritten in place: step, time, dt, % done, ETA.
void print_progress(const exdyn::solver::Progress& p) {
  const double fraction = p.total_steps > 0 ? double(p.step) / double(p.total_steps) : 1.0;
  const double eta = fraction > 0.0 ? p.wall_seconds * (1.0 - fraction) / fraction : 0.0;
  std::fprintf(stderr, "\rstep %ld/%ld  t = %.6e s  dt = %.4e s  %5.1f %%  ETA %s   ", p.step, p.total_steps,
               p.time, p.dt, 100.0 * fraction, format_duration(eta).c_str());
  if (p.step == p.total_steps) std::fputc('\n', stderr);
  std::fflush(stderr);
}

// SIGINT (Ctrl-C) and SIGTERM ask the run to finish its step, write it and a
// checkpoint, and stop (exit 3); a second one ends the process at once (the files
// stay valid, the last whole checkpoint stays: docs/stability.md).
volatile std::sig_atomic_t stop_signal = 0;

// The process's start, for --wall-limit (before MPI's and the deck's setup).
const std::chrono::steady_clock::time_point process_start = std::chrono::steady_clock::now();

extern "C" void request_stop(int signal_number) {
  if (stop_signal != 0) {
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
  }
  stop_signal = signal_number;
}

// exdyn --version: the version, and the instruction sets of the element kernels.
std::string version_text() {
  std::string text = std::string("exdyn ") + exdyn::version + "\nelement kernels: built for";
  for (const exdyn::Isa isa : exdyn::all_isas)
    text += std::string(isa == exdyn::all_isas.front() ? " " : ", ") + exdyn::isa_name(isa) + " (" +
            exdyn::isa_description(isa) + ")";
  const exdyn::Isa best = exdyn::best_available_isa();
  text += std::string("; this CPU runs up to ") + exdyn::isa_name(best);
  try {
    const exdyn::Isa chosen = exdyn::selected_isa();
    text += std::string("; a run uses ") + exdyn::isa_name(chosen) + (chosen == best ? "" : " (EXDYN_ISA)");
  } catch (const exdyn::InputError& error) {
    text += std::string("; ") + error.what();
  }
  return text;
}

struct RunArguments {
  std::string deck;
  std::string output;
  std::vector<std::string> sets;
  int threads = 0;
  std::string isa;  // empty: EXDYN_ISA, else the best this CPU runs
  std::string partition = "bisection";
  std::string weigh = "elements";
  bool quiet = false;
  bool restart = false;
  std::string restart_file;  // empty: the newest checkpoint
  double wall_limit = 0.0;
};

// On many ranks (mpirun) every rank runs the deck; rank 0 alone prints.
int run_command(const RunArguments& arguments, const exdyn::mpi::Communicator& comm) {
  if (!arguments.isa.empty()) exdyn::select_isa(exdyn::parse_isa(arguments.isa, "--isa"));
  const exdyn::input::Deck deck = exdyn::input::read_deck(arguments.deck, parse_overrides(arguments.sets));
  exdyn::solver::RunControls controls;
  controls.output_directory = arguments.output;
  controls.threads = arguments.threads;
  // Every core by default; on many ranks each gets its share of its machine's cores.
  if (controls.threads == 0 && comm.distributed())
    controls.threads =
        std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / comm.ranks_on_this_machine);
  controls.comm = comm;
  controls.partitioning = arguments.partition == "metis" ? exdyn::solver::Partitioning::metis
                                                         : exdyn::solver::Partitioning::bisection;
  controls.weigh_by_work = arguments.weigh == "work";
  controls.stop_signal = &stop_signal;
  controls.restart = arguments.restart;
  controls.restart_file = arguments.restart_file;
  controls.wall_limit = arguments.wall_limit;
  controls.started = process_start;
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
  if (!arguments.quiet && comm.root() && isatty(STDERR_FILENO)) controls.on_progress = print_progress;
  try {
    const exdyn::output::RunSummary summary = exdyn::solver::run_simulation(deck, controls);
    // A local search that failed, and its fallback too, gives no contact force (docs/stability.md):
    // say so, even with --quiet.
    if (!comm.root()) return exit_success;
    for (const std::string& warning : summary.warnings)
      std::fprintf(stderr, "exdyn: warning: %s\n", warning.c_str());
    if (const long failed = summary.contact.not_converged + summary.contact.saddle_points; failed > 0)
      std::fprintf(
          stderr,
          "exdyn: warning: %ld of %ld local contact searches failed (%ld not converged, %ld on a saddle or "
          "maximum) and gave no contact force; see contact in %s.json\n",
          failed, summary.contact.projections, summary.contact.not_converged, summary.contact.saddle_points,
          deck.name.c_str());
    if (!arguments.quiet)
      std::printf(
          "%s: completed %ld steps of dt = %.6g s in %.3f s (%.3g element-cycles/s); results in %s/%s.xmf\n",
          summary.name.c_str(), summary.steps, summary.dt, summary.wall_seconds,
          summary.element_cycles_per_second,
          (arguments.output.empty() ? deck.output.directory : arguments.output).c_str(), deck.name.c_str());
  } catch (const exdyn::RunFailure&) {
    if (controls.on_progress) std::fputc('\n', stderr);
    throw;
  } catch (const exdyn::RunStopped&) {
    if (controls.on_progress) std::fputc('\n', stderr);
    throw;
  }
  return exit_success;
}

}  // namespace

int main(int argc, char** argv) {
  // MPI when mpirun started us (common/mpi.hpp), else nothing of it.
  std::unique_ptr<exdyn::mpi::Session> session;
  try {
    session = std::make_unique<exdyn::mpi::Session>();
  } catch (const std::exception& error) {
    std::cerr << "exdyn: error: " << error.what() << '\n';
    return exit_bad_input;
  }
  const exdyn::mpi::Communicator world = session->world();
  CLI::App app{"exdyn: explicit dynamics with penalty node-to-segment contact"};
  app.set_version_flag("--version", version_text());
  app.require_subcommand(1);

  RunArguments run_arguments;
  CLI::App* run = app.add_subcommand("run", "Run a deck and write NAME.h5, NAME.xmf and NAME.json");
  run->add_option("deck", run_arguments.deck, "The input deck (YAML)")->required();
  run->add_option("--output", run_arguments.output, "Output directory (overrides output.directory)");
  run->add_option("--set", run_arguments.sets, "Override one deck value before validation: KEY=VALUE")
      ->allow_extra_args(false);
  run->add_option(
         "--threads", run_arguments.threads,
         "Threads (default 0: every core; under mpirun the cores of the machine shared by its ranks); the "
         "results are the same bits for any number")
      ->check(CLI::Range(0, 4096));
  run->add_option("--isa", run_arguments.isa,
                  "Instruction set of the element kernels: x86-64-v2 (SSE4.2), x86-64-v3 (AVX2 + FMA) or "
                  "x86-64-v4 (AVX-512); default: EXDYN_ISA, else the best this CPU runs");
  run->add_option("--partition", run_arguments.partition,
                  "How the chunks are dealt to MPI ranks: bisection (recursive coordinate bisection, the "
                  "default) or metis (METIS on the graph of chunks that share nodes); results are the same "
                  "bits either way")
      ->check(CLI::IsMember({"bisection", "metis"}))
      ->capture_default_str();
  run->add_option("--weigh", run_arguments.weigh,
                  "What the partition balances over MPI ranks: elements (the default: element counts, the "
                  "same partition every run) or work (each chunk's element and contact work, timed at the "
                  "start); results are the same bits either way")
      ->check(CLI::IsMember({"work", "elements"}))
      ->capture_default_str();
  run->add_flag("--quiet", run_arguments.quiet, "No progress line and no summary line");
  run->add_option(
         "--restart", run_arguments.restart_file,
         "Go on from the newest checkpoint of the run in the output directory, or from the one named; "
         "writes on into the same NAME.h5 (the same bits as a run never stopped)")
      ->expected(0, 1);
  run->add_option("--wall-limit", run_arguments.wall_limit,
                  "Write a checkpoint and stop (exit 3) before this many wall seconds have passed")
      ->check(CLI::PositiveNumber);

  std::string check_deck;
  std::vector<std::string> check_sets;
  CLI::App* check = app.add_subcommand("check", "Validate a deck and print it with every default filled in");
  check->add_option("deck", check_deck, "The input deck (YAML)")->required();
  check->add_option("--set", check_sets, "Override one deck value before validation: KEY=VALUE")
      ->allow_extra_args(false);

  exdyn::app::ProjectCommandOptions project_options;
  CLI::App* project =
      app.add_subcommand("project", "Run the local contact search on stand-alone cases (CSV)");
  project->add_option("cases", project_options.cases_file, "The cases file (YAML)")->required();
  project->add_option("--method", project_options.methods, "M[,M...] or all")->capture_default_str();
  project->add_option("--initial-guess", project_options.initial_guess, "lsp, center, corners, all or a,b")
      ->capture_default_str();
  project->add_option("--tolerance", project_options.tolerance, "Stop when the step in xi is at most this")
      ->capture_default_str();
  project->add_option("--max-iterations", project_options.max_iterations, "Iteration limit")
      ->capture_default_str();
  project
      ->add_option("--timing-seconds", project_options.timing_seconds,
                   "Least total time spent timing each projection (0: time one run)")
      ->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int status = app.exit(error);
    return status == 0 ? exit_success : exit_bad_input;
  }

  run_arguments.restart = run->count("--restart") > 0;
  try {
    if (*run) return run_command(run_arguments, world);
    if (*check) {
      const exdyn::input::Deck deck = exdyn::input::read_deck(check_deck, parse_overrides(check_sets));
      std::cout << exdyn::input::to_yaml(deck);
      for (const std::string& warning : exdyn::input::deck_warnings(deck))
        std::fprintf(stderr, "exdyn: warning: %s\n", warning.c_str());
      // The mesh, as YAML comments: a user sees a bad mapped mesh before running it.
      const exdyn::mesh::Mesh mesh = exdyn::mesh::build_mesh(deck);
      const auto quality = exdyn::solver::mesh_quality(mesh);
      std::cout << "# mesh: " << mesh.node_count() << " nodes, " << mesh.element_count() << " elements\n";
      for (std::size_t p = 0; p < quality.size(); ++p)
        std::cout << "# part " << deck.parts[p].name << ": " << mesh.parts[p].element_count << " elements, "
                  << mesh.parts[p].node_count << " nodes, volume " << quality[p].volume
                  << " m^3, smallest scaled Jacobian " << quality[p].smallest_scaled_jacobian << " (element "
                  << quality[p].worst_element << ")\n";
      return exit_success;
    }
    if (*project) {
      exdyn::app::run_project_command(project_options, std::cout);
      return exit_success;
    }
  } catch (const exdyn::InputError& error) {
    // Bad input is the same on every rank (the same deck): rank 0 says it, all exit.
    if (world.root()) std::cerr << "exdyn: error: " << error.what() << '\n';
    return exit_bad_input;
  } catch (const exdyn::RunStopped& stopped) {
    if (world.root()) std::cerr << "exdyn: " << stopped.what() << '\n';
    return exit_stopped;
  } catch (const exdyn::RunFailure& failure) {
    // The guards and the stop signals are agreed by all ranks, which fail together.
    if (world.root()) std::cerr << "exdyn: run failed: " << failure.what() << '\n';
    return exit_run_failed;
  } catch (const std::exception& error) {
    // An error of one rank (a file, MPI): the others may be waiting for it, so end them all.
    if (world.distributed()) {
      std::cerr << "exdyn: run failed on rank " << world.rank << ": " << error.what() << '\n';
      session->abort(exit_run_failed);
    }
    std::cerr << "exdyn: run failed: " << error.what() << '\n';
    return exit_run_failed;
  }
  return exit_bad_input;
}
