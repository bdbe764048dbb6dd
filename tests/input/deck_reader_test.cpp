// Valid decks read to the values written, with every default filled in.
#include "input/deck_reader.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "deck_files.hpp"

namespace exdyn::input {
namespace {

using testing::read_text;
using testing::test_deck_path;

TEST(DeckReader, SpecExamplePlateImpactReadsToItsValues) {
  const std::string path = test_deck_path("decks/plate_impact.yaml");
  const Deck deck = read_deck(path);
  EXPECT_EQ(deck.source_file, path);
  EXPECT_EQ(deck.name, "plate_impact");

  ASSERT_EQ(deck.materials.size(), 1u);
  const MaterialOptions& steel = deck.materials[0];
  EXPECT_EQ(steel.name, "steel");
  EXPECT_EQ(steel.model, MaterialModel::linear_elastic);
  EXPECT_EQ(steel.density, 7800.0);
  EXPECT_EQ(steel.youngs_modulus, 2.1e11);
  EXPECT_EQ(steel.poissons_ratio, 0.3);

  ASSERT_EQ(deck.parts.size(), 2u);
  const PartOptions& plate_a = deck.parts[0];
  EXPECT_EQ(plate_a.name, "plate_a");
  EXPECT_EQ(plate_a.box_min, (Vec3{-2.5e-3, 0.0, 0.0}));
  EXPECT_EQ(plate_a.box_max, (Vec3{0.0, 2.5e-5, 2.5e-3}));
  EXPECT_EQ(plate_a.elements, (std::array<int, 3>{100, 1, 100}));
  EXPECT_EQ(plate_a.material, "steel");
  EXPECT_EQ(plate_a.material_index, 0);
  EXPECT_EQ(plate_a.formulation, Formulation::hex8);
  EXPECT_EQ(plate_a.hourglass_model, HourglassModel::assumed_strain);
  EXPECT_EQ(plate_a.hourglass_coefficient, 1.0);
  EXPECT_EQ(plate_a.initial_velocity, (Vec3{1.0, 0.0, 0.0}));
  const PartOptions& plate_b = deck.parts[1];
  EXPECT_EQ(plate_b.name, "plate_b");
  EXPECT_EQ(plate_b.box_min, (Vec3{0.0, 0.0, 0.0}));
  EXPECT_EQ(plate_b.box_max, (Vec3{2.5e-3, 2.5e-5, 2.5e-3}));
  EXPECT_EQ(plate_b.initial_velocity, (Vec3{-1.0, 0.0, 0.0}));

  ASSERT_EQ(deck.boundary_conditions.size(), 2u);
  const BoundaryConditionOptions& plane_strain = deck.boundary_conditions[0];
  ASSERT_EQ(plane_strain.faces.size(), 4u);
  EXPECT_EQ(plane_strain.faces[0], (FaceRef{0, PartFace::ymin}));
  EXPECT_EQ(plane_strain.faces[1], (FaceRef{0, PartFace::ymax}));
  EXPECT_EQ(plane_strain.faces[2], (FaceRef{1, PartFace::ymin}));
  EXPECT_EQ(plane_strain.faces[3], (FaceRef{1, PartFace::ymax}));
  EXPECT_EQ(plane_strain.fix, (std::array<bool, 3>{false, true, false}));
  const BoundaryConditionOptions& symmetry = deck.boundary_conditions[1];
  ASSERT_EQ(symmetry.faces.size(), 2u);
  EXPECT_EQ(symmetry.faces[0], (FaceRef{0, PartFace::zmin}));
  EXPECT_EQ(symmetry.faces[1], (FaceRef{1, PartFace::zmin}));
  EXPECT_EQ(symmetry.fix, (std::array<bool, 3>{false, false, true}));

  ASSERT_EQ(deck.contact.size(), 1u);
  const ContactOptions& interface = deck.contact[0];
  EXPECT_EQ(interface.name, "interface");
  EXPECT_EQ(interface.slave, (std::vector<FaceRef>{{0, PartFace::xmax}}));
  EXPECT_EQ(interface.master, (std::vector<FaceRef>{{1, PartFace::xmin}}));
  EXPECT_TRUE(interface.two_pass);
  EXPECT_EQ(interface.penalty.scale, 1.0);
  EXPECT_FALSE(interface.penalty.stiffness.has_value());
  EXPECT_EQ(interface.penalty.damping, 0.2);
  EXPECT_FALSE(interface.search.cell_size.has_value());
  EXPECT_EQ(interface.local_search.method, contact::SearchMethod::bfgs);
  EXPECT_EQ(interface.local_search.tolerance, 1.0e-10);
  EXPECT_EQ(interface.local_search.max_iterations, 100);
  EXPECT_EQ(interface.local_search.initial_guess, contact::InitialGuess::lsp);
  EXPECT_EQ(interface.local_search.fallback, contact::SearchMethod::robust);

  EXPECT_EQ(deck.time.end_time, 2.32551069659978e-7);
  EXPECT_EQ(deck.time.courant, 0.125);
  EXPECT_FALSE(deck.time.dt.has_value());

  EXPECT_EQ(deck.output.directory, "results");
  EXPECT_EQ(deck.output.every, 64);
  EXPECT_EQ(deck.output.fields,
            (std::vector<OutputField>{OutputField::displacement, OutputField::velocity, OutputField::stress,
                                      OutputField::von_mises, OutputField::contact_force, OutputField::gap}));
  EXPECT_EQ(deck.output.history_every, 1);
}

TEST(DeckReader, MinimalDeckGetsEveryDefault) {
  const Deck deck = read_deck(test_deck_path("decks/minimal.yaml"));
  EXPECT_EQ(deck.name, "bar");
  ASSERT_EQ(deck.parts.size(), 1u);
  const PartOptions& bar = deck.parts[0];
  EXPECT_EQ(bar.material_index, 0);
  EXPECT_EQ(bar.formulation, Formulation::hex8);
  EXPECT_EQ(bar.hourglass_model, HourglassModel::assumed_strain);
  EXPECT_EQ(bar.hourglass_coefficient, 1.0);
  EXPECT_EQ(bar.initial_velocity, (Vec3{0.0, 0.0, 0.0}));
  EXPECT_TRUE(deck.boundary_conditions.empty());
  EXPECT_TRUE(deck.contact.empty());
  EXPECT_EQ(deck.time.end_time, 1.0e-4);
  EXPECT_EQ(deck.time.courant, 0.9);
  EXPECT_FALSE(deck.time.dt.has_value());
  EXPECT_EQ(deck.output.directory, "results");
  EXPECT_EQ(deck.output.every, 100);
  EXPECT_EQ(deck.output.fields,
            std::vector<OutputField>(default_output_fields.begin(), default_output_fields.end()));
  EXPECT_EQ(deck.output.history_every, 1);
  EXPECT_TRUE(deck.output.background);  // the default
}

TEST(DeckReader, ContactPairDefaultsWhenOnlyRequiredKeysAreGiven) {
  const std::string text = read_text(test_deck_path("decks/minimal.yaml")) +
                           "contact:\n"
                           "  - {name: self, slave: [bar.xmin], master: [bar.xmax]}\n";
  const Deck deck = parse_deck(text, "inline.yaml");
  ASSERT_EQ(deck.contact.size(), 1u);
  const ContactOptions& pair = deck.contact[0];
  EXPECT_TRUE(pair.two_pass);
  EXPECT_EQ(pair.penalty, PenaltyOptions{});
  EXPECT_EQ(pair.penalty.scale, 1.0);
  EXPECT_EQ(pair.penalty.damping, 0.2);
  EXPECT_EQ(pair.search, GlobalSearchOptions{});
  EXPECT_EQ(pair.local_search.method, contact::SearchMethod::bfgs);
  EXPECT_EQ(pair.local_search.tolerance, 1.0e-10);
  EXPECT_EQ(pair.local_search.max_iterations, 100);
  EXPECT_EQ(pair.local_search.initial_guess, contact::InitialGuess::lsp);
}

TEST(DeckReader, EveryNonDefaultValueIsRead) {
  const std::string text = R"(name: all-keys_2
materials:
  soft: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e6, poissons_ratio: -0.5}
  steel: {model: linear_elastic, density: 7800, youngs_modulus: 2.1e11, poissons_ratio: 0.49}
parts:
  - name: block
    box: {min: [-1, -2, -3], max: [1, 2, 3]}
    elements: [2, 3, 4]
    material: steel
    formulation: hex8r
    hourglass: {coefficient: 0.1}
    initial_velocity: [+1.5, -2, 3e0]
boundary_conditions:
  - {faces: [block.xmin], fix: [z, x]}
contact:
  - name: self
    slave: [block.zmax, block.ymax]
    master: [block.zmin]
    two_pass: false
    penalty: {stiffness: 1.0e9, damping: 0}
    search: {cell_size: 0.25}
    local_search: {method: robust, tolerance: 1.0e-12, max_iterations: 7, initial_guess: previous, fallback: none}
time: {end_time: 1.0e-3, dt: 1.0e-7}
output: {directory: "out dir", every: 3, fields: [gap, stress], history_every: 5, background: false}
)";
  const Deck deck = parse_deck(text, "inline.yaml");
  EXPECT_EQ(deck.name, "all-keys_2");
  ASSERT_EQ(deck.materials.size(), 2u);
  EXPECT_EQ(deck.materials[0].name, "soft");  // file order, not sorted
  EXPECT_EQ(deck.materials[0].poissons_ratio, -0.5);
  EXPECT_EQ(deck.materials[1].name, "steel");
  const PartOptions& block = deck.parts[0];
  EXPECT_EQ(block.material_index, 1);
  EXPECT_EQ(block.formulation, Formulation::hex8r);
  EXPECT_EQ(block.hourglass_model, HourglassModel::flanagan_belytschko);  // a coefficient alone
  EXPECT_EQ(block.hourglass_coefficient, 0.1);
  EXPECT_EQ(block.elements, (std::array<int, 3>{2, 3, 4}));
  EXPECT_EQ(block.initial_velocity, (Vec3{1.5, -2.0, 3.0}));
  EXPECT_EQ(deck.boundary_conditions[0].fix, (std::array<bool, 3>{true, false, true}));
  const ContactOptions& pair = deck.contact[0];
  EXPECT_EQ(pair.slave, (std::vector<FaceRef>{{0, PartFace::zmax}, {0, PartFace::ymax}}));
  EXPECT_FALSE(pair.two_pass);
  EXPECT_EQ(pair.penalty.stiffness, 1.0e9);
  EXPECT_EQ(pair.penalty.damping, 0.0);
  EXPECT_EQ(pair.search.cell_size, 0.25);
  EXPECT_EQ(pair.local_search.method, contact::SearchMethod::robust);
  EXPECT_EQ(pair.local_search.tolerance, 1.0e-12);
  EXPECT_EQ(pair.local_search.max_iterations, 7);
  EXPECT_EQ(pair.local_search.initial_guess, contact::InitialGuess::previous);
  EXPECT_FALSE(pair.local_search.fallback.has_value());
  EXPECT_EQ(deck.time.dt, 1.0e-7);
  EXPECT_EQ(deck.time.courant, 0.9);
  EXPECT_EQ(deck.output.directory, "out dir");
  EXPECT_EQ(deck.output.every, 3);
  EXPECT_EQ(deck.output.fields, (std::vector<OutputField>{OutputField::gap, OutputField::stress}));
  EXPECT_EQ(deck.output.history_every, 5);
  EXPECT_FALSE(deck.output.background);
}

