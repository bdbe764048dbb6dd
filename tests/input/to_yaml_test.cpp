// to_yaml: the resolved deck with every default; reading it back gives the same Deck.
#include <gtest/gtest.h>

#include "deck_files.hpp"
#include "input/deck_reader.hpp"

namespace exdyn::input {
namespace {

using testing::read_text;
using testing::test_deck_path;

Deck round_trip(const Deck& deck) { return parse_deck(to_yaml(deck), deck.source_file); }

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ToYaml, SpecExampleRoundTrips) {
  const Deck deck = read_deck(test_deck_path("decks/plate_impact.yaml"));
  EXPECT_EQ(round_trip(deck), deck) << to_yaml(deck);
}

TEST(ToYaml, MinimalDeckRoundTripsWithEveryDefaultWritten) {
  const Deck deck = read_deck(test_deck_path("decks/minimal.yaml"));
  EXPECT_EQ(round_trip(deck), deck);
  const std::string text = to_yaml(deck);
  for (const char* line :
       {"formulation: hex8\n", "hourglass: {model: assumed_strain, coefficient: 1}\n",
        "initial_velocity: [0, 0, 0]\n", "perturbation: {fraction: 0, seed: 1}\n",
        "boundary_conditions: []\n", "contact: []\n", "courant: 0.9\n", "directory: results\n",
        "every: 100\n",
        "fields: [displacement, velocity, acceleration, stress, von_mises, contact_force, gap, "
        "plastic_strain]\n",
        "kinematics: auto\n", "f_bar: true\n", "min_dt_ratio: 0.001\n", "history_every: 1\n",
        "background: true\n"})
    EXPECT_TRUE(contains(text, line)) << line << " missing from\n" << text;
}

TEST(ToYaml, ContactPairIsWrittenWithAllItsKeys) {
  const std::string text = to_yaml(read_deck(test_deck_path("decks/plate_impact.yaml")));
  for (const char* line :
       {"slave: [plate_a.xmax]\n", "master: [plate_b.xmin]\n", "two_pass: true\n",
        "penalty: {scale: 1, damping: 0.2}\n", "search: {cell_size: auto}\n",
        "local_search: {method: bfgs, tolerance: 1e-10, max_iterations: 100, initial_guess: lsp, "
        "fallback: robust}\n",
        "- {faces: [plate_a.ymin, plate_a.ymax, plate_b.ymin, plate_b.ymax], fix: [y]}\n",
        "end_time: 2.32551069659978e-07\n", "courant: 0.125\n"})
    EXPECT_TRUE(contains(text, line)) << line << " missing from\n" << text;
}

TEST(ToYaml, DeckWithEveryOptionChangedRoundTrips) {
  Deck deck = read_deck(test_deck_path("decks/plate_impact.yaml"));
  deck.name = "variant-2";
  deck.materials[0].name = "steel 4340";  // needs quotes
  deck.materials[0].density = 1.0 / 3.0;  // needs 17 digits
  for (PartOptions& part : deck.parts) part.material = "steel 4340";
  deck.parts[1].formulation = Formulation::hex8r;
  deck.parts[1].hourglass_coefficient = 0.1;
  deck.parts[0].name = "true";  // would read as a boolean unquoted
  deck.parts[0].perturbation_fraction = 0.3;
  deck.parts[0].perturbation_seed = 12345;
  deck.parts[1].perturbation_fraction = 0.499;  // seed left at its default
  deck.contact[0].two_pass = false;
  deck.contact[0].penalty.stiffness = 3.0e12;
  deck.contact[0].penalty.damping = 0.0;
  deck.contact[0].search.cell_size = 1.0e-4;
  deck.contact[0].local_search = {contact::SearchMethod::hybrid, 1e-13, 12, contact::InitialGuess::previous};
  deck.time.courant = TimeOptions{}.courant;  // a deck read with dt keeps the default courant
  deck.time.dt = 5.1909e-10;
  deck.output.directory = "out/run: \"a\"";
  deck.output.fields = {OutputField::gap};
  deck.output.every = 7;
  deck.output.history_every = 3;
  deck.output.background = false;
  const std::string text = to_yaml(deck);
  const Deck read_back = round_trip(deck);
  EXPECT_EQ(read_back.materials, deck.materials);
  EXPECT_EQ(read_back.parts, deck.parts);
  EXPECT_EQ(read_back.boundary_conditions, deck.boundary_conditions);
  EXPECT_EQ(read_back.contact, deck.contact);
  EXPECT_EQ(read_back.time, deck.time);
  EXPECT_EQ(read_back.output, deck.output);
  EXPECT_EQ(read_back, deck) << text;
  EXPECT_TRUE(contains(text, "dt: 5.1909e-10\n")) << text;
  EXPECT_FALSE(contains(text, "courant")) << text;
  EXPECT_TRUE(contains(text, "penalty: {stiffness: 3e+12, damping: 0}\n")) << text;
  EXPECT_TRUE(contains(text, "perturbation: {fraction: 0.3, seed: 12345}\n")) << text;
  EXPECT_TRUE(contains(text, "perturbation: {fraction: 0.499, seed: 1}\n")) << text;
}

// The plastic models, the kinematics, the spin and min_dt_ratio round-trip.
TEST(ToYaml, MaterialLawsKinematicsAndSpinRoundTrip) {
  Deck deck = read_deck(test_deck_path("decks/plate_impact.yaml"));
  MaterialOptions table = deck.materials[0], johnson_cook = deck.materials[0], linear = deck.materials[0];
  table.name = "table";
  table.model = MaterialModel::elastic_plastic;
  table.hardening = {{0.0, 4e8}, {0.1, 4.5e8}, {1.0 / 3.0, 5e8}};
  table.yield_stress = 4e8;
  linear.name = "linear";
  linear.model = MaterialModel::elastic_plastic;
  linear.yield_stress = 3.5e8;
  linear.hardening_modulus = 1.25e9;
  johnson_cook.name = "jc";
  johnson_cook.model = MaterialModel::johnson_cook;
  johnson_cook.jc_a = 9e7, johnson_cook.jc_b = 2.92e8, johnson_cook.jc_n = 0.31, johnson_cook.jc_c = 0.025;
  johnson_cook.reference_strain_rate = 1e-3;
  deck.materials = {table, linear, johnson_cook};
  deck.parts[0].material = "table", deck.parts[0].material_index = 0;
  deck.parts[1].material = "jc", deck.parts[1].material_index = 2;
  deck.parts[0].kinematics = Kinematics::finite;
  deck.parts[0].f_bar = false;
  deck.parts[1].kinematics = Kinematics::small;
  deck.parts[1].initial_angular_velocity = std::array<Vec3, 2>{Vec3{0.1, 0.2, 0.3}, Vec3{0, 0, 2000}};
  deck.time.min_dt_ratio = 0.05;
  EXPECT_EQ(round_trip(deck), deck) << to_yaml(deck);
}

TEST(ToYaml, PerturbationIsReadAndRoundTrips) {
  const std::string text = read_text(test_deck_path("decks/minimal.yaml"));
  const Deck plain = parse_deck(text, "inline.yaml");
  EXPECT_EQ(plain.parts[0].perturbation_fraction, 0.0);  // absent: the regular grid
  EXPECT_EQ(plain.parts[0].perturbation_seed, 1u);
  // In the file, block style, seed defaulted.
  std::string with_key = text;
  with_key.replace(with_key.find("    material: steel\n"), 20,
                   "    material: steel\n    perturbation:\n      fraction: 0.2\n");
  const Deck in_file = parse_deck(with_key, "inline.yaml");
  EXPECT_EQ(in_file.parts[0].perturbation_fraction, 0.2);
  EXPECT_EQ(in_file.parts[0].perturbation_seed, 1u);
  EXPECT_EQ(round_trip(in_file), in_file);
  // From --set, as the stability study gives it; an empty map keeps the defaults.
  const Deck overridden =
      parse_deck(text, "inline.yaml", {parse_override("parts[0].perturbation={fraction: 0.3, seed: 7}")});
  EXPECT_EQ(overridden.parts[0].perturbation_fraction, 0.3);
  EXPECT_EQ(overridden.parts[0].perturbation_seed, 7u);
  EXPECT_TRUE(contains(to_yaml(overridden), "    perturbation: {fraction: 0.3, seed: 7}\n"))
      << to_yaml(overridden);
  EXPECT_EQ(round_trip(overridden), overridden);
  EXPECT_EQ(parse_deck(text, "inline.yaml", {parse_override("parts[0].perturbation={}")}), plain);
  const Deck zero_seed =
      parse_deck(text, "inline.yaml", {parse_override("parts[0].perturbation={fraction: 0.1, seed: 0}")});
  EXPECT_EQ(zero_seed.parts[0].perturbation_seed, 0u);
  EXPECT_EQ(round_trip(zero_seed), zero_seed);
}

TEST(ToYaml, EmptyFieldListRoundTrips) {
  Deck deck = read_deck(test_deck_path("decks/minimal.yaml"));
  deck.output.fields.clear();
  EXPECT_EQ(round_trip(deck), deck) << to_yaml(deck);
}

TEST(ToYaml, OverriddenDeckEchoesTheOverride) {
  const Deck deck =
      read_deck(test_deck_path("decks/minimal.yaml"), {parse_override("parts[0].elements=[20,2,2]")});
  EXPECT_TRUE(contains(to_yaml(deck), "elements: [20, 2, 2]\n"));
  EXPECT_EQ(round_trip(deck), deck);
}

// Friction, rigid walls and loads: written with every key, read back the same.
TEST(ToYaml, FrictionWallsAndLoadsRoundTrip) {
  const std::string source = std::string(EXDYN_SOURCE_DIR) + "/input/";
  for (const char* name : {"sliding_block.yaml", "oblique_impact.yaml"}) {
    Deck deck = read_deck(source + name);
    EXPECT_EQ(round_trip(deck), deck) << to_yaml(deck);
  }
  Deck deck = read_deck(source + "oblique_impact.yaml");
  deck.rigid_walls[0].velocity = {0, 0, 0.5};
  deck.rigid_walls[0].slave_points = SlavePoints::quadrature;
  deck.rigid_walls[0].friction = FrictionOptions{0.4, 0.2, 3.5};
  deck.loads.push_back({{0, 0, -9.81}, {0}});
  EXPECT_EQ(round_trip(deck), deck) << to_yaml(deck);
  const std::string text = to_yaml(deck);
  for (const char* line :
       {"    friction: {static: 0.4, dynamic: 0.2, decay: 3.5}\n", "    velocity: [0, 0, 0.5]\n",
        "    slave_points: quadrature\n", "  - {gravity: [0, 0, -9.81], parts: [block]}\n"})
    EXPECT_TRUE(contains(text, line)) << line << " missing from\n" << text;
  EXPECT_TRUE(
      contains(to_yaml(read_deck(test_deck_path("decks/plate_impact.yaml"))), "slave_points: auto\n"));
}

// `auto` is the default, and resolves by the slave segments; a deck that asks for
// nodes on 8-node segments is warned about, one that gets them by default is not.
TEST(SlavePointsAuto, IsTheDefaultAndWarnsOnlyOnNodesOfEightNodeSegments) {
  const std::string hex20 = std::string(EXDYN_SOURCE_DIR) + "/input/plate_impact_hex20.yaml";
  const Deck automatic = read_deck(hex20, {{"contact[0].slave_points", "auto"}});
  EXPECT_EQ(automatic.contact[0].slave_points, SlavePoints::automatic);
  EXPECT_TRUE(deck_warnings(automatic).empty());
  EXPECT_EQ(resolved_slave_points(SlavePoints::automatic, true), SlavePoints::quadrature);
  EXPECT_EQ(resolved_slave_points(SlavePoints::automatic, false), SlavePoints::nodes);
  EXPECT_EQ(resolved_slave_points(SlavePoints::nodes, true), SlavePoints::nodes);
  const std::vector<std::string> warnings =
      deck_warnings(read_deck(hex20, {{"contact[0].slave_points", "nodes"}}));
  ASSERT_EQ(warnings.size(), 2u);  // both passes
  EXPECT_TRUE(contains(warnings[0], "slave_points: nodes on the 8-node segments of plate_a.xmax"))
      << warnings[0];
  EXPECT_TRUE(deck_warnings(read_deck(test_deck_path("decks/plate_impact.yaml"),
                                      {{"contact[0].slave_points", "nodes"}}))
                  .empty());  // 4-node segments
}

// A named pair on a part that can fail keeps its faces as they were (docs/contact.md,
// "Faces that erosion opens"): the run says so. `surface: all` follows erosion: no word.
TEST(DeckWarnings, ContactOnAPartThatCanFailIsWarnedAbout) {
  const std::string deck = std::string(EXDYN_SOURCE_DIR) + "/input/plate_impact.yaml";
  EXPECT_TRUE(deck_warnings(read_deck(deck)).empty());
  const std::vector<std::string> warnings = deck_warnings(
      read_deck(deck, {{"materials.steel",
                        "{model: elastic_plastic, density: 7800, youngs_modulus: 2.1e11, "
                        "poissons_ratio: 0.3, yield_stress: 4.0e8, failure: {plastic_strain: 0.3}}"}}));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(contains(warnings[0], "contact pair interface: part plate_a can fail")) << warnings[0];
  EXPECT_TRUE(contains(warnings[0], "use `surface: all`")) << warnings[0];
  EXPECT_TRUE(deck_warnings(read_deck(std::string(EXDYN_SOURCE_DIR) + "/input/punch_through.yaml")).empty());
}

}  // namespace
}  // namespace exdyn::input

