// Domain decomposition: the partition, a rank's part of the model, and the
// exchanges of a step (decomposition.hpp, docs/parallel.md).
#include "ranks/decomposition.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <tuple>
#include <type_traits>

#include "common/errors.hpp"
#include "common/timer.hpp"

namespace exdyn::solver {

namespace {

// Rank r's rows of a dataset of n rows on p ranks: [n r / p, n (r + 1) / p).
std::size_t first_row(std::size_t n, int r, int p) { return n * std::size_t(r) / std::size_t(p); }

}  // namespace

RowExchange row_exchange(const mpi::Communicator& comm, std::size_t n,
                         const std::function<int(std::size_t)>& owner_of, std::vector<std::uint32_t> mine,
                         const std::vector<std::uint32_t>& global_of) {
  RowExchange x;
  const int p = comm.size;
  x.begin = first_row(n, comm.rank, p);
  x.end = first_row(n, comm.rank + 1, p);
  std::sort(mine.begin(), mine.end(),
            [&](std::uint32_t a, std::uint32_t b) { return global_of[a] < global_of[b]; });
  x.send_items = std::move(mine);
  x.send_counts.assign(std::size_t(p), 0);
  int destination = 0;
  for (const std::uint32_t item : x.send_items) {
    while (global_of[item] >= first_row(n, destination + 1, p)) ++destination;
    ++x.send_counts[std::size_t(destination)];
  }
  x.receive_counts.assign(std::size_t(p), 0);
  std::vector<int> owner(x.end - x.begin);
  for (std::size_t g = x.begin; g < x.end; ++g) owner[g - x.begin] = owner_of(g);
  for (const int r : owner) ++x.receive_counts[std::size_t(r)];
  x.send_displacements.assign(std::size_t(p), 0);
  x.receive_displacements.assign(std::size_t(p), 0);
  for (int r = 1; r < p; ++r) {
    x.send_displacements[std::size_t(r)] =
        x.send_displacements[std::size_t(r - 1)] + x.send_counts[std::size_t(r - 1)];
    x.receive_displacements[std::size_t(r)] =
        x.receive_displacements[std::size_t(r - 1)] + x.receive_counts[std::size_t(r - 1)];
  }
  x.receive_rows.resize(x.end - x.begin);
  std::vector<int> next = x.receive_displacements;
  for (std::size_t g = x.begin; g < x.end; ++g)
    x.receive_rows[std::size_t(next[std::size_t(owner[g - x.begin])]++)] =
        static_cast<std::uint32_t>(g - x.begin);
  return x;
}

std::vector<std::uint32_t> contact_face_nodes(const input::Deck& deck, const mesh::Mesh& mesh) {
  std::vector<std::uint32_t> nodes;
  auto add_faces = [&](const std::vector<input::FaceRef>& faces) {
    for (const input::FaceRef& f : faces) {
      const mesh::Face face = mesh::face_of(mesh, f);
      nodes.insert(nodes.end(), face.nodes.begin(), face.nodes.end());
    }
  };
  for (const input::ContactOptions& pair : deck.contact) add_faces(pair.slave), add_faces(pair.master);
  for (const input::RigidWallOptions& wall : deck.rigid_walls) add_faces(wall.slave);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

namespace {

// What every rank knows of the whole model: the rank and colour of every chunk, each
// node's owner (the lowest rank with a chunk on it), the nodes of this rank's chunks,
// and the local number of each node this rank holds (-1: not held).
struct WholeModel {
  const Model& model;
  int me = 0;
  std::vector<int> chunk_rank;           // blocks one after the other
  std::vector<std::vector<int>> colour;  // [block][chunk]
  std::vector<int> owner;                // per global node
  std::vector<std::uint8_t> mine;        // per global node: a chunk of this rank is on it
  std::vector<std::int64_t> local_of;    // per global node

  // visit(block, chunk, rank, colour) for every chunk of the model.
  template <class Visit>
  void for_each_chunk(Visit visit) const {
    std::size_t unit = 0;
    for (std::size_t b = 0; b < model.blocks.size(); ++b)
      for (std::size_t c = 0; c + 1 < model.blocks[b].chunk_begin.size(); ++c, ++unit)
        visit(b, c, chunk_rank[unit], colour[b][c]);
  }
  // visit(node) for every node of every element of chunk c of block b (global ids).
  template <class Visit>
  void for_each_node(std::size_t b, std::size_t c, Visit visit) const {
    const element::ElementBlock& block = model.blocks[b];
    const auto n = std::size_t(block.nodes_per_element);
    for (std::size_t k = n * block.chunk_begin[c]; k < n * block.chunk_begin[c + 1]; ++k)
      visit(block.connectivity[k]);
  }
};

WholeModel whole_model(const Model& global, const mpi::Communicator& comm, Partitioning partitioning,
                       const std::vector<double>& costs) {
  WholeModel w{global, comm.rank, partition_chunks(global, comm.size, partitioning, costs), {}, {}, {}, {}};
  w.colour.resize(global.blocks.size());
  for (std::size_t b = 0; b < global.blocks.size(); ++b) {
    const element::ElementBlock& block = global.blocks[b];
    w.colour[b].assign(block.chunk_begin.size() - 1, 0);
    for (std::size_t k = 0; k < block.colours.size(); ++k)
      for (const std::uint32_t c : block.colours[k]) w.colour[b][c] = int(k);
  }
  w.owner.assign(global.mesh.node_count(), std::numeric_limits<int>::max());
  w.mine.assign(global.mesh.node_count(), 0);
  w.for_each_chunk([&](std::size_t b, std::size_t c, int rank, int) {
    w.for_each_node(b, c, [&](std::uint32_t node) {
      w.owner[node] = std::min(w.owner[node], rank);
      if (rank == w.me) w.mine[node] = 1;
    });
  });
  return w;
}

// The running sums (decomposition.hpp): from the chain of each node of this rank's
// chunks, the (colour, rank) of every chunk on it in colour order (the order of its
// additions on one rank), the messages of each block and colour step (d.steps, by
// global block); and which nodes are shared and owned.
void plan_force_exchange(const WholeModel& w, Decomposition& d) {
  const std::size_t local_nodes = d.global_node.size();
  std::vector<std::vector<std::pair<int, int>>> chain(local_nodes);
  std::vector<std::uint32_t> block_of(local_nodes, 0);
  w.for_each_chunk([&](std::size_t b, std::size_t c, int rank, int colour) {
    w.for_each_node(b, c, [&](std::uint32_t node) {
      if (w.mine[node] == 0) return;
      const auto i = std::size_t(w.local_of[node]);
      block_of[i] = std::uint32_t(b);
      if (chain[i].empty() || chain[i].back() != std::pair{colour, rank}) chain[i].emplace_back(colour, rank);
    });
  });
  std::vector<std::size_t> colours;
  for (const element::ElementBlock& block : w.model.blocks) colours.push_back(block.colours.size());
  plan_force_exchange(d, w.me, std::move(chain), block_of, colours);
}

// This rank's blocks: its chunks of each block (element::slice_block), elements
// renumbered in that order; d.steps kept for these blocks only, each colour's chunks
// split into those that wait for a running sum and those that do not.
void cut_blocks(const WholeModel& w, Model& m, Decomposition& d) {
  const Model& global = w.model;
  const std::size_t local_nodes = d.global_node.size(), blocks = global.blocks.size();
  m.mesh.x_ref.resize(local_nodes);
  for (std::size_t i = 0; i < local_nodes; ++i)
    for (int c = 0; c < 3; ++c)
      m.mesh.x_ref.component(c)[i] = global.mesh.x_ref.component(c)[d.global_node[i]];
  // The parts, for the node counts of the elements (nodes_of) only: without their
  // lattices and faces, which the setup alone reads, from the whole mesh.
  for (const mesh::PartRange& part : global.mesh.parts) {
    mesh::PartRange& local = m.mesh.parts.emplace_back();
    local.order = part.order;
    local.nodes_per_element = part.nodes_per_element;
    local.elements = part.elements;
  }
  for (const element::ElementBlock& block : global.blocks) {
    d.block_first_element.push_back(block.first_element);
    d.block_elements.push_back(block.count);
  }
  std::vector<std::vector<std::uint32_t>> my_chunks(blocks);
  w.for_each_chunk([&](std::size_t b, std::size_t c, int rank, int) {
    if (rank == w.me) my_chunks[b].push_back(std::uint32_t(c));
  });
  std::vector<std::size_t> first_connectivity;
  for (std::size_t b = 0; b < blocks; ++b) {
    const element::ElementBlock& block = global.blocks[b];
    first_connectivity.push_back(m.mesh.connectivity.size());
    for (const std::uint32_t c : my_chunks[b])
      for (std::uint32_t e = block.chunk_begin[c]; e < block.chunk_begin[c + 1]; ++e) {
        d.global_element.push_back(block.first_element + e);
        m.mesh.element_part.push_back(global.mesh.element_part[block.first_element + e]);
        const std::uint32_t* nodes = block.connectivity + std::size_t(block.nodes_per_element) * e;
        for (int k = 0; k < block.nodes_per_element; ++k)
          m.mesh.connectivity.push_back(static_cast<std::uint32_t>(w.local_of[nodes[k]]));
      }
  }
  std::size_t first_element = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    if (my_chunks[b].empty()) continue;
    m.blocks.push_back(element::slice_block(global.blocks[b], my_chunks[b],
                                            m.mesh.connectivity.data() + first_connectivity[b],
                                            static_cast<std::uint32_t>(first_element)));
    first_element += m.blocks.back().count;
  }
  split_colour_steps(my_chunks, m, d);
}

// The rows of the output datasets this rank writes, and where its owned values go.
void plan_output_rows(const WholeModel& w, Decomposition& d) {
  std::vector<int> element_rank(w.model.mesh.element_count(), 0);
  w.for_each_chunk([&](std::size_t b, std::size_t c, int rank, int) {
    const element::ElementBlock& block = w.model.blocks[b];
    for (std::uint32_t e = block.chunk_begin[c]; e < block.chunk_begin[c + 1]; ++e)
      element_rank[block.first_element + e] = rank;
  });
  std::vector<std::uint32_t> owned_nodes, local_elements(d.global_element.size());
  for (std::size_t i = 0; i < d.owned.size(); ++i)
    if (d.owned[i] != 0) owned_nodes.push_back(static_cast<std::uint32_t>(i));
  std::iota(local_elements.begin(), local_elements.end(), 0u);
  d.node_rows = row_exchange(
      d.comm, d.global_nodes, [&](std::size_t g) { return w.owner[g]; }, std::move(owned_nodes),
      d.global_node);
  d.element_rows = row_exchange(
      d.comm, d.global_elements, [&](std::size_t e) { return element_rank[e]; }, std::move(local_elements),
      d.global_element);
}

}  // namespace

void plan_force_exchange(Decomposition& d, int me, std::vector<std::vector<std::pair<int, int>>> chain,
                         const std::vector<std::uint32_t>& block_of,
                         const std::vector<std::size_t>& colours) {
  const std::size_t local_nodes = d.global_node.size(), blocks = colours.size();
  d.steps.resize(blocks);
  int tag = 1;
  for (std::size_t b = 0; b < blocks; ++b) {
    d.steps[b].resize(colours[b] + 1);
    for (auto& step : d.steps[b]) step.tag = tag++;
  }
  // [block][step] -> peer -> nodes
  std::vector<std::vector<std::map<int, std::vector<std::uint32_t>>>> receive(blocks), send(blocks);
  for (std::size_t b = 0; b < blocks; ++b) {
    receive[b].resize(d.steps[b].size());
    send[b].resize(d.steps[b].size());
  }
  d.owned.assign(local_nodes, 0);
  for (std::size_t i = 0; i < local_nodes; ++i) {
    auto& links = chain[i];
    std::sort(links.begin(), links.end());
    links.erase(std::unique(links.begin(), links.end()), links.end());
    std::vector<int> holders;
    for (const auto& link : links) holders.push_back(link.second);
    std::sort(holders.begin(), holders.end());
    holders.erase(std::unique(holders.begin(), holders.end()), holders.end());
    d.owned[i] = !holders.empty() && holders.front() == me;  // the lowest holder owns it
    if (holders.size() < 2) continue;
    ++d.shared_nodes;
    const std::size_t b = block_of[i];
    const auto node = static_cast<std::uint32_t>(i);
    // The running sum passes to the next chunk's rank before its colour ...
    for (std::size_t j = 1; j < links.size(); ++j) {
      const auto [colour, rank] = links[j];
      const int previous = links[j - 1].second;
      if (rank == previous) continue;
      if (rank == me) receive[b][std::size_t(colour)][previous].push_back(node);
      if (previous == me) send[b][std::size_t(colour) - 1][rank].push_back(node);
    }
    // ... and the last one's total to every other holder, after the last colour.
    const std::size_t last_step = d.steps[b].size() - 1;
    const int last = links.back().second;
    for (const int rank : holders) {
      if (rank == last) continue;
      if (rank == me) receive[b][last_step][last].push_back(node);
      if (last == me) send[b][last_step - 1][rank].push_back(node);
    }
  }
  for (std::size_t b = 0; b < blocks; ++b)
    for (std::size_t k = 0; k < d.steps[b].size(); ++k) {
      for (auto& [rank, nodes] : receive[b][k])
        d.steps[b][k].receive.push_back({rank, nodes, std::vector<double>(3 * nodes.size())});
      for (auto& [rank, nodes] : send[b][k])
        d.steps[b][k].send.push_back({rank, nodes, std::vector<double>(3 * nodes.size())});
    }
}

void split_colour_steps(const std::vector<std::vector<std::uint32_t>>& my_chunks, const Model& m,
                        Decomposition& d) {
  std::vector<int> stamp(d.global_node.size(), -1);
  std::vector<std::vector<Decomposition::ColourStep>> steps;
  std::size_t local = 0;
  for (std::size_t b = 0; b < my_chunks.size(); ++b) {
    if (my_chunks[b].empty()) {  // a block without chunks here takes no part in the exchange
      EXDYN_ASSERT(std::all_of(d.steps[b].begin(), d.steps[b].end(),
                               [](const auto& s) { return s.receive.empty() && s.send.empty(); }));
      continue;
    }
    const element::ElementBlock& block = m.blocks[local++];
    for (std::size_t k = 0; k + 1 < d.steps[b].size(); ++k) {
      Decomposition::ColourStep& step = d.steps[b][k];
      const int mark = int(1000 * b + k);
      for (const auto& message : step.receive)
        for (const std::uint32_t node : message.nodes) stamp[node] = mark;
      for (const std::uint32_t c : block.colours[k]) {
        bool waits = false;
        for (std::size_t n = std::size_t(block.nodes_per_element) * block.chunk_begin[c];
             n < std::size_t(block.nodes_per_element) * block.chunk_begin[c + 1] && !waits; ++n)
          waits = stamp[block.connectivity[n]] == mark;
        (waits ? step.waiting_chunks : step.free_chunks).push_back(c);
      }
    }
    steps.push_back(std::move(d.steps[b]));
  }
  d.steps = std::move(steps);
}

LocalRun localize(const Model& global, const std::vector<std::uint32_t>& contact_nodes,
                  const NodalVectors& global_initial_velocity, const mpi::Communicator& comm,
                  Partitioning partitioning, const std::vector<double>& costs) {
  WholeModel w = whole_model(global, comm, partitioning, costs);
  LocalRun run;
  Decomposition& d = run.decomposition;
  d.partitioning = partitioning;
  d.weighed_by_work = !costs.empty();
  d.edge_cut = partition_figures(global, w.chunk_rank).edge_cut;
  d.comm = comm;
  d.global_nodes = global.mesh.node_count();
  d.global_elements = global.mesh.element_count();
  // Local nodes: this rank's chunks' nodes, in global order.
  w.local_of.assign(d.global_nodes, -1);
  for (std::size_t g = 0; g < d.global_nodes; ++g)
    if (w.mine[g] != 0) {
      w.local_of[g] = static_cast<std::int64_t>(d.global_node.size());
      d.global_node.push_back(static_cast<std::uint32_t>(g));
    }
  // The ranks holding each contact node (the contact's owners and ghosts: distributed_contact.hpp).
  std::vector<std::int64_t> contact_index(d.global_nodes, -1);
  for (std::size_t k = 0; k < contact_nodes.size(); ++k) contact_index[contact_nodes[k]] = std::int64_t(k);
  run.contact_holders.resize(contact_nodes.size());
  w.for_each_chunk([&](std::size_t b, std::size_t c, int rank, int) {
    w.for_each_node(b, c, [&](std::uint32_t node) {
      if (contact_index[node] < 0) return;
      std::vector<int>& holders = run.contact_holders[std::size_t(contact_index[node])];
      if (std::find(holders.begin(), holders.end(), rank) == holders.end()) holders.push_back(rank);
    });
  });
  for (std::vector<int>& holders : run.contact_holders) std::sort(holders.begin(), holders.end());
  plan_force_exchange(w, d);
  Model& m = run.model;
  cut_blocks(w, m, d);
  plan_output_rows(w, d);

  // Masses: the global ones (the same bits as one rank); only owned nodes count in
  // the energies.
  const std::size_t local_nodes = d.global_node.size();
  m.mass.resize(local_nodes);
  m.inverse_mass.resize(local_nodes);
  m.counted_mass.resize(local_nodes);
  run.initial_velocity.resize(local_nodes);
  for (std::size_t i = 0; i < local_nodes; ++i) {
    const std::uint32_t g = d.global_node[i];
    m.mass[i] = global.mass[g];
    m.inverse_mass[i] = global.inverse_mass[g];
    m.counted_mass[i] = d.owned[i] != 0 ? global.mass[g] : 0.0;
    for (int c = 0; c < 3; ++c)
      run.initial_velocity.component(c)[i] = global_initial_velocity.component(c)[g];
  }
  if (!global.load_acceleration.empty()) {
    m.load_acceleration.resize(local_nodes);
    for (std::size_t i = 0; i < local_nodes; ++i)
      for (int c = 0; c < 3; ++c)
        m.load_acceleration.component(c)[i] = global.load_acceleration.component(c)[d.global_node[i]];
  }
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t k = 0; k < global.fixed_nodes[c].size(); ++k)
      if (const std::int64_t local = w.local_of[global.fixed_nodes[c][k]]; local >= 0) {
        m.fixed_nodes[c].push_back(static_cast<std::uint32_t>(local));
        m.fixed_velocity[c].push_back(global.fixed_velocity[c][k]);
      }
  m.boundary.resize(global.boundary.size());
  for (std::size_t b = 0; b < global.boundary.size(); ++b) {
    m.boundary[b].velocity = global.boundary[b].velocity;
    for (std::size_t c = 0; c < 3; ++c)
      for (const std::uint32_t g : global.boundary[b].nodes[c])
        if (w.local_of[g] >= 0) m.boundary[b].nodes[c].push_back(static_cast<std::uint32_t>(w.local_of[g]));
  }
  return run;
}

