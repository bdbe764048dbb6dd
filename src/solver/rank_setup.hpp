// Setting up a run on many ranks without the whole model (docs/parallel.md, "Setup").
//
// Every rank walks the parts chunk by chunk, keeping only a chunk's centroid and
// colour (and for METIS the chunk graph): the partition and the colours of the whole
// model, the same on every rank and the same as decomposition.hpp computes from a
// whole model (localize, the reference the tests hold this to). A box (perturbed or
// not) is walked by numbers from its lattice, a cylinder or ball by numbers from its
// blocks (mesh::MappedLattice); an imported part is scattered: rank 0 alone reads the
// file, makes the part whole (mesh::build_part_mesh), walks it and sends each rank the
// chunks' figures, the part's faces and its piece of the part. Then each rank builds
// only its own elements and their nodes, and from the elements around its nodes (a
// halo of one element, never kept) their lumped masses, adding each node's element
// shares in one process's order. The contact surfaces are built from the contact
// faces alone. A block takes the whole block's layout (parallelepipeds or not) and a
// 20-node block its groups of equal Jacobians, gathered with their points from the
// ranks' group starts (element::WholeBlock). No rank holds more than its part, one
// layer of a box's lattice (of a cylinder's or ball's blocks, with their sides), one
// figure per chunk and the contact faces, rank 0 also an imported part while it sets
// up: the same bits as one process.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "common/mpi.hpp"
#include "input/options.hpp"
#include "solver/contact_setup.hpp"
#include "solver/decomposition.hpp"
#include "solver/model.hpp"
#include "solver/partitioning.hpp"

namespace exdyn::solver {

struct RankSetup {
  LocalRun run;                         // this rank's model, velocities, decomposition, contact holders
  double critical_dt = 0.0;             // the whole model's stable step without the Courant factor, s
  std::size_t nodes = 0, elements = 0;  // of the whole model
  // The contact faces' nodes (global ids, ascending) and a model of them alone (its
  // node k is surface_nodes[k]: coordinates, masses, fixed components, the faces of its
  // parts) for build_contact; globalize_contact renumbers what that builds.
  std::vector<std::uint32_t> surface_nodes;
  Model surfaces;
};

// Every rank calls it (collective over comm).
// weigh_by_work: the chunks weighed by their measured work (load_balance.hpp), timed
// on a first setup by elements, which is then dropped.
RankSetup set_up_rank(const input::Deck& deck, const mpi::Communicator& comm, Partitioning partitioning,
                      bool weigh_by_work);

// The pieces of set_up_rank that need no other rank, for the tests that hold them to
// the whole model's (tests/solver/test_decomposition.cpp): each chunk's colour in its
// block and its rank of `ranks` (blocks one after the other); the lumped masses of
// `nodes` (global ids, ascending); the contact faces' nodes and model.
struct SetupChunks {
  std::vector<int> colour, rank;
};
SetupChunks setup_chunks(const input::Deck& deck, int ranks, Partitioning partitioning);
std::vector<double> setup_masses(const input::Deck& deck, const std::vector<std::uint32_t>& nodes);
std::pair<std::vector<std::uint32_t>, Model> contact_faces_model(const input::Deck& deck);

// A contact model built on RankSetup::surfaces, renumbered to global node ids (the
// renumbering keeps the order, so sorted lists stay sorted).
void globalize_contact(ContactModel& contact, const std::vector<std::uint32_t>& surface_nodes);

}  // namespace exdyn::solver
