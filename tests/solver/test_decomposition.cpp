// The domain decomposition (ranks/decomposition.hpp, docs/parallel.md), for virtual
// ranks in one process: localize only reads the communicator's rank and size, so every
// rank's part of a model can be built and checked here. The exchanges themselves run
// through mpirun (scripts/test_mpi.py: every field bit for bit as one process).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <tuple>

#include "common/errors.hpp"
#include "element/element_block.hpp"
#include "input/deck_reader.hpp"
#include "mesh/mesh.hpp"
#include "model/contact_setup.hpp"
#include "model/model.hpp"
#include "ranks/decomposition.hpp"
#include "ranks/distributed_contact.hpp"
#include "ranks/load_balance.hpp"
#include "ranks/rank_setup.hpp"

namespace {

using namespace exdyn;
using solver::Decomposition;

input::Deck deck_of(const std::string& file) {
  return input::read_deck(std::string(EXDYN_SOURCE_DIR) + "/input/" + file, {});
}

std::vector<solver::LocalRun> parts_of(const solver::Model& model, const input::Deck& deck, int ranks) {
  const NodalVectors v = solver::initial_velocity(deck, model);
  const std::vector<std::uint32_t> contact = solver::contact_face_nodes(deck, model.mesh);
  std::vector<solver::LocalRun> runs;
  for (int r = 0; r < ranks; ++r) {
    mpi::Communicator comm;
    comm.rank = r;
    comm.size = ranks;
    runs.push_back(solver::localize(model, contact, v, comm));
  }
  return runs;
}

TEST(PartitionChunks, EveryRankGetsChunksInProportionAndEveryRankComputesTheSame) {
  const input::Deck deck = deck_of("plate_impact.yaml");
  const solver::Model model = solver::build_model(deck);
  std::size_t chunks = 0;
  for (const auto& block : model.blocks) chunks += block.chunk_begin.size() - 1;
  for (int ranks = 1; ranks <= 7; ++ranks) {
    const std::vector<int> rank = solver::partition_chunks(model, ranks);
    ASSERT_EQ(rank.size(), chunks);
    EXPECT_EQ(rank, solver::partition_chunks(model, ranks));
    std::vector<double> elements(std::size_t(ranks), 0.0);
    std::size_t unit = 0;
    for (const auto& block : model.blocks)
      for (std::size_t c = 0; c + 1 < block.chunk_begin.size(); ++c, ++unit) {
        ASSERT_GE(rank[unit], 0);
        ASSERT_LT(rank[unit], ranks);
        elements[std::size_t(rank[unit])] += block.chunk_begin[c + 1] - block.chunk_begin[c];
      }
    const double ideal = double(model.mesh.element_count()) / ranks;
    for (const double e : elements) {
      EXPECT_GT(e, 0.0) << ranks << " ranks";
      // Each cut is placed to half a chunk of its share; log2(ranks) cuts above a rank.
      EXPECT_LE(std::abs(e - ideal), 2.0 * element::element_chunk) << ranks << " ranks";
    }
  }
}

// Weighed by costs (load_balance.hpp), a costly chunk takes a rank's share alone: the
// plates' first chunk costing as much as all the others, 2 ranks split it from them.
TEST(PartitionChunks, CostsWeighTheChunks) {
  const input::Deck deck = deck_of("plate_impact.yaml");
  const solver::Model model = solver::build_model(deck);
  std::size_t chunks = 0;
  for (const auto& block : model.blocks) chunks += block.chunk_begin.size() - 1;
  std::vector<double> costs(chunks, 1.0);
  costs[0] = double(chunks - 1);
  for (const solver::Partitioning partitioning :
       {solver::Partitioning::bisection, solver::Partitioning::metis}) {
    const std::vector<int> rank = solver::partition_chunks(model, 2, partitioning, costs);
    EXPECT_EQ(std::count(rank.begin(), rank.end(), rank[0]), 1);
  }
}

// The measured costs on one process: every chunk costs its elements' time and more
// where it holds slave points.
TEST(ChunkCosts, ElementsAndSlavePoints) {
  const input::Deck deck = deck_of("plate_impact.yaml");
  const solver::Model model = solver::build_model(deck);
  const double dt = solver::critical_time_step(model);
  const solver::ContactModel contact = solver::build_contact(deck, model, 0.125 * dt, dt);
  const std::vector<double> costs = solver::chunk_costs(model, contact, solver::initial_velocity(deck, model),
                                                        0.125 * dt, mpi::Communicator{});
  std::size_t chunks = 0;
  for (const auto& block : model.blocks) chunks += block.chunk_begin.size() - 1;
  ASSERT_EQ(costs.size(), chunks);
  for (const double c : costs) EXPECT_GT(c, 0.0);
  // The chunks at the contact face (plate_a.xmax, plate_b.xmin) hold its slave points.
  EXPECT_GT(*std::max_element(costs.begin(), costs.end()), *std::min_element(costs.begin(), costs.end()));
}

TEST(PartitionChunks, MoreRanksThanChunksIsBadInput) {
  const input::Deck deck = deck_of("contact_patch.yaml");  // 2 parts of one chunk each
  const solver::Model model = solver::build_model(deck);
  EXPECT_NO_THROW(solver::partition_chunks(model, 2));
  try {
    solver::partition_chunks(model, 3);
    FAIL() << "3 ranks for 2 chunks";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("run on at most 2 ranks"), std::string::npos) << error.what();
  }
}