element::ElementEnergies add_forces_across_ranks(const Model& model, Decomposition& d, const NodalVectors& u,
                                                 NodalVectors& f_int, double* stress) {
  element::ElementEnergies total;
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const element::ElementBlock& block = model.blocks[b];
    std::vector<Decomposition::ColourStep>& steps = d.steps[b];
    d.sends.clear();
    for (std::size_t k = 0; k < steps.size(); ++k) {
      Decomposition::ColourStep& step = steps[k];
      const bool colour = k + 1 < steps.size();  // else the totals' step
      d.receives.clear();
      for (Decomposition::Message& m : step.receive) {
        d.receives.emplace_back();
        mpi::check(MPI_Irecv(m.values.data(), int(m.values.size()), MPI_DOUBLE, m.rank, step.tag, d.comm.comm,
                             &d.receives.back()),
                   "MPI_Irecv of the shared forces");
      }
      if (colour) element::add_chunk_forces(block, step.free_chunks, u, f_int, stress);  // while they come
      {
        const ScopedTimer timer(d.exchange_seconds);
        mpi::check(MPI_Waitall(int(d.receives.size()), d.receives.data(), MPI_STATUSES_IGNORE),
                   "MPI_Waitall of the shared forces");
      }
      for (const Decomposition::Message& m : step.receive)
        for (std::size_t j = 0; j < m.nodes.size(); ++j)
          for (int c = 0; c < 3; ++c) f_int.component(c)[m.nodes[j]] = m.values[3 * j + std::size_t(c)];
      if (!colour) break;
      element::add_chunk_forces(block, step.waiting_chunks, u, f_int, stress);
      for (Decomposition::Message& m : step.send) {
        for (std::size_t j = 0; j < m.nodes.size(); ++j)
          for (int c = 0; c < 3; ++c) m.values[3 * j + std::size_t(c)] = f_int.component(c)[m.nodes[j]];
        d.sends.emplace_back();
        mpi::check(MPI_Isend(m.values.data(), int(m.values.size()), MPI_DOUBLE, m.rank, steps[k + 1].tag,
                             d.comm.comm, &d.sends.back()),
                   "MPI_Isend of the shared forces");
      }
    }
    {
      const ScopedTimer timer(d.exchange_seconds);
      mpi::check(MPI_Waitall(int(d.sends.size()), d.sends.data(), MPI_STATUSES_IGNORE),
                 "MPI_Waitall of the shared forces");
    }
    const element::ElementEnergies e = element::chunk_energy_total(block);
    total += e;
  }
  return total;
}

