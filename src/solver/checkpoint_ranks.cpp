// A restart checkpoint on many ranks (checkpoint_ranks.hpp): the time loop's State,
// the element blocks and the contact made one process's, and back.
#include "solver/checkpoint_ranks.hpp"

#include <algorithm>
#include <set>
#include <string>

#include "common/errors.hpp"
#include "common/parallel.hpp"
#include "ranks/contact_checkpoint.hpp"
#include "ranks/rank_checkpoint.hpp"
#include "solver/checkpoint_state.hpp"

namespace exdyn::solver {

namespace {

void pick_nodal(const Decomposition& d, const NodalVectors& whole, NodalVectors& local, const char* what) {
  for (int c = 0; c < 3; ++c)
    pick_rows(whole.component(c), d.global_node, d.global_nodes, local.component(c), what);
}

// A contact array at this rank's contact nodes (local ids) from the whole's (kept where
// the checkpoint has no value: a node no contact touches keeps its initial value).
void pick_contact(const Decomposition& d, const std::vector<std::uint32_t>& saved,
                  const std::vector<std::uint32_t>& contact_nodes, const std::vector<double>& whole,
                  std::vector<double>& local) {
  for (const std::uint32_t l : contact_nodes) {
    const std::uint32_t g = d.global_node[l];
    if (std::binary_search(saved.begin(), saved.end(), g)) local[l] = whole[g];
  }
}

}  // namespace

namespace {

// The runs of items whose values this rank writes (local ids ascending by global id, each
// run consecutive global ids: consecutive local ids too), and each run's place among
// every rank's runs by global id: the number of its piece. Collective.
struct Runs {
  std::vector<std::size_t> first, count;  // local ids
  std::vector<std::size_t> piece;
};
Runs runs_of(const mpi::Communicator& comm, const std::vector<std::uint32_t>& global,
             const std::vector<std::uint8_t>* owned) {
  Runs runs;
  std::vector<std::uint32_t> starts;
  for (std::size_t i = 0; i < global.size(); ++i) {
    if (owned != nullptr && (*owned)[i] == 0) continue;
    const bool goes_on =
        !runs.first.empty() && runs.first.back() + runs.count.back() == i && global[i - 1] + 1 == global[i];
    if (goes_on) {
      ++runs.count.back();
    } else {
      runs.first.push_back(i), runs.count.push_back(1);
      starts.push_back(global[i]);
    }
  }
  std::vector<std::uint32_t> every = mpi::all_gather_varying(comm, starts);
  std::sort(every.begin(), every.end());
  for (const std::uint32_t start : starts)
    runs.piece.push_back(std::size_t(std::lower_bound(every.begin(), every.end(), start) - every.begin()));
  return runs;
}

// A local array of k values an item (k from its size) as the pieces of section `name`.
template <class T>
void add_runs(output::CheckpointWriter& file, const std::string& name, const std::vector<T>& local,
              std::size_t items, const Runs& runs) {
  const std::size_t k = items == 0 ? 0 : local.size() / items;
  for (std::size_t r = 0; r < runs.first.size(); ++r)
    file.add_view(name + "#" + std::to_string(runs.piece[r]), local.data() + k * runs.first[r],
                  k * runs.count[r] * sizeof(T));
}

}  // namespace

void add_state_pieces(output::CheckpointWriter& file, const State& s, Decomposition& d,
                      std::set<std::string>& pieced) {
  // Each node by its owner, each element by its rank: runs of the whole arrays as they
  // lie in memory, no value moved.
  const Runs nodes = runs_of(d.comm, d.global_node, &d.owned);
  const std::size_t node_count = d.global_node.size();
  const auto nodal = [&](const std::string& name, const NodalVectors& local) {
    for (int c = 0; c < 3; ++c) {
      const std::string section = name + "." + char('x' + c);
      pieced.insert(section);
      add_runs(file, section, local.component(c), node_count, nodes);
    }
  };
  nodal("state/displacement", s.displacement);
  nodal("state/velocity", s.velocity);
  nodal("state/load_force", s.load_force);
  for (std::size_t c = 0; c < 3; ++c) {
    const std::string section = "state/flags[" + std::to_string(c) + "]";
    pieced.insert(section);
    add_runs(file, section, s.flags[c], node_count, nodes);
  }
  const Runs elements = runs_of(d.comm, d.global_element, nullptr);
  for (const auto& [name, local] : {std::pair{"state/stress", &s.stress},
                                    {"state/plastic_strain", &s.plastic_strain},
                                    {"state/damage", &s.damage},
                                    {"state/status", &s.status}}) {
    pieced.insert(name);
    add_runs(file, name, *local, d.global_element.size(), elements);
  }
}

WholeState gather_whole_state(const State& s, const Model& model, Decomposition& d,
                              const ContactModel& contact) {
  WholeState w;
  State& t = w.state;
  // The contact arrays at the contact nodes their owners hold, on rank 0 compact (row k
  // the k-th contact node by global id).
  std::vector<std::uint32_t> mine;
  std::vector<double> values;
  for (const std::uint32_t l : contact.nodes) {
    if (d.owned[l] == 0) continue;
    mine.push_back(d.global_node[l]);
    for (const NodalVectors* v : {&s.contact_force, &s.previous_contact_force})
      for (int c = 0; c < 3; ++c) values.push_back(v->component(c)[l]);
    values.push_back(s.gap[l]);
    values.push_back(s.previous_gap[l]);
  }
  const auto all_ids = gather_to_root(d.comm, mine);
  const auto all_values = gather_to_root(d.comm, values);
  if (d.comm.root()) {
    std::vector<std::pair<std::uint32_t, const double*>> nodes;
    for (std::size_t r = 0; r < all_ids.size(); ++r)
      for (std::size_t i = 0; i < all_ids[r].size(); ++i)
        nodes.emplace_back(all_ids[r][i], all_values[r].data() + 8 * i);
    std::sort(nodes.begin(), nodes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    const std::size_t m = nodes.size();
    t.contact_force.resize(m);
    t.previous_contact_force.resize(m);
    t.gap.resize(m);
    t.previous_gap.resize(m);
    for (std::size_t k = 0; k < m; ++k) {
      const double* f = nodes[k].second;
      for (int c = 0; c < 3; ++c) {
        t.contact_force.component(c)[k] = f[c];
        t.previous_contact_force.component(c)[k] = f[3 + c];
      }
      t.gap[k] = f[6];
      t.previous_gap[k] = f[7];
      w.contact_nodes.push_back(nodes[k].first);
      w.contact_rows.push_back(std::uint32_t(k));
    }
  }
  // The step's and the run's values, the same on every rank; the sums each rank keeps
  // of its own (the energy of eroded elements, the loads' work, the reactions) added
  // in rank order.
  t.step = s.step, t.time = s.time, t.stress_step = s.stress_step, t.force_step = s.force_step;
  t.contact_energy = s.contact_energy, t.wall_work = s.wall_work;
  std::vector<double> sums = {s.eroded_energy, s.external_work, double(s.eroded_elements)};
  for (std::size_t b = 0; b < s.reaction.size(); ++b)
    for (std::size_t c = 0; c < 3; ++c) sums.insert(sums.end(), {s.reaction[b][c], s.reaction_error[b][c]});
  const auto all = gather_to_root(d.comm, sums);
  t.reaction.assign(s.reaction.size(), {0.0, 0.0, 0.0});
  t.reaction_error = t.previous_reaction = t.reaction;
  for (std::size_t r = 0; r < all.size(); ++r) {
    t.eroded_energy = r == 0 ? all[r][0] : t.eroded_energy + all[r][0];
    t.external_work = r == 0 ? all[r][1] : t.external_work + all[r][1];
    t.eroded_elements += long(all[r][2]);
  }
  for (std::size_t b = 0; b < t.reaction.size() && !all.empty(); ++b)
    for (std::size_t c = 0; c < 3; ++c) {
      double sum = 0.0, error = 0.0;
      for (const auto& f : all) {
        add_compensated(sum, error, f[3 + 6 * b + 2 * c]);
        add_compensated(sum, error, f[3 + 6 * b + 2 * c + 1]);
      }
      t.reaction[b][c] = sum + error;
    }
  w.blocks = gather_block_scalars(d, model);
  gather_contact(contact, d.contact, w.contact, w.keys);
  return w;
}

void load_whole_state(const output::CheckpointReader& file, State& state, Model& model, Decomposition& d,
                      ContactModel& contact) {
  WholeState w;
  State& t = w.state;
  t.contact_force.resize(d.global_nodes);
  t.previous_contact_force.resize(d.global_nodes);
  t.gap.assign(d.global_nodes, 0.0);
  t.previous_gap.assign(d.global_nodes, 0.0);
  const StateLoader loader{file};
  visit_state(loader, t, w.contact_nodes);
  pick_nodal(d, t.displacement, state.displacement, "state/displacement");
  pick_nodal(d, t.velocity, state.velocity, "state/velocity");
  pick_nodal(d, t.load_force, state.load_force, "state/load_force");
  for (int c = 0; c < 3; ++c)
    pick_rows(t.flags[std::size_t(c)], d.global_node, d.global_nodes, state.flags[std::size_t(c)],
              "state/flags");
  for (int c = 0; c < 3; ++c) {
    pick_contact(d, w.contact_nodes, contact.nodes, t.contact_force.component(c),
                 state.contact_force.component(c));
    pick_contact(d, w.contact_nodes, contact.nodes, t.previous_contact_force.component(c),
                 state.previous_contact_force.component(c));
  }
  pick_contact(d, w.contact_nodes, contact.nodes, t.gap, state.gap);
  pick_contact(d, w.contact_nodes, contact.nodes, t.previous_gap, state.previous_gap);
  pick_rows(t.stress, d.global_element, d.global_elements, state.stress, "state/stress");
  pick_rows(t.plastic_strain, d.global_element, d.global_elements, state.plastic_strain,
            "state/plastic_strain");
  pick_rows(t.damage, d.global_element, d.global_elements, state.damage, "state/damage");
  pick_rows(t.status, d.global_element, d.global_elements, state.status, "state/status");
  state.step = t.step, state.time = t.time, state.stress_step = t.stress_step,
  state.force_step = t.force_step;
  state.internal_force_zero = false;
  state.contact_energy = t.contact_energy, state.wall_work = t.wall_work;
  // Rank 0 goes on from the sums over the ranks; the others from nothing.
  const bool root = d.comm.root();
  const std::array<double, 3> zero{0.0, 0.0, 0.0};
  state.eroded_energy = root ? t.eroded_energy : 0.0;
  state.external_work = root ? t.external_work : 0.0;
  state.eroded_elements = root ? t.eroded_elements : 0;
  state.reaction = root ? t.reaction : std::vector<std::array<double, 3>>(t.reaction.size(), zero);
  state.previous_reaction = root ? t.previous_reaction : state.reaction;
  state.reaction_error = root ? t.reaction_error : state.reaction;

  w.blocks.resize(d.block_first_element.size());
  visit_blocks(loader, w.blocks);
  pick_blocks(d, w.blocks, model);

  w.contact.pairs.resize(contact.pairs.size());
  for (std::size_t k = 0; k < contact.pairs.size(); ++k) {
    w.contact.pairs[k].passes.resize(contact.pairs[k].passes.size());
    w.contact.pairs[k].states.resize(contact.pairs[k].passes.size());
  }
  w.contact.walls.resize(contact.walls.size());
  w.keys.resize(d.contact.passes.size());
  visit_contact(loader, w.contact, &w.keys);
  restore_contact(w.contact, w.keys, contact, d.contact,
                  {d.global_node, model.mesh.x_ref, model.mass, state.displacement, state.velocity});
}

std::uint64_t whole_mesh_hash(const Model& model, const Decomposition& d) {
  std::uint64_t sum = 0;
  std::vector<double> item;
  for (const element::ElementBlock& block : model.blocks)
    for (std::uint32_t e = 0; e < block.count; ++e) {
      item.assign(1, double(global_element_id(d, block.first_element + e)));
      for (int k = 0; k < block.nodes_per_element; ++k) {
        const std::uint32_t n = block.connectivity[std::size_t(block.nodes_per_element) * e + std::size_t(k)];
        item.insert(item.end(), {double(global_node_id(d, n)), model.mesh.x_ref.x[n], model.mesh.x_ref.y[n],
                                 model.mesh.x_ref.z[n]});
      }
      // Mixed (splitmix64's finaliser) so that a sum of element hashes is no weaker than one.
      std::uint64_t h = output::hash_bytes(item.data(), item.size() * sizeof(double));
      h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
      h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
      sum += h ^ (h >> 31);
    }
  if (d.comm.distributed())
    mpi::check(MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_UINT64_T, MPI_SUM, d.comm.comm),
               "MPI_Allreduce of the mesh's hash");
  return sum;
}

}  // namespace exdyn::solver
