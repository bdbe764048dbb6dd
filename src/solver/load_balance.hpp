// The weight of each chunk for the partition over the ranks with `exdyn run --weigh
// work` (docs/parallel.md, "Load balance"): its elements' work and the contact work of
// the slave points it holds.
//
// The costs are measured, since they range over two orders of magnitude (an element:
// 0.009 us for a hex8 row pack to 0.4 us for a hex20; a slave point: 0.05 us for a
// point far from any segment to 1.2 us for one sliding in contact): rank 0 times one
// element pass of each block and one pass of each contact pass at the initial state of
// the whole model, the best of three, and sends the costs to every rank, which then
// computes the same weights. The timing decides only which rank holds which chunk, so
// the results are the same bits whatever it measures.
#pragma once

#include <vector>

#include "common/mpi.hpp"
#include "common/nodal_vectors.hpp"
#include "solver/contact_setup.hpp"
#include "solver/model.hpp"

namespace exdyn::solver {

// Seconds a step of each chunk of the whole model (blocks one after the other): its
// elements' and its slave points' (a slave point counts in the first chunk that holds
// its node, or its slave segment's first node). Every rank calls it; the same result on
// every rank. dt: the first step (s), for the materials' rates.
std::vector<double> chunk_costs(const Model& model, const ContactModel& contact, const NodalVectors& velocity,
                                double dt, const mpi::Communicator& comm);

}  // namespace exdyn::solver
