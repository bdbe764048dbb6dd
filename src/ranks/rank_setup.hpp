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
// shares in one process's order. Each rank builds its contact from the contact faces
// near it alone: of each face the segments with a node it holds (a box's made one at a
// time from its lattice), with a halo of the other ranks' nodes of those segments, so
// that every sum over a held node's segments is whole and in one process's order; the
// figures of a whole surface (the largest inverse master mass, the stability bound of
// a fixed stiffness) are the largest over the ranks (ContactScope). A block takes the
// whole block's layout (parallelepipeds or not) and a 20-node block its groups of
// equal Jacobians, gathered with their points from the ranks' group starts
// (element::WholeBlock). No rank holds more than its part, one layer of a box's lattice
// (of a cylinder's or ball's blocks, with their sides and faces), one figure per chunk
// and an imported part's faces (rank 0 the part while it sets up): the same bits as
// one process.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "common/mpi.hpp"
#include "input/options.hpp"
#include "model/contact_setup.hpp"
#include "model/model.hpp"
#include "ranks/decomposition.hpp"
#include "ranks/partitioning.hpp"

namespace exdyn::solver {

struct RankSetup {
  LocalRun run;                         // this rank's model, velocities, decomposition, contact holders
  double critical_dt = 0.0;             // the whole model's stable step without the Courant factor, s
  std::size_t nodes = 0, elements = 0;  // of the whole model
  // The contact faces near this rank (ContactScope): their nodes (global ids,
  // ascending), a model of them alone (its node k is surface_nodes[k]: coordinates,
  // masses, fixed components, the cut faces of its parts) for build_contact, and whether
  // this rank holds each node; globalize_contact renumbers what build_contact builds.
  std::vector<std::uint32_t> surface_nodes;
  Model surfaces;
  std::vector<std::uint8_t> surface_held;
  // The contact-face nodes this rank holds (global ids, ascending), the ranks holding
  // each in run.contact_holders (distribute_contact).
  std::vector<std::uint32_t> contact_nodes;
  // A deck whose contact follows erosion (set_up_from_whole): the contact as one process
  // builds it (global ids), and contact_nodes all its nodes.
  std::optional<ContactModel> contact;
};

// The scope of build_contact on RankSetup::surfaces: the held nodes, and the largest
// of a figure over comm's ranks (MPI_Allreduce; collective).
ContactScope contact_scope(const RankSetup& setup, const mpi::Communicator& comm);

// Every rank calls it (collective over comm).
// weigh_by_work: the chunks weighed by their measured work (load_balance.hpp), timed
// on a first setup by elements, which is then dropped.
RankSetup set_up_rank(const input::Deck& deck, const mpi::Communicator& comm, Partitioning partitioning,
                      bool weigh_by_work);

// A deck with a contact that follows erosion (`surface: all` over a part that can fail,
// docs/contact.md) on many ranks: each segment of such a surface needs the life of the
// bricks on both its sides, and the surface's edges change with it, wherever the
// bricks lie. Every rank builds the whole model and its contact as one process does
// (the memory of one process a rank while it sets up), and cuts out its part
// (localize: the same partition as set_up_rank's); the contact's passes keep their
// whole surfaces (PassShare::whole). set_up_rank calls it for such a deck.
RankSetup set_up_from_whole(const input::Deck& deck, const mpi::Communicator& comm, Partitioning partitioning,
                            bool weigh_by_work);

// This rank's contact from its setup, global node ids: built on the faces near it and
// renumbered, or set_up_from_whole's.
ContactModel rank_contact(const input::Deck& deck, RankSetup& setup, double dt, double critical_dt,
                          const mpi::Communicator& comm);

// The pieces of set_up_rank that need no other rank, for the tests that hold them to
// the whole model's (tests/solver/test_decomposition.cpp): each chunk's colour in its
// block and its rank of `ranks` (blocks one after the other); the lumped masses of
// `nodes` (global ids, ascending); the contact faces' nodes and model, whole, or near
// the rank whose nodes (global ids, ascending) and model are given (RankSetup::
// surface_nodes, surfaces and surface_held).
struct SetupChunks {
  std::vector<int> colour, rank;
};
SetupChunks setup_chunks(const input::Deck& deck, int ranks, Partitioning partitioning);
std::vector<double> setup_masses(const input::Deck& deck, const std::vector<std::uint32_t>& nodes);
std::pair<std::vector<std::uint32_t>, Model> contact_faces_model(const input::Deck& deck);
RankSetup contact_faces_near(const input::Deck& deck, const std::vector<std::uint32_t>& nodes,
                             const Model& model);

// A contact model built on RankSetup::surfaces, renumbered to global node ids (the
// renumbering keeps the order, so sorted lists stay sorted).
void globalize_contact(ContactModel& contact, const std::vector<std::uint32_t>& surface_nodes);

}  // namespace exdyn::solver
