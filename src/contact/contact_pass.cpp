#include "contact/contact_pass.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/timer.hpp"
#include "contact/penalty.hpp"

namespace exdyn::contact {

namespace {

Vec3 current_position(const NodalVectors& x_ref, const NodalVectors& u, std::uint32_t node) {
  return {x_ref.x[node] + u.x[node], x_ref.y[node] + u.y[node], x_ref.z[node] + u.z[node]};
}

Segment current_segment(const SegmentNodes& ids, const NodalVectors& x_ref, const NodalVectors& u) {
  Segment segment;
  segment.type = ids.type;
  for (int i = 0; i < node_count(ids.type); ++i)
    segment.nodes[std::size_t(i)] = current_position(x_ref, u, ids.nodes[std::size_t(i)]);
  return segment;
}

// The current position of every slave point: a slave node's, or a Gauss point's
// y(xi) = sum N_I(xi) y_I on its slave segment.
void update_slave_points(const ContactSurfaces& surfaces, ContactPassState& state, const NodalVectors& x_ref,
                         const NodalVectors& u) {
  const std::size_t n_points = surfaces.point_count();
  state.slave_points.x.resize(n_points);
  state.slave_points.y.resize(n_points);
  state.slave_points.z.resize(n_points);
  for (std::size_t p = 0; p < n_points; ++p) {
    Vec3 x{};
    if (!surfaces.quadrature) {
      x = current_position(x_ref, u, surfaces.slave_nodes[p]);
    } else {
      const QuadraturePoint& q = surfaces.quadrature_points[p];
      const SegmentNodes& ids = surfaces.slave_segments[q.segment];
      const std::array<double, 8> N = shape_functions(ids.type, q.xi);
      for (int i = 0; i < node_count(ids.type); ++i)
        x = x + N[std::size_t(i)] * current_position(x_ref, u, ids.nodes[std::size_t(i)]);
    }
    state.slave_points.x[p] = x.x;
    state.slave_points.y[p] = x.y;
    state.slave_points.z[p] = x.z;
  }
}

// The largest distance (m) any node of the pass has moved since the last build.
double largest_motion_since_build(const ContactSurfaces& surfaces, const ContactPassState& state,
                                  const NodalVectors& x_ref, const NodalVectors& u) {
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
  bucket_search(state.slave_points, state.boxes, settings.cell_size, state.workspace, state.new_candidates);

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

// The nodes a slave point's force goes to and their weights: the slave node with
// weight 1, or a Gauss point's segment nodes with N_I(xi).
struct SlaveSide {
  int count = 1;
  std::array<std::uint32_t, 8> nodes{};
  std::array<double, 8> weights{};
};

SlaveSide slave_side(const ContactSurfaces& surfaces, std::size_t p) {
  SlaveSide side;
  if (!surfaces.quadrature) {
    side.nodes[0] = surfaces.slave_nodes[p];
    side.weights[0] = 1.0;
    return side;
  }
  const QuadraturePoint& q = surfaces.quadrature_points[p];
  const SegmentNodes& ids = surfaces.slave_segments[q.segment];
  side.count = node_count(ids.type);
  side.nodes = ids.nodes;
  side.weights = shape_functions(ids.type, q.xi);
  return side;
}

}  // namespace

void run_contact_pass(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                      ContactPassState& state, const NodalVectors& x_ref, const NodalVectors& u,
                      const NodalVectors& v, const std::vector<double>& mass, NodalVectors& force,
                      std::vector<double>& gap, ContactStatistics& statistics, ContactPhaseSeconds& seconds) {
  const std::size_t n_points = surfaces.point_count();
  {
    ScopedTimer timer(seconds.global_search);
    update_slave_points(surfaces, state, x_ref, u);
    // A pair within search_distance now was within search_distance + margin at the
    // build as long as no node has moved more than margin / 2 since.
    if (!state.built || largest_motion_since_build(surfaces, state, x_ref, u) > 0.5 * settings.margin)
      rebuild_candidates(surfaces, settings, state, x_ref, u);
  }

  // Local search: project every candidate; each slave point keeps the closest
  // projection that converged to a minimum inside its segment. Ties (a point on
  // an edge or a corner shared by segments) go to the lowest segment index, so
  // such a point is counted once, never twice and never zero times.
  {
    ScopedTimer timer(seconds.local_search);
    // The projections are independent: on the threads, each into its own slot. A few
    // hundred take tens of microseconds, less than a parallel region costs when another
    // process holds the other core (measured: 5 ms a step on 54 candidates).
    const auto candidates = static_cast<std::ptrdiff_t>(state.candidates.size());
    state.results.resize(state.candidates.size());
    state.edge_contacts.resize(state.candidates.size());
    std::pair<std::size_t, std::size_t> mine{0, state.candidates.size()};  // many processes: a share
    if (settings.share) mine = settings.share.range(state.candidates.size());
    const auto first = static_cast<std::ptrdiff_t>(mine.first),
               last = static_cast<std::ptrdiff_t>(mine.second);
#pragma omp parallel for schedule(dynamic, 64) if (last - first >= 512)
    for (std::ptrdiff_t k = first; k < last; ++k) {
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
      state.results[c] = settings.project(segment, point, start, settings.projection);
    }
    if (settings.share) settings.share.complete(state.results);
    // The choice: per slave point, its candidates in order (ties to the first), so the
    // same on any number of threads; the statistics are integer sums and a max.
    state.contacts.assign(n_points, ContactPassState::Contact{});
    long projections = 0, iterations = 0, max_iterations = 0, not_converged = 0, saddle_points = 0;
    const auto points = static_cast<std::ptrdiff_t>(n_points);
#pragma omp parallel for schedule(static) if (candidates >= 512) \
    reduction(+ : projections, iterations, not_converged, saddle_points) reduction(max : max_iterations)
    for (std::ptrdiff_t q = 0; q < points; ++q) {
      const auto p = static_cast<std::size_t>(q);
      double best_distance = std::numeric_limits<double>::infinity();
      std::size_t best = state.candidates.size();  // none
      for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1]; ++c) {
        const ProjectionResult& r = state.results[c];
        ++projections;
        iterations += r.iterations;
        max_iterations = std::max<long>(max_iterations, r.iterations);
        state.previous_xi[c] = std::isfinite(r.xi[0]) && std::isfinite(r.xi[1]) ? r.xi : Xi{0.0, 0.0};
        if (!r.converged) {
          ++not_converged;
          continue;
        }
        if (r.stationary == StationaryKind::saddle || r.stationary == StationaryKind::maximum) {
          ++saddle_points;
          continue;
        }
        if (r.stationary != StationaryKind::minimum || !r.inside) continue;
        if (r.distance < best_distance) best_distance = r.distance, best = c;
      }
      auto& contact = state.contacts[p];
      if (best == state.candidates.size()) {
        // No projection inside a segment: the point may lie behind a fold of the
        // surface (edge_contact.hpp). The closest boundary point of the candidates (ties
        // to the first), if the surface goes on past it and the point lies behind it,
        // along the mean normal of the segments that meet there.
        if (surfaces.edges.empty()) continue;
        const Vec3 point{state.slave_points.x[p], state.slave_points.y[p], state.slave_points.z[p]};
        EdgeContact closest;
        std::size_t closest_candidate = 0;
        for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1]; ++c) {
          const std::uint32_t segment = state.candidates[c].segment;
          const EdgeContact edge = edge_contact(current_segment(surfaces.segments[segment], x_ref, u), point,
                                                state.results[c], surfaces.edges[segment]);
          state.edge_contacts[c] = edge;
          if (edge.found && (!closest.found || edge.distance < closest.distance))
            closest = edge, closest_candidate = c;
        }
        if (!closest.found || !closest.continued) continue;
        const double same_point = 1.0e-9 * surfaces.normal_length[p];
        Vec3 normal{};
        for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1]; ++c)
          if (state.edge_contacts[c].found && norm(state.edge_contacts[c].y - closest.y) <= same_point)
            normal = normal + state.edge_contacts[c].normal;
        if (!(norm(normal) > 0.0)) continue;  // a sheet folded flat on itself: no side is behind
        normal = (1.0 / norm(normal)) * normal;
        const double depth = dot(point - closest.y, normal);  // the gap, m
        if (!(depth < 0.0)) continue;
        contact.segment = state.candidates[closest_candidate].segment;
        contact.xi = closest.xi;
        contact.gap = depth;
        contact.normal = normal;
        continue;
      }
      const std::uint32_t segment = state.candidates[best].segment;
      contact.segment = segment;
      contact.xi = state.results[best].xi;
      contact.gap = state.results[best].gap;
      contact.normal = outward_normal(current_segment(surfaces.segments[segment], x_ref, u), contact.xi);
    }
    statistics.projections += projections;
    statistics.iterations += iterations;
    statistics.max_iterations = std::max(statistics.max_iterations, max_iterations);
    statistics.not_converged += not_converged;
    statistics.saddle_points += saddle_points;
  }

  // Penalty forces: F = max(0, -k g - c (v_s - v_m).n) along n on the slave point,
  // -N_i F n on the segment's nodes (momentum is conserved exactly); a Gauss point's
  // F goes to its segment's nodes as N_I F n. F and the pair's k of every slave point
  // on the threads (large surfaces only: on a few hundred points starting threads
  // costs more than the work); then the scatter, in slave order, alone, since
  // segments share nodes: the same sums on any number of threads.
  {
    ScopedTimer timer(seconds.forces);
    state.force_magnitude.assign(n_points, 0.0);
    state.pair_stiffness.assign(n_points, 0.0);
    const auto points = static_cast<std::ptrdiff_t>(n_points);
#pragma omp parallel for schedule(static) if (points >= 4096)
    for (std::ptrdiff_t q = 0; q < points; ++q) {
      const auto p = static_cast<std::size_t>(q);
      const auto& contact = state.contacts[p];
      if (contact.segment < 0 || contact.gap >= 0.0) continue;
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
      Vec3 slave_velocity{};
      double slave_inverse_mass = 0.0;  // the slave point's 1 / mass, likewise
      for (int i = 0; i < slave.count; ++i) {
        const std::uint32_t node = slave.nodes[std::size_t(i)];
        const double w = slave.weights[std::size_t(i)];
        slave_velocity = slave_velocity + w * Vec3{v.x[node], v.y[node], v.z[node]};
        slave_inverse_mass += w * w / mass[node];
      }
      const Vec3 n = contact.normal;
      const double normal_velocity = dot(slave_velocity - master_velocity, n);
      double k = surfaces.stiffness[p];  // the point pair's stiffness
      if (settings.automatic_stiffness) k *= settings.stiffness_growth;
      if (settings.automatic_stiffness && !surfaces.quadrature) {
        const double inverse_mass = slave_inverse_mass + master_inverse_mass;
        k = std::min(
            {k, settings.stiffness_scale * accurate_stiffness_bound(settings.dt, inverse_mass),
             settings.stiffness_scale * stable_stiffness_bound(settings.dt, settings.courant,
                                                               settings.damping_ratio, inverse_mass)});
      }
      state.pair_stiffness[p] = k;
      k /= settings.pass_count;
      const double slave_mass = surfaces.quadrature ? 1.0 / slave_inverse_mass : mass[slave.nodes[0]];
      const double c = damping_coefficient(settings.damping_ratio, k, slave_mass, 1.0 / master_inverse_mass);
      state.force_magnitude[p] = normal_force(k, c, contact.gap, normal_velocity);
    }
    state.slave_force = Vec3{};
    state.max_penetration = 0.0;
    for (std::size_t p = 0; p < n_points; ++p) {
      const auto& contact = state.contacts[p];
      if (contact.segment < 0) continue;
      const SlaveSide slave = slave_side(surfaces, p);
      for (int i = 0; i < slave.count; ++i) {
        double& g = gap[slave.nodes[std::size_t(i)]];
        g = std::min(g, contact.gap);
      }
      if (contact.gap >= 0.0) continue;
      const SegmentNodes& master = surfaces.segments[static_cast<std::size_t>(contact.segment)];
      const std::array<double, 8> N = shape_functions(master.type, contact.xi);
      const Vec3 F = state.force_magnitude[p] * contact.normal;
      statistics.max_pair_stiffness = std::max(statistics.max_pair_stiffness, state.pair_stiffness[p]);
      for (int i = 0; i < slave.count; ++i) {
        const std::uint32_t node = slave.nodes[std::size_t(i)];
        const double w = slave.weights[std::size_t(i)];
        force.x[node] += w * F.x;
        force.y[node] += w * F.y;
        force.z[node] += w * F.z;
      }
      for (int i = 0; i < node_count(master.type); ++i) {
        const std::uint32_t node = master.nodes[std::size_t(i)];
        force.x[node] -= N[std::size_t(i)] * F.x;
        force.y[node] -= N[std::size_t(i)] * F.y;
        force.z[node] -= N[std::size_t(i)] * F.z;
      }
      state.slave_force = state.slave_force + F;
      state.max_penetration = std::max(state.max_penetration, -contact.gap);
      if (const double depth = -contact.gap / surfaces.normal_length[p];
          depth > statistics.max_penetration_over_h) {
        statistics.max_penetration_over_h = depth;
        statistics.deepest_node = slave.nodes[0];
      }
    }
  }
}

}  // namespace exdyn::contact