namespace {

// Sends `per_item` values of each item of x.send_items (pack(item, out)) to the
// ranks that write their rows; unpack(row, in) places each received item. T: double
// or std::uint32_t.
template <class T = double, class Pack, class Unpack>
void exchange_rows(const Decomposition& d, const RowExchange& x, int per_item, Pack pack, Unpack unpack) {
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::uint32_t>);
  const MPI_Datatype type = std::is_same_v<T, double> ? MPI_DOUBLE : MPI_UINT32_T;
  std::vector<T> out(std::size_t(per_item) * x.send_items.size());
  for (std::size_t k = 0; k < x.send_items.size(); ++k)
    pack(x.send_items[k], out.data() + std::size_t(per_item) * k);
  std::vector<T> in(std::size_t(per_item) * x.receive_rows.size());
  auto scaled = [&](const std::vector<int>& v) {
    std::vector<int> s(v);
    for (int& n : s) n *= per_item;
    return s;
  };
  const std::vector<int> sc = scaled(x.send_counts), sd = scaled(x.send_displacements),
                         rc = scaled(x.receive_counts), rd = scaled(x.receive_displacements);
  mpi::check(MPI_Alltoallv(out.data(), sc.data(), sd.data(), type, in.data(), rc.data(), rd.data(), type,
                           d.comm.comm),
             "MPI_Alltoallv of the output rows");
  for (std::size_t k = 0; k < x.receive_rows.size(); ++k)
    unpack(x.receive_rows[k], in.data() + std::size_t(per_item) * k);
}

}  // namespace

