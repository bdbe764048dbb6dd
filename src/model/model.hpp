// The discrete model built from a deck: mesh, element blocks, lumped mass and
// the fixed velocity components.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "element/element_block.hpp"
#include "input/options.hpp"
#include "mesh/mesh.hpp"

namespace exdyn::solver {

// A boundary condition's share of the prescribed node components, for its reaction
// force: per component, the nodes whose velocity it prescribes and no earlier condition
// does (each node component belongs to one condition), and the value there, m/s.
struct BoundaryNodes {
  std::array<std::vector<std::uint32_t>, 3> nodes;
  std::array<double, 3> velocity{};
};

// The prescribed node components of the deck's conditions: condition_nodes[b] holds
// the nodes of condition b's faces (any ids, repeats allowed). Two conditions that
// prescribe different values for one node component are bad input: `conflict` then
// says so (the caller throws), naming the node by its id here.
struct PrescribedMotion {
  std::array<std::vector<std::uint32_t>, 3> nodes;  // sorted, unique
  std::array<std::vector<double>, 3> velocity;      // the value at each of nodes[c], m/s
  std::vector<BoundaryNodes> boundary;              // per condition
  std::string conflict;
};
PrescribedMotion prescribed_motion(const input::Deck& deck,
                                   const std::vector<std::vector<std::uint32_t>>& condition_nodes);

struct Model {
  mesh::Mesh mesh;
  std::vector<element::ElementBlock> blocks;  // one per part, deck order
  std::vector<double> mass;                   // lumped nodal mass, kg
  std::vector<double> inverse_mass;           // 1 / mass, 1/kg
  // On many ranks (decomposition.hpp): the mass the energy sums count, the owned
  // nodes' (0 elsewhere); empty on one rank, where it is `mass`.
  std::vector<double> counted_mass;
  // The body-force acceleration g of each node (loads: gravity, m/s^2), whose force
  // m g goes with the contact forces; empty when the deck has no loads.
  NodalVectors load_acceleration;
  // Nodes whose x, y or z velocity is prescribed (sorted, unique), and its value, m/s
  // (empty: 0 at every one, e.g. a contact surface's model).
  std::array<std::vector<std::uint32_t>, 3> fixed_nodes;
  std::array<std::vector<double>, 3> fixed_velocity;
  // Per boundary condition (deck order): the nodes whose reaction it reports.
  std::vector<BoundaryNodes> boundary;
};

Model build_model(const input::Deck& deck);

// Initial velocities of every part's nodes, with the prescribed components at their
// values (a boundary condition overrides an initial velocity).
NodalVectors initial_velocity(const input::Deck& deck, const Model& model);
// A part's initial velocity at the point x (m): initial_velocity plus
// omega x (x - axis_point) of initial_angular_velocity, m/s (before the fixed components).
std::array<double, 3> part_initial_velocity(const input::PartOptions& part, const std::array<double, 3>& x);

// Sets the fixed components of a nodal vector field to zero.
void apply_fixed_components(const Model& model, NodalVectors& field);
// Whether a node's component c is held at rest (prescribed at velocity 0): what makes a
// face a symmetry plane or a support for the contact. A moving face is not one.
bool held_at_rest(const Model& model, int c, std::uint32_t node);
// Sets the prescribed components of a velocity field to their values.
void apply_prescribed_velocity(const Model& model, NodalVectors& velocity);

// Stable step of the model without the Courant factor: min over elements of L_e / c1, s.
double critical_time_step(const Model& model);

// The time step in force and the number of steps to reach time.end_time.
struct TimeStepping {
  double dt = 0.0;
  long steps = 0;
};
TimeStepping time_stepping(const input::TimeOptions& time, double critical_dt);

}  // namespace exdyn::solver
