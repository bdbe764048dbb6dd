// The chunks' costs for the partition (load_balance.hpp).
#include "ranks/load_balance.hpp"

#include <algorithm>
#include <functional>
#include <limits>

#include "common/timer.hpp"
#include "contact/rigid_wall.hpp"

namespace exdyn::solver {

namespace {

constexpr int repeats = 3;  // the best of three: the least disturbed by the machine

}  // namespace

std::vector<double> element_costs(const Model& model, double dt) {
  std::vector<double> costs;
  const NodalVectors u(model.mesh.node_count());
  NodalVectors f(model.mesh.node_count());
  for (const element::ElementBlock& block : model.blocks) {
    element::set_material_time_step(block, dt);
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < repeats; ++k) {
      Stopwatch watch;
      element::add_internal_forces(block, u, f, nullptr);
      best = std::min(best, watch.seconds());
    }
    costs.push_back(best / double(std::max<std::uint32_t>(block.count, 1)));
  }
  return costs;
}

std::vector<double> contact_costs(const Model& model, const ContactModel& contact,
                                  const NodalVectors& velocity) {
  std::vector<double> costs;
  const NodalVectors u(model.mesh.node_count());
  NodalVectors f(model.mesh.node_count());
  std::vector<double> gap(model.mesh.node_count(), std::numeric_limits<double>::infinity());
  auto time_pass = [&](auto&& run, std::size_t points) {
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < repeats; ++k) {
      Stopwatch watch;
      run();
      best = std::min(best, watch.seconds());
    }
    costs.push_back(points > 0 ? best / double(points) : 0.0);
  };
  for (const ContactPair& pair : contact.pairs)
    for (const contact::ContactSurfaces& pass : pair.passes)
      time_pass(
          [&] {
            contact::ContactPassState state;  // a first pass: the search included
            contact::ContactStatistics statistics;
            contact::ContactPhaseSeconds seconds;
            contact::run_contact_pass(pass, pair.settings, state, model.mesh.x_ref, u, velocity, model.mass,
                                      f, gap, statistics, seconds);
          },
          pass.point_count());
  for (const RigidWall& wall : contact.walls)
    time_pass(
        [&] {
          contact::WallState state;
          contact::ContactStatistics statistics;
          contact::ContactPhaseSeconds seconds;
          contact::run_wall_pass(wall.surfaces, wall.plane, wall.settings, state, model.mesh.x_ref, u,
                                 velocity, model.mass, 0.0, f, gap, statistics, seconds);
        },
        wall.surfaces.point_count());
  return costs;
}

void add_point_costs(const ContactModel& contact, const std::vector<double>& pass_costs,
                     const std::function<std::size_t(std::uint32_t)>& chunk_of_node,
                     std::vector<double>& chunk) {
  std::size_t k = 0;
  auto add_points = [&](const contact::ContactSurfaces& s, double cost) {
    for (std::size_t p = 0; p < s.point_count(); ++p) {
      const std::uint32_t node =
          s.quadrature ? s.slave_segments[s.quadrature_points[p].segment].nodes[0] : s.slave_nodes[p];
      chunk[chunk_of_node(node)] += cost;
    }
  };
  for (const ContactPair& pair : contact.pairs)
    for (const contact::ContactSurfaces& pass : pair.passes) add_points(pass, pass_costs[k++]);
  for (const RigidWall& wall : contact.walls) add_points(wall.surfaces, pass_costs[k++]);
}

std::vector<double> chunk_costs(const Model& model, const ContactModel& contact, const NodalVectors& velocity,
                                double dt, const mpi::Communicator& comm) {
  std::vector<double> costs;
  if (comm.root()) {
    costs = element_costs(model, dt);
    const std::vector<double> passes = contact_costs(model, contact, velocity);
    costs.insert(costs.end(), passes.begin(), passes.end());
  }
  std::size_t passes = 0;
  for (const ContactPair& pair : contact.pairs) passes += pair.passes.size();
  costs.resize(model.blocks.size() + passes + contact.walls.size());
  if (comm.distributed())
    mpi::check(MPI_Bcast(costs.data(), int(costs.size()), MPI_DOUBLE, 0, comm.comm),
               "MPI_Bcast of the costs");

  // Each chunk: its elements' cost; the first chunk of each node.
  std::vector<double> chunk;
  std::vector<std::int64_t> first_chunk(model.mesh.node_count(), -1);
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const element::ElementBlock& block = model.blocks[b];
    for (std::size_t c = 0; c + 1 < block.chunk_begin.size(); ++c) {
      const auto n = std::size_t(block.nodes_per_element);
      for (std::size_t k = n * block.chunk_begin[c]; k < n * block.chunk_begin[c + 1]; ++k)
        if (first_chunk[block.connectivity[k]] < 0)
          first_chunk[block.connectivity[k]] = std::int64_t(chunk.size());
      chunk.push_back(costs[b] * double(block.chunk_begin[c + 1] - block.chunk_begin[c]));
    }
  }
  // Each slave point in the chunk of its node (or of its slave segment's first node).
  add_point_costs(
      contact, std::vector<double>(costs.begin() + std::ptrdiff_t(model.blocks.size()), costs.end()),
      [&](std::uint32_t node) { return std::size_t(first_chunk[node]); }, chunk);
  return chunk;
}

}  // namespace exdyn::solver
