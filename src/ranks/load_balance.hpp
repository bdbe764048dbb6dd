// The weight of each chunk for the partition over the ranks with `exdyn run --weigh
// work` (docs/parallel.md, "Load balance"): its elements' work and the contact work of
// the slave points it holds.
//
// The costs are measured, since they range over two orders of magnitude (an element:
// 0.009 us for a hex8 row pack to 0.4 us for a hex20; a slave point: 0.05 us for a
// point far from any segment to 1.2 us for one sliding in contact): one element pass of
// each block and one pass of each contact pass at the initial state, the best of three,
// the same costs then on every rank, which computes the same weights. A run times them
// on a first setup of the ranks' parts (rank_setup.cpp: element_costs, contact_costs,
// add_point_costs); chunk_costs times a whole model (on rank 0), for localize. The timing
// decides only which rank holds which chunk, so the results are the same bits whatever
// it measures.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "common/mpi.hpp"
#include "common/nodal_vectors.hpp"
#include "model/contact_setup.hpp"
#include "model/model.hpp"

namespace exdyn::solver {

// Seconds a step of each chunk of the whole model (blocks one after the other): its
// elements' and its slave points' (a slave point counts in the first chunk that holds
// its node, or its slave segment's first node). Every rank calls it; the same result on
// every rank. dt: the first step (s), for the materials' rates.
std::vector<double> chunk_costs(const Model& model, const ContactModel& contact, const NodalVectors& velocity,
                                double dt, const mpi::Communicator& comm);

// Its pieces, for a model that is a rank's part (rank_setup.cpp). Seconds of one
// element pass of each block per element (the best of three; dt for the materials'
// rates), and of one contact pass per slave point (pairs' passes, then walls; at u = 0
// with the velocities given, on the model the contact's node ids index).
std::vector<double> element_costs(const Model& model, double dt);
std::vector<double> contact_costs(const Model& model, const ContactModel& contact,
                                  const NodalVectors& velocity);
// chunk[chunk_of_node(node)] += each slave point's pass cost (pass_costs: contact_costs'
// order), the point counted at its node or at its slave segment's first node.
void add_point_costs(const ContactModel& contact, const std::vector<double>& pass_costs,
                     const std::function<std::size_t(std::uint32_t)>& chunk_of_node,
                     std::vector<double>& chunk);

}  // namespace exdyn::solver
