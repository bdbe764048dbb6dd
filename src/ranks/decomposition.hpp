// Domain decomposition for many ranks (docs/parallel.md).
//
// The unit of work is a chunk of an element block (element_chunk consecutive
// elements, the unit of the threaded schedule): the chunks are split among the ranks
// by recursive coordinate bisection of their centroids (or METIS), and each rank keeps
// its chunks as blocks of their own (the same kernels, packs and colours) and the nodes
// they touch, numbered locally in ascending global order: built by each rank alone
// (rank_setup.hpp), or cut from a whole model (localize, element::slice_block: the
// reference the unit tests hold the rank setup to). A
// node touched by the chunks of several ranks is shared; each of them holds it and
// computes its update, and the lowest of them owns it (counts its energy, writes it).
//
// The internal force of a node is the sum of its chunks' forces, added colour by
// colour (on one rank, the colours one after the other). On many ranks that sum is
// passed along: the rank of a shared node's first chunk adds it and sends the running
// sum to the rank of the next chunk (a non-blocking message per neighbour and colour),
// which goes on from it, and the last one sends the total to every other holder. So
// every node gets the same additions in the same order as on one rank: the fields are
// the same bits. While a rank waits for a colour's running sums it computes that
// colour's chunks that need none (the interior work).
//
// Contact is distributed too (distributed_contact.hpp): each rank searches its own
// slave points against the master segments near them.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "common/mpi.hpp"
#include "common/nodal_vectors.hpp"
#include "input/options.hpp"
#include "model/model.hpp"
#include "ranks/distributed_contact.hpp"
#include "ranks/partitioning.hpp"

namespace exdyn::solver {

// The rank of each chunk of each block of the (whole) model, blocks one after the
// other. bisection: recursive coordinate bisection of the chunk centroids. Each cut goes across
// the longest side of the box of its chunks and is placed so that the two sides get
// elements in proportion to their ranks; the chunks are taken block by block (in the
// order of the blocks' means along that side) and, within a block, along the block's
// own longest side, so a cut runs between parts or straight across one. Ties are
// broken by chunk number: every rank computes the same partition. Throws InputError
// when there are more ranks than chunks.
// metis: the graph whose vertices are the chunks, weighted by their elements, and whose
// edges join chunks that share nodes, weighted by the nodes they share, cut by
// METIS_PartGraphKway (recursive for 2 ranks) into parts of equal weight within 3 %,
// with the fewest shared nodes METIS finds; its seed is fixed, so every rank computes
// the same partition. Throws InputError when a part would be empty.
// costs: each chunk's seconds a step (load_balance.hpp), to weigh the chunks by instead
// of their elements; empty: by their elements.
std::vector<int> partition_chunks(const Model& model, int ranks,
                                  Partitioning partitioning = Partitioning::bisection,
                                  const std::vector<double>& costs = {});

// The bisection of partition_chunks on the chunks' centroids (m), weights and blocks
// (blocks one after the other), for a model that no rank holds whole (rank_setup.hpp).
// elements: the model's, for the error when there are more ranks than chunks.
std::vector<int> bisect_chunks(const std::vector<std::array<double, 3>>& centroid,
                               const std::vector<double>& weight, const std::vector<std::uint32_t>& block_of,
                               int ranks, std::size_t elements);
// The chunks' weights (their elements) made their measured costs (seconds a step,
// load_balance.hpp) in elements of the mean chunk's cost per element, at least 1 each.
void weigh_by_costs(std::vector<double>& weight, const std::vector<double>& costs);
// Throws InputError when `ranks` ranks cannot each get one of `chunks` chunks.
void check_rank_count(int ranks, std::size_t chunks, std::size_t elements);

// The graph of chunks (blocks one after the other): for each chunk its neighbours, the
// chunks sharing a node with it (ascending), each with the number of nodes they share.
struct ChunkGraph {
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> neighbours;  // (chunk, shared nodes)
};
// The METIS partition of partition_chunks on the graph and the chunks' weights (the
// same on every rank: METIS's seed is fixed). Throws InputError when METIS fails or
// leaves a rank without a chunk.
std::vector<int> metis_chunks(const ChunkGraph& graph, const std::vector<double>& weight, int ranks);

// The figures of a partition (docs/parallel.md, "Partitions"): the chunk graph's edge
// cut (the shared nodes summed over the pairs of chunks on different ranks) and the
// nodes used by more than one rank.
struct PartitionFigures {
  long edge_cut = 0;
  long shared_nodes = 0;
};
PartitionFigures partition_figures(const Model& model, const std::vector<int>& chunk_rank);

// The rows of one dataset (nodes or elements) this rank writes, and how the values
// of its owned items travel there: rank r writes rows [N r / P, N (r + 1) / P).
struct RowExchange {
  std::size_t begin = 0, end = 0;         // this rank's rows
  std::vector<std::uint32_t> send_items;  // local ids of the owned items, ascending global id
  std::vector<int> send_counts, send_displacements, receive_counts, receive_displacements;  // items
  std::vector<std::uint32_t> receive_rows;  // each received item's row minus `begin`
};

struct Decomposition {
  mpi::Communicator comm;
  std::size_t global_nodes = 0, global_elements = 0;
  std::vector<std::uint32_t> global_node;     // local node -> global node, ascending
  std::vector<std::uint32_t> global_element;  // local element -> global element
  std::vector<std::uint8_t> owned;            // per local node: 1 if this rank owns it
  // The whole model's blocks (one per part; a local block's is its elements' part): the
  // first global element and the elements of each (a checkpoint's chunks).
  std::vector<std::uint32_t> block_first_element, block_elements;

