#include "contact/contact_pass.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/parallel.hpp"
#include "common/timer.hpp"
#include "contact/contact_choice.hpp"
#include "contact/force_scatter.hpp"
#include "contact/mortar_pass.hpp"
#include "contact/penalty.hpp"
#include "contact/single_surface.hpp"
#include "contact/slave_points.hpp"

namespace exdyn::contact {

double largest_motion_since_build(const ContactSurfaces& surfaces, const ContactPassState& state,
                                  const NodalVectors& x_ref, const NodalVectors& u) {
  if (!state.built) return std::numeric_limits<double>::infinity();
  double largest_squared = 0.0;  // a max: the same on any number of threads
  const auto count = static_cast<std::ptrdiff_t>(surfaces.moving_nodes.size());
#pragma omp parallel for schedule(static) reduction(max : largest_squared) if (count >= 4096)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const Vec3 x = current_position(x_ref, u, surfaces.moving_nodes[i]);
    const Vec3 d =
        x - Vec3{state.moving_at_build.x[i], state.moving_at_build.y[i], state.moving_at_build.z[i]};
    largest_squared = std::max(largest_squared, dot(d, d));
  }
  return std::sqrt(largest_squared);
}

namespace {

// Global search: new candidates from the bucket grid; a pair that was a
// candidate before keeps its point from the last step (both lists are sorted).
// A quadrature point lies on its slave segment, so the motion of the slave nodes
// bounds its motion too.
void rebuild_candidates(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                        ContactPassState& state, const NodalVectors& x_ref, const NodalVectors& u) {
  segment_boxes(
      [&](std::uint32_t node) {
        return std::array<double, 3>{x_ref.x[node] + u.x[node], x_ref.y[node] + u.y[node],
                                     x_ref.z[node] + u.z[node]};
      },
      surfaces.segments, settings.search_distance + settings.margin, state.boxes);
  bucket_search(state.slave_points, state.boxes, settings.cell_size, state.workspace, state.new_candidates,
                surfaces.point_live, surfaces.segment_live);
  // A single surface never checks a point against a segment that shares a node with it,
  // nor against one that faces its way, nor one it lies far behind (single_surface.hpp):
  // until the next search none of them can turn to face it within the search distance.
  if (surfaces.single_surface) {
    std::size_t normal_of = std::numeric_limits<std::size_t>::max();  // the point n is of
    Vec3 n{};
    const double behind = settings.search_distance + settings.margin;
    std::erase_if(state.new_candidates, [&](const CandidatePair& pair) {
      if (shares_node(surfaces, pair.point, pair.segment)) return true;
      if (pair.point != normal_of) normal_of = pair.point, n = point_normal(surfaces, pair.point, x_ref, u);
      const Segment segment = current_segment(surfaces.segments[pair.segment], x_ref, u);
      const Vec3 point{state.slave_points.x[pair.point], state.slave_points.y[pair.point],
                       state.slave_points.z[pair.point]};
      return dot(n, outward_normal(segment, Xi{0.0, 0.0})) >= same_way_cosine ||
             behind_beyond(segment, point, behind);
    });
  }

  // Carry the previous points over (merge of two sorted lists).
  state.new_previous_xi.assign(state.new_candidates.size(),
                               Xi{std::numeric_limits<double>::quiet_NaN(), 0.0});
  std::size_t old = 0;
  auto before = [](const CandidatePair& a, const CandidatePair& b) {
    return a.point < b.point || (a.point == b.point && a.segment < b.segment);
  };
  for (std::size_t c = 0; c < state.new_candidates.size(); ++c) {
    while (old < state.candidates.size() && before(state.candidates[old], state.new_candidates[c])) ++old;
    if (old < state.candidates.size() && state.candidates[old] == state.new_candidates[c])
      state.new_previous_xi[c] = state.previous_xi[old];
  }
  std::swap(state.candidates, state.new_candidates);
  std::swap(state.previous_xi, state.new_previous_xi);
  // Where each slave point's candidates start (they are sorted by point).
  state.point_begin.assign(surfaces.point_count() + 1, 0);
  for (const CandidatePair& pair : state.candidates) ++state.point_begin[pair.point + 1];
  for (std::size_t p = 0; p < surfaces.point_count(); ++p) state.point_begin[p + 1] += state.point_begin[p];

  state.moving_at_build.resize(surfaces.moving_nodes.size());
  for (std::size_t i = 0; i < surfaces.moving_nodes.size(); ++i) {
    const Vec3 x = current_position(x_ref, u, surfaces.moving_nodes[i]);
    state.moving_at_build.x[i] = x.x;
    state.moving_at_build.y[i] = x.y;
    state.moving_at_build.z[i] = x.z;
  }
  state.built = true;
  ++state.rebuilds;
}

// The stick anchor of a slipping point goes to y, the point it slid to (a point of the
// master surface's tangent plane at the old anchor, m): to the closest inside projection
// of y, first on the anchor's segment and, if y left it, on the slave point's other
// candidates, so that the anchor crosses onto the next segment and is not reset. With
// no inside projection (y slid off the edge of the master surface) it stays on its
// segment at the closest xi of [-1,1]^2.
Anchor relocate_anchor(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                       const ContactPassState& state, std::size_t p, Vec3 y, Anchor anchor,
                       const NodalVectors& x_ref, const NodalVectors& u) {
  // From the least-squares guess, as the contact's own projection: exact at once on a
  // flat segment, so that mirror images stay mirror images.
  auto project_onto = [&](std::int64_t segment) {
    const Segment current = current_segment(surfaces.segments[static_cast<std::size_t>(segment)], x_ref, u);
    bool settled = false;
    return project_settled(settings, current, y, initial_guess_lsp(current, y), settled);
  };
  auto is_minimum_inside = [](const ProjectionResult& r) {
    return r.converged && r.inside && r.stationary == StationaryKind::minimum;
  };
  const ProjectionResult own = project_onto(anchor.segment);
  if (is_minimum_inside(own)) return Anchor{anchor.segment, own.xi};
  double best_distance = std::numeric_limits<double>::infinity();
  Anchor best{anchor.segment,
              {std::clamp(std::isfinite(own.xi[0]) ? own.xi[0] : 0.0, -1.0, 1.0),
               std::clamp(std::isfinite(own.xi[1]) ? own.xi[1] : 0.0, -1.0, 1.0)}};
  for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1]; ++c) {
    const std::int64_t segment = state.candidates[c].segment;
    if (segment == anchor.segment) continue;
    const ProjectionResult r = project_onto(segment);
    if (is_minimum_inside(r) && r.distance < best_distance)
      best_distance = r.distance, best = {segment, r.xi};
  }
  return best;
}

