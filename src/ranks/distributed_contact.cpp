// Contact on many ranks: the shares, the candidate searches with the box exchange,
// the ghost nodes and the force records (distributed_contact.hpp, docs/parallel.md).
#include "ranks/distributed_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>

#include "common/errors.hpp"
#include "common/timer.hpp"
#include "contact/bucket_search.hpp"
#include "contact/rigid_wall.hpp"
#include "contact/slave_points.hpp"
#include "ranks/contact_share.hpp"

namespace exdyn::solver {

using namespace shares;

namespace {

// Sends each link's buffer and receives into each link's buffer (sizes and tags known
// to both).
void exchange(DistributedContact& dc, std::vector<NodeLink*>& sends, std::vector<NodeLink*>& receives) {
  std::vector<MPI_Request>& requests = dc.requests;
  requests.clear();
  requests.reserve(sends.size() + receives.size());
  for (NodeLink* link : receives) {
    requests.emplace_back();
    mpi::check(MPI_Irecv(link->buffer.data(), int(link->buffer.size()), MPI_DOUBLE, link->rank, link->tag,
                         dc.comm.comm, &requests.back()),
               "MPI_Irecv of contact nodes");
  }
  for (NodeLink* link : sends) {
    requests.emplace_back();
    mpi::check(MPI_Isend(link->buffer.data(), int(link->buffer.size()), MPI_DOUBLE, link->rank, link->tag,
                         dc.comm.comm, &requests.back()),
               "MPI_Isend of contact nodes");
    dc.messages_sent += 1;
    dc.bytes_sent += double(sizeof(double) * link->buffer.size());
  }
  const ScopedTimer timer(dc.wait_seconds);
  mpi::check(MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE),
             "MPI_Waitall of contact nodes");
}

// The lowest rank holding every node of a segment (one exists: the rank of the element
// whose face it is), or -1 where a node is not among contact_nodes (a halo segment of
// this rank's faces: not its own).
int segment_owner(const contact::SegmentNodes& segment, const std::vector<std::uint32_t>& contact_nodes,
                  const std::vector<std::vector<int>>& holders) {
  for (int i = 0; i < contact::node_count(segment.type); ++i)
    if (index_in(contact_nodes, segment.nodes[std::size_t(i)]) == contact_nodes.size()) return -1;
  const auto holders_of = [&](std::uint32_t node) -> const std::vector<int>& {
    return holders[index_in(contact_nodes, node)];
  };
  for (const int rank : holders_of(segment.nodes[0])) {
    bool all = true;
    for (int i = 1; i < contact::node_count(segment.type) && all; ++i) {
      const std::vector<int>& h = holders_of(segment.nodes[std::size_t(i)]);
      all = std::binary_search(h.begin(), h.end(), rank);
    }
    if (all) return rank;
  }
  EXDYN_ASSERT(false);
  return -1;
}

// Who holds the contact's nodes: this rank, the contact nodes it holds (global ids,
// ascending) and the ranks holding each (ascending; the first its owner).
struct Holders {
  int me = 0;
  const std::vector<std::uint32_t>& contact_nodes;
  const std::vector<std::vector<int>>& holders;
  int segment_owner(const contact::SegmentNodes& segment) const {
    return solver::segment_owner(segment, contact_nodes, holders);
  }
};

// The sorted, unique nodes of `segments`, added to `nodes`.
void add_segment_nodes(const std::vector<contact::SegmentNodes>& segments,
                       std::vector<std::uint32_t>& nodes) {
  for (const contact::SegmentNodes& s : segments)
    nodes.insert(nodes.end(), s.nodes.begin(), s.nodes.begin() + contact::node_count(s.type));
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
}

// A single surface's slave node p of `whole` as an own point: its sides, and its corners
// with each segment's index in the whole pass (the view's own and ghost segments hold
// them all after a search: each contains the node, so each overlaps this rank's box).
void own_node_sides(const contact::ContactSurfaces& whole, const PassPlace& place, std::size_t p,
                    contact::ContactSurfaces& own) {
  if (own.side_begin.empty()) own.side_begin.push_back(0), own.corner_begin.push_back(0);
  own.side_stiffness.insert(own.side_stiffness.end(), whole.side_stiffness.begin() + whole.side_begin[p],
                            whole.side_stiffness.begin() + whole.side_begin[p + 1]);
  own.side_begin.push_back(std::uint32_t(own.side_stiffness.size()));
  for (std::uint32_t k = whole.corner_begin[p]; k < whole.corner_begin[p + 1]; ++k) {
    contact::NodeCorner corner = whole.node_corners[k];
    corner.segment = place.segment_ids.empty() ? corner.segment : place.segment_ids[corner.segment];
    own.node_corners.push_back(corner);
  }
  own.corner_begin.push_back(std::uint32_t(own.node_corners.size()));
  own.first_part_point.push_back(whole.first_part_point[p]);
}

// The share's own slave points: (mortar) the slave segments this rank owns, each keyed
// by its index in the whole pass; the slave nodes it owns; or the quadrature points of
// the slave segments it owns.
void own_points(const contact::ContactSurfaces& whole, const PassPlace& place, const Holders& h,
                PassShare& share) {
  contact::ContactSurfaces& own = share.own;
  if (whole.mortar) {
    for (std::size_t s = 0; s < whole.slave_segments.size(); ++s) {
      if (h.segment_owner(whole.slave_segments[s]) != h.me) continue;
      own.slave_segments.push_back(whole.slave_segments[s]);
      share.point_keys.push_back(place.point_keys.empty() ? std::uint64_t(s) : place.point_keys[s]);
      own.segment_kappa.push_back(whole.segment_kappa[s]);
      own.segment_length.push_back(whole.segment_length[s]);
      own.slave_area_per_mass.push_back(whole.slave_area_per_mass[s]);
      if (whole.single_surface) own.first_part_point.push_back(whole.first_part_point[s]);
    }
    add_segment_nodes(own.slave_segments, own.slave_nodes);
  } else if (!whole.quadrature) {
    for (std::size_t p = 0; p < whole.slave_nodes.size(); ++p) {
      const std::uint32_t node = whole.slave_nodes[p];
      const std::size_t k = index_in(h.contact_nodes, node);
      if (k == h.contact_nodes.size() || h.holders[k].front() != h.me) continue;
      own.slave_nodes.push_back(node);
      share.point_keys.push_back(node);  // slave nodes ascend: the order of one process
      own.stiffness.push_back(whole.stiffness[p]);
      own.normal_length.push_back(whole.normal_length[p]);
      if (whole.single_surface) own_node_sides(whole, place, p, own);
    }
  } else {
    std::vector<std::int64_t> renumbered(whole.slave_segments.size(), -1);
    own.face_count = whole.face_count;
    for (std::size_t s = 0; s < whole.slave_segments.size(); ++s)
      if (h.segment_owner(whole.slave_segments[s]) == h.me) {
        renumbered[s] = std::int64_t(own.slave_segments.size());
        own.slave_segments.push_back(whole.slave_segments[s]);
        if (!whole.face_kappa.empty())
          own.face_kappa.insert(own.face_kappa.end(),
                                whole.face_kappa.begin() + std::ptrdiff_t(s * whole.face_count),
                                whole.face_kappa.begin() + std::ptrdiff_t((s + 1) * whole.face_count));
      }
    for (std::size_t p = 0; p < whole.quadrature_points.size(); ++p) {
      contact::QuadraturePoint q = whole.quadrature_points[p];
      if (renumbered[q.segment] < 0) continue;
      q.segment = std::uint32_t(renumbered[q.segment]);
      own.quadrature_points.push_back(q);
      share.point_keys.push_back(place.point_keys.empty() ? std::uint32_t(p) : place.point_keys[p]);
      own.stiffness.push_back(whole.stiffness[p]);
      own.normal_length.push_back(whole.normal_length[p]);
      if (whole.single_surface) own.first_part_point.push_back(whole.first_part_point[p]);
    }
    add_segment_nodes(own.slave_segments, own.slave_nodes);
  }
}

// The share's own master segments (those this rank owns), keyed by their index in the
// whole pass, and the nodes that move with the pass (its slave and master nodes).
void own_segments(const contact::ContactSurfaces& whole, const PassPlace& place, const Holders& h,
                  PassShare& share) {
  contact::ContactSurfaces& own = share.own;
  for (std::size_t s = 0; s < whole.segments.size(); ++s)
    if (h.segment_owner(whole.segments[s]) == h.me) {
      own.segments.push_back(whole.segments[s]);
      share.segment_ids.push_back(place.segment_ids.empty() ? std::uint32_t(s) : place.segment_ids[s]);
      if (!whole.edges.empty()) own.edges.push_back(whole.edges[s]);
      if (whole.mortar) own.master_area_per_mass.push_back(whole.master_area_per_mass[s]);
      if (whole.single_surface) {  // the segments across its edges by their index in the whole pass
        own.first_part_segment.push_back(whole.first_part_segment[s]);
        if (!whole.segment_face.empty()) own.segment_face.push_back(whole.segment_face[s]);
        std::array<std::int32_t, 4> next = whole.edge_neighbours[s];
        for (std::int32_t& n : next)
          if (n >= 0 && !place.segment_ids.empty()) n = std::int32_t(place.segment_ids[std::size_t(n)]);
        own.edge_neighbours.push_back(next);
      }
    }
  own.moving_nodes = own.slave_nodes;
  add_segment_nodes(own.segments, own.moving_nodes);
}

// This rank's share of one pass (`whole`, global node ids: the whole pass, or the pass
// on the faces near this rank with its places in the whole pass, `place`). folds: the
// pass has contact at folds (a pair's pass: ContactSurfaces::edges), whether or not
// this rank holds a master segment of it (a rank that holds none gets all its
// segments, and their edges, from the others).
PassShare make_share(const contact::ContactSurfaces& whole, const PassPlace& place, std::uint64_t index,
                     int me, const std::vector<std::uint32_t>& global_node, const Model& local,
                     const std::vector<std::uint32_t>& contact_nodes,
                     const std::vector<std::vector<int>>& holders, bool folds) {
  PassShare share;
  share.index = index;
  share.edges = folds;
  EXDYN_ASSERT(whole.edges.empty() || whole.edges.size() == whole.segments.size());
  contact::ContactSurfaces& own = share.own;
  own.quadrature = whole.quadrature;
  own.mortar = whole.mortar;
  own.triangle_points = whole.triangle_points;
  own.single_surface = whole.single_surface;
  const Holders h{me, contact_nodes, holders};
  own_points(whole, place, h, share);
  own_segments(whole, place, h, share);
  // The store's fixed part: the moving nodes, all held here.
  ContactStore& store = share.store;
  store.fixed = own.moving_nodes.size();
  store.global = own.moving_nodes;
  store.x_ref.resize(store.fixed);
  store.u.resize(store.fixed);
  store.v.resize(store.fixed);
  store.mass.resize(store.fixed);
  for (std::size_t i = 0; i < store.fixed; ++i) {
    const std::size_t l = index_in(global_node, store.global[i]);
    EXDYN_ASSERT(l < global_node.size());
    store.local.push_back(std::int64_t(l));
    store.owner.push_back(holders[index_in(contact_nodes, store.global[i])].front());
    for (int c = 0; c < 3; ++c) store.x_ref.component(c)[i] = local.mesh.x_ref.component(c)[l];
    store.mass[i] = local.mass[l];
  }
  // The view: the own points as they are, the own segments until the first search.
  contact::ContactSurfaces& view = share.view;
  view = own;
  for (std::uint32_t& node : view.slave_nodes) node = std::uint32_t(index_in(store.global, node));
  for (contact::SegmentNodes& s : view.slave_segments) s = in_store(s, store);
  for (contact::SegmentNodes& s : view.segments) s = in_store(s, store);
  for (std::uint32_t& node : view.moving_nodes) node = std::uint32_t(index_in(store.global, node));
  share.known = share.segment_ids;
  if (own.single_surface) shares::index_single_surface(share);
  if (!whole.segment_element.empty()) {  // a surface that follows erosion: built whole on every rank
    EXDYN_ASSERT(place.segment_ids.empty() && !whole.mortar);
    share.whole = whole;
    for (const std::uint64_t key : share.point_keys) {
      const std::size_t p =
          whole.quadrature ? std::size_t(key) : index_in(whole.slave_nodes, std::uint32_t(key));
      EXDYN_ASSERT(p < whole.point_count());
      share.whole_point.push_back(std::uint32_t(p));
    }
    shares::apply_life(share);
  }
  return share;
}

// Plans the totals of the shared contact nodes: from each one's owner to its other holders.
void plan_totals(DistributedContact& dc, const std::vector<std::uint32_t>& global_node) {
  std::vector<std::vector<std::uint32_t>> send(std::size_t(dc.comm.size)), receive(std::size_t(dc.comm.size));
  for (std::size_t k = 0; k < dc.held.size(); ++k) {
    const std::vector<int>& h = dc.holders[k];
    if (h.size() < 2) continue;
    const auto node = std::uint32_t(index_in(global_node, dc.held[k]));
    if (h.front() == dc.comm.rank)
      for (std::size_t j = 1; j < h.size(); ++j) send[std::size_t(h[j])].push_back(node);
    else
      receive[std::size_t(h.front())].push_back(node);
  }
  for (int r = 0; r < dc.comm.size; ++r) {
    if (!send[std::size_t(r)].empty())
      dc.total_sends.push_back(
          {r, total_tag, send[std::size_t(r)], std::vector<double>(3 * send[std::size_t(r)].size())});
    if (!receive[std::size_t(r)].empty())
      dc.total_receives.push_back(
          {r, total_tag, receive[std::size_t(r)], std::vector<double>(3 * receive[std::size_t(r)].size())});
  }
}

// The held nodes of every store from this rank's arrays, the ghosts from their owners.
void refresh_stores(DistributedContact& dc, const NodalVectors& u, const NodalVectors& v) {
  std::vector<NodeLink*>& sends = dc.send_links;
  std::vector<NodeLink*>& receives = dc.receive_links;
  sends.clear();
  receives.clear();
  for (PassShare& share : dc.passes) {
    ContactStore& store = share.store;
    for (std::size_t i = 0; i < store.global.size(); ++i) {
      if (store.local[i] < 0) continue;
      const auto l = std::size_t(store.local[i]);
      for (int c = 0; c < 3; ++c) {
        store.u.component(c)[i] = u.component(c)[l];
        store.v.component(c)[i] = v.component(c)[l];
      }
    }
    for (NodeLink& link : share.ghost_sends) {
      for (std::size_t k = 0; k < link.nodes.size(); ++k)
        for (int c = 0; c < 3; ++c) {
          link.buffer[6 * k + std::size_t(c)] = u.component(c)[link.nodes[k]];
          link.buffer[6 * k + 3 + std::size_t(c)] = v.component(c)[link.nodes[k]];
        }
      sends.push_back(&link);
    }
    for (NodeLink& link : share.ghost_receives) receives.push_back(&link);
  }
  exchange(dc, sends, receives);  // a message per neighbour and pass, tagged by the pass
  for (PassShare& share : dc.passes)
    for (const NodeLink& link : share.ghost_receives)
      for (std::size_t k = 0; k < link.nodes.size(); ++k)
        for (int c = 0; c < 3; ++c) {
          share.store.u.component(c)[link.nodes[k]] = link.buffer[6 * k + std::size_t(c)];
          share.store.v.component(c)[link.nodes[k]] = link.buffer[6 * k + 3 + std::size_t(c)];
        }
}

// The ranks this rank sends force records to (the owners its stores name) and those
// that send it theirs: after a candidate search (the stores change), agreed with one
// MPI_Alltoall of a flag a rank.
void plan_record_peers(DistributedContact& dc) {
  const auto ranks = std::size_t(dc.comm.size);
  std::vector<int> to(ranks, 0), from(ranks, 0);
  for (const PassShare& share : dc.passes)
    for (const int owner : share.store.owner) to[std::size_t(owner)] = 1;
  to[std::size_t(dc.comm.rank)] = 0;
  {
    const ScopedTimer timer(dc.wait_seconds);
    mpi::check(MPI_Alltoall(to.data(), 1, MPI_INT, from.data(), 1, MPI_INT, dc.comm.comm),
               "MPI_Alltoall of the contact's peers");
  }
  dc.record_sends.clear();
  dc.record_receives.clear();
  for (std::size_t r = 0; r < ranks; ++r) {
    if (to[r] != 0) dc.record_sends.push_back(int(r));
    if (from[r] != 0) dc.record_receives.push_back(int(r));
  }
}

// The records of every pass to the owners of their nodes, each owner adding its
// nodes' records in the order of one process (by node, then key); then the totals of
// the shared contact nodes from their owners to the other holders.
void add_records(DistributedContact& dc, std::vector<std::vector<contact::ForceRecord>>& out,
                 const std::vector<std::uint32_t>& global_node, NodalVectors& force,
                 std::vector<double>& gap) {
  // To the owners this rank's stores name (record_peers: empty messages too, so that
  // each receiver knows how many to expect), from those that name this rank.
  std::vector<contact::ForceRecord>& in = dc.incoming;
  in.swap(out[std::size_t(dc.comm.rank)]);  // this rank's own records (the old buffer goes back, emptied)
  out[std::size_t(dc.comm.rank)].clear();
  std::vector<MPI_Request>& requests = dc.requests;
  requests.clear();
  requests.reserve(dc.record_sends.size());
  for (const int rank : dc.record_sends) {
    const std::vector<contact::ForceRecord>& records = out[std::size_t(rank)];
    requests.emplace_back();
    mpi::check(MPI_Isend(records.data(), int(sizeof(contact::ForceRecord) * records.size()), MPI_BYTE, rank,
                         record_tag, dc.comm.comm, &requests.back()),
               "MPI_Isend of contact forces");
    dc.messages_sent += 1;
    dc.bytes_sent += double(sizeof(contact::ForceRecord) * records.size());
  }
  for (std::size_t r = 0; r < out.size(); ++r)  // every record's owner is a peer
    EXDYN_ASSERT(out[r].empty() || int(r) == dc.comm.rank ||
                 std::binary_search(dc.record_sends.begin(), dc.record_sends.end(), int(r)));
  {
    const ScopedTimer timer(dc.wait_seconds);
    for (const int rank : dc.record_receives) {
      MPI_Status status;
      mpi::check(MPI_Probe(rank, record_tag, dc.comm.comm, &status), "MPI_Probe of contact forces");
      int bytes = 0;
      mpi::check(MPI_Get_count(&status, MPI_BYTE, &bytes), "MPI_Get_count of contact forces");
      const std::size_t at = in.size();
      in.resize(at + std::size_t(bytes) / sizeof(contact::ForceRecord));
      mpi::check(MPI_Recv(in.data() + at, bytes, MPI_BYTE, rank, record_tag, dc.comm.comm, MPI_STATUS_IGNORE),
                 "MPI_Recv of contact forces");
    }
    mpi::check(MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE),
               "MPI_Waitall of contact forces");
  }
  std::sort(in.begin(), in.end(), [](const contact::ForceRecord& a, const contact::ForceRecord& b) {
    return a.node < b.node || (a.node == b.node && a.key < b.key);
  });
  std::size_t local = 0;
  for (std::size_t k = 0; k < in.size(); ++k) {
    const contact::ForceRecord& r = in[k];
    if (k == 0 || r.node != in[k - 1].node) {
      local = index_in(global_node, r.node);
      EXDYN_ASSERT(local < global_node.size());  // the owner holds it
    }
    if (r.kind == contact::ForceRecord::gap) {
      gap[local] = std::min(gap[local], r.value[0]);
      continue;
    }
    force.x[local] += r.value[0];
    force.y[local] += r.value[1];
    force.z[local] += r.value[2];
  }
  std::vector<NodeLink*>& sends = dc.send_links;
  std::vector<NodeLink*>& receives = dc.receive_links;
  sends.clear();
  receives.clear();
  for (NodeLink& link : dc.total_sends) {
    for (std::size_t k = 0; k < link.nodes.size(); ++k)
      for (int c = 0; c < 3; ++c) link.buffer[3 * k + std::size_t(c)] = force.component(c)[link.nodes[k]];
    sends.push_back(&link);
  }
  for (NodeLink& link : dc.total_receives) receives.push_back(&link);
  exchange(dc, sends, receives);
  for (const NodeLink& link : dc.total_receives)
    for (std::size_t k = 0; k < link.nodes.size(); ++k)
      for (int c = 0; c < 3; ++c) force.component(c)[link.nodes[k]] = link.buffer[3 * k + std::size_t(c)];
}

}  // namespace

