// Contact on many ranks: the shares, the candidate searches with the box exchange,
// the ghost nodes and the force records (distributed_contact.hpp, docs/parallel.md).
#include "solver/distributed_contact.hpp"

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

namespace exdyn::solver {

namespace {

// Tags of the contact's point-to-point messages, apart from the force exchange's.
// (Within the 32767 every MPI allows; the force exchange's count from 1, a few per block.)
constexpr int record_tag = 30000, total_tag = 30001, ghost_tag = 30002;  // + the pass

template <class T>
std::size_t index_in(const std::vector<T>& sorted, T value) {
  const auto at = std::lower_bound(sorted.begin(), sorted.end(), value);
  return at != sorted.end() && *at == value ? std::size_t(at - sorted.begin()) : sorted.size();
}

// A segment as it travels at a search: its index in the whole pass, its nodes (global
// ids) and what lies past its edges.
struct SegmentPayload {
  std::uint32_t id = 0;
  contact::SegmentNodes nodes;
  contact::SegmentEdges edges;
  double area_per_mass = 0.0;  // mortar: the mean a / m of its nodes (ContactSurfaces), m^2/kg
};
// A node the receiver does not hold: its owner and its data at the search.
struct NodePayload {
  std::uint32_t global = 0;
  int owner = 0;
  double x_ref[3], u[3], v[3], mass;
};
static_assert(std::is_trivially_copyable_v<SegmentPayload> && std::is_trivially_copyable_v<NodePayload> &&
              std::is_trivially_copyable_v<contact::ForceRecord>);

// Items of type T to every rank (MPI_Alltoallv as bytes): out[r] to rank r; returns
// what each rank sent here. Counts the bytes and messages sent.
template <class T>
std::vector<std::vector<T>> all_to_all(DistributedContact& dc, const std::vector<std::vector<T>>& out) {
  const auto ranks = std::size_t(dc.comm.size);
  std::vector<int> send_counts(ranks), receive_counts(ranks), send_at(ranks, 0), receive_at(ranks, 0);
  std::vector<T> flat;
  for (std::size_t r = 0; r < ranks; ++r) {
    send_counts[r] = int(sizeof(T) * out[r].size());
    send_at[r] = int(sizeof(T) * flat.size());
    flat.insert(flat.end(), out[r].begin(), out[r].end());
    if (int(r) != dc.comm.rank && !out[r].empty())
      dc.messages_sent += 1, dc.bytes_sent += double(send_counts[r]);
  }
  std::vector<T> in;
  {
    const ScopedTimer timer(dc.wait_seconds);
    mpi::check(MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, dc.comm.comm),
               "MPI_Alltoall of the contact's counts");
    for (std::size_t r = 1; r < ranks; ++r) receive_at[r] = receive_at[r - 1] + receive_counts[r - 1];
    in.resize(std::size_t(receive_at[ranks - 1] + receive_counts[ranks - 1]) / sizeof(T));
    mpi::check(MPI_Alltoallv(flat.data(), send_counts.data(), send_at.data(), MPI_BYTE, in.data(),
                             receive_counts.data(), receive_at.data(), MPI_BYTE, dc.comm.comm),
               "MPI_Alltoallv of the contact's data");
  }
  std::vector<std::vector<T>> from(ranks);
  for (std::size_t r = 0; r < ranks; ++r) {
    const auto first = in.begin() + receive_at[r] / std::ptrdiff_t(sizeof(T));
    from[r].assign(first, first + receive_counts[r] / std::ptrdiff_t(sizeof(T)));
  }
  return from;
}

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

// This rank's share of one pass (`whole`, global node ids: the whole pass, or the pass
// on the faces near this rank with its places in the whole pass, `place`).
PassShare make_share(const contact::ContactSurfaces& whole, const PassPlace& place, std::uint64_t index,
                     int me, const std::vector<std::uint32_t>& global_node, const Model& local,
                     const std::vector<std::uint32_t>& contact_nodes,
                     const std::vector<std::vector<int>>& holders) {
  PassShare share;
  share.index = index;
  share.edges = !whole.edges.empty();
  contact::ContactSurfaces& own = share.own;
  own.quadrature = whole.quadrature;
  own.mortar = whole.mortar;
  own.triangle_points = whole.triangle_points;
  if (whole.mortar) {  // its slave segments, each keyed by its index in the whole pass
    for (std::size_t s = 0; s < whole.slave_segments.size(); ++s) {
      if (segment_owner(whole.slave_segments[s], contact_nodes, holders) != me) continue;
      own.slave_segments.push_back(whole.slave_segments[s]);
      share.point_keys.push_back(place.point_keys.empty() ? std::uint64_t(s) : place.point_keys[s]);
      own.segment_kappa.push_back(whole.segment_kappa[s]);
      own.segment_length.push_back(whole.segment_length[s]);
      own.slave_area_per_mass.push_back(whole.slave_area_per_mass[s]);
      own.slave_nodes.insert(
          own.slave_nodes.end(), whole.slave_segments[s].nodes.begin(),
          whole.slave_segments[s].nodes.begin() + contact::node_count(whole.slave_segments[s].type));
    }
    std::sort(own.slave_nodes.begin(), own.slave_nodes.end());
    own.slave_nodes.erase(std::unique(own.slave_nodes.begin(), own.slave_nodes.end()), own.slave_nodes.end());
  } else if (!whole.quadrature) {
    for (std::size_t p = 0; p < whole.slave_nodes.size(); ++p) {
      const std::uint32_t node = whole.slave_nodes[p];
      const std::size_t k = index_in(contact_nodes, node);
      if (k == contact_nodes.size() || holders[k].front() != me) continue;
      own.slave_nodes.push_back(node);
      share.point_keys.push_back(node);  // slave nodes ascend: the order of one process
      own.stiffness.push_back(whole.stiffness[p]);
      own.normal_length.push_back(whole.normal_length[p]);
    }
  } else {
    std::vector<std::int64_t> renumbered(whole.slave_segments.size(), -1);
    for (std::size_t s = 0; s < whole.slave_segments.size(); ++s)
      if (segment_owner(whole.slave_segments[s], contact_nodes, holders) == me) {
        renumbered[s] = std::int64_t(own.slave_segments.size());
        own.slave_segments.push_back(whole.slave_segments[s]);
      }
    for (std::size_t p = 0; p < whole.quadrature_points.size(); ++p) {
      contact::QuadraturePoint q = whole.quadrature_points[p];
      if (renumbered[q.segment] < 0) continue;
      q.segment = std::uint32_t(renumbered[q.segment]);
      own.quadrature_points.push_back(q);
      share.point_keys.push_back(place.point_keys.empty() ? std::uint32_t(p) : place.point_keys[p]);
      own.stiffness.push_back(whole.stiffness[p]);
      own.normal_length.push_back(whole.normal_length[p]);
    }
    for (const contact::SegmentNodes& s : own.slave_segments)
      own.slave_nodes.insert(own.slave_nodes.end(), s.nodes.begin(),
                             s.nodes.begin() + contact::node_count(s.type));
    std::sort(own.slave_nodes.begin(), own.slave_nodes.end());
    own.slave_nodes.erase(std::unique(own.slave_nodes.begin(), own.slave_nodes.end()), own.slave_nodes.end());
  }
  for (std::size_t s = 0; s < whole.segments.size(); ++s)
    if (segment_owner(whole.segments[s], contact_nodes, holders) == me) {
      own.segments.push_back(whole.segments[s]);
      share.segment_ids.push_back(place.segment_ids.empty() ? std::uint32_t(s) : place.segment_ids[s]);
      if (!whole.edges.empty()) own.edges.push_back(whole.edges[s]);
      if (whole.mortar) own.master_area_per_mass.push_back(whole.master_area_per_mass[s]);
    }
  own.moving_nodes = own.slave_nodes;
  for (const contact::SegmentNodes& s : own.segments)
    own.moving_nodes.insert(own.moving_nodes.end(), s.nodes.begin(),
                            s.nodes.begin() + contact::node_count(s.type));
  std::sort(own.moving_nodes.begin(), own.moving_nodes.end());
  own.moving_nodes.erase(std::unique(own.moving_nodes.begin(), own.moving_nodes.end()),
                         own.moving_nodes.end());

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

// The box of this rank's slave points now, and of the stick anchors of its points in
// contact (friction: an anchor's segment must stay in the view), m.
contact::Box point_box(const PassShare& share, const contact::ContactPassState& state) {
  contact::Box box;
  box.lo.fill(std::numeric_limits<double>::infinity());
  box.hi.fill(-std::numeric_limits<double>::infinity());
  auto add = [&](const contact::Vec3& x) {
    const double c[3] = {x.x, x.y, x.z};
    for (int k = 0; k < 3; ++k) box.lo[k] = std::min(box.lo[k], c[k]), box.hi[k] = std::max(box.hi[k], c[k]);
  };
  if (share.view.mortar) {  // every point of its slave segments, wherever the pieces fall
    for (const contact::SegmentNodes& ids : share.view.slave_segments) {
      const contact::SegmentBox b =
          contact::segment_box(contact::current_segment(ids, share.store.x_ref, share.store.u));
      add(b.lo), add(b.hi);
    }
  } else {
    NodalVectors points;
    contact::update_slave_points(share.view, share.store.x_ref, share.store.u, points);
    for (std::size_t p = 0; p < points.size(); ++p) add({points.x[p], points.y[p], points.z[p]});
  }
  for (const contact::Anchor& anchor : state.anchors) {
    if (anchor.segment < 0) continue;
    const contact::SegmentNodes& ids = share.view.segments[std::size_t(anchor.segment)];
    contact::Segment segment;
    segment.type = ids.type;
    for (int i = 0; i < contact::node_count(ids.type); ++i)
      segment.nodes[std::size_t(i)] =
          contact::current_position(share.store.x_ref, share.store.u, ids.nodes[std::size_t(i)]);
    add(contact::evaluate(segment, anchor.xi).y);
  }
  return box;
}

bool overlap(const contact::Box& a, const contact::Box& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

// A new candidate search of one pass (every rank together): the box exchange, the
// ghost segments and their nodes, the view and the store; the pass's candidates and
// anchors follow their segments into the new view, and the pass searches again.
void search_again(DistributedContact& dc, PassShare& share, const contact::ContactPassSettings& settings,
                  contact::ContactPassState& state, const std::vector<std::uint32_t>& global_node,
                  const NodalVectors& x_ref, const std::vector<double>& mass, const NodalVectors& u,
                  const NodalVectors& v) {
  const auto ranks = std::size_t(dc.comm.size);
  const int me = dc.comm.rank;
  const contact::Box mine = point_box(share, state);
  const double six[6] = {mine.lo[0], mine.lo[1], mine.lo[2], mine.hi[0], mine.hi[1], mine.hi[2]};
  std::vector<double> boxes;
  {
    const ScopedTimer timer(dc.wait_seconds);
    boxes = mpi::all_gather(dc.comm, six, 6);
  }
  dc.bytes_sent += 48.0 * double(ranks - 1), dc.messages_sent += double(ranks - 1);

  // Each own segment to every rank whose points' box its capture box overlaps, with
  // the nodes that rank does not hold. The segment boxes are the bucket search's.
  std::vector<contact::SegmentNodes> own_in_store(share.own.segments.size());
  for (std::size_t i = 0; i < own_in_store.size(); ++i)
    own_in_store[i] = in_store(share.own.segments[i], share.store);
  std::vector<contact::Box> own_boxes;
  const ContactStore& store = share.store;
  contact::segment_boxes(
      [&](std::uint32_t node) {
        return std::array<double, 3>{store.x_ref.x[node] + store.u.x[node],
                                     store.x_ref.y[node] + store.u.y[node],
                                     store.x_ref.z[node] + store.u.z[node]};
      },
      own_in_store, settings.search_distance + settings.margin, own_boxes);
  std::vector<std::vector<SegmentPayload>> segments_out(ranks);
  std::vector<std::vector<NodePayload>> nodes_out(ranks);
  std::vector<std::vector<std::uint32_t>> sent_nodes(ranks);  // global ids, per rank
  for (std::size_t r = 0; r < ranks; ++r) {
    if (int(r) == me) continue;
    const contact::Box theirs{{boxes[6 * r], boxes[6 * r + 1], boxes[6 * r + 2]},
                              {boxes[6 * r + 3], boxes[6 * r + 4], boxes[6 * r + 5]}};
    for (std::size_t i = 0; i < own_boxes.size(); ++i) {
      if (!overlap(own_boxes[i], theirs)) continue;
      const contact::SegmentNodes& s = share.own.segments[i];
      segments_out[r].push_back({share.segment_ids[i], s,
                                 share.own.edges.empty() ? contact::SegmentEdges{} : share.own.edges[i],
                                 share.own.mortar ? share.own.master_area_per_mass[i] : 0.0});
      for (int k = 0; k < contact::node_count(s.type); ++k) {
        const std::uint32_t g = s.nodes[std::size_t(k)];
        const std::vector<int>& h = dc.holders[index_in(dc.held, g)];
        if (!std::binary_search(h.begin(), h.end(), int(r))) sent_nodes[r].push_back(g);
      }
    }
    std::vector<std::uint32_t>& sent = sent_nodes[r];
    std::sort(sent.begin(), sent.end());
    sent.erase(std::unique(sent.begin(), sent.end()), sent.end());
    for (const std::uint32_t g : sent) {
      const std::size_t i = store_index(store, g);  // a node of an own segment: in the fixed part
      NodePayload n;
      n.global = g;
      n.owner = store.owner[i];
      n.mass = store.mass[i];
      for (int c = 0; c < 3; ++c) {
        n.x_ref[c] = store.x_ref.component(c)[i];
        n.u[c] = store.u.component(c)[i];
        n.v[c] = store.v.component(c)[i];
      }
      nodes_out[r].push_back(n);
    }
  }
  std::vector<SegmentPayload> ghosts;
  for (const auto& from : all_to_all(dc, segments_out)) ghosts.insert(ghosts.end(), from.begin(), from.end());
  const std::vector<std::vector<NodePayload>> nodes_in = all_to_all(dc, nodes_out);

  // The new view's segments: own and ghost, by index in the whole pass.
  std::sort(ghosts.begin(), ghosts.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  std::vector<std::uint32_t> known;
  std::vector<contact::SegmentNodes> known_segments;  // global node ids
  std::vector<contact::SegmentEdges> known_edges;
  std::vector<double> known_area_per_mass;
  for (std::size_t i = 0, j = 0; i < share.segment_ids.size() || j < ghosts.size();) {
    const bool own =
        j == ghosts.size() || (i < share.segment_ids.size() && share.segment_ids[i] < ghosts[j].id);
    if (own) {
      known.push_back(share.segment_ids[i]);
      known_segments.push_back(share.own.segments[i]);
      known_edges.push_back(share.own.edges.empty() ? contact::SegmentEdges{} : share.own.edges[i]);
      known_area_per_mass.push_back(share.own.mortar ? share.own.master_area_per_mass[i] : 0.0);
      ++i;
    } else {
      known.push_back(ghosts[j].id);
      known_segments.push_back(ghosts[j].nodes);
      known_edges.push_back(ghosts[j].edges);
      known_area_per_mass.push_back(ghosts[j].area_per_mass);
      ++j;
    }
  }

  // The store: the fixed part, then every other node of a ghost segment, held here
  // (from this rank's arrays) or a ghost (from the node payloads).
  ContactStore& s = share.store;
  std::vector<std::uint32_t> extra;
  for (const SegmentPayload& g : ghosts)
    for (int k = 0; k < contact::node_count(g.nodes.type); ++k) {
      const std::uint32_t node = g.nodes.nodes[std::size_t(k)];
      if (!std::binary_search(s.global.begin(), s.global.begin() + std::ptrdiff_t(s.fixed), node))
        extra.push_back(node);
    }
  std::sort(extra.begin(), extra.end());
  extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
  const std::size_t size = s.fixed + extra.size();
  s.global.resize(s.fixed);
  s.global.insert(s.global.end(), extra.begin(), extra.end());
  for (NodalVectors* vectors : {&s.x_ref, &s.u, &s.v})  // keeping the fixed part (resize would zero it)
    for (int c = 0; c < 3; ++c) vectors->component(c).resize(size);
  s.local.resize(size);
  s.owner.resize(size);
  s.mass.resize(size);
  std::size_t ghost_nodes = 0;
  for (std::size_t i = s.fixed; i < size; ++i) {
    const std::uint32_t g = s.global[i];
    const std::size_t l = index_in(global_node, g);
    if (l == global_node.size()) {
      s.local[i] = -1;
      ++ghost_nodes;
      continue;
    }
    s.local[i] = std::int64_t(l);
    s.owner[i] = dc.holders[index_in(dc.held, g)].front();
    s.mass[i] = mass[l];
    for (int c = 0; c < 3; ++c) {
      s.x_ref.component(c)[i] = x_ref.component(c)[l];
      s.u.component(c)[i] = u.component(c)[l];
      s.v.component(c)[i] = v.component(c)[l];
    }
  }
  share.ghost_receives.clear();
  for (std::size_t r = 0; r < ranks; ++r) {
    if (nodes_in[r].empty()) continue;
    NodeLink link{
        int(r), ghost_tag + int(share.index % 2048), {}, std::vector<double>(6 * nodes_in[r].size())};
    for (const NodePayload& n : nodes_in[r]) {
      const std::size_t i = store_index(s, n.global);
      EXDYN_ASSERT(i < size && s.local[i] < 0);
      link.nodes.push_back(std::uint32_t(i));
      s.owner[i] = n.owner;
      s.mass[i] = n.mass;
      for (int c = 0; c < 3; ++c) {
        s.x_ref.component(c)[i] = n.x_ref[c];
        s.u.component(c)[i] = n.u[c];
        s.v.component(c)[i] = n.v[c];
      }
    }
    share.ghost_receives.push_back(std::move(link));
  }
  share.ghost_sends.clear();
  for (std::size_t r = 0; r < ranks; ++r) {
    if (nodes_out[r].empty()) continue;
    NodeLink link{
        int(r), ghost_tag + int(share.index % 2048), {}, std::vector<double>(6 * nodes_out[r].size())};
    for (const NodePayload& n : nodes_out[r])
      link.nodes.push_back(std::uint32_t(index_in(global_node, n.global)));
    share.ghost_sends.push_back(std::move(link));
  }

  // The view and the pass's state in it.
  std::vector<std::uint32_t> old_known = std::move(share.known);
  share.known = std::move(known);
  contact::ContactSurfaces& view = share.view;
  view.segments.clear();
  for (const contact::SegmentNodes& g : known_segments) view.segments.push_back(in_store(g, s));
  view.edges.clear();
  if (share.edges) view.edges = known_edges;
  if (view.mortar) view.master_area_per_mass = known_area_per_mass;
  auto renumber = [&](std::uint32_t old) -> std::int64_t {
    const std::size_t k = index_in(share.known, old_known[old]);
    return k < share.known.size() ? std::int64_t(k) : -1;
  };
  std::size_t kept = 0;
  for (std::size_t c = 0; c < state.candidates.size(); ++c) {
    const std::int64_t k = renumber(state.candidates[c].segment);
    if (k < 0) continue;
    state.candidates[kept] = {state.candidates[c].point, std::uint32_t(k)};
    state.previous_xi[kept] = state.previous_xi[c];
    ++kept;
  }
  state.candidates.resize(kept);
  state.previous_xi.resize(kept);
  for (contact::Anchor& anchor : state.anchors) {
    if (anchor.segment < 0) continue;
    anchor.segment = renumber(std::uint32_t(anchor.segment));
    EXDYN_ASSERT(anchor.segment >= 0);  // its point lies in this rank's box: the segment came
  }
  // Mortar: the pieces of the last step name their master segments in the new view (a
  // piece whose segment did not come is not a piece again: it keeps no anchor).
  {
    auto& pieces = state.mortar.identity;
    const bool anchors = state.anchors.size() == pieces.size();
    std::size_t kept_pieces = 0;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      const std::int64_t k = renumber(pieces[p].master);
      if (k < 0) continue;
      pieces[kept_pieces] = {pieces[p].slave, std::uint32_t(k), pieces[p].index};
      if (anchors) state.anchors[kept_pieces] = state.anchors[p];
      ++kept_pieces;
    }
    pieces.resize(kept_pieces);
    if (anchors) state.anchors.resize(kept_pieces);
  }
  state.built = false;
  share.ghost_segments = ghosts.size();
  share.ghost_nodes = ghost_nodes;
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
                                     index++, comm.rank, global_node, local, contact_nodes, holders));
      pair.passes[p] = dc.passes.back().view;
    }
    pair.places = {};
  }
  for (RigidWall& wall : contact.walls) {
    dc.passes.push_back(make_share(wall.surfaces, wall.place, index++, comm.rank, global_node, local,
                                   contact_nodes, holders));
    wall.surfaces = dc.passes.back().view;
    wall.place = {};
  }
  dc.local_statistics.resize(contact.pairs.size() + contact.walls.size());
  return dc;
}

