// A flat rigid wall (docs/contact.md, "Rigid walls"): the slave points of its faces
// (slave nodes or the Gauss points of slave segments, as in a contact pair) stay on
// the side its normal points to. The plane moves at a constant velocity V:
//   P(t) = P_0 + V t,  gap d = (x_s - P(t)).n  (m, negative behind the wall).
// The wall pushes as the body's mirror image through the plane would in a two-pass
// contact pair: the image point lies at gap 2 d and approaches at 2 (v_s - V).n, its
// mass is the slave point's own, and the pair's stiffness k comes from the same rule
// (the slave faces against themselves). So a bar on a wall moves as each of two equal
// bars meeting at the plane between them. With friction, the stick anchor is a point
// of the plane, carried with it.
#pragma once

#include <cstdint>
#include <vector>

#include "common/nodal_vectors.hpp"
#include "contact/contact_pass.hpp"
#include "contact/friction.hpp"

namespace exdyn::contact {

struct WallPlane {
  Vec3 point{};     // P_0, m
  Vec3 normal{};    // n, unit length, towards the bodies
  Vec3 velocity{};  // V, m/s
};

struct WallState {
  // friction: each slave point's anchor relative to P(t) (m); anchored 0: none
  std::vector<Vec3> anchors;
  std::vector<std::uint8_t> anchored;
  // scratch
  NodalVectors slave_points;
  std::vector<Vec3> point_force;    // the wall's force on each slave point, N
  std::vector<double> dissipation;  // friction work of each slave point this step, J
  std::vector<double> stiffness;    // k of each slave point's image pair, N/m
  // This step: the wall's total force on the bodies (N), its normal and tangential
  // parts, the deepest penetration (m, >= 0); the run's friction work so far (J).
  Vec3 force{}, normal_force{}, tangential_force{};
  Vec3 previous_force{};  // the step before's force, N (for the work of a moving wall)
  double max_penetration = 0.0;
  long slipping = 0, sticking = 0;
  double friction_work = 0.0;
};

// The wall's forces on the slave points at x = x_ref + u (m) with velocities v (m/s)
// at time t (s), added to `force` (N); each slave node's gap to the wall written to
// gap[node] where smaller. `surfaces` holds the slave side only (no segments);
// `settings` the penalty rule (pass_count 2: the image pair's two passes), damping and
// friction. With `records`, the forces and gaps go there (contact_pass.hpp).
void run_wall_pass(const ContactSurfaces& surfaces, const WallPlane& wall,
                   const ContactPassSettings& settings, WallState& state, const NodalVectors& x_ref,
                   const NodalVectors& u, const NodalVectors& v, const std::vector<double>& mass, double time,
                   NodalVectors& force, std::vector<double>& gap, ContactStatistics& statistics,
                   ContactPhaseSeconds& seconds, RecordSink* records = nullptr);

}  // namespace exdyn::contact