namespace shares {

// A node's place in the store (global id in), or store.global.size().
std::size_t store_index(const ContactStore& store, std::uint32_t node) {
  const auto fixed_end = store.global.begin() + std::ptrdiff_t(store.fixed);
  auto at = std::lower_bound(store.global.begin(), fixed_end, node);
  if (at != fixed_end && *at == node) return std::size_t(at - store.global.begin());
  at = std::lower_bound(fixed_end, store.global.end(), node);
  return at != store.global.end() && *at == node ? std::size_t(at - store.global.begin())
                                                 : store.global.size();
}

// The ids of a segment's nodes in the store (global ids in, store ids out).
contact::SegmentNodes in_store(contact::SegmentNodes segment, const ContactStore& store) {
  for (int i = 0; i < contact::node_count(segment.type); ++i) {
    std::uint32_t& node = segment.nodes[std::size_t(i)];
    const std::size_t k = store_index(store, node);
    EXDYN_ASSERT(k < store.global.size());
    node = std::uint32_t(k);
  }
  return segment;
}

}  // namespace shares

DistributedContact distribute_contact(ContactModel& contact, const mpi::Communicator& comm,
                                      const std::vector<std::uint32_t>& global_node, const Model& local,
                                      const std::vector<std::uint32_t>& contact_nodes,
                                      const std::vector<std::vector<int>>& holders) {
  DistributedContact dc;
  dc.comm = comm;
  for (std::size_t k = 0; k < contact_nodes.size(); ++k)
    if (std::binary_search(global_node.begin(), global_node.end(), contact_nodes[k])) {
      dc.held.push_back(contact_nodes[k]);
      dc.holders.push_back(holders[k]);
    }
  contact.nodes.clear();
  for (const std::uint32_t g : dc.held) contact.nodes.push_back(std::uint32_t(index_in(global_node, g)));
  plan_totals(dc, global_node);
  std::uint64_t index = 0;
  for (ContactPair& pair : contact.pairs) {
    for (std::size_t p = 0; p < pair.passes.size(); ++p) {
      dc.passes.push_back(make_share(pair.passes[p], p < pair.places.size() ? pair.places[p] : PassPlace{},
                                     index++, comm.rank, global_node, local, contact_nodes, holders, true));
      pair.passes[p] = dc.passes.back().view;
    }
    pair.places = {};
  }
  for (RigidWall& wall : contact.walls) {
    dc.passes.push_back(make_share(wall.surfaces, wall.place, index++, comm.rank, global_node, local,
                                   contact_nodes, holders, false));
    wall.surfaces = dc.passes.back().view;
    wall.place = {};
  }
  dc.local_statistics.resize(contact.pairs.size() + contact.walls.size());
  return dc;
}

