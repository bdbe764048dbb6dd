// A run's setup on many ranks, each rank building only its part (rank_setup.hpp).
#include "ranks/rank_setup.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>

#include "common/errors.hpp"
#include "element/corner_checks.hpp"
#include "element/element_family.hpp"
#include "material/elastic.hpp"
#include "material/material_law.hpp"
#include "mesh/mapped.hpp"
#include "mesh/mesh.hpp"
#include "model/memory_estimate.hpp"
#include "ranks/load_balance.hpp"
#include "ranks/setup_parts.hpp"

namespace exdyn::solver {

using namespace setup;

namespace {

// This rank's chunks of each part (part-local chunk numbers, ascending).
using MyChunks = std::vector<std::vector<std::uint32_t>>;
MyChunks chunks_of_rank(const SetupParts& deck_parts, const Chunks& chunks, int me) {
  MyChunks mine(deck_parts.list.size());
  for (const SetupPart& part : deck_parts.list)
    for (std::size_t c = 0; c < part.chunks; ++c)
      if (chunks.rank[part.first_chunk + c] == me) mine[std::size_t(part.index)].push_back(std::uint32_t(c));
  return mine;
}

// Calls element(part, e) for each element e of `mine`, part by part, in the whole
// model's order.
template <class Element>
void for_each_element(const SetupParts& deck_parts, const MyChunks& mine, Element element) {
  for (const SetupPart& part : deck_parts.list)
    for (const std::uint32_t c : mine[std::size_t(part.index)])
      for (std::uint32_t e = c * chunk_size; e < std::min((c + 1) * chunk_size, part.element_count); ++e)
        element(part, e);
}

// d.global_element and d.global_node: the rank's elements and their nodes, ascending.
// Sized first: grown by doubling, the lists would keep up to twice their size for the
// whole run (the node list, before its duplicates go, 8 or 20 entries an element).
// Returns the connectivity's length (the entries of the node list before they go).
std::size_t list_elements_and_nodes(const SetupParts& deck_parts, const MyChunks& mine, Decomposition& d) {
  std::size_t elements = 0, entries = 0;
  for_each_element(deck_parts, mine, [&](const SetupPart& part, std::uint32_t) {
    ++elements;
    entries += std::size_t(part.nodes_per_element);
  });
  d.global_element.reserve(elements);
  d.global_node.reserve(entries);
  for_each_element(deck_parts, mine, [&](const SetupPart& part, std::uint32_t e) {
    d.global_element.push_back(part.first_element + e);
    for (const std::uint32_t g : part.element_nodes(e)) d.global_node.push_back(g);
  });
  std::sort(d.global_node.begin(), d.global_node.end());
  d.global_node.erase(std::unique(d.global_node.begin(), d.global_node.end()), d.global_node.end());
  d.global_node.shrink_to_fit();
  return entries;
}

// The running sums' plan from the chunks around each node; the edge cut counted at
// the owners (each pair of chunks on different ranks, once per node they share).
// Collective over d.comm.
void plan_rank_exchange(const SetupParts& deck_parts, const Chunks& chunks, Decomposition& d) {
  const int me = d.comm.rank;
  const std::size_t local_nodes = d.global_node.size();
  std::vector<std::vector<std::pair<int, int>>> chain(local_nodes);
  std::vector<std::uint32_t> block_of(local_nodes);
  long edge_cut = 0;
  for (std::size_t i = 0; i < local_nodes; ++i) {
    const SetupPart& part = deck_parts.part_of_node(d.global_node[i]);
    const std::vector<std::size_t> around = chunks_at(part, d.global_node[i]);
    int owner = std::numeric_limits<int>::max();
    for (const std::size_t c : around) {
      chain[i].emplace_back(chunks.colour[c], chunks.rank[c]);
      owner = std::min(owner, chunks.rank[c]);
    }
    if (owner == me)
      for (std::size_t a = 0; a < around.size(); ++a)
        for (std::size_t b = a + 1; b < around.size(); ++b)
          edge_cut += chunks.rank[around[a]] != chunks.rank[around[b]];
    block_of[i] = std::uint32_t(part.index);
  }
  mpi::check(MPI_Allreduce(&edge_cut, &d.edge_cut, 1, MPI_LONG, MPI_SUM, d.comm.comm),
             "MPI_Allreduce of the edge cut");
  plan_force_exchange(d, me, std::move(chain), block_of, chunks.colours);
}

// The rank's mesh: its nodes' coordinates and its chunks' elements (local node ids),
// part by part in the whole model's order. Returns each part's first connectivity entry.
std::vector<std::size_t> mesh_of_rank(const SetupParts& deck_parts, const MyChunks& mine,
                                      const Decomposition& d, std::size_t entries, mesh::Mesh& mesh) {
  auto local_of = [&](std::uint32_t g) {
    return std::uint32_t(std::lower_bound(d.global_node.begin(), d.global_node.end(), g) -
                         d.global_node.begin());
  };
  mesh.x_ref = deck_parts.points(d.global_node);
  for (const SetupPart& part : deck_parts.list) mesh.parts.push_back(part.range());
  mesh.connectivity.reserve(entries);
  mesh.element_part.reserve(d.global_element.size());
  std::vector<std::size_t> first_connectivity(deck_parts.list.size());
  for (const SetupPart& part : deck_parts.list) {
    first_connectivity[std::size_t(part.index)] = mesh.connectivity.size();
    for (const std::uint32_t c : mine[std::size_t(part.index)])
      for (std::uint32_t e = c * chunk_size; e < std::min((c + 1) * chunk_size, part.element_count); ++e) {
        for (const std::uint32_t g : part.element_nodes(e)) mesh.connectivity.push_back(local_of(g));
        mesh.element_part.push_back(part.index);
      }
  }
  return first_connectivity;
}

// Each part's elements on this rank, and the layout the whole block's elements allow
// (two flags a part: parallelepipeds, axis-aligned): the ranks' layouts together (a
// rank's elements may allow a faster one, such as a cylinder's square core).
// Collective over comm.
std::vector<int> whole_layouts(const SetupParts& deck_parts, const std::vector<std::uint32_t>& part_count,
                               const std::vector<std::size_t>& first_connectivity, const mesh::Mesh& mesh,
                               const mpi::Communicator& comm) {
  std::vector<int> layout(2 * deck_parts.list.size(), 1);
  for (const SetupPart& part : deck_parts.list) {
    const auto p = std::size_t(part.index);
    const element::WholeBlock own =
        element::element_layout(part.options->formulation, part_count[p],
                                mesh.connectivity.data() + first_connectivity[p], mesh.x_ref);
    layout[2 * p] = own.parallelepipeds ? 1 : 0;
    layout[2 * p + 1] = own.axis_aligned ? 1 : 0;
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, layout.data(), int(layout.size()), MPI_INT, MPI_MIN, comm.comm),
             "MPI_Allreduce of the blocks' layouts");
  return layout;
}

// The rank's blocks, one per part with chunks here, each with the whole block's
// colours, layout and stable step. Returns the whole model's stable step without the
// Courant factor (critical_time_step), s. Collective over comm.
double blocks_of_rank(const input::Deck& deck, const SetupParts& deck_parts, const Chunks& chunks,
                      const MyChunks& my_chunks, const std::vector<std::size_t>& first_connectivity,
                      const Decomposition& d, Model& m) {
  const std::size_t parts = deck_parts.list.size();
  std::vector<std::uint32_t> part_count(parts, 0);
  for (const SetupPart& part : deck_parts.list)
    for (const std::uint32_t c : my_chunks[std::size_t(part.index)])
      part_count[std::size_t(part.index)] +=
          std::min((c + 1) * chunk_size, part.element_count) - c * chunk_size;
  const std::vector<int> layout = whole_layouts(deck_parts, part_count, first_connectivity, m.mesh, d.comm);
  // Each block's stable step, and a 20-node block's step scale (ElementBlock::
  // step_scale: its family step over its corner-based step): the whole block's, each an
  // exact minimum over the ranks; the model's stable step is the least of them.
  std::vector<double> steps(2 * parts, std::numeric_limits<double>::infinity());
  std::vector<std::size_t> block_of_part(parts, ~std::size_t{0});  // ~0: none here
  std::uint32_t first_element = 0;
  for (const SetupPart& part : deck_parts.list) {
    const auto p = std::size_t(part.index);
    const auto& mine = my_chunks[p];
    const input::PartOptions& options = *part.options;
    const input::MaterialOptions& material = deck.materials.at(std::size_t(options.material_index));
    const material::MaterialLaw law =
        material::make_law(material, input::resolved_kinematics(options, material), options.f_bar);
    const std::uint32_t* connectivity = m.mesh.connectivity.data() + first_connectivity[p];
    element::WholeBlock whole{layout[2 * p] != 0, layout[2 * p + 1] != 0, {}};
    if (part.order == 2 && law.linear_small() && whole.parallelepipeds)  // collective: every rank
      whole.group_points = whole_block_groups(part, part_count[p], connectivity, m.mesh.x_ref,
                                              d.global_element.data() + first_element, d.comm);
    if (mine.empty()) continue;
    m.blocks.push_back(element::make_element_block(
        options.formulation,
        material::elastic_constants(material.youngs_modulus, material.poissons_ratio, material.density),
        input::HourglassControl(options.hourglass_model, options.hourglass_coefficient), first_element,
        part_count[p], connectivity, m.mesh.x_ref, law, std::move(whole)));
    element::ElementBlock& block = m.blocks.back();
    block_of_part[p] = m.blocks.size() - 1;
    first_element += part_count[p];
    steps[2 * p] = element::critical_time_step(block, m.mesh.x_ref);
    if (block.nodes_per_element != 8)
      steps[2 * p + 1] =
          element::current_time_step(block, m.mesh.x_ref, NodalVectors(m.mesh.x_ref.size())).dt;
    // The whole block's colours, each keeping its index (possibly with no chunk here).
    EXDYN_ASSERT(block.chunk_begin.size() == mine.size() + 1);
    block.colours.assign(chunks.colours[p], {});
    for (std::size_t local = 0; local < mine.size(); ++local)
      block.colours[std::size_t(chunks.colour[part.first_chunk + mine[local]])].push_back(
          std::uint32_t(local));
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, steps.data(), int(steps.size()), MPI_DOUBLE, MPI_MIN, d.comm.comm),
             "MPI_Allreduce of the blocks' stable steps");
  double critical_dt = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < parts; ++p) {
    critical_dt = std::min(critical_dt, steps[2 * p]);
    if (block_of_part[p] != ~std::size_t{0} && m.blocks[block_of_part[p]].nodes_per_element != 8)
      m.blocks[block_of_part[p]].step_scale = steps[2 * p] / steps[2 * p + 1];
  }
  return critical_dt;
}

