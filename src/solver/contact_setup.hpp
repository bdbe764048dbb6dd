// The contact pairs and rigid walls of a deck as passes of the contact library:
// surfaces from the named faces, the penalty stiffness of every slave point, the
// search and friction settings.
#pragma once

#include <string>
#include <vector>

#include "contact/contact_pass.hpp"
#include "contact/rigid_wall.hpp"
#include "input/options.hpp"
#include "solver/model.hpp"

namespace exdyn::solver {

struct ContactPair {
  std::string name;
  input::SlavePoints slave_points = input::SlavePoints::nodes;
  contact::ContactPassSettings settings;
  std::vector<contact::ContactSurfaces> passes;  // slave -> master, and master -> slave if two_pass
  std::vector<contact::ContactPassState> states;
  // Accumulated over the run (contact.pairs.NAME of the summary).
  contact::ContactStatistics statistics;
  contact::ContactPhaseSeconds seconds;
  double max_force = 0.0;  // largest |force on the slave side| of a step, N

  // This step's total contact force on the pair's slave side (N): the first pass's
  // slave-side force minus the second pass's (whose slave side is the pair's master side).
  contact::Vec3 slave_force() const;
  // Its normal and tangential (friction) parts, N.
  contact::Vec3 normal_force() const;
  contact::Vec3 tangential_force() const;
  // This step's deepest penetration of either pass, m.
  double max_penetration() const;
  contact::Vec3 first_pass_less_second(contact::Vec3 contact::ContactPassState::*member) const;
};

struct RigidWall {
  std::string name;
  contact::WallPlane plane;
  contact::ContactSurfaces surfaces;  // the slave side (no segments)
  contact::ContactPassSettings settings;
  contact::WallState state;
  contact::ContactStatistics statistics;
  contact::ContactPhaseSeconds seconds;
  double max_force = 0.0;  // largest |force on the bodies| of a step, N
};

struct ContactModel {
  std::vector<ContactPair> pairs;
  std::vector<RigidWall> walls;
  std::vector<std::uint32_t> nodes;  // every node of every contact surface and wall, unique

  bool empty() const { return pairs.empty() && walls.empty(); }
  // "contact pair NAME" or "rigid wall NAME": the first with the deepest penetration
  // (statistics.max_penetration_over_h); for messages.
  std::string deepest_contact() const;
  // Dissipated by friction since the start, all pairs and walls, J.
  double friction_work() const;
};

// dt: the step in force (s); critical_dt: the mesh's stable step without the
// Courant factor (s), whose ratio is the Courant number the stiffness bound needs.
ContactModel build_contact(const input::Deck& deck, const Model& model, double dt, double critical_dt);

// The step in force follows the deformation: the automatic stiffness of every pair
// and wall follows it (ContactPassSettings::stiffness_growth). fall: dt^{n-1/2} / dt^{1/2}.
void follow_time_step(ContactModel& contact, double fall);

}  // namespace exdyn::solver
