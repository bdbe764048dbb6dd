// The run summary NAME.json (../shared/spec/output.md), written at the end of
// every run, a failed one too.
#pragma once

#include <string>
#include <vector>

namespace exdyn::output {

struct PhaseSeconds {
  double element_forces = 0.0;
  double contact_global_search = 0.0;
  double contact_local_search = 0.0;
  double contact_forces = 0.0;
  double time_integration = 0.0;
  double output = 0.0;
  double guards = 0.0;  // the run-time checks of docs/stability.md (not in the spec's list: an addition)
  double contact_segmentation = 0.0;  // mortar: cutting slave segments into pieces (an addition too)
};

struct EnergySummary {
  double initial_total = 0.0;
  double final_total = 0.0;
  double max_relative_error = 0.0;  // max |E_total(t) - E_total(0)| / max(E seen)
  // At the last step, J (ours, after the spec's keys):
  double internal = 0.0;      // stored elastic energy plus plastic work
  double hourglass = 0.0;     // hourglass spring energy (hex8r)
  double plastic_work = 0.0;  // a part of internal
  double eroded = 0.0;        // the energy that left with eroded elements so far
  long eroded_elements = 0;   // elements failed and removed so far
};

struct ContactFigures {
  long projections = 0;
  double mean_iterations = 0.0;
  long max_iterations = 0;
  long not_converged = 0;
  long saddle_points = 0;
  double max_penetration_over_h = 0.0;
  double penalty_stiffness = 0.0;  // the largest node (or point) pair stiffness used, N/m
  long fallbacks = 0;              // failed projections settled again by local_search.fallback
};

// One contact pair's figures (contact.pairs.NAME).
struct ContactPairSummary {
  std::string name;
  std::string slave_points;  // "nodes" or "quadrature"
  std::string method;        // the local search method
  ContactFigures figures;
  double local_search_seconds = 0.0;  // wall time of the pair's local search, s
  double segmentation_seconds = 0.0;  // mortar: wall time of its segmentation, s
  double max_force = 0.0;             // largest |total force on the slave side| over the steps, N
  double friction_work = 0.0;         // dissipated by its friction, J
  // The step of the largest sum of the points' |F_n| (N) and the points pressed then.
  double peak_normal_force_sum = 0.0;
  long points_in_contact_at_peak = 0;
};

// One rigid wall's figures (contact.rigid_walls.NAME), an addition to the spec's keys.
struct WallSummary {
  std::string name;
  std::string slave_points;  // "nodes" or "quadrature"
  double max_force = 0.0;    // largest |force on the bodies| over the steps, N
  double max_penetration_over_h = 0.0;
  double penalty_stiffness = 0.0;  // the largest point stiffness used, N/m
  double friction_work = 0.0;      // J
};

struct ContactSummary : ContactFigures {
  std::vector<ContactPairSummary> pairs;  // deck order
  std::vector<WallSummary> walls;         // deck order
};

// The run-time guards (docs/stability.md); an addition to the spec's keys.
struct GuardSummary {
  long inversion_passes = 0;           // steps at which every element was checked for inversion
  double largest_energy_growth = 0.0;  // largest growth of the guard's energy / the largest energy seen
};

// Many ranks (docs/parallel.md): what one step's exchanges cost, over all ranks;
// an addition to the spec's mpi.ranks.
struct MpiSummary {
  long shared_nodes = 0;                // nodes held by more than one rank (counted once per holder)
  long messages_per_step = 0;           // force messages of one step, all ranks
  double bytes_per_step = 0.0;          // their bytes
  long contact_nodes = 0;               // ghost contact nodes, all ranks (the largest of each rank's)
  double exchange_seconds = 0.0;        // the longest time a rank waited in the exchanges, s
  std::string partition = "bisection";  // how the chunks were dealt (exdyn run --partition)
  std::string weigh = "elements";       // what the partition balanced (exdyn run --weigh)
  std::string setup = "whole";          // "by_rank": each rank built only its part (ranks/rank_setup.hpp)
  long edge_cut = 0;                    // shared nodes summed over pairs of chunks on different ranks
  // Each rank's figures (mpi.per_rank, one entry per rank): its peak resident memory,
  // its share of the contact (solver::ContactShareFigures) and its force messages.
  struct Rank {
    double peak_resident_mb = 0.0;
    double contact_nodes = 0.0;  // the contact nodes of its chunks
    double contact_points = 0.0, contact_segments = 0.0, ghost_segments = 0.0, ghost_nodes = 0.0;
    double contact_messages_per_step = 0.0, contact_bytes_per_step = 0.0;
    double force_messages_per_step = 0.0, force_bytes_per_step = 0.0;
    double wait_seconds = 0.0;     // waiting in the force and contact exchanges, s
    double element_seconds = 0.0;  // computing element forces (waits excluded), s
    double contact_seconds = 0.0;  // in its contact passes (searches, projections, forces), s
  };
  std::vector<Rank> per_rank;
};

// Restart checkpoints (docs/output.md, "Checkpoints"): the one a run went on from
// (restart), and those it wrote (checkpoints); additions to the spec's keys.
struct RestartSummary {
  long from_step = -1;     // the step the run went on at; < 0: not a restart
  std::string checkpoint;  // the file it went on from
};
struct CheckpointSummary {
  long written = 0;
  double seconds = 0.0;          // wall time of writing them all, s
  double largest_seconds = 0.0;  // of the slowest one, s
  double bytes = 0.0;            // the size of one (the last), bytes
  std::string last;              // the last one's file
};

struct RunSummary {
  std::string name;
  std::string status = "completed";  // "completed", "failed" or "stopped" (on request, after a checkpoint)
  std::string message;
  std::string exdyn_version;
  int threads = 1;  // per rank
  int ranks = 1;    // MPI ranks (mpi.ranks)
  MpiSummary mpi;
  std::string isa;  // the instruction set the element kernels ran with (common/isa.hpp)
  long nodes = 0;
  long elements = 0;
  long steps = 0;
  double dt = 0.0;      // the first step, s
  double dt_min = 0.0;  // the smallest step (the step follows the deformation: finite strain), s
  double end_time = 0.0;
  std::vector<std::string> warnings;  // what the run found questionable (also printed)
  double wall_seconds = 0.0;
  double element_cycles_per_second = 0.0;  // elements x steps / wall seconds of the time loop
  PhaseSeconds phase_seconds;
  EnergySummary energy;
  ContactSummary contact;
  GuardSummary guard_checks;
  RestartSummary restart;
  CheckpointSummary checkpoints;
};

// Writes the summary as JSON to `path` (atomically: temporary file + rename).
void write_summary(const std::string& path, const RunSummary& summary);

}  // namespace exdyn::output
