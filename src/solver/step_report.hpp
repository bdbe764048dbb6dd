// What the time loop (solver/simulation.cpp) reports: the messages of its guards, the
// fields of a written step, the run summary's figures, and the figures of a step
// agreed over the ranks.
#pragma once

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
// The nodal update's sums, the element energies and the stop signal over the ranks.
NodalUpdate reduce_over_ranks(const mpi::Communicator& comm, NodalUpdate update, Energies& energy,
                              const volatile std::sig_atomic_t* stop_signal, int& stop_requested);
// The exchanges' figures over the ranks and each rank's (mpi.per_rank; one process:
// its memory and contact).
void summarise_ranks(const Decomposition& d, const ContactModel& contact, const output::PhaseSeconds& phases,
                     output::MpiSummary& out);

}  // namespace exdyn::solver
