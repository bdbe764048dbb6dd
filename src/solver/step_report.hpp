// What the time loop (solver/simulation.cpp) reports: the messages of its guards, the
// fields of a written step, the run summary's figures, and the figures of a step
// agreed over the ranks.
#pragma once

#include <array>
#include <csignal>
#include <string>
#include <utility>
#include <vector>

#include "common/mpi.hpp"
#include "output/result_writer.hpp"
#include "output/summary.hpp"
#include "solver/step_passes.hpp"

namespace exdyn::solver {

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
  void write(State& state, double dt);

 private:
  output::ResultWriter& writer_;
  const Model& model_;
  Decomposition& d_;
  NodalVectors velocity_;
  std::vector<double> von_mises_;
  NodalVectors contact_only_;  // with loads: f_contact alone (state.contact_force holds f_load too)
};

// The node with the largest |v|_1 (m/s), for a guard's message.
std::string describe_fastest_node(const Decomposition& d, const NodalVectors& velocity);
// The first node or element with a non-finite value (every rank calls it).
std::string describe_non_finite(const Model& model, Decomposition& d, State& state);
std::string format_time(double seconds);
std::string format_number(double value);
void summarise_contact(const ContactModel& contact, const contact::ContactStatistics& statistics,
                       output::RunSummary& summary);
// Small strain reads a rotation as a strain (docs/theory.md, "Finite strain"): once a
// small-strain part's stress reaches 10 % strain (|sigma| / E at a written step), the
// warning that says so (`when`: " at step ..."), else "". Every rank calls it (one
// gather: the largest ratio and its part over the ranks).
std::string small_strain_warning(const input::Deck& deck, const Model& model, const State& state,
                                 const mpi::Communicator& comm, const std::string& when);
// A prescribed velocity starts as a jump: a free neighbour of a driven node of equal
// mass m gets dt a <= 4 V in its first step at the stability limit, so the dt^2 a^2 term
// of the energy guard's E_mean can show up to 1/8 m (4 V)^2 = 2 m V^2 with nothing
// unstable. The guard's scale counts 2 sum m V^2 over the driven node components (J,
// over the ranks).
double prescribed_jump_energy(const Model& model, const mpi::Communicator& comm);
// The nodal update's sums, the element energies, the boundary reactions (in: this
// rank's sums and their compensations, out: the whole) and the stop asked for on any
// rank (`signal`: a signal's number, stop_at_wall_limit, or 0; the largest over the ranks).
NodalUpdate reduce_over_ranks(const mpi::Communicator& comm, NodalUpdate update, Energies& energy,
                              std::vector<std::array<double, 3>>& reactions,
                              const std::vector<std::array<double, 3>>& reaction_errors, int signal,
                              int& stop_requested);

// What a rank asks for beside a signal (above every signal's number; the largest
// wins): a checkpoint by checkpoint.every_seconds (no stop), a stop at --wall-limit.
inline constexpr int checkpoint_by_clock = 512;
inline constexpr int stop_at_wall_limit = 1024;
// The exchanges' figures over the ranks and each rank's (mpi.per_rank; one process:
// its memory and contact).
void summarise_ranks(const Decomposition& d, const ContactModel& contact, const output::PhaseSeconds& phases,
                     output::MpiSummary& out);

}  // namespace exdyn::solver