// Every element on one rank; every node owned by one rank, held by every rank with a
// chunk on it; the masses and coordinates are the global ones, bit for bit.
TEST(Localize, ElementsOnceNodesOwnedOnceMassesTheGlobalBits) {
  const input::Deck deck = deck_of("contact_patch_hex20.yaml");
  const solver::Model model = solver::build_model(deck);
  const std::vector<std::uint32_t> contact = solver::contact_face_nodes(deck, model.mesh);
  for (int ranks : {2, 3, 5}) {
    const std::vector<solver::LocalRun> runs = parts_of(model, deck, ranks);
    std::vector<int> element_seen(model.mesh.element_count(), 0), node_owned(model.mesh.node_count(), 0);
    for (const solver::LocalRun& run : runs) {
      const Decomposition& d = run.decomposition;
      EXPECT_TRUE(std::is_sorted(d.global_node.begin(), d.global_node.end()));
      for (const std::uint32_t e : d.global_element) ++element_seen[e];
      for (std::size_t i = 0; i < d.global_node.size(); ++i) {
        const std::uint32_t g = d.global_node[i];
        node_owned[g] += d.owned[i];
        EXPECT_EQ(run.model.mass[i], model.mass[g]);
        EXPECT_EQ(run.model.mesh.x_ref.z[i], model.mesh.x_ref.z[g]);
        EXPECT_EQ(run.model.counted_mass[i], d.owned[i] ? model.mass[g] : 0.0);
      }
      // Only the nodes of its chunks: the contact is distributed (distributed_contact.hpp).
      std::set<std::uint32_t> chunk_nodes;
      for (const auto& block : run.model.blocks)
        for (std::size_t k = 0; k < std::size_t(block.nodes_per_element) * block.count; ++k)
          chunk_nodes.insert(d.global_node[block.connectivity[k]]);
      EXPECT_EQ(chunk_nodes.size(), d.global_node.size());
      // Each contact node's holders: the ranks holding it.
      for (std::size_t k = 0; k < contact.size(); ++k) {
        const bool held = std::binary_search(d.global_node.begin(), d.global_node.end(), contact[k]);
        const auto& h = run.contact_holders[k];
        EXPECT_EQ(held, std::binary_search(h.begin(), h.end(), int(&run - runs.data())));
      }
      std::size_t elements = 0;
      for (const auto& block : run.model.blocks) elements += block.count;
      EXPECT_EQ(elements, d.global_element.size());
    }
    EXPECT_TRUE(std::all_of(element_seen.begin(), element_seen.end(), [](int n) { return n == 1; }));
    EXPECT_TRUE(std::all_of(node_owned.begin(), node_owned.end(), [](int n) { return n == 1; }));
  }
}

