// The contact's state in a checkpoint on many ranks (contact_checkpoint.hpp): each
// rank's passes in its view's numbering made one process's (slave points by ascending
// key, segments by their index in the whole pass), and back on any number of ranks.
#include "ranks/contact_checkpoint.hpp"

#include <algorithm>
#include <numeric>
#include <tuple>
#include <type_traits>

#include "common/errors.hpp"
#include "contact/mortar_pass.hpp"
#include "ranks/contact_share.hpp"
#include "ranks/rank_checkpoint.hpp"

namespace exdyn::solver {

using namespace shares;

namespace {

// Where each point of the whole pass comes from: (rank, its index there), by ascending key.
struct PointOrder {
  std::vector<std::uint64_t> keys;
  std::vector<std::pair<std::size_t, std::size_t>> from;
};
PointOrder point_order(const mpi::Communicator& comm, const std::vector<std::uint64_t>& keys) {
  PointOrder order;
  const auto all = gather_to_root(comm, keys);
  std::vector<std::tuple<std::uint64_t, std::size_t, std::size_t>> items;
  for (std::size_t r = 0; r < all.size(); ++r)
    for (std::size_t i = 0; i < all[r].size(); ++i) items.emplace_back(all[r][i], r, i);
  std::sort(items.begin(), items.end());
  for (const auto& [key, r, i] : items) order.keys.push_back(key), order.from.emplace_back(r, i);
  return order;
}

// A per-point array of every rank in the whole pass's order on rank 0: sized by the
// points, or empty where no rank sized it. Collective.
template <class T>
void gather_points(const mpi::Communicator& comm, const PointOrder& order, const std::vector<T>& mine,
                   std::size_t points, std::vector<T>& whole) {
  const auto all = gather_to_root(comm, mine.size() == points ? mine : std::vector<T>{});
  whole.clear();
  if (!comm.root()) return;
  std::size_t total = 0;
  for (const auto& from : all) total += from.size();
  if (total == 0) return;
  EXDYN_ASSERT(total == order.keys.size());
  for (const auto& [r, i] : order.from) whole.push_back(all[r][i]);
}

// A pass's per-candidate arrays in the whole pass's order on rank 0 (candidate points
// the whole pass's, segments the whole pass's). Collective.
void gather_candidates(const mpi::Communicator& comm, const PointOrder& order, const PassShare& share,
                       const contact::ContactPassState& state, contact::ContactPassState& whole) {
  const std::size_t points = share.point_keys.size();
  std::vector<std::uint32_t> counts(points, 0), segments;
  if (state.point_begin.size() == points + 1)
    for (std::size_t p = 0; p < points; ++p)
      counts[p] = std::uint32_t(state.point_begin[p + 1] - state.point_begin[p]);
  for (const contact::CandidatePair& c : state.candidates) segments.push_back(share.known[c.segment]);
  const auto all_counts = gather_to_root(comm, counts);
  const auto all_segments = gather_to_root(comm, segments);
  const auto all_xi = gather_to_root(comm, state.previous_xi);
  const bool admitted = state.admitted.size() == state.candidates.size() && !state.candidates.empty();
  const auto all_admitted = gather_to_root(comm, admitted ? state.admitted : std::vector<std::uint8_t>{});
  whole.candidates.clear(), whole.previous_xi.clear(), whole.admitted.clear(), whole.point_begin.clear();
  if (!comm.root()) return;
  // Each rank's first candidate of each of its points.
  std::vector<std::vector<std::size_t>> begin(all_counts.size());
  bool any_admitted = false;
  for (std::size_t r = 0; r < all_counts.size(); ++r) {
    begin[r].assign(1, 0);
    for (const std::uint32_t n : all_counts[r]) begin[r].push_back(begin[r].back() + n);
    any_admitted = any_admitted || !all_admitted[r].empty();
  }
  whole.point_begin.push_back(0);
  for (std::size_t w = 0; w < order.from.size(); ++w) {
    const auto [r, i] = order.from[w];
    for (std::size_t c = begin[r][i]; c < begin[r][i + 1]; ++c) {
      whole.candidates.push_back({std::uint32_t(w), all_segments[r][c]});
      whole.previous_xi.push_back(all_xi[r][c]);
      if (any_admitted) whole.admitted.push_back(all_admitted[r].empty() ? 0 : all_admitted[r][c]);
    }
    whole.point_begin.push_back(whole.candidates.size());
  }
}

// Values of the pass's segments (own ones, by whole-pass index) on rank 0, by index.
template <class T>
std::vector<T> gather_segments(const mpi::Communicator& comm, const std::vector<std::uint32_t>& ids,
                               const std::vector<T>& mine) {
  const auto all_ids = gather_to_root(comm, mine.size() == ids.size() ? ids : std::vector<std::uint32_t>{});
  const auto all = gather_to_root(comm, mine.size() == ids.size() ? mine : std::vector<T>{});
  std::vector<T> whole;
  if (!comm.root()) return whole;
  std::size_t total = 0;
  for (const auto& from : all) total += from.size();
  whole.resize(total);
  for (std::size_t r = 0; r < all.size(); ++r)
    for (std::size_t i = 0; i < all[r].size(); ++i) {
      EXDYN_ASSERT(all_ids[r][i] < total);
      whole[all_ids[r][i]] = all[r][i];
    }
  return whole;
}

// The positions at the last search of the pass's moving nodes (global ids, ascending)
// on rank 0.
void gather_moving(const mpi::Communicator& comm, const PassShare& share,
                   const contact::ContactPassState& state, std::vector<std::uint32_t>& ids,
                   NodalVectors& at_build) {
  struct Moving {
    std::uint32_t node;
    double x[3];
  };
  std::vector<Moving> mine;
  if (state.moving_at_build.size() == share.view.moving_nodes.size())
    for (std::size_t i = 0; i < share.view.moving_nodes.size(); ++i)
      mine.push_back({share.store.global[share.view.moving_nodes[i]],
                      {state.moving_at_build.x[i], state.moving_at_build.y[i], state.moving_at_build.z[i]}});
  const auto all = gather_to_root(comm, mine);
  ids.clear();
  at_build = NodalVectors();
  if (!comm.root()) return;
  std::vector<Moving> every;
  for (const auto& from : all) every.insert(every.end(), from.begin(), from.end());
  std::stable_sort(every.begin(), every.end(),
                   [](const Moving& a, const Moving& b) { return a.node < b.node; });
  for (const Moving& m : every) {  // a node of segments on several ranks: the same bits on each
    if (!ids.empty() && ids.back() == m.node) continue;
    ids.push_back(m.node);
    for (int c = 0; c < 3; ++c) at_build.component(c).push_back(m.x[c]);
  }
}

// A view's segment as its whole-pass index (-1 stays -1).
std::int64_t whole_index(const PassShare& share, std::int64_t segment) {
  return segment < 0 ? segment : std::int64_t(share.known[std::size_t(segment)]);
}

void gather_point_state(const mpi::Communicator& comm, const PointOrder& order, const PassShare& share,
                        const contact::ContactPassState& state, contact::ContactPassState& w);
void gather_mortar(const mpi::Communicator& comm, const PointOrder& order, const PassShare& share,
                   const contact::ContactPassState& state, contact::ContactPassState& w);
void restore_mortar(DistributedContact& dc, PassShare& share, std::size_t whole_segments,
                    const contact::ContactPassState& w, const std::vector<std::size_t>& place,
                    contact::ContactPassState& state, const RestartNodes& nodes);

void gather_pass(const mpi::Communicator& comm, const PassShare& share,
                 const contact::ContactPassState& state, contact::ContactSurfaces& whole_surfaces,
                 contact::ContactPassState& whole, std::vector<std::uint64_t>& keys) {
  const PointOrder order = point_order(comm, share.point_keys);
  keys = order.keys;
  contact::ContactPassState& w = whole;
  // The scalars are every rank's (the figures summed over the ranks each step).
  w.built = state.built, w.rebuilds = state.rebuilds;
  w.slave_force = state.slave_force, w.slave_normal_force = state.slave_normal_force;
  w.slave_tangential_force = state.slave_tangential_force, w.max_penetration = state.max_penetration;
  w.normal_force_sum = state.normal_force_sum, w.tangential_force_sum = state.tangential_force_sum;
  w.points_in_contact = state.points_in_contact, w.slipping = state.slipping, w.sticking = state.sticking;
  w.friction_work = state.friction_work;
  if (share.own.mortar)
    gather_mortar(comm, order, share, state, w);
  else
    gather_point_state(comm, order, share, state, w);
  gather_moving(comm, share, state, whole_surfaces.moving_nodes, w.moving_at_build);
  // The surface as erosion left it: the whole pass every rank keeps; otherwise the own
  // segments' edges and neighbours (whole-pass indices), set up once.
  if (!share.whole.segment_element.empty()) {
    whole_surfaces.segment_live = share.whole.segment_live;
    whole_surfaces.point_live = share.whole.point_live;
    whole_surfaces.edges = share.whole.edges;
    whole_surfaces.edge_neighbours = share.whole.edge_neighbours;
  } else {
    whole_surfaces.edges = gather_segments(comm, share.segment_ids, share.own.edges);
    whole_surfaces.edge_neighbours = gather_segments(comm, share.segment_ids, share.own.edge_neighbours);
  }
}

// The candidates of the last search and each point's arrays of the last step.
void gather_point_state(const mpi::Communicator& comm, const PointOrder& order, const PassShare& share,
                        const contact::ContactPassState& state, contact::ContactPassState& w) {
  const std::size_t points = share.point_keys.size();
  gather_candidates(comm, order, share, state, w);
  std::vector<contact::ContactPassState::Contact> contacts = state.contacts;
  for (auto& c : contacts) c.segment = whole_index(share, c.segment);
  std::vector<contact::Anchor> anchors = state.anchors;
  for (auto& a : anchors) a.segment = whole_index(share, a.segment);
  std::vector<std::int64_t> last = state.last_segment;
  for (auto& s : last) s = whole_index(share, s);
  gather_points(comm, order, contacts, points, w.contacts);
  gather_points(comm, order, anchors, points, w.anchors);
  gather_points(comm, order, last, points, w.last_segment);
  gather_points(comm, order, state.exposure_offset, points, w.exposure_offset);
  gather_points(comm, order, state.force_magnitude, points, w.force_magnitude);
  gather_points(comm, order, state.point_force, points, w.point_force);
  gather_points(comm, order, state.pair_stiffness, points, w.pair_stiffness);
  gather_points(comm, order, state.tangential_force, points, w.tangential_force);
  gather_points(comm, order, state.dissipation, points, w.dissipation);
}

// Mortar (mortar_pass.hpp): a point is a piece of a slave segment, cut again each step,
// so what the next step reads of the last is the segment pairs of the last search (by
// slave segment, its key its index in the whole pass) and the pieces of the last step
// with their friction anchors, which the next step's points of the same piece take. The
// pieces in one process's order: by slave segment, master segment, place.
void gather_mortar(const mpi::Communicator& comm, const PointOrder& order, const PassShare& share,
                   const contact::ContactPassState& state, contact::ContactPassState& w) {
  const contact::MortarState& m = state.mortar;
  const std::size_t segments = share.point_keys.size();
  std::vector<std::uint32_t> counts(segments, 0), masters;
  if (m.pair_begin.size() == segments + 1)
    for (std::size_t s = 0; s < segments; ++s)
      counts[s] = std::uint32_t(m.pair_begin[s + 1] - m.pair_begin[s]);
  for (const contact::CandidatePair& pair : m.pairs) masters.push_back(share.known[pair.segment]);
  const auto all_counts = gather_to_root(comm, counts);
  const auto all_masters = gather_to_root(comm, masters);
  struct Piece {
    contact::MortarState::Identity identity;  // slave: the key; master: the whole-pass index
    contact::Anchor anchor;                   // segment: the whole-pass index
  };
  const bool anchored = !m.identity.empty() && state.anchors.size() == m.identity.size();
  std::vector<Piece> pieces;
  for (std::size_t p = 0; p < m.identity.size(); ++p) {
    const contact::MortarState::Identity& id = m.identity[p];
    Piece piece{{std::uint32_t(share.point_keys[id.slave]), share.known[id.master], id.index}, {}};
    if (anchored) piece.anchor = {whole_index(share, state.anchors[p].segment), state.anchors[p].xi};
    pieces.push_back(piece);
  }
  const auto all_pieces = gather_to_root(comm, pieces);
  const auto any_anchored = gather_to_root(comm, std::vector<std::uint8_t>{std::uint8_t(anchored ? 1 : 0)});
  contact::MortarState& wm = w.mortar;
  if (!comm.root()) return;
  std::vector<std::vector<std::size_t>> begin(all_counts.size());
  for (std::size_t r = 0; r < all_counts.size(); ++r) {
    begin[r].assign(1, 0);
    for (const std::uint32_t n : all_counts[r]) begin[r].push_back(begin[r].back() + n);
  }
  wm.pair_begin.assign(1, 0);
  for (std::size_t k = 0; k < order.from.size(); ++k) {
    const auto [r, i] = order.from[k];
    for (std::size_t c = begin[r][i]; c < begin[r][i + 1]; ++c)
      wm.pairs.push_back({std::uint32_t(order.keys[k]), all_masters[r][c]});
    wm.pair_begin.push_back(wm.pairs.size());
  }
  std::vector<Piece> every;
  for (const auto& from : all_pieces) every.insert(every.end(), from.begin(), from.end());
  std::sort(every.begin(), every.end(),
            [](const Piece& a, const Piece& b) { return a.identity < b.identity; });
  const bool with_anchors = std::any_of(any_anchored.begin(), any_anchored.end(),
                                        [](const std::vector<std::uint8_t>& a) { return a[0] != 0; });
  for (const Piece& piece : every) {
    wm.identity.push_back(piece.identity);
    if (with_anchors) w.anchors.push_back(piece.anchor);
  }
}

void gather_wall(const mpi::Communicator& comm, const PassShare& share, const contact::WallState& state,
                 contact::WallState& whole, std::vector<std::uint64_t>& keys) {
  const PointOrder order = point_order(comm, share.point_keys);
  keys = order.keys;
  const std::size_t points = share.point_keys.size();
  whole = state;  // the figures: every rank's
  gather_points(comm, order, state.anchors, points, whole.anchors);
  gather_points(comm, order, state.anchored, points, whole.anchored);
  gather_points(comm, order, state.point_force, points, whole.point_force);
  gather_points(comm, order, state.dissipation, points, whole.dissipation);
  gather_points(comm, order, state.stiffness, points, whole.stiffness);
  whole.slave_points = NodalVectors();
}

// Each own point's place in the whole pass (keys ascending).
std::vector<std::size_t> places_of(const PassShare& share, const std::vector<std::uint64_t>& keys) {
  std::vector<std::size_t> place;
  for (const std::uint64_t key : share.point_keys) {
    const std::size_t w = index_in(keys, key);
    if (w == keys.size()) throw InputError("the checkpoint's contact lacks a slave point of this run");
    place.push_back(w);
  }
  return place;
}

// The own points' values of a whole pass's per-point array (empty stays empty).
template <class T>
void pick_points(const std::vector<T>& whole, const std::vector<std::size_t>& place, std::size_t points,
                 std::vector<T>& mine) {
  if (whole.size() != points) {
    mine.clear();
    return;
  }
  mine.resize(place.size());
  for (std::size_t p = 0; p < place.size(); ++p) mine[p] = whole[place[p]];
}

void restore_pass(DistributedContact& dc, PassShare& share, const contact::ContactSurfaces& whole_surfaces,
                  const contact::ContactPassState& w, const std::vector<std::uint64_t>& keys,
                  contact::ContactPassState& state, const RestartNodes& nodes) {
  const std::vector<std::size_t> place = places_of(share, keys);
  const std::size_t points = keys.size();
  state.built = w.built, state.rebuilds = w.rebuilds;
  state.slave_force = w.slave_force, state.slave_normal_force = w.slave_normal_force;
  state.slave_tangential_force = w.slave_tangential_force, state.max_penetration = w.max_penetration;
  state.normal_force_sum = w.normal_force_sum, state.tangential_force_sum = w.tangential_force_sum;
  state.points_in_contact = w.points_in_contact, state.slipping = w.slipping, state.sticking = w.sticking;
  state.friction_work = w.friction_work;
  share.local_friction_work = dc.comm.root() ? w.friction_work : 0.0;  // the sum over the ranks goes on
  // The positions at the last search of the own moving nodes, by global id.
  state.moving_at_build = NodalVectors();
  if (w.moving_at_build.size() > 0) {
    const std::vector<std::uint32_t>& ids = whole_surfaces.moving_nodes;
    state.moving_at_build.resize(share.view.moving_nodes.size());
    for (std::size_t i = 0; i < share.view.moving_nodes.size(); ++i) {
      const std::size_t k = index_in(ids, share.store.global[share.view.moving_nodes[i]]);
      if (k == ids.size()) throw InputError("the checkpoint's contact lacks a moving node of this run");
      for (int c = 0; c < 3; ++c) state.moving_at_build.component(c)[i] = w.moving_at_build.component(c)[k];
    }
  }
  if (share.own.mortar) {
    restore_mortar(dc, share, keys.size(), w, place, state, nodes);
    return;
  }
  pick_points(w.contacts, place, points, state.contacts);
  pick_points(w.anchors, place, points, state.anchors);
  pick_points(w.last_segment, place, points, state.last_segment);
  pick_points(w.exposure_offset, place, points, state.exposure_offset);
  pick_points(w.force_magnitude, place, points, state.force_magnitude);
  pick_points(w.point_force, place, points, state.point_force);
  pick_points(w.pair_stiffness, place, points, state.pair_stiffness);
  pick_points(w.tangential_force, place, points, state.tangential_force);
  pick_points(w.dissipation, place, points, state.dissipation);
  state.candidates.clear(), state.previous_xi.clear(), state.admitted.clear(), state.point_begin.clear();
  if (w.point_begin.size() == points + 1) {
    const bool admitted = w.admitted.size() == w.candidates.size() && !w.candidates.empty();
    state.point_begin.push_back(0);
    for (std::size_t p = 0; p < place.size(); ++p) {
      for (std::size_t c = w.point_begin[place[p]]; c < w.point_begin[place[p] + 1]; ++c) {
        state.candidates.push_back({std::uint32_t(p), w.candidates[c].segment});
        state.previous_xi.push_back(w.previous_xi[c]);
        if (admitted) state.admitted.push_back(w.admitted[c]);
      }
      state.point_begin.push_back(state.candidates.size());
    }
  }
  // A surface that follows erosion: the whole pass as the checkpoint left it, and the
  // own segments' edges and neighbours from it (open_eroded_shares).
  if (!share.whole.segment_element.empty()) {
    contact::ContactSurfaces& whole = share.whole;
    if (whole_surfaces.segment_live.size() != whole.segments.size() ||
        whole_surfaces.point_live.size() != whole.point_count() ||
        whole_surfaces.edges.size() != whole.edges.size() ||
        whole_surfaces.edge_neighbours.size() != whole.edge_neighbours.size())
      throw InputError("the checkpoint's contact is of another surface");
    whole.segment_live = whole_surfaces.segment_live;
    whole.point_live = whole_surfaces.point_live;
    whole.edges = whole_surfaces.edges;
    whole.edge_neighbours = whole_surfaces.edge_neighbours;
    for (std::size_t i = 0; i < share.own.segments.size(); ++i) {
      const std::uint32_t id = share.segment_ids[i];
      if (!share.own.edges.empty()) share.own.edges[i] = whole.edges[id];
      if (share.own.single_surface) share.own.edge_neighbours[i] = whole.edge_neighbours[id];
    }
  }
  // The segments the state names (and a single surface's corners at its nodes) in the view.
  std::vector<std::uint32_t> needed;
  for (const contact::CandidatePair& c : state.candidates) needed.push_back(c.segment);
  for (const auto& c : state.contacts)
    if (c.segment >= 0) needed.push_back(std::uint32_t(c.segment));
  for (const contact::Anchor& a : state.anchors)
    if (a.segment >= 0) needed.push_back(std::uint32_t(a.segment));
  for (const std::int64_t s : state.last_segment)
    if (s >= 0) needed.push_back(std::uint32_t(s));
  for (const contact::NodeCorner& corner : share.own.node_corners) needed.push_back(corner.segment);
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
  std::vector<contact::ContactPassState::Contact> contacts = std::move(state.contacts);
  state.contacts.clear();
  restore_view(dc, share, needed, state, nodes.global_node, nodes.x_ref, nodes.mass, nodes.u, nodes.v);
  for (auto& c : contacts)
    if (c.segment >= 0) {
      const std::size_t k = index_in(share.known, std::uint32_t(c.segment));
      EXDYN_ASSERT(k < share.known.size());
      c.segment = std::int64_t(k);
    }
  state.contacts = std::move(contacts);
}

// Mortar (gather_mortar): the own slave segments' pairs and pieces, with their anchors,
// and a view of every master segment they name; the pass's view of its segments.
void restore_mortar(DistributedContact& dc, PassShare& share, std::size_t whole_segments,
                    const contact::ContactPassState& w, const std::vector<std::size_t>& place,
                    contact::ContactPassState& state, const RestartNodes& nodes) {
  const contact::MortarState& wm = w.mortar;
  contact::MortarState& m = state.mortar;
  const std::size_t segments = place.size();
  m.pairs.clear(), m.identity.clear(), m.previous_identity.clear(), m.previous_anchors.clear();
  m.pair_begin.clear();
  state.anchors.clear();
  state.candidates.clear(), state.previous_xi.clear(), state.point_begin.clear(), state.contacts.clear(),
      state.last_segment.clear();
  std::vector<std::uint32_t> needed;
  if (wm.pair_begin.size() == whole_segments + 1) {
    m.pair_begin.assign(1, 0);
    for (std::size_t s = 0; s < segments; ++s) {
      for (std::size_t c = wm.pair_begin[place[s]]; c < wm.pair_begin[place[s] + 1]; ++c) {
        m.pairs.push_back({std::uint32_t(s), wm.pairs[c].segment});
        needed.push_back(wm.pairs[c].segment);
      }
      m.pair_begin.push_back(m.pairs.size());
    }
  }
  const bool anchored = w.anchors.size() == wm.identity.size() && !wm.identity.empty();
  for (std::size_t k = 0; k < wm.identity.size(); ++k) {
    const contact::MortarState::Identity& id = wm.identity[k];
    const std::size_t s = index_in(share.point_keys, std::uint64_t(id.slave));
    if (s == share.point_keys.size()) continue;  // another rank's slave segment
    m.identity.push_back({std::uint32_t(s), id.master, id.index});
    needed.push_back(id.master);
    if (!anchored) continue;
    state.anchors.push_back(w.anchors[k]);
    if (w.anchors[k].segment >= 0) needed.push_back(std::uint32_t(w.anchors[k].segment));
  }
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
  restore_view(dc, share, needed, state, nodes.global_node, nodes.x_ref, nodes.mass, nodes.u, nodes.v);
  for (contact::CandidatePair& pair : m.pairs) {  // the view's numbering (restore_view renumbers the pieces)
    const std::size_t k = index_in(share.known, pair.segment);
    EXDYN_ASSERT(k < share.known.size());
    pair.segment = std::uint32_t(k);
  }
  contact::set_mortar_view_segments(share.view, m);
}

void restore_wall(const mpi::Communicator& comm, PassShare& share, const contact::WallState& w,
                  const std::vector<std::uint64_t>& keys, contact::WallState& state) {
  const std::vector<std::size_t> place = places_of(share, keys);
  const std::size_t points = keys.size();
  NodalVectors slave_points = std::move(state.slave_points);
  state = w;
  state.slave_points = std::move(slave_points);
  pick_points(w.anchors, place, points, state.anchors);
  pick_points(w.anchored, place, points, state.anchored);
  pick_points(w.point_force, place, points, state.point_force);
  pick_points(w.dissipation, place, points, state.dissipation);
  pick_points(w.stiffness, place, points, state.stiffness);
  share.local_friction_work = comm.root() ? w.friction_work : 0.0;
}

}  // namespace

void gather_contact(const ContactModel& contact, DistributedContact& dc, ContactModel& whole,
                    std::vector<std::vector<std::uint64_t>>& keys) {
  whole = ContactModel();
  keys.assign(dc.passes.size(), {});
  std::size_t k = 0, statistics = 0;
  for (const ContactPair& pair : contact.pairs) {
    ContactPair& w = whole.pairs.emplace_back();
    w.name = pair.name;
    w.statistics = pair.statistics;  // every rank's sum
    w.seconds = pair.seconds;
    w.max_force = pair.max_force;
    w.peak_normal_force_sum = pair.peak_normal_force_sum;
    w.points_in_contact_at_peak = pair.points_in_contact_at_peak;
    w.passes.resize(pair.passes.size());
    w.states.resize(pair.passes.size());
    for (std::size_t p = 0; p < pair.passes.size(); ++p, ++k)
      gather_pass(dc.comm, dc.passes[k], pair.states[p], w.passes[p], w.states[p], keys[k]);
    ++statistics;
  }
  for (const RigidWall& wall : contact.walls) {
    RigidWall& w = whole.walls.emplace_back();
    w.name = wall.name;
    w.statistics = wall.statistics;
    w.seconds = wall.seconds;
    w.max_force = wall.max_force;
    gather_wall(dc.comm, dc.passes[k], wall.state, w.state, keys[k]);
    ++k, ++statistics;
  }
}

void restore_contact(const ContactModel& whole, const std::vector<std::vector<std::uint64_t>>& keys,
                     ContactModel& contact, DistributedContact& dc, const RestartNodes& nodes) {
  if (whole.pairs.size() != contact.pairs.size() || whole.walls.size() != contact.walls.size() ||
      keys.size() != dc.passes.size())
    throw InputError("the checkpoint's contact is of another deck");
  std::size_t k = 0, statistics = 0;
  for (std::size_t i = 0; i < contact.pairs.size(); ++i) {
    ContactPair& pair = contact.pairs[i];
    const ContactPair& w = whole.pairs[i];
    if (w.states.size() != pair.states.size())
      throw InputError("the checkpoint's contact is of another deck");
    pair.statistics = w.statistics;
    pair.seconds = w.seconds;
    pair.max_force = w.max_force;
    pair.peak_normal_force_sum = w.peak_normal_force_sum;
    pair.points_in_contact_at_peak = w.points_in_contact_at_peak;
    // This rank's share of the run's statistics: all of it on rank 0 (sums and maxima).
    dc.local_statistics[statistics++] = dc.comm.root() ? w.statistics : contact::ContactStatistics{};
    for (std::size_t p = 0; p < pair.passes.size(); ++p, ++k) {
      restore_pass(dc, dc.passes[k], w.passes[p], w.states[p], keys[k], pair.states[p], nodes);
      pair.passes[p] = dc.passes[k].view;
    }
  }
  for (std::size_t i = 0; i < contact.walls.size(); ++i, ++k) {
    RigidWall& wall = contact.walls[i];
    const RigidWall& w = whole.walls[i];
    wall.statistics = w.statistics;
    wall.seconds = w.seconds;
    wall.max_force = w.max_force;
    dc.local_statistics[statistics++] = dc.comm.root() ? w.statistics : contact::ContactStatistics{};
    restore_wall(dc.comm, dc.passes[k], w.state, keys[k], wall.state);
  }
  dc.steps = 0;  // the first step plans the force records' peers (the stores changed)
}

}  // namespace exdyn::solver
