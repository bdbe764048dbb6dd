// The discrete model built from a deck: mesh, element blocks, lumped mass and
// the fixed velocity components.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "element/element_block.hpp"
#include "input/options.hpp"
#include "mesh/mesh.hpp"

namespace exdyn::solver {

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
  // Nodes whose x, y or z velocity is held at zero (sorted, unique).
  std::array<std::vector<std::uint32_t>, 3> fixed_nodes;
};

Model build_model(const input::Deck& deck);

// Initial velocities of every part's nodes, with the fixed components zeroed
// (a boundary condition overrides an initial velocity).
NodalVectors initial_velocity(const input::Deck& deck, const Model& model);
// A part's initial velocity at the point x (m): initial_velocity plus
// omega x (x - axis_point) of initial_angular_velocity, m/s (before the fixed components).
std::array<double, 3> part_initial_velocity(const input::PartOptions& part, const std::array<double, 3>& x);

// Sets the fixed components of a nodal vector field to zero.
void apply_fixed_components(const Model& model, NodalVectors& field);

// Stable step of the model without the Courant factor: min over elements of L_e / c1, s.
double critical_time_step(const Model& model);

// The time step in force and the number of steps to reach time.end_time.
struct TimeStepping {
  double dt = 0.0;
  long steps = 0;
};
TimeStepping time_stepping(const input::TimeOptions& time, double critical_dt);

}  // namespace exdyn::solver
