// Contact on many ranks (docs/parallel.md, "Contact across ranks").
//
// Each rank owns the slave points and the master segments of its elements: a slave
// node is its node's owner's (the lowest rank holding it), a segment (a master
// segment, or the slave segment of a Gauss point) the lowest rank holding all its
// nodes. A pass runs on each rank as on one process (contact::run_contact_pass), on a
// view: the rank's own slave points against its own segments and the ghost segments
// other ranks sent it at the last candidate search. At each search the ranks swap the
// boxes of their slave points (box exchange: one MPI_Allgather of six numbers a rank
// and pass); a rank sends each of its segments whose box, inflated by the capture
// distance, overlaps another rank's box, with the nodes of that segment the receiver
// does not hold. Between searches those nodes' u and v come each step from the
// segment's owner. A candidate of one process lies inside its segment's inflated box,
// so each rank finds exactly the candidates of its points that one process finds.
//
// The forces and gaps come out as records (contact_pass.hpp) and go to each node's
// owner, which adds them in the order of one process (pass after pass, slave point
// after slave point); the owner sends the total of a shared node to its other holders.
// So every field is the same bits as one process's. The pass's figures (the force
// histories, the statistics of the summary, the contact work) are summed over the
// ranks in rank order: the histories differ from one process in the last bits.
#pragma once

#include <cstdint>
#include <vector>

#include "common/mpi.hpp"
#include "common/nodal_vectors.hpp"
#include "contact/contact_pass.hpp"
#include "model/contact_setup.hpp"
#include "model/model.hpp"