// The rank's nodes: masses (the owned ones count in the energies), fixed components,
// gravity (build_model's, node by node) and initial velocities.
void nodes_of_rank(const input::Deck& deck, const SetupParts& deck_parts, const Decomposition& d, Model& m,
                   NodalVectors& initial_velocity) {
  const std::size_t local_nodes = d.global_node.size();
  m.mass = masses_of(deck, deck_parts, d.global_node);
  m.inverse_mass.resize(local_nodes);
  m.counted_mass.resize(local_nodes);
  for (std::size_t i = 0; i < local_nodes; ++i) {
    EXDYN_ASSERT(m.mass[i] > 0.0);
    m.inverse_mass[i] = 1.0 / m.mass[i];
    m.counted_mass[i] = d.owned[i] != 0 ? m.mass[i] : 0.0;
  }
  PrescribedMotion motion = fixed_of(deck, deck_parts, d.global_node);
  // A conflict at a node some ranks hold: every rank stops with the first rank's message.
  if (const std::string conflict = mpi::first_message(d.comm, motion.conflict); !conflict.empty())
    throw InputError(conflict);
  m.fixed_nodes = std::move(motion.nodes);
  m.fixed_velocity = std::move(motion.velocity);
  m.boundary = std::move(motion.boundary);
  if (!deck.loads.empty()) {
    m.load_acceleration.resize(local_nodes);
    for (const input::LoadOptions& load : deck.loads)
      for (std::size_t i = 0; i < local_nodes; ++i) {
        const int p = deck_parts.part_of_node(d.global_node[i]).index;
        if (!load.parts.empty() && std::find(load.parts.begin(), load.parts.end(), p) == load.parts.end())
          continue;
        for (int c = 0; c < 3; ++c) m.load_acceleration.component(c)[i] += load.gravity[std::size_t(c)];
      }
  }
  initial_velocity = initial_velocities(deck_parts, d.global_node, m);
}