// Every message sent is received: the same nodes (global ids, in the same order), from
// the sender's step k to the receiver's step k + 1 (the tag names the block and step).
TEST(Localize, EverySentRunningSumIsReceivedAtTheNextColourStep) {
  const input::Deck deck = deck_of("hertz_ball.yaml");
  const solver::Model model = solver::build_model(deck);
  for (int ranks : {2, 3, 4}) {
    const std::vector<solver::LocalRun> runs = parts_of(model, deck, ranks);
    // (from, to, tag) -> global nodes
    std::map<std::tuple<int, int, int>, std::vector<std::uint32_t>> sent, received;
    std::size_t messages = 0;
    for (int r = 0; r < ranks; ++r) {
      const Decomposition& d = runs[std::size_t(r)].decomposition;
      for (const auto& steps : d.steps)
        for (std::size_t k = 0; k < steps.size(); ++k) {
          for (const auto& m : steps[k].send) {
            ASSERT_LT(k + 1, steps.size());
            auto& nodes = sent[{r, m.rank, steps[k + 1].tag}];
            for (const std::uint32_t i : m.nodes) nodes.push_back(d.global_node[i]);
            ++messages;
          }
          for (const auto& m : steps[k].receive) {
            auto& nodes = received[{m.rank, r, steps[k].tag}];
            for (const std::uint32_t i : m.nodes) nodes.push_back(d.global_node[i]);
          }
        }
    }
    EXPECT_GT(messages, 0u) << ranks << " ranks share nodes";
    EXPECT_EQ(sent, received) << ranks << " ranks";
  }
}

// The contact's shares (distributed_contact.hpp): every slave point and every master
// segment of every pass belongs to exactly one rank, which holds all its nodes; a rank
// holds a part of the surface, not all of it.
TEST(DistributeContact, EveryPointAndSegmentBelongsToOneRankThatHoldsItsNodes) {
  for (const char* file :
       {"plate_impact.yaml", "contact_patch_hex20.yaml", "hertz_ball.yaml", "tube_impact.yaml"}) {
    const input::Deck deck = deck_of(file);
    const solver::Model model = solver::build_model(deck);
    const std::vector<std::uint32_t> contact = solver::contact_face_nodes(deck, model.mesh);
    const double dt = 1e-8;  // s: any step, the same for both
    const solver::ContactModel whole = solver::build_contact(deck, model, 0.5 * dt, dt);
    std::size_t chunks = 0;
    for (const auto& block : model.blocks) chunks += block.chunk_begin.size() - 1;
    for (int ranks : {2, 3, 5}) {
      if (std::size_t(ranks) > chunks) continue;
      const std::vector<solver::LocalRun> runs = parts_of(model, deck, ranks);
      // Per pass, per whole-pass item (by its key: a slave node's global id, a
      // quadrature point's or a segment's index): the ranks that own it.
      std::vector<std::map<std::uint64_t, int>> points;
      std::vector<std::map<std::uint32_t, int>> segments;
      auto add_pass = [&](const contact::ContactSurfaces& pass) {
        auto& keys = points.emplace_back();
        for (std::size_t p = 0; p < pass.point_count(); ++p)
          keys[pass.quadrature ? std::uint64_t(p) : pass.slave_nodes[p]] = 0;
        auto& ids = segments.emplace_back();
        for (std::size_t s = 0; s < pass.segments.size(); ++s) ids[std::uint32_t(s)] = 0;
      };
      for (const auto& pair : whole.pairs)
        for (const auto& pass : pair.passes) add_pass(pass);
      for (const auto& wall : whole.walls) add_pass(wall.surfaces);
      for (int r = 0; r < ranks; ++r) {
        const solver::LocalRun& run = runs[std::size_t(r)];
        solver::ContactModel mine = whole;
        mpi::Communicator comm;
        comm.rank = r;
        comm.size = ranks;
        const solver::DistributedContact dc = solver::distribute_contact(
            mine, comm, run.decomposition.global_node, run.model, contact, run.contact_holders);
        ASSERT_EQ(dc.passes.size(), points.size());
        for (std::size_t k = 0; k < dc.passes.size(); ++k) {
          const solver::PassShare& share = dc.passes[k];
          for (const std::uint64_t p : share.point_keys) ++points[k].at(p);
          for (const std::uint32_t s : share.segment_ids) ++segments[k].at(s);
          for (const std::uint32_t g : share.store.global)  // the own points' and segments' nodes
            EXPECT_TRUE(std::binary_search(run.decomposition.global_node.begin(),
                                           run.decomposition.global_node.end(), g))
                << file;
        }
      }
      for (const auto& pass : points)
        for (const auto& [key, n] : pass) ASSERT_EQ(n, 1) << file << ", " << ranks << " ranks";
      for (const auto& pass : segments)
        for (const auto& [id, n] : pass) ASSERT_EQ(n, 1) << file << ", " << ranks << " ranks";
    }
  }
}

std::mt19937_64 rng{14};

