// What a checkpoint holds of the model's state (checkpoint_state.hpp). Scratch that a
// step writes before it reads it (the projections of this step, the scatter's slots,
// the bucket grid, the per-chunk sums) is not saved.
#include "solver/checkpoint_state.hpp"

#include <algorithm>
#include <type_traits>

#include "common/errors.hpp"
#include "contact/mortar_pass.hpp"

namespace exdyn::solver {

namespace {

std::string at(const std::string& prefix, std::size_t k) { return prefix + std::to_string(k) + "/"; }

template <class Archive>
constexpr bool saving = std::is_same_v<std::remove_const_t<Archive>, StateSaver>;

// The key of each slave point of a whole pass, ascending (distributed_contact.hpp): a
// slave node's global id, a quadrature point's index, a mortar slave segment's index.
std::vector<std::uint64_t> whole_point_keys(const contact::ContactSurfaces& s) {
  std::vector<std::uint64_t> keys;
  if (!s.mortar && !s.quadrature) return {s.slave_nodes.begin(), s.slave_nodes.end()};
  keys.resize(s.mortar ? s.slave_segments.size() : s.quadrature_points.size());
  for (std::size_t p = 0; p < keys.size(); ++p) keys[p] = p;
  return keys;
}

// The positions of the moving nodes at the last search, with the nodes' global ids: a
// restart on another number of ranks finds each node's by its id. A whole pass made for
// the file (checkpoint_ranks.cpp: no moving nodes yet) takes both as saved.
template <class Archive>
void visit_moving(Archive& a, const std::string& p, std::vector<std::uint32_t>& moving_nodes,
                  NodalVectors& at_build) {
  if constexpr (saving<Archive>) {
    a(p + "moving_nodes", moving_nodes);
    a(p + "moving_at_build", at_build);
  } else {
    std::vector<std::uint32_t> ids;
    NodalVectors values;
    a(p + "moving_nodes", ids);
    a(p + "moving_at_build", values);
    if (moving_nodes.empty() || values.size() == 0) {
      if (moving_nodes.empty()) moving_nodes = std::move(ids);
      at_build = std::move(values);
      return;
    }
    if (values.size() != ids.size()) throw InputError("the checkpoint's " + p + "moving_at_build is damaged");
    at_build.resize(moving_nodes.size());
    for (std::size_t i = 0; i < moving_nodes.size(); ++i) {
      const auto at = std::lower_bound(ids.begin(), ids.end(), moving_nodes[i]);
      if (at == ids.end() || *at != moving_nodes[i])
        throw InputError("the checkpoint's " + p + "moving_nodes is of another contact");
      for (int c = 0; c < 3; ++c)
        at_build.component(c)[i] = values.component(c)[std::size_t(at - ids.begin())];
    }
  }
}

template <class Archive>
void visit_pass(Archive& a, const std::string& p, contact::ContactSurfaces& s, contact::ContactPassState& t,
                std::vector<std::uint64_t>& keys) {
  a(p + "point_keys", keys);
  // The surface as erosion has left it (opened_faces.hpp).
  a(p + "segment_live", s.segment_live);
  a(p + "point_live", s.point_live);
  a(p + "edges", s.edges);
  a(p + "edge_neighbours", s.edge_neighbours);
  // The candidates of the last search and what decides the next (contact_pass.hpp).
  a(p + "built", t.built);
  a(p + "rebuilds", t.rebuilds);
  a(p + "candidates", t.candidates);
  a(p + "point_begin", t.point_begin);
  a(p + "previous_xi", t.previous_xi);
  visit_moving(a, p, s.moving_nodes, t.moving_at_build);
  a(p + "anchors", t.anchors);
  a(p + "contacts", t.contacts);
  a(p + "admitted", t.admitted);
  a(p + "last_segment", t.last_segment);
  a(p + "exposure_offset", t.exposure_offset);
  // This step's forces and figures, which the history and the summary read.
  a(p + "force_magnitude", t.force_magnitude);
  a(p + "point_force", t.point_force);
  a(p + "pair_stiffness", t.pair_stiffness);
  a(p + "tangential_force", t.tangential_force);
  a(p + "dissipation", t.dissipation);
  a(p + "slave_force", t.slave_force);
  a(p + "slave_normal_force", t.slave_normal_force);
  a(p + "slave_tangential_force", t.slave_tangential_force);
  a(p + "max_penetration", t.max_penetration);
  a(p + "normal_force_sum", t.normal_force_sum);
  a(p + "tangential_force_sum", t.tangential_force_sum);
  a(p + "points_in_contact", t.points_in_contact);
  a(p + "slipping", t.slipping);
  a(p + "sticking", t.sticking);
  a(p + "friction_work", t.friction_work);
  // Mortar (mortar_pass.hpp): the segment pairs of the last search and the pieces of the
  // last step, whose friction anchors the next step's points of the same piece take.
  contact::MortarState& m = t.mortar;
  a(p + "mortar/pairs", m.pairs);
  a(p + "mortar/pair_begin", m.pair_begin);
  a(p + "mortar/centres", m.centres);
  a(p + "mortar/identity", m.identity);
  a(p + "mortar/previous_identity", m.previous_identity);
  a(p + "mortar/previous_anchors", m.previous_anchors);
}

// The values of `full` at the nodes `at` (`where`: each one's place among the saved
// nodes, or -1: not saved): a contact array's, whose other nodes keep what
// set_initial_state gave them (0, or m g with loads) for the whole run.
template <class Archive>
void visit_at(Archive& a, const std::string& name, std::vector<double>& full,
              const std::vector<std::uint32_t>& at, const std::vector<std::int64_t>& where) {
  std::vector<double> values(at.size());
  if constexpr (std::is_same_v<Archive, StateSaver>) {
    for (std::size_t i = 0; i < at.size(); ++i) values[i] = full[at[i]];
    a(name, values);
  } else {
    values.clear();
    a(name, values);
    for (std::size_t i = 0; i < at.size(); ++i) {
      if (where[i] < 0) continue;
      if (std::size_t(where[i]) >= values.size())
        throw InputError("the checkpoint's " + name + " is of another contact");
      full[at[i]] = values[std::size_t(where[i])];
    }
  }
}

template <class Archive>
void visit_at(Archive& a, const std::string& name, NodalVectors& full, const std::vector<std::uint32_t>& at,
              const std::vector<std::int64_t>& where) {
  for (int c = 0; c < 3; ++c) visit_at(a, name + "." + char('x' + c), full.component(c), at, where);
}

}  // namespace

template <class Archive>
void visit_blocks(Archive& a, const std::vector<element::ElementBlock>& blocks) {
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const std::string p = at("block", b);
    element::MaterialState& m = blocks[b].material_state;
    a(p + "points", m.points);
    a(p + "committed", m.committed);
    a(p + "hourglass", m.hourglass);
    a(p + "plastic_strain", m.plastic_strain);
    a(p + "dt", m.dt);
    element::ElementFailure& f = blocks[b].failure;
    a(p + "status", f.status);
    a(p + "damage", f.damage);
    a(p + "failure_plastic_strain", f.plastic_strain);
    a(p + "any_not_alive", f.any_not_alive);
    a(p + "distorted", f.distorted);
    a(p + "held", f.held);
  }
}

