// The contact's state in a restart checkpoint on many ranks (docs/output.md,
// "Checkpoints"; solver/checkpoint_ranks.cpp). A checkpoint holds one process's
// numbering: each pass's slave points by ascending key (distributed_contact.hpp), its
// segments by their index in the whole pass, its moving nodes by global id. Each rank
// holds its own points in its view's numbering; gather_contact makes the whole on rank
// 0, and restore_contact gives each rank of a run on any number of ranks its points'
// state, and a view of every segment that state names (the own segments, and the
// others from their owners), so that its next steps compute the same bits as the run
// that never stopped.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/nodal_vectors.hpp"
#include "model/contact_setup.hpp"
#include "ranks/distributed_contact.hpp"

namespace exdyn::solver {

// The contact's state in one process's numbering on rank 0 (`whole`: each pair's passes
// and states, each wall's state, their figures; elsewhere unset), with each pass's
// point keys (pairs' passes, then the walls). Collective over dc.comm.
void gather_contact(const ContactModel& contact, DistributedContact& dc, ContactModel& whole,
                    std::vector<std::vector<std::uint64_t>>& keys);

// This rank's arrays a restart view is made from.
struct RestartNodes {
  const std::vector<std::uint32_t>& global_node;
  const NodalVectors& x_ref;
  const std::vector<double>& mass;
  const NodalVectors& u;
  const NodalVectors& v;
};

// The contact's state from `whole` (read from a checkpoint on every rank) into this
// rank's passes and views. Collective over dc.comm.
void restore_contact(const ContactModel& whole, const std::vector<std::vector<std::uint64_t>>& keys,
                     ContactModel& contact, DistributedContact& dc, const RestartNodes& nodes);

}  // namespace exdyn::solver