NodalVectors random_displacement(std::size_t n) {
  std::uniform_real_distribution<double> value(-1e-6, 1e-6);
  NodalVectors u(n);
  for (int c = 0; c < 3; ++c)
    for (double& x : u.component(c)) x = value(rng);
  return u;
}

// A slice of a block's chunks adds, at every node that only its chunks touch, the same
// bits as the whole block; a slice of all of them, the same bits everywhere.
TEST(SliceBlock, TheSameBitsAtTheNodesOfItsChunksAlone) {
  for (const char* file : {"plate_impact.yaml", "hertz_ball.yaml", "cylinders.yaml"}) {
    const input::Deck deck = deck_of(file);
    const solver::Model model = solver::build_model(deck);
    const NodalVectors u = random_displacement(model.mesh.node_count());
    for (const element::ElementBlock& block : model.blocks) {
      NodalVectors whole(model.mesh.node_count());
      element::add_internal_forces(block, u, whole, nullptr);
      const std::size_t chunks = block.chunk_begin.size() - 1;
      std::vector<std::uint32_t> all(chunks), odd;
      for (std::uint32_t c = 0; c < chunks; ++c) {
        all[c] = c;
        if (c % 2 == 1 || chunks == 1) odd.push_back(c);
      }
      for (const auto* subset : {&all, &odd}) {
        std::vector<std::uint32_t> connectivity;
        std::vector<int> touched(model.mesh.node_count(), 0);  // by chunks of the slice (1) or others (2)
        const auto n = std::size_t(block.nodes_per_element);
        for (std::uint32_t c = 0; c < chunks; ++c) {
          const bool in = std::binary_search(subset->begin(), subset->end(), c);
          for (std::size_t k = n * block.chunk_begin[c]; k < n * block.chunk_begin[c + 1]; ++k) {
            touched[block.connectivity[k]] |= in ? 1 : 2;
            if (in) connectivity.push_back(block.connectivity[k]);
          }
        }
        const element::ElementBlock slice = element::slice_block(block, *subset, connectivity.data(), 0);
        NodalVectors part(model.mesh.node_count());
        element::add_internal_forces(slice, u, part, nullptr);
        std::size_t compared = 0;
        for (std::size_t i = 0; i < touched.size(); ++i) {
          if (touched[i] != 1) continue;
          ++compared;
          for (int c = 0; c < 3; ++c)
            ASSERT_EQ(part.component(c)[i], whole.component(c)[i]) << file << " node " << i;
        }
        EXPECT_GT(compared, 0u) << file;
      }
    }
  }
}

// Setting up rank by rank (ranks/rank_setup.hpp) walks the parts chunk by chunk in
// place of the whole model: the colours, the partition, the masses and the contact
// surfaces must be the whole model's, bit for bit. Decks: the plates (two parts), the
// sliding block (two parts of other sizes, friction, gravity), the wall deck, the
// plates graded and long along x (a chunk spans rows: the colours' node window wraps),
// the plates of 20-node elements, graded, and the contact patch of 20-node elements
// on 8-node ones (a mixed mesh); cylinders and balls by numbers: the Hertz ball (a
// mapped ball of 20-node elements cut twice, on a graded box), the Taylor rods and the
// mirror cylinders (mapped cylinders of 8- and 20-node elements), the rail (20-node);
// parts made whole: the plates read from a Gmsh file, and the plates perturbed.
std::vector<input::Deck> setup_decks() {
  std::vector<input::Deck> decks{deck_of("plate_impact.yaml"),        deck_of("sliding_block.yaml"),
                                 deck_of("oblique_impact.yaml"),      deck_of("plate_impact.yaml"),
                                 deck_of("plate_impact_hex20.yaml"),  deck_of("plate_impact_hex20.yaml"),
                                 deck_of("contact_patch_hex20.yaml"), deck_of("hertz_ball.yaml"),
                                 deck_of("taylor_rods.yaml"),         deck_of("cylinders.yaml"),
                                 deck_of("block_on_rail.yaml"),       deck_of("plate_impact_gmsh.yaml"),
                                 deck_of("plate_impact.yaml"),        deck_of("c_slot.yaml")};
  decks[1].parts[0].elements = {16, 16, 2};
  decks[1].parts[1].elements = {32, 28, 2};
  decks[2].parts[0].elements = {80, 1, 40};
  input::Deck& graded = decks[3];
  graded.parts[0].elements = {700, 1, 30};
  graded.parts[0].grading = {3.0, 1.0, 0.5};
  graded.parts[1].elements = {650, 2, 3};
  input::Deck& graded20 = decks[5];
  graded20.parts[0].elements = {90, 3, 20};
  graded20.parts[0].grading = {0.3, 2.0, 1.5};
  graded20.parts[1].elements = {40, 1, 33};
  graded20.parts[1].grading = {4.0, 1.0, 1.0};
  decks[6].parts[1].formulation = input::Formulation::hex8;
  decks[7].parts[0].elements = {6, 2};  // smaller: a 20-node block's step is an eigenvalue each
  decks[7].parts[1].elements = {6, 6, 4};
  decks[9].parts[0].elements = {16, 4, 2};  // the cylinders of 20-node elements too
  decks[9].parts[1].elements = {12, 3, 2};
  input::Deck& perturbed = decks[12];
  perturbed.parts[0].elements = {40, 1, 30};
  perturbed.parts[0].perturbation_fraction = 0.2;
  perturbed.parts[1].perturbation_fraction = 0.1;
  perturbed.parts[1].perturbation_seed = 7;
  // A single surface on a Gmsh part's whole boundary, by its sides, with quadrature points
  // capped per face (ContactSurfaces::face_kappa).
  input::Deck& slot = decks[13];
  slot.parts[0].mesh.path = std::string(EXDYN_SOURCE_DIR) + "/input/meshes/c_slot_hex20.msh";
  slot.parts[0].formulation = input::Formulation::hex20;
  return decks;
}