void rows_of(Decomposition& d, const NodalVectors& local, NodalVectors& rows) {
  const RowExchange& x = d.node_rows;
  rows.resize(x.end - x.begin);
  exchange_rows(
      d, x, 3,
      [&](std::uint32_t item, double* out) {
        for (int c = 0; c < 3; ++c) out[c] = local.component(c)[item];
      },
      [&](std::uint32_t row, const double* in) {
        for (int c = 0; c < 3; ++c) rows.component(c)[row] = in[c];
      });
}

// One column at a time: the messages' buffers hold one value an item, not 3 or 6 (at
// the output steps they were the rank's largest figure beside its part).
void rows_of(Decomposition& d, const NodalVectors& local, double* rows) {
  for (int c = 0; c < 3; ++c) {
    const double* values = local.component(c).data();
    exchange_rows(
        d, d.node_rows, 1, [&](std::uint32_t item, double* out) { *out = values[item]; },
        [&](std::uint32_t row, const double* in) { rows[3 * std::size_t(row) + std::size_t(c)] = *in; });
  }
}

void rows_of(Decomposition& d, const double* local, int k, bool nodal, double* rows) {
  const auto n = std::size_t(k);
  for (std::size_t c = 0; c < n; ++c)
    exchange_rows(
        d, nodal ? d.node_rows : d.element_rows, 1,
        [&](std::uint32_t item, double* out) { *out = local[n * item + c]; },
        [&](std::uint32_t row, const double* in) { rows[n * row + c] = *in; });
}