namespace exdyn::input {
namespace {

// A checkpoint's deck against the deck a restart reads (docs/output.md, "Checkpoints").
TEST(RestartDifference, OnlyEndTimeOutputAndCheckpointMayChange) {
  const Deck deck = read_deck(testing::test_deck_path("decks/plate_impact.yaml"));
  const std::string saved = to_yaml(deck);
  EXPECT_EQ(restart_difference(saved, deck), "");
  Deck further = deck;
  further.time.end_time *= 2.0;
  further.output.every = 7;
  further.output.fields = {OutputField::displacement};
  further.checkpoint = {10, 0.0, 3};
  EXPECT_EQ(restart_difference(saved, further), "");
  Deck other = deck;
  other.materials[0].youngs_modulus *= 1.0 + 1e-15;  // the last bits count
  EXPECT_NE(restart_difference(saved, other).find("materials." + other.materials[0].name + ".youngs_modulus"),
            std::string::npos)
      << restart_difference(saved, other);
  other = deck;
  other.time.courant = 0.5;
  EXPECT_EQ(restart_difference(saved, other).rfind("time.courant (the checkpoint's ", 0), 0u)
      << restart_difference(saved, other);
  other = deck;
  other.parts.push_back(other.parts[0]);
  other.parts.back().name = "extra";
  EXPECT_EQ(restart_difference(saved, other).rfind("parts", 0), 0u) << restart_difference(saved, other);
}

TEST(ToYaml, CheckpointRoundTripsAndIsLeftOutWhenNone) {
  Deck deck = read_deck(testing::test_deck_path("decks/plate_impact.yaml"));
  EXPECT_FALSE(contains(to_yaml(deck), "checkpoint:"));
  deck.checkpoint = {100, 600.0, 3};
  EXPECT_EQ(round_trip(deck), deck) << to_yaml(deck);
  EXPECT_TRUE(contains(to_yaml(deck), "checkpoint:\n  every: 100\n  every_seconds: 600\n  keep: 3\n"));
}

}  // namespace
}  // namespace exdyn::input
