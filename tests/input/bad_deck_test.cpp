// Malformed decks (tests/input/bad_decks/*.yaml, also the seeds of the input fuzzer):
// each is rejected with an InputError naming the file, the line and the key path.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "deck_files.hpp"
#include "input/deck_reader.hpp"

namespace exdyn::input {
namespace {

struct BadDeck {
  const char* file;          // under tests/input/bad_decks/
  const char* key_path;      // the key path the error names ("" when there is none)
  int line;                  // 1-based; 0 when the error has no position (empty file)
  const char* message_part;  // a piece of what the message must say
};

void PrintTo(const BadDeck& deck, std::ostream* out) { *out << deck.file; }

// Line numbers count the comment on line 1 of each file.
const BadDeck bad_decks[] = {
    {"mesh_missing_file.yaml", "parts[0].mesh.file", 7,
     "no_such_mesh.msh': it does not exist or is not readable"},
    {"mesh_not_a_mesh.yaml", "parts[0].mesh.file", 7, "mesh_not_a_mesh.yaml' is not a Gmsh mesh"},
    {"mesh_unknown_volume.yaml", "parts[0].mesh.volume", 7,
     "tube_hex8.msh' has no physical volume 'tubes'; did you mean 'tube'?"},
    {"mesh_unknown_surface.yaml", "boundary_conditions[0].faces[1]", 10,
     "unknown side 'outside' of the mesh part 'tube' in face 'tube.outside'; did you mean 'tube.outer'?"},
    {"mesh_with_elements.yaml", "parts[0].elements", 8, "elements does not apply to a mesh part"},
    {"wrong_type_density.yaml", "materials.steel.density", 4, "expected a number > 0, got heavy"},
    {"missing_time.yaml", "time", 2, "missing required key 'time'"},
    {"checkpoint_without_rule.yaml", "checkpoint", 13, "give every (steps) or every_seconds"},
    {"checkpoint_every_zero.yaml", "checkpoint.every", 12, "expected an integer >= 1 (steps), got 0"},
    {"unknown_key_typo.yaml", "materials.steel.densty", 4, "unknown key 'densty'; did you mean 'density'?"},
    {"negative_density.yaml", "materials.steel.density", 4, "expected a number > 0, got -7800"},
    {"poissons_ratio_half.yaml", "materials.steel.poissons_ratio", 4,
     "expected a number in (-1, 0.5), got 0.5"},
    {"zero_size_box.yaml", "parts[0].box.max", 7, "y: max 0 <= min 0"},
    {"unknown_material.yaml", "parts[0].material", 9, "unknown material 'stel'; did you mean 'steel'?"},
    {"unknown_face.yaml", "boundary_conditions[0].faces[1]", 15, "did you mean 'plate_b.ymin'?"},
    {"courant_and_dt.yaml", "time.dt", 13, "not both"},
    {"empty_file.yaml", "", 0, "the deck is empty"},
    {"yaml_syntax_error.yaml", "", 9, "YAML syntax error"},
    {"elements_float.yaml", "parts[0].elements[1]", 8, "expected an integer >= 1, got 1.5 (not an integer)"},
    {"elements_two_entries.yaml", "parts[0].elements", 8, "expected a list of 3 integers >= 1"},
    {"duplicate_part_names.yaml", "parts[1].name", 10, "part name 'plate_a' is used twice"},
    {"unknown_formulation.yaml", "parts[0].formulation", 10,
     "unknown formulation 'tet4'; expected hex8, hex8r, hex20, hex20r"},
    {"unknown_local_search_method.yaml", "contact[0].local_search.method", 21,
     "unknown local search method 'bgfs'; did you mean 'bfgs'?"},
    {"unknown_output_field.yaml", "output.fields[1]", 14, "unknown output field 'strain'"},
    {"penalty_scale_and_stiffness.yaml", "contact[0].penalty.stiffness", 20, "not both"},
    {"scalar_instead_of_list.yaml", "boundary_conditions[0].fix", 15,
     "expected a non-empty list of components"},
    {"deck_is_a_list.yaml", "", 2, "expected the deck to be a map"},
    {"duplicate_key.yaml", "parts[0].elements", 9, "key 'elements' is given twice (first at line 8)"},
    {"unknown_part_in_contact.yaml", "contact[0].master[0]", 19, "unknown part 'plate_c'"},
    {"unknown_top_level_key.yaml", "solver", 12, "unknown key 'solver'; the keys here are name, materials"},
    {"max_iterations_zero.yaml", "contact[0].local_search.max_iterations", 21,
     "expected an integer >= 1, got 0"},
    {"unknown_fallback.yaml", "contact[0].local_search.fallback", 21,
     "unknown fallback method 'robustly'; did you mean 'robust'?"},
    {"unknown_initial_guess.yaml", "contact[0].local_search.initial_guess", 21,
     "unknown initial guess 'corner'; expected lsp, center, previous"},
    {"run_name_with_space.yaml", "name", 2, "expected a name of letters, digits, _ and -"},
    {"yield_stress_zero.yaml", "materials.copper.yield_stress", 4,
     "expected a number > 0 (the initial yield stress), got 0"},
    {"hardening_decreasing.yaml", "materials.copper.hardening[2][1]", 9, "the hardening table decreases"},
    {"hardening_not_at_zero.yaml", "materials.copper.hardening[0][0]", 9, "starts at eps_p = 0, got 0.01"},
    {"johnson_cook_n_zero.yaml", "materials.copper.n", 4,
     "expected a number > 0 (the hardening exponent), got 0"},
    {"kinematics_unknown.yaml", "parts[0].kinematics", 10,
     "unknown kinematics 'large'; expected auto, small, finite"},
    {"min_dt_ratio_one.yaml", "time.min_dt_ratio", 12, "expected a number in (0, 1)"},
    {"erode_with_dt.yaml", "time.erode", 13, "give courant, not dt"},
    {"thermal_melting_below_room.yaml", "materials.steel.thermal_softening.melting_temperature", 12,
     "expected a temperature above room_temperature (293 K), got 250"},
    {"thermal_on_elastic_plastic.yaml", "materials.steel.thermal_softening", 10,
     "'thermal_softening' belongs to model johnson_cook; this material is elastic_plastic"},
    {"erode_nothing_fails.yaml", "time.erode", 12, "no part's material has `failure`"},
    {"erode_small_strain.yaml", "time.erode", 13, "part 'bar' can fail but runs small strain"},
    {"yield_stress_on_elastic.yaml", "materials.steel.yield_stress", 4, "belongs to model elastic_plastic"},
    {"fix_unknown_component.yaml", "boundary_conditions[0].fix[1]", 15, "unknown component 'w'"},
    {"velocity_and_fix.yaml", "boundary_conditions[0].velocity", 15,
     "give either fix (held at rest) or velocity"},
    {"velocity_unknown_component.yaml", "boundary_conditions[0].velocity.w", 15, "the keys here are x, y, z"},
    {"velocity_not_a_number.yaml", "boundary_conditions[0].velocity.y", 15,
     "expected a velocity (m/s), got fast"},
    {"boundary_without_motion.yaml", "boundary_conditions[0]", 15, "expected fix: [components] or velocity"},
    {"failure_negative_strain.yaml", "materials.steel.failure.plastic_strain", 4,
     "expected a number > 0 (the failure plastic strain eps_f), got -0.2"},
    {"failure_on_linear_elastic.yaml", "materials.steel.failure", 4,
     "a linear_elastic material does not fail"},
    {"failure_jc_negative_strain.yaml", "materials.steel.failure.johnson_cook.D1", 4,
     "at the triaxiality sigma* = 1.5: the failure strain must be > 0"},
    {"failure_jc_rate_term.yaml", "materials.steel.failure.johnson_cook.D4", 4,
     "at the rate ratio 1e12: the failure strain must be > 0"},
    {"failure_jc_missing_d2.yaml", "materials.steel.failure.johnson_cook.D2", 4, "missing required key 'D2'"},
    {"failure_two_models.yaml", "materials.steel.failure.johnson_cook", 4,
     "give either plastic_strain or johnson_cook, not both"},
    {"mortar_on_eroding_surface.yaml", "contact[0].slave_points", 12,
     "mortar does not follow the faces erosion opens"},
    {"missing_part_material.yaml", "parts[0].material", 6, "missing required key 'material' in parts[0]"},
    {"two_documents.yaml", "", 12, "more than one YAML document"},
    {"comma_at_document_start.yaml", "", 2, "expected the deck to be a map with keys name, materials"},
    {"damping_negative.yaml", "contact[0].penalty.damping", 20, "expected a number >= 0, got -0.1"},
    {"cell_size_word.yaml", "contact[0].search.cell_size", 21,
     "expected a number > 0 or auto, got automatic"},
    {"two_pass_word.yaml", "contact[0].two_pass", 20, "expected true or false, got maybe"},
    {"surface_with_slave.yaml", "contact[0].slave", 19,
     "a contact entry with `surface` (single-surface contact) names no `slave`"},
    {"surface_empty.yaml", "contact[0].surface", 18, "expected a non-empty list of face names"},
    {"surface_unknown_face.yaml", "contact[0].surface[1]", 18,
     "unknown side 'xmni' of the box part 'plate_b' in face 'plate_b.xmni'; did you mean 'plate_b.xmin'?"},
    {"surface_word.yaml", "contact[0].surface", 18, "expected `all` or a non-empty list of face names"},
    {"surface_all_held.yaml", "contact[0].surface", 21, "`all` finds no exterior face"},
    {"perturbation_fraction_half.yaml", "parts[0].perturbation.fraction", 10,
     "expected a number in [0, 0.5) (a fraction of the element length h), got 0.5: at 0.5 or more a node can "
     "reach or pass its neighbour"},
    {"perturbation_seed_negative.yaml", "parts[0].perturbation.seed", 12, "expected an integer >= 0, got -1"},
    {"hourglass_on_hex20.yaml", "parts[0].hourglass", 11, "hourglass applies to hex8r parts"},
    {"quadrature_zero.yaml", "contact[0].quadrature", 21,
     "expected an integer from 1 to 6 (Gauss points per direction on each slave segment), got 0"},
    {"unknown_slave_points.yaml", "contact[0].slave_points", 20,
     "unknown slave points 'gauss'; expected auto, nodes, quadrature"},
    {"contact_name_with_slash.yaml", "contact[0].name", 17, "expected a contact pair name without '/'"},
    {"friction_dynamic_above_static.yaml", "contact[0].friction.dynamic", 18,
     "expected mu_d <= mu_s (the static coefficient, 0.2), got 0.3"},
    {"rigid_wall_zero_normal.yaml", "rigid_walls[0].normal", 17, "expected a non-zero normal"},
    {"load_unknown_part.yaml", "loads[0].parts[0]", 15, "unknown part 'plate_c'"},
    {"keep_unknown_half_space.yaml", "parts[0].sphere.keep[1]", 7, "unknown half-space 'w-'"},
    {"cylinder_zero_radius.yaml", "parts[0].cylinder.radius", 7, "expected a number > 0, got 0"},
    {"keep_with_odd_around.yaml", "parts[0].elements[0]", 8,
     "n_around must be even when `keep` cuts the part"},
    {"grading_zero.yaml", "parts[0].grading[2]", 9, "expected a number > 0, got 0"},
    {"sphere_three_counts.yaml", "parts[0].elements", 8,
     "expected a list of 2 integers >= 1 [n_around, n_radius]"},
    {"two_geometry_keys.yaml", "parts[0].sphere", 8,
     "a part has exactly one geometry key; this one has box and sphere"},
    {"keep_across_cylinder_axis.yaml", "parts[0].cylinder.keep[0]", 7, "a cut across the cylinder's axis"},
    {"face_of_sphere_xmin.yaml", "boundary_conditions[0].faces[0]", 11,
     "unknown side 'xmin' of the sphere part 'ball'"},
};

class BadDeckTest : public ::testing::TestWithParam<BadDeck> {};

TEST_P(BadDeckTest, IsRejectedNamingFileLineAndKeyPath) {
  const BadDeck& bad = GetParam();
  const std::string path = testing::test_deck_path(std::string("bad_decks/") + bad.file);
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  try {
    read_deck(path);
    FAIL() << "no error for " << bad.file;
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(error.location().file, path) << message;
    EXPECT_EQ(error.location().line, bad.line) << message;
    if (bad.line > 0) {
      EXPECT_GT(error.location().column, 0) << message;
    }
    EXPECT_EQ(error.key_path(), bad.key_path) << message;
    EXPECT_NE(message.find(bad.key_path), std::string::npos) << message;
    EXPECT_NE(message.find(bad.message_part), std::string::npos) << message;
    // The message starts with "file:line:column: " so editors can jump to it.
    const std::string prefix = bad.line > 0 ? path + ":" + std::to_string(bad.line) + ":" : path + ": ";
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
  }
}

// The test is named after the file, without ".yaml".
std::string file_stem(const ::testing::TestParamInfo<BadDeck>& parameter) {
  const std::string file = parameter.param.file;
  return file.substr(0, file.find('.'));
}

INSTANTIATE_TEST_SUITE_P(BadDecks, BadDeckTest, ::testing::ValuesIn(bad_decks), file_stem);

TEST(BadDecks, EveryFileInTheFolderIsChecked) {
  std::set<std::string> listed;
  for (const BadDeck& bad : bad_decks) listed.insert(bad.file);
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testing::test_deck_path("bad_decks"))) {
    ++files;
    EXPECT_TRUE(listed.count(entry.path().filename().string()) == 1) << entry.path() << " has no expectation";
  }
  EXPECT_EQ(files, listed.size());
}