TEST(DeckReader, HourglassBlockIsAcceptedForFullIntegration) {
  const std::string text = read_text(test_deck_path("decks/minimal.yaml"));
  std::string with_hourglass = text;
  with_hourglass.replace(with_hourglass.find("    material: steel\n"), 20,
                         "    material: steel\n    formulation: hex8\n    hourglass: {coefficient: 0.1}\n");
  const Deck deck = parse_deck(with_hourglass, "inline.yaml");
  EXPECT_EQ(deck.parts[0].formulation, Formulation::hex8);
  EXPECT_EQ(deck.parts[0].hourglass_coefficient, 0.1);
}

TEST(DeckReader, HourglassModelSetsItsOwnDefaultCoefficient) {
  const std::string text = read_text(test_deck_path("decks/minimal.yaml"));
  const auto part_with = [&](const std::string& hourglass) {
    std::string deck = text;
    deck.replace(deck.find("    material: steel\n"), 20,
                 "    material: steel\n    formulation: hex8r\n    hourglass: " + hourglass + "\n");
    return parse_deck(deck, "inline.yaml").parts[0];
  };
  const PartOptions fb = part_with("{model: flanagan_belytschko}");
  EXPECT_EQ(fb.hourglass_model, HourglassModel::flanagan_belytschko);
  EXPECT_EQ(fb.hourglass_coefficient, 0.05);
  const PartOptions scaled = part_with("{model: assumed_strain, coefficient: 0.5}");
  EXPECT_EQ(scaled.hourglass_model, HourglassModel::assumed_strain);
  EXPECT_EQ(scaled.hourglass_coefficient, 0.5);
  const PartOptions physical = part_with("{model: assumed_strain}");
  EXPECT_EQ(physical.hourglass_coefficient, 1.0);
  try {
    part_with("{model: puso}");
    ADD_FAILURE() << "an unknown hourglass model was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("parts[0].hourglass.model"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("assumed_strain"), std::string::npos) << e.what();
  }
}