// Coulomb friction of slave point p at `point` (m) in contact with normal force F_n (N)
// and normal stiffness k (N/m, the tangential one too), slipping at slip_velocity
// (m/s, tangential): its tangential force, its dissipation and its anchor
// (friction.hpp). A point new to contact is taken to have touched at the start of
// the step, where it was a step's slip dt v_slip ago: its anchor is the contact point
// less that slip, so a point that arrives sliding slips from its first step.
void add_friction(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                  ContactPassState& state, std::size_t p, Vec3 point, double k, double normal_force,
                  Vec3 slip_velocity, const NodalVectors& x_ref, const NodalVectors& u) {
  const auto& contact = state.contacts[p];
  Anchor& anchor = state.anchors[p];
  const bool new_contact = anchor.segment < 0;
  if (new_contact) anchor = Anchor{contact.segment, contact.xi};
  const Vec3 y_anchor =
      evaluate(current_segment(surfaces.segments[static_cast<std::size_t>(anchor.segment)], x_ref, u),
               anchor.xi)
          .y;
  const Vec3 tangent_gap =
      new_contact ? settings.dt * slip_velocity : tangential_part(point - y_anchor, contact.normal);
  const TangentialForce t =
      coulomb_force(tangent_gap, k, normal_force, settings.friction.coefficient(norm(slip_velocity)));
  state.tangential_force[p] = t.force;
  state.dissipation[p] = t.dissipation;
  // Where the anchor goes: the contact point less the slip the spring keeps (a new
  // contact), or the old anchor moved by the slip (a slipping one).
  if (new_contact && norm(tangent_gap) > 0.0)
    anchor = relocate_anchor(surfaces, settings, state, p, y_anchor - tangent_gap + t.anchor_shift, anchor,
                             x_ref, u);
  else if (t.slip)
    anchor = relocate_anchor(surfaces, settings, state, p, y_anchor + t.anchor_shift, anchor, x_ref, u);
}