namespace exdyn::solver {

// The nodes one pass works on, on this rank: first (`fixed` of them) the nodes of its
// own slave points and segments, held here, then those of the ghost segments, each
// held here or a ghost (local -1) whose u and v arrive each step. Global ids ascend in
// each of the two parts.
struct ContactStore {
  std::size_t fixed = 0;
  std::vector<std::uint32_t> global;
  std::vector<std::int64_t> local;  // local node id, or -1: a ghost
  std::vector<int> owner;           // the node's owner (its forces go there)
  NodalVectors x_ref, u, v;         // m, m, m/s
  std::vector<double> mass;         // kg
};

// Nodes travelling to or from one rank each step, in a fixed order.
struct NodeLink {
  int rank = 0;
  int tag = 0;
  std::vector<std::uint32_t> nodes;  // sent: local ids; received: store ids
  std::vector<double> buffer;
};

// One pass (a pair's, or a rigid wall's) on this rank.
struct PassShare {
  std::uint64_t index = 0;  // the pass's place in the order of one process
  bool edges = false;       // the pass has contact at folds (ContactSurfaces::edges)
  // This rank's slave points and segments (global node ids).
  contact::ContactSurfaces own;
  std::vector<std::uint64_t> point_keys;   // each own point's index in the whole pass
  std::vector<std::uint32_t> segment_ids;  // each own segment's index in the whole pass
  // From the last candidate search: the view the pass runs on (store node ids; its
  // segments: own and ghost, by ascending index in the whole pass) and the traffic.
  contact::ContactSurfaces view;
  std::vector<std::uint32_t> known;  // whole-pass index of each view segment
  ContactStore store;
  std::vector<NodeLink> ghost_sends, ghost_receives;
  std::size_t ghost_segments = 0, ghost_nodes = 0;  // in the view and the store
  double local_friction_work = 0.0;                 // this rank's points', J (the state holds all ranks')
  contact::RecordSink sink;  // the pass's records of a step (kept: no allocation a step)
  // A surface that follows erosion (ContactSurfaces::segment_element): the whole pass
  // (global node ids; every rank the same), whose segments and points the elements'
  // life brings on and off the surface, each own point's index in it, and whether it
  // changed since the last search (then the pass searches again at once).
  contact::ContactSurfaces whole;
  std::vector<std::uint32_t> whole_point;
  bool opened = false;
};

// This rank's share of the contact (docs/output.md, mpi.per_rank), summed over the
// passes: its slave points, the segments of its views (own and ghost), the ghost
// segments and nodes, each the largest of the run; the bytes and messages it sent in
// the contact's exchanges per step, and its time waiting in them.
struct ContactShareFigures {
  double points = 0, segments = 0, ghost_segments = 0, ghost_nodes = 0;
  double messages_per_step = 0, bytes_per_step = 0, wait_seconds = 0;
};

struct DistributedContact {
  mpi::Communicator comm;
  std::vector<PassShare> passes;                             // the pairs' passes, then the walls
  std::vector<contact::ContactStatistics> local_statistics;  // this rank's, per pair then per wall
  // The contact nodes held here (global ids, ascending) and the ranks holding each.
  std::vector<std::uint32_t> held;
  std::vector<std::vector<int>> holders;
  // Totals of shared contact nodes: from their owner to the other holders (local ids).
  std::vector<NodeLink> total_sends, total_receives;
  // The ranks this rank sends force records to, and receives them from (ascending).
  std::vector<int> record_sends, record_receives;
  // Traffic of this rank: bytes and messages it sent in the contact's exchanges, over
  // the steps; the largest share.
  double bytes_sent = 0.0, messages_sent = 0.0;
  long steps = 0;
  ContactShareFigures largest;
  double wait_seconds = 0.0;  // in the contact's exchanges, s
  // A step's scratch, kept so that a step allocates nothing once the sizes settle:
  // each pass's motion since its search, and the records for each rank.
  std::vector<double> motion;
  std::vector<std::vector<contact::ForceRecord>> outgoing;
  std::vector<contact::ForceRecord> incoming;  // the records this rank adds
  std::vector<NodeLink*> send_links, receive_links;
  std::vector<MPI_Request> requests;
};

// This rank's share of the contact (`contact`, global node ids: of the whole model, or
// built on the faces near this rank with the places of its items, ContactScope):
// `contact`'s passes and walls become their views and contact.nodes the held contact
// nodes (local ids). global_node: the rank's local -> global node ids; `local`: its
// model; holders: the ranks holding each of contact_nodes (every contact-face node,
// localize's, or those held here, RankSetup's). A slave node's key is its global id,
// a quadrature point's its index in the whole pass.
DistributedContact distribute_contact(ContactModel& contact, const mpi::Communicator& comm,
                                      const std::vector<std::uint32_t>& global_node, const Model& local,
                                      const std::vector<std::uint32_t>& contact_nodes,
                                      const std::vector<std::vector<int>>& holders);

// The contact passes of one step at time `time` (s) on every rank, at u^n with
// v^{n-1/2} (this rank's arrays; `model` its part): adds the contact forces to `force`
// and keeps the smallest gaps in `gap` (held contact nodes; they start from f_load and
// +infinity; the owners' gaps are complete), the same bits as one process.
void run_distributed_contact(ContactModel& contact, DistributedContact& dc, const Model& model,
                             const std::vector<std::uint32_t>& global_node, const NodalVectors& u,
                             const NodalVectors& v, double time, NodalVectors& force,
                             std::vector<double>& gap);

// The step's figures of the passes summed over the ranks (the states' forces,
// penetrations, stick and slip counts and friction work, the statistics), and
// `power`, the contact power of this rank's owned nodes: returns the sum over ranks.
double reduce_contact_figures(ContactModel& contact, DistributedContact& dc, double power);

ContactShareFigures contact_share_figures(const DistributedContact& dc);

// The surfaces that follow erosion on every rank (docs/contact.md, "Faces that erosion
// opens"), at the start of a step after an element failed anywhere: the ranks gather
// the failed elements (`model`'s, global_element its local -> global element ids, of
// global_elements) and each brings every such pass to them, as one process does
// (follow_life on the whole pass); a pass that changed searches again in this step's
// contact. Collective over dc.comm.
void open_eroded_shares(ContactModel& contact, DistributedContact& dc, const Model& model,
                        const std::vector<std::uint32_t>& global_element, std::size_t global_elements);

}  // namespace exdyn::solver