template <class Archive>
void visit_contact(Archive& a, ContactModel& contact, std::vector<std::vector<std::uint64_t>>* keys) {
  std::size_t pass = 0;
  for (std::size_t k = 0; k < contact.pairs.size(); ++k) {
    ContactPair& pair = contact.pairs[k];
    const std::string p = at("pair", k);
    a(p + "statistics", pair.statistics);
    a(p + "seconds", pair.seconds);
    a(p + "max_force", pair.max_force);
    a(p + "peak_normal_force_sum", pair.peak_normal_force_sum);
    a(p + "points_in_contact_at_peak", pair.points_in_contact_at_peak);
    for (std::size_t q = 0; q < pair.passes.size(); ++q) {
      std::vector<std::uint64_t> mine;
      std::vector<std::uint64_t>& pass_keys = keys != nullptr ? (*keys)[pass++] : mine;
      if (saving<Archive> && keys == nullptr) pass_keys = whole_point_keys(pair.passes[q]);
      visit_pass(a, at(p + "pass", q), pair.passes[q], pair.states[q], pass_keys);
    }
  }
  for (std::size_t k = 0; k < contact.walls.size(); ++k) {
    RigidWall& wall = contact.walls[k];
    contact::WallState& s = wall.state;
    const std::string p = at("wall", k);
    std::vector<std::uint64_t> mine;
    std::vector<std::uint64_t>& keys_here = keys != nullptr ? (*keys)[pass++] : mine;
    if (saving<Archive> && keys == nullptr) keys_here = whole_point_keys(wall.surfaces);
    a(p + "point_keys", keys_here);
    a(p + "statistics", wall.statistics);
    a(p + "seconds", wall.seconds);
    a(p + "max_force", wall.max_force);
    a(p + "anchors", s.anchors);
    a(p + "anchored", s.anchored);
    a(p + "point_force", s.point_force);
    a(p + "dissipation", s.dissipation);
    a(p + "stiffness", s.stiffness);
    a(p + "force", s.force);
    a(p + "normal_force", s.normal_force);
    a(p + "tangential_force", s.tangential_force);
    a(p + "previous_force", s.previous_force);
    a(p + "max_penetration", s.max_penetration);
    a(p + "slipping", s.slipping);
    a(p + "sticking", s.sticking);
    a(p + "friction_work", s.friction_work);
  }
}