TEST(DeckReader, PrescribedVelocityIsFixWithValuesAndRoundTrips) {
  const std::string text = read_text(test_deck_path("decks/minimal.yaml")) +
                           "boundary_conditions:\n"
                           "  - {faces: [bar.zmax], velocity: {z: -10.0, x: 0}}\n"
                           "  - {faces: [bar.zmin], fix: [z]}\n";
  const Deck deck = parse_deck(text, "inline.yaml");
  ASSERT_EQ(deck.boundary_conditions.size(), 2u);
  const BoundaryConditionOptions& moving = deck.boundary_conditions[0];
  EXPECT_EQ(moving.fix, (std::array<bool, 3>{true, false, true}));
  EXPECT_EQ(moving.velocity, (std::array<double, 3>{0.0, 0.0, -10.0}));
  EXPECT_TRUE(moving.moving());
  EXPECT_FALSE(deck.boundary_conditions[1].moving());
  EXPECT_EQ(parse_deck(to_yaml(deck), "inline.yaml"), deck) << to_yaml(deck);
  // `fix: [x]` is `velocity: {x: 0}`.
  std::string zero = text;
  zero.replace(zero.find("fix: [z]"), 8, "velocity: {z: 0}");
  EXPECT_EQ(parse_deck(zero, "inline.yaml").boundary_conditions, deck.boundary_conditions);
}

