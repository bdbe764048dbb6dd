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

Segment current_segment(const Quad& quad, const NodalVectors& x_ref, const NodalVectors& u) {
  Segment segment;
  segment.type = SegmentType::quad4;
  for (int i = 0; i < 4; ++i) segment.nodes[i] = current_position(x_ref, u, quad[i]);
  return segment;
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
void rebuild_candidates(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                        ContactPassState& state, const NodalVectors& x_ref, const NodalVectors& u) {
  const std::size_t n_slaves = surfaces.slave_nodes.size();
  state.slave_points.resize(n_slaves);
  for (std::size_t p = 0; p < n_slaves; ++p) {
    const Vec3 x = current_position(x_ref, u, surfaces.slave_nodes[p]);
    state.slave_points.x[p] = x.x;
    state.slave_points.y[p] = x.y;
    state.slave_points.z[p] = x.z;
  }
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

}  // namespace

void run_contact_pass(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                      ContactPassState& state, const NodalVectors& x_ref, const NodalVectors& u,
                      const NodalVectors& v, const std::vector<double>& mass, NodalVectors& force,
                      std::vector<double>& gap, ContactStatistics& statistics, ContactPhaseSeconds& seconds) {
  const std::size_t n_slaves = surfaces.slave_nodes.size();
  {
    ScopedTimer timer(seconds.global_search);
    // A pair within search_distance now was within search_distance + margin at the
    // build as long as no node has moved more than margin / 2 since.
    if (!state.built || largest_motion_since_build(surfaces, state, x_ref, u) > 0.5 * settings.margin)
      rebuild_candidates(surfaces, settings, state, x_ref, u);
  }

  // Local search: project every candidate; each slave node keeps the closest
  // projection that converged to a minimum inside its segment. Ties (a node on
  // an edge or a corner shared by segments) go to the lowest segment index, so
  // such a node is counted once, never twice and never zero times.
  {
    ScopedTimer timer(seconds.local_search);
    // The projections are independent: on the threads, each into its own slot.
    const auto candidates = static_cast<std::ptrdiff_t>(state.candidates.size());
    state.results.resize(state.candidates.size());
#pragma omp parallel for schedule(dynamic, 64)
    for (std::ptrdiff_t k = 0; k < candidates; ++k) {
      const auto c = static_cast<std::size_t>(k);
      const CandidatePair pair = state.candidates[c];
      const Segment segment = current_segment(surfaces.segments[pair.segment], x_ref, u);
      const Vec3 point = current_position(x_ref, u, surfaces.slave_nodes[pair.point]);
      Xi start{0.0, 0.0};
      if (settings.initial_guess == InitialGuess::lsp ||
          (settings.initial_guess == InitialGuess::previous && std::isnan(state.previous_xi[c][0])))
        start = initial_guess_lsp(segment, point);
      else if (settings.initial_guess == InitialGuess::previous)
        start = state.previous_xi[c];
      state.results[c] = settings.project(segment, point, start, settings.projection);
    }
    // The choice, in candidate order (the same on any number of threads).
    state.contacts.assign(n_slaves, ContactPassState::Contact{});
    double best_distance = 0.0;
    std::uint32_t current_point = std::numeric_limits<std::uint32_t>::max();
    for (std::size_t c = 0; c < state.candidates.size(); ++c) {
      const CandidatePair pair = state.candidates[c];
      if (pair.point != current_point) {
        current_point = pair.point;
        best_distance = std::numeric_limits<double>::infinity();
      }
      const ProjectionResult& r = state.results[c];
      ++statistics.projections;
      statistics.iterations += r.iterations;
      statistics.max_iterations = std::max<long>(statistics.max_iterations, r.iterations);
      state.previous_xi[c] = std::isfinite(r.xi[0]) && std::isfinite(r.xi[1]) ? r.xi : Xi{0.0, 0.0};
      if (!r.converged) {
        ++statistics.not_converged;
        continue;
      }
      if (r.stationary == StationaryKind::saddle || r.stationary == StationaryKind::maximum) {
        ++statistics.saddle_points;
        continue;
      }
      if (r.stationary != StationaryKind::minimum || !r.inside) continue;
      if (r.distance < best_distance) {
        best_distance = r.distance;
        auto& contact = state.contacts[pair.point];
        contact.segment = pair.segment;
        contact.xi = r.xi;
        contact.gap = r.gap;
        contact.normal = outward_normal(current_segment(surfaces.segments[pair.segment], x_ref, u), r.xi);
      }
    }
  }

  // Penalty forces: F = max(0, -k g - c (v_s - v_m).n) along n on the slave node,
  // -N_i F n on the segment's nodes (momentum is conserved exactly). F and the pair's
  // k of every slave node on the threads (large surfaces only: on a few hundred nodes
  // starting threads costs more than the work); then the scatter, in slave order,
  // alone, since segments share nodes: the same sums on any number of threads.
  {
    ScopedTimer timer(seconds.forces);
    state.force_magnitude.assign(n_slaves, 0.0);
    state.pair_stiffness.assign(n_slaves, 0.0);
    const auto slaves = static_cast<std::ptrdiff_t>(n_slaves);
#pragma omp parallel for schedule(static) if (slaves >= 4096)
    for (std::ptrdiff_t q = 0; q < slaves; ++q) {
      const auto p = static_cast<std::size_t>(q);
      const auto& contact = state.contacts[p];
      if (contact.segment < 0 || contact.gap >= 0.0) continue;
      const std::uint32_t slave = surfaces.slave_nodes[p];
      const Quad& quad = surfaces.segments[static_cast<std::size_t>(contact.segment)];
      const std::array<double, 8> N = shape_functions(SegmentType::quad4, contact.xi);
      Vec3 master_velocity{};
      double master_inverse_mass = 0.0;  // sum N_i^2 / m_i: the master point's 1 / mass
      for (int i = 0; i < 4; ++i) {
        master_velocity = master_velocity + N[i] * Vec3{v.x[quad[i]], v.y[quad[i]], v.z[quad[i]]};
        master_inverse_mass += N[i] * N[i] / mass[quad[i]];
      }
      const Vec3 n = contact.normal;
      const double normal_velocity = dot(Vec3{v.x[slave], v.y[slave], v.z[slave]} - master_velocity, n);
      const double slave_inverse_mass = 1.0 / mass[slave];
      double k = surfaces.stiffness[p];  // the node pair's stiffness
      if (settings.automatic_stiffness) {
        const double inverse_mass = slave_inverse_mass + master_inverse_mass;
        k = std::min(
            {k, settings.stiffness_scale * accurate_stiffness_bound(settings.dt, inverse_mass),
             settings.stiffness_scale * stable_stiffness_bound(settings.dt, settings.courant,
                                                               settings.damping_ratio, inverse_mass)});
      }
      state.pair_stiffness[p] = k;
      k /= settings.pass_count;
      const double c = damping_coefficient(settings.damping_ratio, k, mass[slave], 1.0 / master_inverse_mass);
      state.force_magnitude[p] = normal_force(k, c, contact.gap, normal_velocity);
    }
    for (std::size_t p = 0; p < n_slaves; ++p) {
      const auto& contact = state.contacts[p];
      const std::uint32_t slave = surfaces.slave_nodes[p];
      if (contact.segment < 0) continue;
      gap[slave] = std::min(gap[slave], contact.gap);
      if (contact.gap >= 0.0) continue;
      const Quad& quad = surfaces.segments[static_cast<std::size_t>(contact.segment)];
      const std::array<double, 8> N = shape_functions(SegmentType::quad4, contact.xi);
      const Vec3 n = contact.normal;
      const double F = state.force_magnitude[p];
      statistics.max_pair_stiffness = std::max(statistics.max_pair_stiffness, state.pair_stiffness[p]);
      force.x[slave] += F * n.x;
      force.y[slave] += F * n.y;
      force.z[slave] += F * n.z;
      for (int i = 0; i < 4; ++i) {
        force.x[quad[i]] -= N[i] * F * n.x;
        force.y[quad[i]] -= N[i] * F * n.y;
        force.z[quad[i]] -= N[i] * F * n.z;
      }
      if (const double depth = -contact.gap / surfaces.normal_length[p];
          depth > statistics.max_penetration_over_h) {
        statistics.max_penetration_over_h = depth;
        statistics.deepest_node = slave;
      }
    }
  }
}

}  // namespace exdyn::contact