// The penalty force of slave point p along its normal (state.force_magnitude), its
// pair's stiffness (state.pair_stiffness) and, with friction, its tangential force:
// F = max(0, -k g - c (v_s - v_m).n), k the point pair's stiffness (capped when
// automatic), c the dashpot of its reduced mass.
void point_force(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                 ContactPassState& state, std::size_t p, const NodalVectors& x_ref, const NodalVectors& u,
                 const NodalVectors& v, const std::vector<double>& mass) {
  const bool friction = settings.friction.enabled;
  const auto& contact = state.contacts[p];
  if (contact.segment < 0 || contact.gap >= 0.0) {
    if (friction) state.anchors[p] = Anchor{};  // out of contact: no stick to keep
    return;
  }
  const SegmentNodes& master = surfaces.segments[static_cast<std::size_t>(contact.segment)];
  const std::array<double, 8> N = shape_functions(master.type, contact.xi);
  Vec3 master_velocity{};
  double master_inverse_mass = 0.0;  // sum N_i^2 / m_i: the master point's 1 / mass
  for (int i = 0; i < node_count(master.type); ++i) {
    const std::uint32_t node = master.nodes[std::size_t(i)];
    master_velocity = master_velocity + N[std::size_t(i)] * Vec3{v.x[node], v.y[node], v.z[node]};
    master_inverse_mass += N[std::size_t(i)] * N[std::size_t(i)] / mass[node];
  }
  const SlaveSide slave = slave_side(surfaces, p);
  const SlaveMotion motion = slave_motion(slave, v, mass);  // the slave point's velocity and 1 / mass
  const Vec3 slave_velocity = motion.velocity;
  const double slave_inverse_mass = motion.inverse_mass;
  const Vec3 n = contact.normal;
  const double normal_velocity = dot(slave_velocity - master_velocity, n);
  // The point pair's stiffness: a single surface's node takes its side's facing the
  // contact, its Gauss point the kappa capped for the face of the segment it meets.
  double k = surfaces.stiffness[p];
  if (surfaces.single_surface && !surfaces.quadrature) {
    k = side_stiffness(surfaces, p, contact.normal, x_ref, u);
  } else if (!surfaces.face_kappa.empty()) {
    const QuadraturePoint& q = surfaces.quadrature_points[p];
    k = surfaces.face_kappa[q.segment * surfaces.face_count +
                            surfaces.segment_face[std::size_t(contact.segment)]] *
        q.weight;
  }
  if (settings.automatic_stiffness) k *= settings.stiffness_growth;
  if (settings.automatic_stiffness && !surfaces.quadrature) {
    const double inverse_mass = slave_inverse_mass + master_inverse_mass;
    k = std::min({k, settings.stiffness_scale * accurate_stiffness_bound(settings.dt, inverse_mass),
                  settings.stiffness_scale * stable_stiffness_bound(settings.dt, settings.courant,
                                                                    settings.damping_ratio, inverse_mass)});
  }
  state.pair_stiffness[p] = k;
  k /= settings.pass_count;
  const double slave_mass = surfaces.quadrature ? 1.0 / slave_inverse_mass : mass[slave.nodes[0]];
  // A mortar point's dashpot: on the reduced mass per area of its segments times its
  // weight, so that a uniform approach gives a uniform traction.
  const double c = surfaces.point_mass.empty()
                       ? damping_coefficient(settings.damping_ratio, k, slave_mass, 1.0 / master_inverse_mass)
                       : settings.damping_ratio * 2.0 * std::sqrt(k * surfaces.point_mass[p]);
  state.force_magnitude[p] = normal_force(k, c, contact.gap, normal_velocity);
  if (friction && !(state.force_magnitude[p] > 0.0)) state.anchors[p] = Anchor{};
  state.point_force[p] = state.force_magnitude[p] * contact.normal;
  if (friction && state.force_magnitude[p] > 0.0) {
    const Vec3 point{state.slave_points.x[p], state.slave_points.y[p], state.slave_points.z[p]};
    const Vec3 slip_velocity = tangential_part(slave_velocity - master_velocity, n);
    add_friction(surfaces, settings, state, p, point, k, state.force_magnitude[p], slip_velocity, x_ref, u);
    state.point_force[p] = state.point_force[p] + state.tangential_force[p];
  }
}