TEST(RankSetup, ColoursAndPartitionAreTheWholeModels) {
  for (const input::Deck& deck : setup_decks()) {
    const solver::Model model = solver::build_model(deck);
    std::vector<int> colour;
    for (const auto& block : model.blocks) {
      std::vector<int> of(block.chunk_begin.size() - 1, -1);
      for (std::size_t k = 0; k < block.colours.size(); ++k)
        for (const std::uint32_t c : block.colours[k]) of[c] = int(k);
      colour.insert(colour.end(), of.begin(), of.end());
    }
    for (const int ranks : {1, 2, 3, 5})
      for (const auto partitioning : {solver::Partitioning::bisection, solver::Partitioning::metis}) {
        if (std::size_t(ranks) > colour.size()) continue;
        // METIS may leave a rank without a chunk: then both refuse, with the same words.
        std::string whole_error, lattice_error;
        std::vector<int> whole_rank;
        solver::SetupChunks chunks;
        try {
          whole_rank = solver::partition_chunks(model, ranks, partitioning);
        } catch (const InputError& e) {
          whole_error = e.what();
        }
        try {
          chunks = solver::setup_chunks(deck, ranks, partitioning);
        } catch (const InputError& e) {
          lattice_error = e.what();
        }
        EXPECT_EQ(lattice_error, whole_error) << deck.name << ", " << ranks << " ranks";
        if (!whole_error.empty()) continue;
        EXPECT_EQ(chunks.colour, colour) << deck.name;
        EXPECT_EQ(chunks.rank, whole_rank) << deck.name << ", " << ranks << " ranks, " << int(partitioning);
      }
  }
}

TEST(RankSetup, MassesAreTheWholeModelsBitForBit) {
  for (const input::Deck& deck : setup_decks()) {
    const solver::Model model = solver::build_model(deck);
    std::vector<std::uint32_t> every(model.mesh.node_count()), some;
    std::iota(every.begin(), every.end(), 0u);
    for (std::uint32_t g = 0; g < every.size(); g += 7)
      some.push_back(g);  // a sparse set: halos of their own
    EXPECT_EQ(solver::setup_masses(deck, every), model.mass) << deck.name;
    const std::vector<double> masses = solver::setup_masses(deck, some);
    for (std::size_t k = 0; k < some.size(); ++k) ASSERT_EQ(masses[k], model.mass[some[k]]) << deck.name;
  }
}