TEST(DeckReader, FailureIsReadAndAddsDamageAndStatusToTheDefaultFields) {
  std::string text = read_text(test_deck_path("decks/minimal.yaml"));
  text.replace(
      text.find("{model: linear_elastic,"), 23,
      "{model: johnson_cook, A: 4.9e8, B: 3.8e8, n: 0.73, failure: {johnson_cook: {D1: 0.05, D2: 3.44, "
      "D3: -2.12, D4: 0.002}},");
  const Deck deck = parse_deck(text, "inline.yaml");
  const MaterialOptions& steel = deck.materials[0];
  EXPECT_EQ(steel.failure, FailureModel::johnson_cook);
  EXPECT_EQ(steel.failure_d, (std::array<double, 5>{0.05, 3.44, -2.12, 0.002, 0.0}));
  std::vector<OutputField> fields(default_output_fields.begin(), default_output_fields.end());
  fields.push_back(OutputField::damage);
  fields.push_back(OutputField::status);
  EXPECT_EQ(deck.output.fields, fields);
  EXPECT_EQ(parse_deck(to_yaml(deck), "inline.yaml"), deck) << to_yaml(deck);
  // A list of fields is the list: no damage unless asked.
  EXPECT_EQ(parse_deck(text + "output: {fields: [stress]}\n", "inline.yaml").output.fields,
            std::vector<OutputField>{OutputField::stress});
  std::string strain = text;
  strain.replace(strain.find("{johnson_cook: {D1: 0.05, D2: 3.44, D3: -2.12, D4: 0.002}}"), 58,
                 "{plastic_strain: 0.3}");
  const Deck plain = parse_deck(strain, "inline.yaml");
  EXPECT_EQ(plain.materials[0].failure, FailureModel::plastic_strain);
  EXPECT_EQ(plain.materials[0].failure_strain, 0.3);
  EXPECT_EQ(parse_deck(to_yaml(plain), "inline.yaml"), plain);
}

TEST(DeckReader, EmptyOptionalSectionsTakeTheirDefaults) {
  const std::string text =
      read_text(test_deck_path("decks/minimal.yaml")) + "boundary_conditions:\ncontact: []\noutput:\n";
  const Deck deck = parse_deck(text, "inline.yaml");
  EXPECT_TRUE(deck.boundary_conditions.empty());
  EXPECT_TRUE(deck.contact.empty());
  EXPECT_EQ(deck.output, OutputOptions{});
}

TEST(DeckReader, SearchCellSizeAutoMeansUnset) {
  const std::string text =
      read_text(test_deck_path("decks/minimal.yaml")) +
      "contact:\n"
      "  - {name: self, slave: [bar.xmin], master: [bar.xmax], search: {cell_size: auto}}\n";
  EXPECT_FALSE(parse_deck(text, "inline.yaml").contact[0].search.cell_size.has_value());
}

TEST(DeckReader, MissingFileIsAnInputErrorNamingThePath) {
  const std::string path = test_deck_path("decks/no_such_deck.yaml");
  try {
    read_deck(path);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
  }
}

TEST(DeckReader, DirectoryIsAnInputError) { EXPECT_THROW(read_deck(test_deck_path("decks")), InputError); }

TEST(Options, NamesAreTheDeckSpellings) {
  EXPECT_STREQ(name(MaterialModel::linear_elastic), "linear_elastic");
  EXPECT_STREQ(name(Formulation::hex8), "hex8");
  EXPECT_STREQ(name(Formulation::hex8r), "hex8r");
  EXPECT_STREQ(name(PartFace::xmin), "xmin");
  EXPECT_STREQ(name(PartFace::zmax), "zmax");
  EXPECT_STREQ(name(OutputField::von_mises), "von_mises");
  EXPECT_STREQ(name(OutputField::contact_force), "contact_force");
  const Deck deck = read_deck(test_deck_path("decks/plate_impact.yaml"));
  EXPECT_EQ(face_name(deck, deck.contact[0].master[0]), "plate_b.xmin");
  EXPECT_EQ(face_name(deck, FaceRef{0, PartFace::ymax}), "plate_a.ymax");
}

}  // namespace
}  // namespace exdyn::input