// a^n and f_int(u^n) are not saved: whatever reads them next computes them first
// (compute_accelerations, forces_of_this_step); the restored f_int is cleared by the
// next element pass (internal_force_zero false).
template <class Archive>
void visit_state(Archive& a, State& s, std::vector<std::uint32_t>& contact_nodes,
                 const std::vector<std::uint32_t>* rows) {
  // The contact nodes by global id; `where` places this run's among them.
  std::vector<std::uint32_t> saved = contact_nodes;
  a("state/contact_nodes", saved);
  if (!saving<Archive> && contact_nodes.empty()) contact_nodes = saved;
  std::vector<std::int64_t> where(contact_nodes.size(), -1);
  for (std::size_t i = 0; i < contact_nodes.size(); ++i) {
    const auto at = std::lower_bound(saved.begin(), saved.end(), contact_nodes[i]);
    if (at != saved.end() && *at == contact_nodes[i]) where[i] = at - saved.begin();
  }
  const std::vector<std::uint32_t>& at = rows != nullptr ? *rows : contact_nodes;
  a("state/step", s.step);
  a("state/time", s.time);
  a("state/displacement", s.displacement);
  a("state/velocity", s.velocity);
  a("state/flags", s.flags);
  visit_at(a, "state/contact_force", s.contact_force, at, where);
  visit_at(a, "state/previous_contact_force", s.previous_contact_force, at, where);
  a("state/load_force", s.load_force);
  visit_at(a, "state/gap", s.gap, at, where);
  visit_at(a, "state/previous_gap", s.previous_gap, at, where);
  a("state/stress", s.stress);
  a("state/plastic_strain", s.plastic_strain);
  a("state/damage", s.damage);
  a("state/status", s.status);
  a("state/eroded_energy", s.eroded_energy);
  a("state/eroded_elements", s.eroded_elements);
  a("state/stress_step", s.stress_step);
  a("state/force_step", s.force_step);
  if constexpr (!std::is_same_v<Archive, StateSaver>) s.internal_force_zero = false;
  a("state/contact_energy", s.contact_energy);
  a("state/external_work", s.external_work);
  a("state/wall_work", s.wall_work);
  a("state/reaction", s.reaction);
  a("state/previous_reaction", s.previous_reaction);
  a("state/reaction_error", s.reaction_error);
}

void finish_loading_contact(ContactModel& contact) {
  for (ContactPair& pair : contact.pairs)
    for (std::size_t q = 0; q < pair.passes.size(); ++q)
      if (pair.passes[q].mortar && pair.states[q].built)
        contact::set_mortar_view_segments(pair.passes[q], pair.states[q].mortar);
}

template void visit_blocks(StateSaver&, const std::vector<element::ElementBlock>&);
template void visit_blocks(const StateLoader&, const std::vector<element::ElementBlock>&);
template void visit_contact(StateSaver&, ContactModel&, std::vector<std::vector<std::uint64_t>>*);
template void visit_contact(const StateLoader&, ContactModel&, std::vector<std::vector<std::uint64_t>>*);
template void visit_state(StateSaver&, State&, std::vector<std::uint32_t>&,
                          const std::vector<std::uint32_t>*);
template void visit_state(const StateLoader&, State&, std::vector<std::uint32_t>&,
                          const std::vector<std::uint32_t>*);

}  // namespace exdyn::solver