  // The force exchange of each block, per colour step k = 0 .. colours (the last:
  // the totals): the running sums received before colour k's waiting chunks, the
  // chunks that need none (computed first), and the sums sent after colour k (for
  // the receivers' step k + 1). Nodes of a message in ascending global order.
  struct Message {
    int rank = 0;
    std::vector<std::uint32_t> nodes;  // local ids
    std::vector<double> values;        // 3 per node: the buffer
  };
  struct ColourStep {
    std::vector<Message> receive, send;
    std::vector<std::uint32_t> free_chunks, waiting_chunks;  // local chunks of the colour
    int tag = 0;                                             // of the messages received at this step
  };
  std::vector<std::vector<ColourStep>> steps;  // [block][k]
  std::size_t shared_nodes = 0;                // nodes held by more than one rank
  Partitioning partitioning = Partitioning::bisection;
  bool weighed_by_work = false;  // the chunks weighed by their measured work (load_balance.hpp)
  bool set_up_by_rank = false;   // each rank built only its part (rank_setup.hpp), not the whole model
  long edge_cut = 0;             // of the whole partition (partition_figures), the same on every rank

  RowExchange node_rows, element_rows;

  // The contact's shares and exchanges (distributed_contact.hpp).
  DistributedContact contact;

  // Requests of the exchanges in flight.
  std::vector<MPI_Request> receives, sends;
  double exchange_seconds = 0.0;  // waited for the force messages and the contact's, s
};

// The part of a run one rank holds: its model (local numbering) and initial velocities.
struct LocalRun {
  Model model;
  NodalVectors initial_velocity;
  Decomposition decomposition;
  // The ranks whose chunks hold each node of `contact_nodes` (ascending; the first is
  // its owner), for the contact's distribution (distributed_contact.hpp).
  std::vector<std::vector<int>> contact_holders;
};

// The pieces of localize that a rank building only its own part (rank_setup.hpp) shares.
// How the owners' items (owner_of(global id) for this rank's rows) reach the ranks
// that write their rows. `mine`: this rank's owned items (local ids; sorted here by
// global id, global_of).
RowExchange row_exchange(const mpi::Communicator& comm, std::size_t n,
                         const std::function<int(std::size_t)>& owner_of, std::vector<std::uint32_t> mine,
                         const std::vector<std::uint32_t>& global_of);
// d.steps, d.owned and d.shared_nodes from the (colour, rank) of every chunk on each
// local node (chain, in any order), the global block of each local node, and the
// colours of each global block.
void plan_force_exchange(Decomposition& d, int me, std::vector<std::vector<std::pair<int, int>>> chain,
                         const std::vector<std::uint32_t>& block_of, const std::vector<std::size_t>& colours);
// Splits each colour's chunks of this rank's blocks (m.blocks: one per global block with
// chunks here, my_chunks[b] its global chunks) into those that wait for a running sum
// and those that do not, and keeps d.steps for those blocks only.
void split_colour_steps(const std::vector<std::vector<std::uint32_t>>& my_chunks, const Model& m,
                        Decomposition& d);

// Every node of the faces of the deck's contact pairs (global ids, ascending).
std::vector<std::uint32_t> contact_face_nodes(const input::Deck& deck, const mesh::Mesh& mesh);

// Cuts the global model into this rank's part: a block per global block with chunks
// here, and the nodes of those chunks; and finds the holders of each of
// `contact_nodes` (global ids, ascending). Runs set up rank by rank (rank_setup.hpp);
// this is the reference the unit tests hold that to.
LocalRun localize(const Model& global, const std::vector<std::uint32_t>& contact_nodes,
                  const NodalVectors& global_initial_velocity, const mpi::Communicator& comm,
                  Partitioning partitioning = Partitioning::bisection, const std::vector<double>& costs = {});

// The global id of local node `node` (itself on one rank).
inline std::uint32_t global_node_id(const Decomposition& d, std::uint32_t node) {
  return d.global_node.empty() ? node : d.global_node[node];
}
inline std::uint32_t global_element_id(const Decomposition& d, std::uint32_t element) {
  return d.global_element.empty() ? element : d.global_element[element];
}

// f_int (N) of this rank's blocks with the running sums of the shared nodes passed
// along (the header); returns the rank's element energies. Every rank calls it.
element::ElementEnergies add_forces_across_ranks(const Model& model, Decomposition& d, const NodalVectors& u,
                                                 NodalVectors& f_int, double* stress);

// The rows this rank writes of a nodal vector field, from the owners: as vectors, or
// into `rows` as (rows, 3) row-major (node_rows.end - node_rows.begin rows, the
// file's layout); and of a field of k values per element (stress: 6) or per node
// (k = 1, `nodal`) into `rows`, k a row.
void rows_of(Decomposition& d, const NodalVectors& local, NodalVectors& rows);
void rows_of(Decomposition& d, const NodalVectors& local, double* rows);
void rows_of(Decomposition& d, const double* local, int k, bool nodal, double* rows);

// This rank's rows of the mesh (node_rows, element_rows), for the output: the
// coordinates, and per element its nodes (global ids), part and node count, from the
// ranks that hold them; no rank gathers the whole mesh.
struct MeshRows {
  NodalVectors x_ref;
  std::vector<std::uint32_t> connectivity;
  std::vector<std::int32_t> element_part;
  std::vector<std::uint8_t> element_nodes;
};
MeshRows mesh_rows(Decomposition& d, const mesh::Mesh& local);

// Messages and bytes of one step's force exchange on this rank (docs/parallel.md).
struct HaloFigures {
  std::size_t shared_nodes = 0, messages_sent = 0, bytes_sent = 0;
};
HaloFigures halo_figures(const Decomposition& d);

}  // namespace exdyn::solver