// On a single surface: where erosion exposes a face, the bodies on either side may
// already overlap it (the eroded element was crushed or sheared flat), and a point
// beside a face across a convex edge, that the facing rule (single_surface.hpp) admits
// only as the two turn to face each other, may be behind it by then (a Taylor rod's
// side above its spreading rim, against the impact face: docs/contact.md). A contact that begins, or passes
// to another segment, deeper than begun_inside of the element length (no step's motion makes that: v dt < 0.1
// L while v < 0.1 c / Courant) began inside: its gap counts from that start g0 < 0, as LS-DYNA's IGNORE
// counts initial penetrations. The offset o = g0 follows the point out, o = max(o, g), so that the force
// resists any deeper penetration and none is added while the overlap heals (g - o = 0); out of contact it is
// forgotten.
void apply_exposure_offsets(const ContactSurfaces& surfaces, ContactPassState& state) {
  const std::size_t n = surfaces.point_count();
  state.exposure_offset.resize(n, 0.0);
  state.last_segment.resize(n, -1);
  for (std::size_t p = 0; p < n; ++p) {
    ContactPassState::Contact& contact = state.contacts[p];
    double& offset = state.exposure_offset[p];
    const bool touching = contact.segment >= 0 && contact.gap < 0.0;
    if (!touching)
      offset = 0.0;
    else if (contact.segment != state.last_segment[p] &&
             contact.gap < -begun_inside * surfaces.normal_length[p])
      offset = contact.gap;
    else if (offset < 0.0)
      offset = std::max(offset, contact.gap);
    state.last_segment[p] = touching ? contact.segment : -1;
    if (touching) contact.gap -= offset;
  }
}

// Slave points per chunk of the force pass: a surface of one chunk runs in place (on a
// few hundred points starting threads costs more than the work).
constexpr std::size_t force_chunk = 256;