TEST(BadDecks, UnknownKeyFarFromEveryKnownOneListsTheAllowedKeys) {
  const std::string text =
      testing::read_text(testing::test_deck_path("decks/minimal.yaml")) + "output: {frequency: 10}\n";
  try {
    parse_deck(text, "inline.yaml");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key_path(), "output.frequency");
    EXPECT_NE(std::string(error.what())
                  .find("the keys here are directory, every, fields, history_every, background"),
              std::string::npos)
        << error.what();
  }
}

TEST(BadDecks, QuotedNumberIsAStringNotANumber) {
  std::string text = testing::read_text(testing::test_deck_path("decks/minimal.yaml"));
  text.replace(text.find("end_time: 1.0e-4"), 16, "end_time: \"1.0e-4\"");
  try {
    parse_deck(text, "inline.yaml");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key_path(), "time.end_time");
    EXPECT_NE(std::string(error.what()).find("got the quoted string \"1.0e-4\""), std::string::npos)
        << error.what();
  }
}

TEST(BadDecks, PerturbationValuesOutOfRangeAreRejectedNamingTheKey) {
  const std::string text = testing::read_text(testing::test_deck_path("decks/minimal.yaml"));
  const std::pair<const char*, const char*> cases[] = {
      {"{fraction: -0.1}", "parts[0].perturbation.fraction"},
      {"{fraction: 0.7, seed: 1}", "parts[0].perturbation.fraction"},
      {"{fraction: .nan}", "parts[0].perturbation.fraction"},
      {"{fraction: 0.1, seed: 1.5}", "parts[0].perturbation.seed"},
      {"{fraction: 0.1, seed: 3000000000}", "parts[0].perturbation.seed"},
      {"{fractoin: 0.1}", "parts[0].perturbation.fractoin"},
      {"0.1", "parts[0].perturbation"},
  };
  for (const auto& [value, key_path] : cases) {
    try {
      parse_deck(text, "inline.yaml", {parse_override(std::string("parts[0].perturbation=") + value)});
      ADD_FAILURE() << "no error for " << value;
    } catch (const InputError& error) {
      EXPECT_EQ(error.key_path(), key_path) << error.what();
    }
  }
}

TEST(BadDecks, NonFiniteNumbersAreRejected) {
  std::string text = testing::read_text(testing::test_deck_path("decks/minimal.yaml"));
  text.replace(text.find("end_time: 1.0e-4"), 16, "end_time: .inf");
  EXPECT_THROW(parse_deck(text, "inline.yaml"), InputError);
}

}  // namespace
}  // namespace exdyn::input