// The output rows: a node's owner is the lowest rank of the chunks around it, an
// element's the rank of its chunk. Collective over d.comm.
void plan_output_rows(const SetupParts& deck_parts, const Chunks& chunks, Decomposition& d) {
  std::vector<std::uint32_t> owned, elements(d.global_element.size());
  for (std::size_t i = 0; i < d.global_node.size(); ++i)
    if (d.owned[i] != 0) owned.push_back(std::uint32_t(i));
  std::iota(elements.begin(), elements.end(), 0u);
  d.node_rows = row_exchange(
      d.comm, d.global_nodes,
      [&](std::size_t g) {
        return owner_of_node(deck_parts.part_of_node(std::uint32_t(g)), std::uint32_t(g), chunks);
      },
      std::move(owned), d.global_node);
  d.element_rows = row_exchange(
      d.comm, d.global_elements,
      [&](std::size_t e) {
        const SetupPart& part = deck_parts.part_of_element(e);
        return chunks.rank[part.first_chunk + (e - part.first_element) / chunk_size];
      },
      std::move(elements), d.global_element);
}

// The contact faces near this rank: their model, and the ranks holding each of their
// nodes held here.
void contact_faces_of_rank(const input::Deck& deck, const SetupParts& deck_parts, const Chunks& chunks,
                           RankSetup& setup) {
  const NearRank near{setup.run.decomposition.global_node, setup.run.model};
  SurfaceModel surfaces = surface_model(deck, deck_parts, &near);
  setup.surface_nodes = std::move(surfaces.nodes);
  setup.surfaces = std::move(surfaces.model);
  setup.surface_held = std::move(surfaces.held);
  for (std::size_t k = 0; k < setup.surface_nodes.size(); ++k) {
    if (setup.surface_held[k] == 0) continue;
    const std::uint32_t g = setup.surface_nodes[k];
    setup.contact_nodes.push_back(g);
    std::vector<int>& holders = setup.run.contact_holders.emplace_back();
    for (const std::size_t c : chunks_at(deck_parts.part_of_node(g), g)) holders.push_back(chunks.rank[c]);
    std::sort(holders.begin(), holders.end());
    holders.erase(std::unique(holders.begin(), holders.end()), holders.end());
  }
}