// The pass's sums and largest figures (the histories and the summary's), in slave point
// order.
void sum_pass_figures(const ContactSurfaces& surfaces, bool friction, ContactPassState& state,
                      ContactStatistics& statistics) {
  state.slave_force = state.slave_normal_force = state.slave_tangential_force = Vec3{};
  state.max_penetration = 0.0;
  state.normal_force_sum = state.tangential_force_sum = 0.0;
  state.points_in_contact = 0;
  state.slipping = state.sticking = 0;
  // A single surface's force is the force on its first part from the others: its
  // points' forces on the others' segments, less the forces of the others' points on
  // its segments (their reactions); within one part they cancel (sums `reaction`).
  Vec3 reaction_force{}, reaction_normal{}, reaction_tangential{};
  for (std::size_t p = 0; p < state.contacts.size(); ++p) {
    const auto& contact = state.contacts[p];
    if (contact.segment < 0 || contact.gap >= 0.0) continue;
    if (friction && state.force_magnitude[p] > 0.0) {
      state.friction_work += state.dissipation[p];
      ++(state.dissipation[p] > 0.0 ? state.slipping : state.sticking);
    }
    statistics.max_pair_stiffness = std::max(statistics.max_pair_stiffness, state.pair_stiffness[p]);
    if (state.force_magnitude[p] > 0.0) {
      ++state.points_in_contact;
      state.normal_force_sum += state.force_magnitude[p];
      if (friction) state.tangential_force_sum += norm(state.tangential_force[p]);
    }
    const bool own_point = !surfaces.single_surface || surfaces.first_part_point[p] != 0;
    const bool own_segment =
        surfaces.single_surface && surfaces.first_part_segment[std::size_t(contact.segment)] != 0;
    if (own_point != own_segment) {
      Vec3& force_sum = own_point ? state.slave_force : reaction_force;
      Vec3& normal_sum = own_point ? state.slave_normal_force : reaction_normal;
      Vec3& tangential_sum = own_point ? state.slave_tangential_force : reaction_tangential;
      if (friction && state.force_magnitude[p] > 0.0)
        tangential_sum = tangential_sum + state.tangential_force[p];
      normal_sum = normal_sum + state.force_magnitude[p] * contact.normal;
      force_sum = force_sum + state.point_force[p];
    }
    state.max_penetration = std::max(state.max_penetration, -contact.gap);
    if (const double depth = -contact.gap / surfaces.normal_length[p];
        depth > statistics.max_penetration_over_h) {
      statistics.max_penetration_over_h = depth;
      statistics.deepest_node = surfaces.quadrature
                                    ? surfaces.slave_segments[surfaces.quadrature_points[p].segment].nodes[0]
                                    : surfaces.slave_nodes[p];
    }
  }
  state.slave_force = state.slave_force - reaction_force;
  state.slave_normal_force = state.slave_normal_force - reaction_normal;
  state.slave_tangential_force = state.slave_tangential_force - reaction_tangential;
}

}  // namespace