MeshRows mesh_rows(Decomposition& d, const mesh::Mesh& local) {
  MeshRows rows;
  rows_of(d, local.x_ref, rows.x_ref);
  // Per element its node ids (global; past its own nodes ~0), part and node count:
  // the widest element's nodes + 2 unsigned values.
  const std::size_t elements = local.element_count();
  std::vector<std::size_t> first(elements + 1, 0);  // each element's first connectivity entry
  int widest = 8;
  for (std::size_t e = 0; e < elements; ++e) {
    first[e + 1] = first[e] + std::size_t(local.nodes_of(e));
    widest = std::max(widest, local.nodes_of(e));
  }
  mpi::check(MPI_Allreduce(MPI_IN_PLACE, &widest, 1, MPI_INT, MPI_MAX, d.comm.comm),
             "MPI_Allreduce of the element size");
  const auto width = std::size_t(widest);
  rows.element_part.resize(d.element_rows.end - d.element_rows.begin);
  rows.element_nodes.resize(rows.element_part.size());
  std::vector<std::uint32_t> table(width * rows.element_part.size());
  exchange_rows<std::uint32_t>(
      d, d.element_rows, int(width + 2),
      [&](std::uint32_t e, std::uint32_t* out) {
        const std::size_t nodes = first[e + 1] - first[e];
        for (std::size_t k = 0; k < width; ++k)
          out[k] = k < nodes ? global_node_id(d, local.connectivity[first[e] + k]) : ~0u;
        out[width] = static_cast<std::uint32_t>(local.element_part[e]);
        out[width + 1] = static_cast<std::uint32_t>(nodes);
      },
      [&](std::uint32_t row, const std::uint32_t* in) {
        std::copy_n(in, width, table.data() + width * row);
        rows.element_part[row] = static_cast<std::int32_t>(in[width]);
        rows.element_nodes[row] = static_cast<std::uint8_t>(in[width + 1]);
      });
  for (std::size_t e = 0; e < rows.element_part.size(); ++e)
    rows.connectivity.insert(rows.connectivity.end(), table.begin() + std::ptrdiff_t(width * e),
                             table.begin() + std::ptrdiff_t(width * e + rows.element_nodes[e]));
  return rows;
}

HaloFigures halo_figures(const Decomposition& d) {
  HaloFigures h;
  h.shared_nodes = d.shared_nodes;
  for (const auto& block : d.steps)
    for (const auto& step : block)
      for (const auto& m : step.send) {
        ++h.messages_sent;
        h.bytes_sent += sizeof(double) * m.values.size();
      }
  return h;
}

}  // namespace exdyn::solver