namespace {

// Which pairs' passes search again: the largest motion since their last search, per
// pass, over all ranks (an exact max: every rank decides as one process does).
void largest_motions(const ContactModel& contact, DistributedContact& dc) {
  std::vector<double>& motion = dc.motion;
  motion.clear();
  std::size_t k = 0;
  for (const ContactPair& pair : contact.pairs)
    for (std::size_t p = 0; p < pair.passes.size(); ++p, ++k) {
      const PassShare& share = dc.passes[k];
      motion.push_back(
          contact::largest_motion_since_build(share.view, pair.states[p], share.store.x_ref, share.store.u));
    }
  if (motion.empty()) return;
  const ScopedTimer timer(dc.wait_seconds);
  mpi::check(
      MPI_Allreduce(MPI_IN_PLACE, motion.data(), int(motion.size()), MPI_DOUBLE, MPI_MAX, dc.comm.comm),
      "MPI_Allreduce of the contact's motion");
}

// A pass's sink made ready for this step's records.
contact::RecordSink& ready_sink(PassShare& share) {
  contact::RecordSink& sink = share.sink;
  sink.records.clear();
  sink.pass = share.index;
  sink.point_keys = &share.point_keys;
  return sink;
}

// After a pass: the deepest slave node as a global id (the pass names it by its store
// id), and its records to their nodes' owners (dc.outgoing).
void after_pass(DistributedContact& dc, const PassShare& share, contact::ContactStatistics& s,
                double deepest_before) {
  if (s.max_penetration_over_h > deepest_before) s.deepest_node = share.store.global[s.deepest_node];
  for (contact::ForceRecord r : share.sink.records) {
    const int owner = share.store.owner[r.node];
    r.node = share.store.global[r.node];
    dc.outgoing[std::size_t(owner)].push_back(r);
  }
}

// The largest share figures so far (ContactShareFigures), with this step's.
void note_share_figures(DistributedContact& dc) {
  ContactShareFigures now;
  for (const PassShare& share : dc.passes) {
    now.points += double(share.own.mortar ? share.own.slave_segments.size() : share.own.point_count());
    now.segments += double(share.view.segments.size());
    now.ghost_segments += double(share.ghost_segments);
    now.ghost_nodes += double(share.ghost_nodes);
  }
  dc.largest.points = std::max(dc.largest.points, now.points);
  dc.largest.segments = std::max(dc.largest.segments, now.segments);
  dc.largest.ghost_segments = std::max(dc.largest.ghost_segments, now.ghost_segments);
  dc.largest.ghost_nodes = std::max(dc.largest.ghost_nodes, now.ghost_nodes);
}

}  // namespace