void run_contact_pass(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                      ContactPassState& state, const NodalVectors& x_ref, const NodalVectors& u,
                      const NodalVectors& v, const std::vector<double>& mass, NodalVectors& force,
                      std::vector<double>& gap, ContactStatistics& statistics, ContactPhaseSeconds& seconds,
                      RecordSink* records, bool search_when_moved) {
  if (surfaces.mortar) {
    run_mortar_pass(surfaces, settings, state, x_ref, u, v, mass, force, gap, statistics, seconds, records,
                    search_when_moved);
    return;
  }
  const std::size_t n_points = surfaces.point_count();
  {
    ScopedTimer timer(seconds.global_search);
    update_slave_points(surfaces, x_ref, u, state.slave_points);
    // A pair within search_distance now was within search_distance + margin at the
    // build as long as no node has moved more than margin / 2 since.
    if (search_when_moved ? largest_motion_since_build(surfaces, state, x_ref, u) > 0.5 * settings.margin
                          : !state.built)
      rebuild_candidates(surfaces, settings, state, x_ref, u);
  }

  // Local search: project every candidate; each slave point keeps one contact
  // (contact_choice.hpp): the closest projection that converged to a minimum inside its
  // segment, or at an edge or corner shared by segments, or at a fold's edge. A point on
  // a shared edge or corner is counted once, never twice and never zero times.
  {
    ScopedTimer timer(seconds.local_search);
    // The projections are independent: on the threads, each into its own slot. A few
    // hundred take tens of microseconds, less than a parallel region costs when another
    // process holds the other core (measured: 5 ms a step on 54 candidates).
    const auto candidates = static_cast<std::ptrdiff_t>(state.candidates.size());
    state.results.resize(state.candidates.size());
    state.edge_contacts.resize(state.candidates.size());
    if (surfaces.single_surface) state.admitted.resize(state.candidates.size());
    long fallbacks = 0;
#pragma omp parallel for schedule(dynamic, 64) if (candidates >= 512) reduction(+ : fallbacks)
    for (std::ptrdiff_t k = 0; k < candidates; ++k) {
      const auto c = static_cast<std::size_t>(k);
      const CandidatePair pair = state.candidates[c];
      const Segment segment = current_segment(surfaces.segments[pair.segment], x_ref, u);
      const Vec3 point{state.slave_points.x[pair.point], state.slave_points.y[pair.point],
                       state.slave_points.z[pair.point]};
      Xi start{0.0, 0.0};
      if (settings.initial_guess == InitialGuess::lsp ||
          (settings.initial_guess == InitialGuess::previous && std::isnan(state.previous_xi[c][0])))
        start = initial_guess_lsp(segment, point);
      else if (settings.initial_guess == InitialGuess::previous)
        start = state.previous_xi[c];
      bool settled = false;
      state.results[c] = project_settled(settings, segment, point, start, settled);
      fallbacks += settled ? 1 : 0;
    }
    // The choice: per slave point, its candidates in order (ties to the first), so the
    // same on any number of threads; the statistics are integer sums and a max.
    state.contacts.assign(n_points, ContactPassState::Contact{});
    long projections = 0, iterations = 0, max_iterations = 0, not_converged = 0, saddle_points = 0;
    const auto points = static_cast<std::ptrdiff_t>(n_points);
#pragma omp parallel for schedule(static) if (candidates >= 512) \
    reduction(+ : projections, iterations, not_converged, saddle_points) reduction(max : max_iterations)
    for (std::ptrdiff_t q = 0; q < points; ++q) {
      const auto p = static_cast<std::size_t>(q);
      if (surfaces.single_surface) admit_candidates(surfaces, settings, state, p, x_ref, u);
      for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1]; ++c) {
        const ProjectionResult& r = state.results[c];
        ++projections;
        iterations += r.iterations;
        max_iterations = std::max<long>(max_iterations, r.iterations);
        state.previous_xi[c] = std::isfinite(r.xi[0]) && std::isfinite(r.xi[1]) ? r.xi : Xi{0.0, 0.0};
        if (!admitted(surfaces, state, c)) continue;
        if (!r.converged)
          ++not_converged;
        else if (r.stationary == StationaryKind::saddle || r.stationary == StationaryKind::maximum)
          ++saddle_points;
      }
      choose_contact(surfaces, state, p, x_ref, u);
    }
    if (surfaces.single_surface) apply_exposure_offsets(surfaces, state);
    statistics.projections += projections;
    statistics.iterations += iterations;
    statistics.max_iterations = std::max(statistics.max_iterations, max_iterations);
    statistics.not_converged += not_converged;
    statistics.saddle_points += saddle_points;
    statistics.fallbacks += fallbacks;
  }

  // Penalty forces: F = max(0, -k g - c (v_s - v_m).n) along n on the slave point,
  // -N_i F n on the segment's nodes (momentum is conserved exactly); a Gauss point's
  // F goes to its segment's nodes as N_I F n. F and the pair's k of every slave point
  // on the threads, in chunks of force_chunk points (point_force); then the scatter, in
  // slave order, alone, since segments share nodes: the same sums on any number of
  // threads.
  {
    ScopedTimer timer(seconds.forces);
    state.force_magnitude.assign(n_points, 0.0);
    state.point_force.assign(n_points, Vec3{});
    state.pair_stiffness.assign(n_points, 0.0);
    const bool friction = settings.friction.enabled;
    if (friction) {
      state.tangential_force.assign(n_points, Vec3{});
      state.dissipation.assign(n_points, 0.0);
      state.anchors.resize(n_points);
    }
    for_each_chunk(
        n_points,
        [&](std::size_t begin, std::size_t end, std::size_t) {
          for (std::size_t p = begin; p < end; ++p)
            point_force(surfaces, settings, state, p, x_ref, u, v, mass);
        },
        force_chunk);
    sum_pass_figures(surfaces, friction, state, statistics);
    // The forces and gaps onto the nodes: a surface of more than one chunk on the
    // threads, in the order of one process (force_scatter.hpp).
    if (records != nullptr)
      scatter_to_records(surfaces, state, *records);
    else if (n_points > force_chunk)
      scatter_by_chunks(surfaces, state, force, gap, force_chunk, state.scatter);
    else
      scatter_in_point_order(surfaces, state, force, gap);
  }
}

}  // namespace exdyn::contact