// The contact built on the faces alone and renumbered: the whole model's surfaces.
TEST(RankSetup, ContactFromTheFacesIsTheWholeModels) {
  for (const input::Deck& deck : setup_decks()) {
    const solver::Model model = solver::build_model(deck);
    const double dt = solver::critical_time_step(model);
    const solver::ContactModel whole = solver::build_contact(deck, model, 0.1 * dt, dt);
    auto [nodes, faces] = solver::contact_faces_model(deck);
    EXPECT_EQ(nodes, solver::contact_face_nodes(deck, model.mesh)) << deck.name;
    solver::ContactModel built = solver::build_contact(deck, faces, 0.1 * dt, dt);
    solver::globalize_contact(built, nodes);
    EXPECT_EQ(built.nodes, whole.nodes) << deck.name;
    auto same = [&](const contact::ContactSurfaces& a, const contact::ContactSurfaces& b) {
      auto ids = [](const std::vector<contact::SegmentNodes>& list) {
        std::vector<std::array<std::uint32_t, 8>> out;
        for (const auto& s : list) out.push_back(s.nodes);
        return out;
      };
      EXPECT_EQ(a.slave_nodes, b.slave_nodes) << deck.name;
      EXPECT_EQ(a.moving_nodes, b.moving_nodes) << deck.name;
      EXPECT_EQ(ids(a.slave_segments), ids(b.slave_segments)) << deck.name;
      EXPECT_EQ(ids(a.segments), ids(b.segments)) << deck.name;
      EXPECT_EQ(a.stiffness, b.stiffness) << deck.name;
      EXPECT_EQ(a.normal_length, b.normal_length) << deck.name;
      EXPECT_EQ(a.face_kappa, b.face_kappa) << deck.name;
      EXPECT_EQ(a.face_count, b.face_count) << deck.name;
      EXPECT_EQ(a.segment_face, b.segment_face) << deck.name;
      ASSERT_EQ(a.edges.size(), b.edges.size());
      for (std::size_t k = 0; k < a.edges.size(); ++k) {
        EXPECT_EQ(a.edges[k].continued, b.edges[k].continued) << deck.name;
        EXPECT_EQ(a.edges[k].mirror_axis, b.edges[k].mirror_axis) << deck.name;
      }
    };
    ASSERT_EQ(built.pairs.size(), whole.pairs.size());
    for (std::size_t p = 0; p < whole.pairs.size(); ++p) {
      ASSERT_EQ(built.pairs[p].passes.size(), whole.pairs[p].passes.size());
      for (std::size_t k = 0; k < whole.pairs[p].passes.size(); ++k)
        same(built.pairs[p].passes[k], whole.pairs[p].passes[k]);
      EXPECT_EQ(built.pairs[p].settings.search_distance, whole.pairs[p].settings.search_distance);
    }
    ASSERT_EQ(built.walls.size(), whole.walls.size());
    for (std::size_t w = 0; w < whole.walls.size(); ++w)
      same(built.walls[w].surfaces, whole.walls[w].surfaces);
  }
}

