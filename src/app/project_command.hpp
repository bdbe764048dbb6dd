// `exdyn project CASES.yaml`: the local contact search on stand-alone cases,
// CSV on standard output (../shared/spec/cli.md).
//
// One row per case x method x initial guess, cases in file order, then methods
// in the order given (`all`: the order of contact::search_method_names), then
// initial guesses in the order lsp, center, corner1..corner4.
// Columns: id,method,initial_guess,xi1,xi2,converged,iterations,evaluations,
//          stationary,inside,distance,gap,nanoseconds
//  - initial_guess: `lsp` (one least-squares step from the centre), `center`,
//    `corner1`..`corner4` for (-1,-1) (1,-1) (1,1) (-1,1) (the node order), or
//    "a;b" for a point given by --initial-guess a,b or by the case's own
//    `initial_guess` key (a semicolon: no comma inside a CSV field);
//  - xi1, xi2, distance, gap: 17 significant digits (%.17g);
//  - converged, inside: 0 or 1; stationary: minimum, saddle, maximum or none;
//  - nanoseconds: wall time of one projection: 5 batches of repetitions, each
//    of at least timing_seconds / 5, and the least batch average (the least
//    disturbed by other work); the initial guess's own LSP step is not timed.
#pragma once

#include <ostream>
#include <string>

namespace exdyn::app {

struct ProjectCommandOptions {
  std::string cases_file;
  std::string methods = "bfgs";  // M[,M...] or "all"
  // lsp | center | corners | all | "a,b" (also "a;b"); empty (not given): the
  // case's own `initial_guess` when it has one, otherwise lsp.
  std::string initial_guess;
  double tolerance = 1.0e-10;      // > 0
  int max_iterations = 100;        // >= 1
  double timing_seconds = 1.0e-3;  // minimum total time per timed projection; 0: time one run
};

// Runs every case x method x initial guess and writes the CSV to `out`.
// Throws InputError on a bad cases file or option (exit status 2).
void run_project_command(const ProjectCommandOptions& options, std::ostream& out);

}  // namespace exdyn::app