// This rank's part of the model, its chunks chunks.rank's. Collective over comm.
RankSetup build_part(const input::Deck& deck, const mpi::Communicator& comm, const SetupParts& deck_parts,
                     const Chunks& chunks, Partitioning partitioning) {
  RankSetup setup;
  setup.nodes = deck_parts.nodes;
  setup.elements = deck_parts.elements;
  Decomposition& d = setup.run.decomposition;
  Model& m = setup.run.model;
  d.comm = comm;
  d.global_nodes = deck_parts.nodes;
  d.global_elements = deck_parts.elements;
  d.partitioning = partitioning;
  d.set_up_by_rank = true;
  for (const SetupPart& part : deck_parts.list) {
    d.block_first_element.push_back(part.first_element);
    d.block_elements.push_back(part.element_count);
  }

  const MyChunks mine = chunks_of_rank(deck_parts, chunks, comm.rank);
  const std::size_t entries = list_elements_and_nodes(deck_parts, mine, d);
  plan_rank_exchange(deck_parts, chunks, d);
  const std::vector<std::size_t> first_connectivity = mesh_of_rank(deck_parts, mine, d, entries, m.mesh);
  setup.critical_dt = blocks_of_rank(deck, deck_parts, chunks, mine, first_connectivity, d, m);
  split_colour_steps(mine, m, d);
  nodes_of_rank(deck, deck_parts, d, m, setup.run.initial_velocity);
  plan_output_rows(deck_parts, chunks, d);
  contact_faces_of_rank(deck, deck_parts, chunks, setup);
  return setup;
}

