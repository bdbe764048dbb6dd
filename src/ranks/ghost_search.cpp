// The search that brings a pass's ghost segments on many ranks (contact_share.hpp,
// docs/parallel.md): the box exchange, the ghosts, the store and the view.
#include <algorithm>
#include <array>
#include <limits>

#include "common/errors.hpp"
#include "contact/bucket_search.hpp"
#include "contact/slave_points.hpp"
#include "ranks/contact_share.hpp"

namespace exdyn::solver::shares {

namespace {

// Whether own segment i of the share is on its surface (a surface that follows erosion:
// one off it is no candidate, so it travels to no rank and stays out of the views).
bool own_segment_on(const PassShare& share, std::size_t i) {
  return share.whole.segment_live.empty() || share.whole.segment_live[share.segment_ids[i]] != 0;
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

// What a search sends and receives: the ghost segments that came (ascending id), and
// the nodes sent to and received from each rank.
struct GhostExchange {
  std::vector<SegmentPayload> ghosts;
  std::vector<std::vector<NodePayload>> nodes_in, nodes_out;
};

// A node of an own segment (in the store's fixed part) as it travels.
NodePayload payload_of(const ContactStore& store, std::uint32_t g) {
  const std::size_t i = store_index(store, g);
  NodePayload n;
  n.global = g;
  n.owner = store.owner[i];
  n.mass = store.mass[i];
  for (int c = 0; c < 3; ++c) {
    n.x_ref[c] = store.x_ref.component(c)[i];
    n.u[c] = store.u.component(c)[i];
    n.v[c] = store.v.component(c)[i];
  }
  return n;
}

// Own segments to other ranks: segment i to rank r where send(r, i), with its nodes
// that rank does not hold. Collective over dc.comm.
template <class Send>
GhostExchange send_segments(DistributedContact& dc, const PassShare& share, const Send& send) {
  const auto ranks = std::size_t(dc.comm.size);
  std::vector<std::vector<SegmentPayload>> segments_out(ranks);
  GhostExchange x;
  x.nodes_out.resize(ranks);
  for (std::size_t r = 0; r < ranks; ++r) {
    if (int(r) == dc.comm.rank) continue;
    std::vector<std::uint32_t> sent;  // global ids
    for (std::size_t i = 0; i < share.own.segments.size(); ++i) {
      if (!send(r, i) || !own_segment_on(share, i)) continue;
      const contact::SegmentNodes& s = share.own.segments[i];
      segments_out[r].push_back({share.segment_ids[i], s,
                                 share.own.edges.empty() ? contact::SegmentEdges{} : share.own.edges[i],
                                 share.own.mortar ? share.own.master_area_per_mass[i] : 0.0});
      if (share.own.single_surface) {
        segments_out[r].back().first_part = share.own.first_part_segment[i];
        segments_out[r].back().neighbours = share.own.edge_neighbours[i];
        if (!share.own.segment_face.empty()) segments_out[r].back().face = share.own.segment_face[i];
      }
      for (int k = 0; k < contact::node_count(s.type); ++k) {
        const std::uint32_t g = s.nodes[std::size_t(k)];
        const std::vector<int>& h = dc.holders[index_in(dc.held, g)];
        if (!std::binary_search(h.begin(), h.end(), int(r))) sent.push_back(g);
      }
    }
    std::sort(sent.begin(), sent.end());
    sent.erase(std::unique(sent.begin(), sent.end()), sent.end());
    for (const std::uint32_t g : sent) x.nodes_out[r].push_back(payload_of(share.store, g));
  }
  for (const auto& from : all_to_all(dc, segments_out))
    x.ghosts.insert(x.ghosts.end(), from.begin(), from.end());
  x.nodes_in = all_to_all(dc, x.nodes_out);
  std::sort(x.ghosts.begin(), x.ghosts.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return x;
}

// The box exchange: each own segment goes to every rank whose points' box its capture
// box overlaps, with the nodes that rank does not hold. The segment boxes are the
// bucket search's. Collective over dc.comm.
GhostExchange exchange_ghosts(DistributedContact& dc, const PassShare& share,
                              const contact::ContactPassSettings& settings,
                              const contact::ContactPassState& state) {
  const auto ranks = std::size_t(dc.comm.size);
  const contact::Box mine = point_box(share, state);
  const double six[6] = {mine.lo[0], mine.lo[1], mine.lo[2], mine.hi[0], mine.hi[1], mine.hi[2]};
  std::vector<double> boxes;
  {
    const ScopedTimer timer(dc.wait_seconds);
    boxes = mpi::all_gather(dc.comm, six, 6);
  }
  dc.bytes_sent += 48.0 * double(ranks - 1), dc.messages_sent += double(ranks - 1);
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
  return send_segments(dc, share, [&](std::size_t r, std::size_t i) {
    const contact::Box theirs{{boxes[6 * r], boxes[6 * r + 1], boxes[6 * r + 2]},
                              {boxes[6 * r + 3], boxes[6 * r + 4], boxes[6 * r + 5]}};
    return overlap(own_boxes[i], theirs);
  });
}

// The new view's segments: own and ghost, by index in the whole pass (global node ids).
struct KnownSegments {
  std::vector<std::uint32_t> ids;
  std::vector<contact::SegmentNodes> segments;
  std::vector<contact::SegmentEdges> edges;
  std::vector<double> area_per_mass;
  std::vector<std::uint8_t> first_part;                 // single surface
  std::vector<std::array<std::int32_t, 4>> neighbours;  // single surface: by whole-pass index
  std::vector<std::uint32_t> face;                      // single surface: segment_face
};
KnownSegments merge_known(const PassShare& share, const std::vector<SegmentPayload>& ghosts) {
  KnownSegments known;
  for (std::size_t i = 0, j = 0; i < share.segment_ids.size() || j < ghosts.size();) {
    const bool own =
        j == ghosts.size() || (i < share.segment_ids.size() && share.segment_ids[i] < ghosts[j].id);
    if (own && !own_segment_on(share, i)) {
      ++i;
      continue;
    }
    if (own) {
      known.ids.push_back(share.segment_ids[i]);
      known.segments.push_back(share.own.segments[i]);
      known.edges.push_back(share.own.edges.empty() ? contact::SegmentEdges{} : share.own.edges[i]);
      known.area_per_mass.push_back(share.own.mortar ? share.own.master_area_per_mass[i] : 0.0);
      if (share.own.single_surface) {
        known.first_part.push_back(share.own.first_part_segment[i]);
        known.neighbours.push_back(share.own.edge_neighbours[i]);
        if (!share.own.segment_face.empty()) known.face.push_back(share.own.segment_face[i]);
      }
      ++i;
    } else {
      known.ids.push_back(ghosts[j].id);
      known.segments.push_back(ghosts[j].nodes);
      known.edges.push_back(ghosts[j].edges);
      known.area_per_mass.push_back(ghosts[j].area_per_mass);
      known.first_part.push_back(ghosts[j].first_part);
      known.neighbours.push_back(ghosts[j].neighbours);
      if (!share.own.segment_face.empty()) known.face.push_back(ghosts[j].face);
      ++j;
    }
  }
  return known;
}

// The store: the fixed part, then every other node of a ghost segment, held here
// (from this rank's arrays) or a ghost (its data from the node payloads, filled by
// link_ghosts). Returns the ghost nodes.
std::size_t fill_store(ContactStore& s, const DistributedContact& dc,
                       const std::vector<SegmentPayload>& ghosts,
                       const std::vector<std::uint32_t>& global_node, const NodalVectors& x_ref,
                       const std::vector<double>& mass, const NodalVectors& u, const NodalVectors& v) {
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
  return ghost_nodes;
}

// The ghost nodes' links: their data from the payloads received into the store, and
// the nodes this rank sends each step (local ids).
void link_ghosts(PassShare& share, const GhostExchange& x, const std::vector<std::uint32_t>& global_node) {
  ContactStore& s = share.store;
  share.ghost_receives.clear();
  for (std::size_t r = 0; r < x.nodes_in.size(); ++r) {
    if (x.nodes_in[r].empty()) continue;
    NodeLink link{
        int(r), ghost_tag + int(share.index % 2048), {}, std::vector<double>(6 * x.nodes_in[r].size())};
    for (const NodePayload& n : x.nodes_in[r]) {
      const std::size_t i = store_index(s, n.global);
      EXDYN_ASSERT(i < s.global.size() && s.local[i] < 0);
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
  for (std::size_t r = 0; r < x.nodes_out.size(); ++r) {
    if (x.nodes_out[r].empty()) continue;
    NodeLink link{
        int(r), ghost_tag + int(share.index % 2048), {}, std::vector<double>(6 * x.nodes_out[r].size())};
    for (const NodePayload& n : x.nodes_out[r])
      link.nodes.push_back(std::uint32_t(index_in(global_node, n.global)));
    share.ghost_sends.push_back(std::move(link));
  }
}

// The view of the known segments, and the pass's state in it: its candidates, anchors
// and (mortar) pieces follow their segments; those whose segment did not come go.
void renumber_state(PassShare& share, KnownSegments known, contact::ContactPassState& state) {
  std::vector<std::uint32_t> old_known = std::move(share.known);
  share.known = std::move(known.ids);
  contact::ContactSurfaces& view = share.view;
  view.segments.clear();
  for (const contact::SegmentNodes& g : known.segments) view.segments.push_back(in_store(g, share.store));
  view.edges.clear();
  if (share.edges) view.edges = std::move(known.edges);
  if (view.mortar) view.master_area_per_mass = std::move(known.area_per_mass);
  if (view.single_surface) {
    view.first_part_segment = std::move(known.first_part);
    view.edge_neighbours = std::move(known.neighbours);
    view.segment_face = std::move(known.face);
    index_single_surface(share);
  }
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
  // A single surface: the segment each point last touched (the rule of a contact that
  // begins deep; its point in contact lies in this rank's box: the segment came).
  for (std::int64_t& last : state.last_segment)
    if (last >= 0) last = renumber(std::uint32_t(last));
  // Mortar: the pieces of the last step name their master segments in the new view (a
  // piece whose segment did not come is not a piece again: it keeps no anchor).
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

}  // namespace

void index_single_surface(PassShare& share) {
  contact::ContactSurfaces& view = share.view;
  const contact::ContactSurfaces& own = share.own;
  if (view.edge_neighbours.size() != view.segments.size()) {  // the first view: the own segments
    view.first_part_segment = own.first_part_segment;
    view.edge_neighbours = own.edge_neighbours;
    view.segment_face = own.segment_face;
  }
  for (auto& next : view.edge_neighbours)
    for (std::int32_t& n : next)
      if (n >= 0) {
        const std::size_t k = index_in(share.known, std::uint32_t(n));
        n = k < share.known.size() ? std::int32_t(k) : -1;
      }
  // The corners: those whose segment is in the view (after a search, all of them).
  view.node_corners.clear();
  view.corner_begin.assign(1, 0);
  for (std::size_t p = 0; p + 1 < own.corner_begin.size(); ++p) {
    for (std::uint32_t c = own.corner_begin[p]; c < own.corner_begin[p + 1]; ++c) {
      contact::NodeCorner corner = own.node_corners[c];
      const std::size_t k = index_in(share.known, corner.segment);
      if (k == share.known.size()) continue;
      corner.segment = std::uint32_t(k);
      view.node_corners.push_back(corner);
    }
    view.corner_begin.push_back(std::uint32_t(view.node_corners.size()));
  }
}

// A new candidate search of one pass (every rank together): the box exchange, the
// ghost segments and their nodes, the view and the store; the pass's candidates and
// anchors follow their segments into the new view, and the pass searches again.
void search_again(DistributedContact& dc, PassShare& share, const contact::ContactPassSettings& settings,
                  contact::ContactPassState& state, const std::vector<std::uint32_t>& global_node,
                  const NodalVectors& x_ref, const std::vector<double>& mass, const NodalVectors& u,
                  const NodalVectors& v) {
  const GhostExchange x = exchange_ghosts(dc, share, settings, state);
  KnownSegments known = merge_known(share, x.ghosts);
  const std::size_t ghost_nodes = fill_store(share.store, dc, x.ghosts, global_node, x_ref, mass, u, v);
  link_ghosts(share, x, global_node);
  renumber_state(share, std::move(known), state);
  if (!share.whole.segment_element.empty()) apply_life(share);
  share.opened = false;
  state.built = false;
  share.ghost_segments = x.ghosts.size();
  share.ghost_nodes = ghost_nodes;
}

void restore_view(DistributedContact& dc, PassShare& share, const std::vector<std::uint32_t>& needed,
                  contact::ContactPassState& state, const std::vector<std::uint32_t>& global_node,
                  const NodalVectors& x_ref, const std::vector<double>& mass, const NodalVectors& u,
                  const NodalVectors& v) {
  EXDYN_ASSERT(std::is_sorted(needed.begin(), needed.end()));
  std::vector<std::vector<std::uint32_t>> asked(std::size_t(dc.comm.size), needed);
  asked[std::size_t(dc.comm.rank)].clear();
  const std::vector<std::vector<std::uint32_t>> wanted = all_to_all(dc, asked);
  const GhostExchange x = send_segments(dc, share, [&](std::size_t r, std::size_t i) {
    return std::binary_search(wanted[r].begin(), wanted[r].end(), share.segment_ids[i]);
  });
  KnownSegments known = merge_known(share, x.ghosts);
  const std::size_t ghost_nodes = fill_store(share.store, dc, x.ghosts, global_node, x_ref, mass, u, v);
  link_ghosts(share, x, global_node);
  // The state names its segments by their whole-pass index: the old view is the whole pass.
  share.known.resize(needed.empty() ? 0 : std::size_t(needed.back()) + 1);
  for (std::size_t k = 0; k < share.known.size(); ++k) share.known[k] = std::uint32_t(k);
  renumber_state(share, std::move(known), state);
  if (!share.whole.segment_element.empty()) apply_life(share);
  share.opened = false;
  share.ghost_segments = x.ghosts.size();
  share.ghost_nodes = ghost_nodes;
}

}  // namespace exdyn::solver::shares