void run_distributed_contact(ContactModel& contact, DistributedContact& dc, const Model& model,
                             const std::vector<std::uint32_t>& global_node, const NodalVectors& u,
                             const NodalVectors& v, double time, NodalVectors& force,
                             std::vector<double>& gap) {
  ++dc.steps;
  refresh_stores(dc, u, v);

  // Which pairs' passes search again: the largest motion since their last search over
  // all ranks (an exact max: every rank decides as one process does).
  std::vector<double>& motion = dc.motion;
  motion.clear();
  {
    std::size_t k = 0;
    for (ContactPair& pair : contact.pairs)
      for (std::size_t p = 0; p < pair.passes.size(); ++p, ++k) {
        const PassShare& share = dc.passes[k];
        motion.push_back(contact::largest_motion_since_build(share.view, pair.states[p], share.store.x_ref,
                                                             share.store.u));
      }
  }
  if (!motion.empty()) {
    const ScopedTimer timer(dc.wait_seconds);
    mpi::check(
        MPI_Allreduce(MPI_IN_PLACE, motion.data(), int(motion.size()), MPI_DOUBLE, MPI_MAX, dc.comm.comm),
        "MPI_Allreduce of the contact's motion");
  }

  // The passes, their forces and gaps as records, sent to their nodes' owners.
  std::vector<std::vector<contact::ForceRecord>>& out = dc.outgoing;
  out.resize(std::size_t(dc.comm.size));
  for (auto& records : out) records.clear();
  auto send_records = [&](const PassShare& share, const contact::RecordSink& sink) {
    for (contact::ForceRecord r : sink.records) {
      const int owner = share.store.owner[r.node];
      r.node = share.store.global[r.node];
      out[std::size_t(owner)].push_back(r);
    }
  };
  // A pass writes its records only; these stay empty.
  NodalVectors no_force;
  std::vector<double> no_gap;
  // The deepest slave node as a global id (the pass names it by its store id).
  auto name_deepest = [](contact::ContactStatistics& s, double before, const PassShare& share) {
    if (s.max_penetration_over_h > before) s.deepest_node = share.store.global[s.deepest_node];
  };
  std::size_t k = 0, statistics = 0;
  bool searched = dc.steps == 1;  // the first step: the walls' stores too
  for (ContactPair& pair : contact.pairs) {
    for (std::size_t p = 0; p < pair.passes.size(); ++p, ++k) {
      PassShare& share = dc.passes[k];
      contact::ContactPassState& state = pair.states[p];
      if (motion[k] > 0.5 * pair.settings.margin) {
        search_again(dc, share, pair.settings, state, global_node, model.mesh.x_ref, model.mass, u, v);
        pair.passes[p] = share.view;  // the pair's own copy (the summary's counts)
        searched = true;
      }
      contact::RecordSink& sink = share.sink;
      sink.records.clear();
      sink.pass = share.index;
      sink.point_keys = &share.point_keys;
      state.friction_work = share.local_friction_work;
      contact::ContactStatistics& mine = dc.local_statistics[statistics];
      const double deepest = mine.max_penetration_over_h;
      // The search is decided above, from the motion over all ranks: the pass does not
      // measure it again.
      contact::run_contact_pass(share.view, pair.settings, state, share.store.x_ref, share.store.u,
                                share.store.v, share.store.mass, no_force, no_gap, mine, pair.seconds, &sink,
                                false);
      name_deepest(mine, deepest, share);
      share.local_friction_work = state.friction_work;
      send_records(share, sink);
    }
    ++statistics;
  }
  for (RigidWall& wall : contact.walls) {
    PassShare& share = dc.passes[k++];
    contact::RecordSink& sink = share.sink;
    sink.records.clear();
    sink.pass = share.index;
    sink.point_keys = &share.point_keys;
    wall.state.friction_work = share.local_friction_work;
    contact::ContactStatistics& mine = dc.local_statistics[statistics++];
    const double deepest = mine.max_penetration_over_h;
    contact::run_wall_pass(wall.surfaces, wall.plane, wall.settings, wall.state, share.store.x_ref,
                           share.store.u, share.store.v, share.store.mass, time, no_force, no_gap, mine,
                           wall.seconds, &sink);
    name_deepest(mine, deepest, share);
    share.local_friction_work = wall.state.friction_work;
    send_records(share, sink);
  }
  if (searched) plan_record_peers(dc);
  add_records(dc, out, global_node, force, gap);
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

}  // namespace exdyn::solver