// Each chunk's seconds a step (chunk_costs' figures) from a first setup of the parts:
// its elements at their block's cost per element, timed on the ranks' parts (the least
// over the ranks holding one), and the slave points of its nodes at their pass's cost
// per point, timed on the contact faces near each rank (the least over the ranks with
// points). Collective over comm.
std::vector<double> measured_costs(const input::Deck& deck, const mpi::Communicator& comm,
                                   const SetupParts& deck_parts, const Chunks& chunks,
                                   const RankSetup& trial) {
  const double dt = time_stepping(deck.time, trial.critical_dt).dt;
  const Model& m = trial.run.model;
  const Decomposition& d = trial.run.decomposition;
  std::vector<double> part_cost(deck_parts.list.size(), std::numeric_limits<double>::infinity());
  const std::vector<double> block_cost = element_costs(m, dt);
  for (std::size_t b = 0; b < m.blocks.size(); ++b)
    part_cost[std::size_t(deck_parts.part_of_element(d.global_element[m.blocks[b].first_element]).index)] =
        block_cost[b];
  mpi::check(
      MPI_Allreduce(MPI_IN_PLACE, part_cost.data(), int(part_cost.size()), MPI_DOUBLE, MPI_MIN, comm.comm),
      "MPI_Allreduce of the element costs");
  const ContactModel contact =
      build_contact(deck, trial.surfaces, dt, trial.critical_dt, contact_scope(trial, comm));  // faces' ids
  std::vector<double> pass_cost = contact_costs(
      trial.surfaces, contact, initial_velocities(deck_parts, trial.surface_nodes, trial.surfaces));
  {
    std::size_t k = 0;  // a rank without points of a pass has no figure for it
    for (const ContactPair& pair : contact.pairs)
      for (const contact::ContactSurfaces& pass : pair.passes)
        if (pass.point_count() == 0)
          pass_cost[k++] = std::numeric_limits<double>::infinity();
        else
          ++k;
    for (const RigidWall& wall : contact.walls)
      if (wall.surfaces.point_count() == 0)
        pass_cost[k++] = std::numeric_limits<double>::infinity();
      else
        ++k;
  }
  if (!pass_cost.empty())
    mpi::check(
        MPI_Allreduce(MPI_IN_PLACE, pass_cost.data(), int(pass_cost.size()), MPI_DOUBLE, MPI_MIN, comm.comm),
        "MPI_Allreduce of the contact costs");
  for (double& c : pass_cost)
    if (std::isinf(c)) c = 0.0;

  // Each point counted by one rank: the rank of the first chunk holding its node, into
  // that chunk (the last slot takes the points counted elsewhere).
  std::vector<double> points(chunks.weight.size() + 1, 0.0);
  add_point_costs(
      contact, pass_cost,
      [&](std::uint32_t face_node) {
        if (trial.surface_held[face_node] == 0) return chunks.weight.size();
        const std::uint32_t g = trial.surface_nodes[face_node];
        const std::size_t c = chunks_at(deck_parts.part_of_node(g), g).front();
        return chunks.rank[c] == comm.rank ? c : chunks.weight.size();
      },
      points);
  mpi::check(
      MPI_Allreduce(MPI_IN_PLACE, points.data(), int(chunks.weight.size()), MPI_DOUBLE, MPI_SUM, comm.comm),
      "MPI_Allreduce of the contact costs of the chunks");
  std::vector<double> cost(chunks.weight.size());
  for (std::size_t c = 0; c < cost.size(); ++c)
    cost[c] = part_cost[chunks.block_of[c]] * chunks.weight[c] + points[c];
  return cost;
}

// The ranks of comm on this machine (the memory check's share).
int ranks_on_this_machine(const mpi::Communicator& comm) {
  MPI_Comm here = MPI_COMM_NULL;
  mpi::check(MPI_Comm_split_type(comm.comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &here),
             "MPI_Comm_split_type of the ranks on this machine");
  int ranks_here = 1;
  MPI_Comm_size(here, &ranks_here);
  MPI_Comm_free(&here);
  return ranks_here;
}

}  // namespace

RankSetup set_up_rank(const input::Deck& deck, const mpi::Communicator& comm, Partitioning partitioning,
                      bool weigh_by_work) {
  for (const input::ContactOptions& pair : deck.contact)
    if (input::follows_erosion(deck, pair)) return set_up_from_whole(deck, comm, partitioning, weigh_by_work);
  // The memory check with this machine's share of the model.
  check_mesh_size(deck, MachineShare{comm.size, ranks_on_this_machine(comm)});

  // Rank 0 reads each Gmsh file once, for all the parts it holds.
  std::map<std::string, input::GmshMesh> files;
  auto read = [&](const std::string& file, const SourceLocation& where, const std::string& key_path) {
    auto known = files.find(file);
    if (known == files.end()) known = files.emplace(file, input::read_gmsh(file, where, key_path)).first;
    return known->second;
  };
  SetupParts deck_parts(deck, read, &comm);
  files.clear();  // the files, once the parts are made
  Chunks chunks = walk_chunks(deck_parts, &comm);
  chunks.rank = partition_parts(deck_parts, chunks, comm.size, partitioning, &comm);
  if (weigh_by_work) {  // a first setup by elements, timed, then the chunks weighed by their costs
    scatter_pieces(deck_parts, chunks, comm);
    const std::vector<double> costs = measured_costs(
        deck, comm, deck_parts, chunks, build_part(deck, comm, deck_parts, chunks, partitioning));
    weigh_by_costs(chunks.weight, costs);
    chunks.rank = partition_parts(deck_parts, chunks, comm.size, partitioning, &comm);
  }
  chunks.centroid = {};
  scatter_pieces(deck_parts, chunks, comm);
  RankSetup setup = build_part(deck, comm, deck_parts, chunks, partitioning);
  setup.run.decomposition.weighed_by_work = weigh_by_work;
  return setup;
}