// Each rank's contact built on the faces near it alone (RankSetup::surfaces, ContactScope),
// its largest figures over the ranks, is its share of the whole model's, bit for bit:
// the same slave points with the same keys, stiffnesses and normal lengths, the same
// segments with the same ids and edges. The ranks' largest figures are taken in two
// rounds: each rank's asked figures, then the largest of each over the ranks.
TEST(RankSetup, ContactNearEachRankIsItsShareOfTheWholeModels) {
  std::vector<input::Deck> decks = setup_decks();
  for (const char* file : {"contact_patch_hex20.yaml", "tube_impact.yaml"}) decks.push_back(deck_of(file));
  for (const input::Deck& deck : decks) {
    if (deck.contact.empty() && deck.rigid_walls.empty()) continue;
    const solver::Model model = solver::build_model(deck);
    const std::vector<std::uint32_t> contact = solver::contact_face_nodes(deck, model.mesh);
    const double dt = solver::critical_time_step(model);
    const solver::ContactModel whole = solver::build_contact(deck, model, 0.1 * dt, dt);
    std::size_t chunks = 0;
    for (const auto& block : model.blocks) chunks += block.chunk_begin.size() - 1;
    for (int ranks : {2, 3}) {
      if (std::size_t(ranks) > chunks) continue;
      const std::vector<solver::LocalRun> runs = parts_of(model, deck, ranks);
      std::vector<solver::RankSetup> near;
      std::vector<std::vector<double>> asked(runs.size());
      for (std::size_t r = 0; r < runs.size(); ++r) {
        near.push_back(solver::contact_faces_near(deck, runs[r].decomposition.global_node, runs[r].model));
        solver::ContactScope scope{&near.back().surface_held, [&](double figure) {
                                     asked[r].push_back(figure);
                                     return figure;
                                   }};
        (void)solver::build_contact(deck, near.back().surfaces, 0.1 * dt, dt, scope);
      }
      std::vector<double> largest(asked[0].size(), 0.0);
      for (const auto& figures : asked) {
        ASSERT_EQ(figures.size(), largest.size()) << deck.name;  // every rank asks as often
        for (std::size_t k = 0; k < figures.size(); ++k) largest[k] = std::max(largest[k], figures[k]);
      }
      for (int r = 0; r < ranks; ++r) {
        const solver::LocalRun& run = runs[std::size_t(r)];
        std::size_t asked_at = 0;
        solver::ContactScope scope{&near[std::size_t(r)].surface_held,
                                   [&](double) { return largest.at(asked_at++); }};
        solver::ContactModel built =
            solver::build_contact(deck, near[std::size_t(r)].surfaces, 0.1 * dt, dt, scope);
        solver::globalize_contact(built, near[std::size_t(r)].surface_nodes);
        solver::ContactModel share_of_whole = whole;
        mpi::Communicator comm;
        comm.rank = r;
        comm.size = ranks;
        const solver::DistributedContact mine = solver::distribute_contact(
            built, comm, run.decomposition.global_node, run.model, contact, run.contact_holders);
        const solver::DistributedContact expected = solver::distribute_contact(
            share_of_whole, comm, run.decomposition.global_node, run.model, contact, run.contact_holders);
        ASSERT_EQ(mine.passes.size(), expected.passes.size());
        for (std::size_t k = 0; k < mine.passes.size(); ++k) {
          const solver::PassShare& a = mine.passes[k];
          const solver::PassShare& b = expected.passes[k];
          const std::string where =
              deck.name + ", rank " + std::to_string(r) + " of " + std::to_string(ranks);
          EXPECT_EQ(a.point_keys, b.point_keys) << where;
          EXPECT_EQ(a.segment_ids, b.segment_ids) << where;
          EXPECT_EQ(a.own.slave_nodes, b.own.slave_nodes) << where;
          EXPECT_EQ(a.own.moving_nodes, b.own.moving_nodes) << where;
          EXPECT_EQ(a.own.stiffness, b.own.stiffness) << where;
          EXPECT_EQ(a.own.normal_length, b.own.normal_length) << where;
          EXPECT_EQ(a.store.global, b.store.global) << where;
          EXPECT_EQ(a.store.mass, b.store.mass) << where;
          auto ids = [](const std::vector<contact::SegmentNodes>& list) {
            std::vector<std::array<std::uint32_t, 8>> out;
            for (const auto& s : list) out.push_back(s.nodes);
            return out;
          };
          EXPECT_EQ(ids(a.own.slave_segments), ids(b.own.slave_segments)) << where;
          EXPECT_EQ(ids(a.own.segments), ids(b.own.segments)) << where;
          ASSERT_EQ(a.own.quadrature_points.size(), b.own.quadrature_points.size()) << where;
          for (std::size_t p = 0; p < a.own.quadrature_points.size(); ++p) {
            EXPECT_EQ(a.own.quadrature_points[p].segment, b.own.quadrature_points[p].segment) << where;
            EXPECT_EQ(a.own.quadrature_points[p].weight, b.own.quadrature_points[p].weight) << where;
          }
          ASSERT_EQ(a.own.edges.size(), b.own.edges.size()) << where;
          for (std::size_t e = 0; e < a.own.edges.size(); ++e) {
            EXPECT_EQ(a.own.edges[e].continued, b.own.edges[e].continued) << where;
            EXPECT_EQ(a.own.edges[e].mirror_axis, b.own.edges[e].mirror_axis) << where;
          }
        }
      }
    }
  }
}

// A perturbed part that inverts an element: the setup refuses it as build_mesh does,
// in the same words.
TEST(RankSetup, AnInvertedElementIsRefusedAsBuildMeshRefusesIt) {
  input::Deck deck = deck_of("plate_impact.yaml");
  deck.parts[1].perturbation_fraction = 0.45;
  std::string whole, parts;
  try {
    mesh::build_mesh(deck);
  } catch (const InputError& e) {
    whole = e.what();
  }
  try {
    solver::setup_chunks(deck, 2, solver::Partitioning::bisection);
  } catch (const InputError& e) {
    parts = e.what();
  }
  EXPECT_NE(whole.find("inverts element"), std::string::npos) << whole;
  EXPECT_EQ(parts, whole);
}

}  // namespace