void run_distributed_contact(ContactModel& contact, DistributedContact& dc, const Model& model,
                             const std::vector<std::uint32_t>& global_node, const NodalVectors& u,
                             const NodalVectors& v, double time, NodalVectors& force,
                             std::vector<double>& gap) {
  ++dc.steps;
  refresh_stores(dc, u, v);
  largest_motions(contact, dc);
  // The passes, their forces and gaps as records, sent to their nodes' owners. A pass
  // writes its records only: its force and gap stay empty.
  dc.outgoing.resize(std::size_t(dc.comm.size));
  for (auto& records : dc.outgoing) records.clear();
  NodalVectors no_force;
  std::vector<double> no_gap;
  std::size_t k = 0, statistics = 0;
  bool searched = dc.steps == 1;  // the first step: the walls' stores too
  for (ContactPair& pair : contact.pairs) {
    for (std::size_t p = 0; p < pair.passes.size(); ++p, ++k) {
      PassShare& share = dc.passes[k];
      contact::ContactPassState& state = pair.states[p];
      if (dc.motion[k] > 0.5 * pair.settings.margin || share.opened) {
        search_again(dc, share, pair.settings, state, global_node, model.mesh.x_ref, model.mass, u, v);
        pair.passes[p] = share.view;  // the pair's own copy (the summary's counts)
        searched = true;
      }
      contact::RecordSink& sink = ready_sink(share);
      state.friction_work = share.local_friction_work;
      contact::ContactStatistics& mine = dc.local_statistics[statistics];
      const double deepest = mine.max_penetration_over_h;
      // The search is decided above, from the motion over all ranks: the pass does not
      // measure it again.
      contact::run_contact_pass(share.view, pair.settings, state, share.store.x_ref, share.store.u,
                                share.store.v, share.store.mass, no_force, no_gap, mine, pair.seconds, &sink,
                                false);
      share.local_friction_work = state.friction_work;
      after_pass(dc, share, mine, deepest);
    }
    ++statistics;
  }
  for (RigidWall& wall : contact.walls) {
    PassShare& share = dc.passes[k++];
    contact::RecordSink& sink = ready_sink(share);
    wall.state.friction_work = share.local_friction_work;
    contact::ContactStatistics& mine = dc.local_statistics[statistics++];
    const double deepest = mine.max_penetration_over_h;
    contact::run_wall_pass(wall.surfaces, wall.plane, wall.settings, wall.state, share.store.x_ref,
                           share.store.u, share.store.v, share.store.mass, time, no_force, no_gap, mine,
                           wall.seconds, &sink);
    share.local_friction_work = wall.state.friction_work;
    after_pass(dc, share, mine, deepest);
  }
  if (searched) plan_record_peers(dc);
  add_records(dc, dc.outgoing, global_node, force, gap);
  note_share_figures(dc);
}

}  // namespace exdyn::solver