RankSetup set_up_from_whole(const input::Deck& deck, const mpi::Communicator& comm, Partitioning partitioning,
                            bool weigh_by_work) {
  // The memory check: each rank on this machine holds the whole model.
  check_mesh_size(deck, MachineShare{1, ranks_on_this_machine(comm)});
  const Model whole = build_model(deck);
  RankSetup setup;
  setup.critical_dt = critical_time_step(whole);
  setup.nodes = whole.mesh.node_count();
  setup.elements = whole.mesh.element_count();
  // One process's contact (its first step is the clock's: time_stepping's).
  setup.contact =
      build_contact(deck, whole, time_stepping(deck.time, setup.critical_dt).dt, setup.critical_dt);
  setup.contact_nodes = setup.contact->nodes;
  const NodalVectors velocity = initial_velocity(deck, whole);
  const std::vector<double> costs =
      weigh_by_work
          ? chunk_costs(whole, *setup.contact, velocity, time_stepping(deck.time, setup.critical_dt).dt, comm)
          : std::vector<double>{};
  setup.run = localize(whole, setup.contact_nodes, velocity, comm, partitioning, costs);
  setup.run.decomposition.weighed_by_work = weigh_by_work;
  return setup;
}

ContactModel rank_contact(const input::Deck& deck, RankSetup& setup, double dt, double critical_dt,
                          const mpi::Communicator& comm) {
  if (setup.contact) {
    ContactModel contact = std::move(*setup.contact);
    setup.contact.reset();
    return contact;
  }
  ContactModel contact = build_contact(deck, setup.surfaces, dt, critical_dt, contact_scope(setup, comm));
  globalize_contact(contact, setup.surface_nodes);
  return contact;
}

SetupChunks setup_chunks(const input::Deck& deck, int ranks, Partitioning partitioning) {
  const SetupParts deck_parts(deck);
  const Chunks chunks = walk_chunks(deck_parts);
  return {chunks.colour, partition_parts(deck_parts, chunks, ranks, partitioning)};
}

std::vector<double> setup_masses(const input::Deck& deck, const std::vector<std::uint32_t>& nodes) {
  return masses_of(deck, SetupParts(deck), nodes);
}

std::pair<std::vector<std::uint32_t>, Model> contact_faces_model(const input::Deck& deck) {
  SurfaceModel whole = surface_model(deck, SetupParts(deck), nullptr);
  return {std::move(whole.nodes), std::move(whole.model)};
}

RankSetup contact_faces_near(const input::Deck& deck, const std::vector<std::uint32_t>& nodes,
                             const Model& model) {
  const NearRank near{nodes, model};
  SurfaceModel surfaces = surface_model(deck, SetupParts(deck), &near);
  RankSetup setup;
  setup.surface_nodes = std::move(surfaces.nodes);
  setup.surfaces = std::move(surfaces.model);
  setup.surface_held = std::move(surfaces.held);
  return setup;
}

ContactScope contact_scope(const RankSetup& setup, const mpi::Communicator& comm) {
  ContactScope scope;
  scope.held = &setup.surface_held;
  scope.largest = [comm](double figure) {
    mpi::check(MPI_Allreduce(MPI_IN_PLACE, &figure, 1, MPI_DOUBLE, MPI_MAX, comm.comm),
               "MPI_Allreduce of a contact figure");
    return figure;
  };
  return scope;
}

void globalize_contact(ContactModel& contact, const std::vector<std::uint32_t>& surface_nodes) {
  auto ids = [&](std::vector<std::uint32_t>& nodes) {
    for (std::uint32_t& n : nodes) n = surface_nodes[n];
  };
  auto segments = [&](std::vector<contact::SegmentNodes>& list) {
    for (contact::SegmentNodes& s : list)
      for (int k = 0; k < contact::node_count(s.type); ++k)
        s.nodes[std::size_t(k)] = surface_nodes[s.nodes[std::size_t(k)]];
  };
  auto surfaces = [&](contact::ContactSurfaces& s) {
    ids(s.slave_nodes);
    ids(s.moving_nodes);
    segments(s.slave_segments);
    segments(s.segments);
  };
  for (ContactPair& pair : contact.pairs)
    for (contact::ContactSurfaces& s : pair.passes) surfaces(s);
  for (RigidWall& wall : contact.walls) surfaces(wall.surfaces);
  ids(contact.nodes);
}

}  // namespace exdyn::solver
