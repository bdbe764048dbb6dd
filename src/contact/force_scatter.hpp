// The scatter of a contact pass's point forces onto the nodes (contact_pass.hpp):
// slave point p in contact writes its gap to its slave nodes (the smallest stays) and,
// pressed (gap < 0), adds w_I F to its slave nodes and -N_i F to its master segment's
// nodes, F = state.point_force[p]. Segments share nodes, so a node's sum depends on
// the order of its additions: one process adds them in slave point order, and so do
// both versions here, to the bit.
#pragma once

#include <cstddef>
#include <vector>

#include "common/nodal_vectors.hpp"
#include "contact/contact_pass.hpp"

namespace exdyn::contact {

// Every point's writes in slave point order, alone: the reference.
void scatter_in_point_order(const ContactSurfaces& surfaces, const ContactPassState& state,
                            NodalVectors& force, std::vector<double>& gap);

// The same writes on the threads, the points in chunks of `chunk` consecutive points.
// A node's first chunk (the lowest that writes it, found first) writes it on the
// threads, its points in order; the writes of later chunks to it follow, alone, in
// point order. So each node sees its additions in point order, as one process.
void scatter_by_chunks(const ContactSurfaces& surfaces, const ContactPassState& state, NodalVectors& force,
                       std::vector<double>& gap, std::size_t chunk, ScatterScratch& scratch);

// The same writes as records of the point's slots (on many ranks: distributed_contact.hpp
// adds them at the nodes' owners in the order of one process), slave slots 0..7,
// master slots 8..15.
void scatter_to_records(const ContactSurfaces& surfaces, const ContactPassState& state, RecordSink& records);

}  // namespace exdyn::contact
