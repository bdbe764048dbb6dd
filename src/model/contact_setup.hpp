// The contact pairs and rigid walls of a deck as passes of the contact library:
// surfaces from the named faces, the penalty stiffness of every slave point, the
// search and friction settings.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "contact/contact_pass.hpp"
#include "contact/rigid_wall.hpp"
#include "input/options.hpp"
#include "model/model.hpp"

namespace exdyn::solver {

// Where a pass's slave points and master segments stand in the whole pass (one
// process's order) when it was built on faces cut to those near one rank
// (ContactScope): each quadrature point's index among the whole pass's points and each
// master segment's among its segments. Empty: the pass is whole (item k is k).
struct PassPlace {
  std::vector<std::uint32_t> point_keys, segment_ids;
};

struct ContactPair {
  std::string name;
  input::SlavePoints slave_points = input::SlavePoints::nodes;
  contact::ContactPassSettings settings;
  std::vector<contact::ContactSurfaces> passes;  // slave -> master, and master -> slave if two_pass
  std::vector<contact::ContactPassState> states;
  std::vector<PassPlace> places;  // of each pass (its faces cut to a rank's: ContactScope)
  // Accumulated over the run (contact.pairs.NAME of the summary).
  contact::ContactStatistics statistics;
  contact::ContactPhaseSeconds seconds;
  double max_force = 0.0;  // largest |force on the slave side| of a step, N
  // The step of the largest sum of the points' normal force magnitudes: that sum (N) and
  // the points pressed then (both passes).
  double peak_normal_force_sum = 0.0;
  long points_in_contact_at_peak = 0;

  // This step's total contact force on the pair's slave side (N): the first pass's
  // slave-side force minus the second pass's (whose slave side is the pair's master side).
  contact::Vec3 slave_force() const;
  // Its normal and tangential (friction) parts, N.
  contact::Vec3 normal_force() const;
  contact::Vec3 tangential_force() const;
  // This step's deepest penetration of either pass, m.
  double max_penetration() const;
  // This step's sums over both passes' points of |F_n| and |F_t| (N), and the points pressed.
  double normal_force_sum() const;
  double tangential_force_sum() const;
  long points_in_contact() const;
  // After a step's passes: max_force and the peak of normal_force_sum() followed.
  void follow_peaks();
  contact::Vec3 first_pass_less_second(contact::Vec3 contact::ContactPassState::*member) const;
};

struct RigidWall {
  std::string name;
  contact::WallPlane plane;
  contact::ContactSurfaces surfaces;  // the slave side (no segments)
  PassPlace place;                    // its faces cut to a rank's (ContactScope)
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
  std::vector<double> node_power;    // scratch of the contact power: per node of `nodes`, W x 2

  bool empty() const { return pairs.empty() && walls.empty(); }
  // "contact pair NAME" or "rigid wall NAME": the first with the deepest penetration
  // (statistics.max_penetration_over_h); for messages.
  std::string deepest_contact() const;
  // Dissipated by friction since the start, all pairs and walls, J.
  double friction_work() const;
};

// What build_contact sees on one rank of many (rank_setup.hpp): the model's contact
// faces cut to the segments with a node held here (mesh::Face::segment_index), the
// nodes of the other ranks among theirs (a halo) at infinite mass. `held` marks the
// nodes held here; every sum over a held node's segments is then complete and in one
// process's order. `largest` gives the largest of a figure over the ranks (collective:
// every rank asks in the same order), for the figures over a whole surface.
struct ContactScope {
  const std::vector<std::uint8_t>* held = nullptr;
  std::function<double(double)> largest;
};

// dt: the step in force (s); critical_dt: the mesh's stable step without the
// Courant factor (s), whose ratio is the Courant number the stiffness bound needs.
// scope: one rank's faces of many (each pass's places, PassPlace); none: one process.
ContactModel build_contact(const input::Deck& deck, const Model& model, double dt, double critical_dt,
                           const ContactScope& scope = {});

// The step in force follows the deformation: the automatic stiffness of every pair
// and wall follows it (ContactPassSettings::stiffness_growth). fall: dt^{n-1/2} / dt^{1/2}.
void follow_time_step(ContactModel& contact, double fall);

}  // namespace exdyn::solver
