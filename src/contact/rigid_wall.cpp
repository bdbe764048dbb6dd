#include "contact/rigid_wall.hpp"

#include <algorithm>
#include <cmath>

#include "common/timer.hpp"
#include "contact/penalty.hpp"
#include "contact/slave_points.hpp"

namespace exdyn::contact {

void run_wall_pass(const ContactSurfaces& surfaces, const WallPlane& wall,
                   const ContactPassSettings& settings, WallState& state, const NodalVectors& x_ref,
                   const NodalVectors& u, const NodalVectors& v, const std::vector<double>& mass, double time,
                   NodalVectors& force, std::vector<double>& gap, ContactStatistics& statistics,
                   ContactPhaseSeconds& seconds, RecordSink* records) {
  ScopedTimer timer(seconds.forces);
  const std::size_t n_points = surfaces.point_count();
  update_slave_points(surfaces, x_ref, u, state.slave_points);
  const Vec3 n = wall.normal;
  const Vec3 plane_point = wall.point + time * wall.velocity;  // P(t)
  const bool friction = settings.friction.enabled;
  state.point_force.assign(n_points, Vec3{});
  state.dissipation.assign(n_points, 0.0);
  state.stiffness.assign(n_points, 0.0);
  state.anchors.resize(n_points);
  state.anchored.resize(n_points, 0);

  // Each point on the threads (its own slots); the sums after, in point order.
  const auto points = static_cast<std::ptrdiff_t>(n_points);
#pragma omp parallel for schedule(static) if (points >= 4096)
  for (std::ptrdiff_t q = 0; q < points; ++q) {
    const auto p = static_cast<std::size_t>(q);
    const Vec3 x{state.slave_points.x[p], state.slave_points.y[p], state.slave_points.z[p]};
    const double d = dot(x - plane_point, n);  // the gap to the wall, m
    if (!(d < 0.0)) {
      state.anchored[p] = 0;
      continue;
    }
    const SlaveMotion motion = slave_motion(slave_side(surfaces, p), v, mass);
    const Vec3 relative_velocity = motion.velocity - wall.velocity;
    // The image pair: inverse mass 1/m_s + 1/m_s, gap 2 d, approach 2 (v_s - V).n.
    const double inverse_mass = 2.0 * motion.inverse_mass;
    double k = surfaces.stiffness[p];
    if (settings.automatic_stiffness) k *= settings.stiffness_growth;
    if (settings.automatic_stiffness && !surfaces.quadrature)
      k = std::min({k, settings.stiffness_scale * accurate_stiffness_bound(settings.dt, inverse_mass),
                    settings.stiffness_scale * stable_stiffness_bound(settings.dt, settings.courant,
                                                                      settings.damping_ratio, inverse_mass)});
    state.stiffness[p] = k;
    const double k_pass = k / settings.pass_count;
    const double m_s = 1.0 / motion.inverse_mass;
    const double c = damping_coefficient(settings.damping_ratio, k_pass, m_s, m_s);
    const double F_n =
        settings.pass_count * normal_force(k_pass, c, 2.0 * d, 2.0 * dot(relative_velocity, n));
    Vec3 F = F_n * n;
    if (friction && F_n > 0.0) {
      // The anchor, a point of the plane carried with it; the spring's stiffness per
      // unit tangential gap is the image pair's per unit penetration, 2 k.
      // A point new to contact touched at the start of the step, a step's slip back
      // (as in a contact pair, contact_pass.cpp).
      const Vec3 slip_velocity = tangential_part(relative_velocity, n);
      if (state.anchored[p] == 0) {
        state.anchors[p] = x - d * n - plane_point - settings.dt * slip_velocity;
        state.anchored[p] = 1;
      }
      const Vec3 anchor = plane_point + state.anchors[p];
      const double mu = settings.friction.coefficient(norm(slip_velocity));
      const TangentialForce t = coulomb_force(tangential_part(x - anchor, n), 2.0 * k, F_n, mu);
      F = F + t.force;
      state.dissipation[p] = t.dissipation;
      if (t.slip) state.anchors[p] = state.anchors[p] + t.anchor_shift;
    } else {
      state.anchored[p] = 0;
    }
    state.point_force[p] = F;
  }

  state.previous_force = state.force;
  state.force = state.normal_force = state.tangential_force = Vec3{};
  state.max_penetration = 0.0;
  state.slipping = state.sticking = 0;
  for (std::size_t p = 0; p < n_points; ++p) {
    const SlaveSide side = slave_side(surfaces, p);
    const double d =
        dot(Vec3{state.slave_points.x[p], state.slave_points.y[p], state.slave_points.z[p]} - plane_point, n);
    for (int i = 0; i < side.count; ++i) {
      if (records != nullptr) {
        records->gap(p, i, side.nodes[std::size_t(i)], d);
        continue;
      }
      double& g = gap[side.nodes[std::size_t(i)]];
      g = std::min(g, d);
    }
    if (!(d < 0.0)) continue;
    const Vec3 F = state.point_force[p];
    if (records != nullptr)
      add_to_slave(side, F, p, *records);
    else
      add_to_slave(side, F, force);
    const Vec3 F_n = dot(F, n) * n;
    state.force = state.force + F;
    state.normal_force = state.normal_force + F_n;
    state.tangential_force = state.tangential_force + (F - F_n);
    state.friction_work += state.dissipation[p];
    if (friction && state.anchored[p] != 0) ++(state.dissipation[p] > 0.0 ? state.slipping : state.sticking);
    state.max_penetration = std::max(state.max_penetration, -d);
    statistics.max_pair_stiffness = std::max(statistics.max_pair_stiffness, state.stiffness[p]);
    if (const double depth = -d / surfaces.normal_length[p]; depth > statistics.max_penetration_over_h) {
      statistics.max_penetration_over_h = depth;
      statistics.deepest_node = side.nodes[0];
    }
  }
}

}  // namespace exdyn::contact
