// The command line (../shared/spec/cli.md) through the real executable: exit
// statuses, `check`, `--set`, and that bad input writes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "../support/run_exdyn.hpp"
#include "../support/temp_dir.hpp"

namespace {

exdyn::testing::CommandResult exdyn(const std::string& arguments) {
  return exdyn::testing::run_exdyn(arguments);
}

std::string deck(const std::string& name) { return std::string(EXDYN_SOURCE_DIR) + "/input/" + name; }

// `check`'s echo is a deck that checks to the same text (after the first line, which names the file).
void expect_echo_checks_to_itself(const exdyn::testing::CommandResult& first,
                                  const exdyn::testing::TempDir& directory) {
  std::ofstream(directory.file("echo.yaml")) << first.output;
  const auto second = exdyn("check " + directory.file("echo.yaml"));
  ASSERT_EQ(second.status, 0) << second.output;
  auto body = [](const std::string& text) { return text.substr(text.find('\n')); };
  EXPECT_EQ(body(second.output), body(first.output));
}

TEST(Cli, VersionAndHelpExitZero) {
  const auto version = exdyn("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_NE(version.output.find("exdyn 0.1.0"), std::string::npos) << version.output;
  for (const char* args : {"--help", "run --help", "check --help", "project --help"}) {
    const auto help = exdyn(args);
    EXPECT_EQ(help.status, 0) << args;
  }
  EXPECT_NE(exdyn("run --help").output.find("--set"), std::string::npos);
}

// The Gmsh library (and the ~120 libraries it needs) is loaded by a deck with a mesh
// file alone: the dynamic loader's own account (LD_DEBUG=files) of what a process opens.
TEST(Cli, OnlyADeckWithAMeshFileLoadsTheGmshLibrary) {
  const auto opened = [](const std::string& arguments) {
    return exdyn::testing::run_exdyn(arguments, "LD_DEBUG=files").output;
  };
  const std::string version = opened("--version");
  const std::string box = opened("check " + deck("plate_impact.yaml"));
  const std::string mesh = opened("check " + deck("plate_impact_gmsh.yaml"));
  ASSERT_NE(box.find("file=libhdf5"), std::string::npos) << box;  // the loader's account is there
  EXPECT_EQ(version.find("libgmsh"), std::string::npos) << version;
  EXPECT_EQ(box.find("libgmsh"), std::string::npos) << box;
  EXPECT_NE(mesh.find("file=libgmsh"), std::string::npos) << mesh;
  EXPECT_NE(mesh.find("libexdyn_gmsh_reader"), std::string::npos) << mesh;
}

TEST(Cli, BadUsageExitsTwo) {
  EXPECT_EQ(exdyn("").status, 2);
  EXPECT_EQ(exdyn("frobnicate").status, 2);
  EXPECT_EQ(exdyn("run").status, 2);
  EXPECT_EQ(exdyn("run " + deck("wave_bar.yaml") + " --set time.courant").status, 2);
  EXPECT_EQ(exdyn("run /nonexistent/deck.yaml").status, 2);
}

TEST(Cli, CheckPrintsTheResolvedDeckWithDefaultsAndOverrides) {
  const auto result = exdyn("check " + deck("wave_bar.yaml") + " --set time.courant=0.25");
  ASSERT_EQ(result.status, 0) << result.output;
  EXPECT_NE(result.output.find("courant: 0.25"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("formulation: hex8"), std::string::npos)
      << result.output;  // a default filled in
  EXPECT_NE(result.output.find("history_every: 1"), std::string::npos) << result.output;
}

TEST(Cli, CheckOutputIsAValidDeckThatChecksToTheSameText) {
  exdyn::testing::TempDir directory;
  const auto first = exdyn("check " + deck("plate_impact_reference.yaml"));
  ASSERT_EQ(first.status, 0) << first.output;
  expect_echo_checks_to_itself(first, directory);
}

// Slave nodes on 8-node segments: `check` and `run` say what it does to the answer.
TEST(Cli, NodesOnEightNodeSegmentsAreWarnedAboutByCheckAndRun) {
  const auto warned =
      exdyn("check " + deck("plate_impact_hex20.yaml") + " --set contact[0].slave_points=nodes");
  ASSERT_EQ(warned.status, 0) << warned.output;
  EXPECT_NE(warned.output.find(
                "exdyn: warning: contact pair interface: slave_points: nodes on the 8-node segments"),
            std::string::npos)
      << warned.output;
  const auto quiet =
      exdyn("check " + deck("plate_impact_hex20.yaml") + " --set contact[0].slave_points=auto");
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  EXPECT_EQ(quiet.output.find("warning"), std::string::npos) << quiet.output;
  exdyn::testing::TempDir directory;
  const auto run = exdyn("run " + deck("plate_impact_hex20.yaml") + " --output " + directory.path().string() +
                         " --set contact[0].slave_points=nodes --set time.end_time=1e-9 --quiet");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("warning: contact pair interface: slave_points: nodes"), std::string::npos)
      << run.output;
}

// A mapped part: check reports the mesh (a quarter ball's cube-sphere: its smallest
// scaled Jacobian is 1/sqrt(3), at the cube's corners) and echoes the sphere keys.
TEST(Cli, CheckReportsTheMeshOfAMappedPartAndEchoesItsKeys) {
  exdyn::testing::TempDir directory;
  std::ofstream(directory.file("ball.yaml"))
      << "name: ball\nmaterials:\n  steel: {model: linear_elastic, density: 7800, youngs_modulus: 2.1e11, "
         "poissons_ratio: 0.3}\nparts:\n  - name: ball\n    sphere: {center: [0, 0, 0], radius: 0.01, keep: "
         "[x+, y+]}\n    elements: [4, 2]\n    grading: [1, 0.5]\n    material: steel\n    formulation: "
         "hex20\nboundary_conditions:\n  - {faces: [ball.cut_x], fix: [x]}\ntime:\n  end_time: 1.0e-6\n";
  const auto first = exdyn("check " + directory.file("ball.yaml"));
  ASSERT_EQ(first.status, 0) << first.output;
  EXPECT_NE(first.output.find("sphere: {center: [0, 0, 0], radius: 0.01, keep: [x+, y+]}"), std::string::npos)
      << first.output;
  EXPECT_NE(first.output.find("# part ball: 64 elements"), std::string::npos) << first.output;
  EXPECT_NE(first.output.find("smallest scaled Jacobian 0.57735"), std::string::npos) << first.output;
  expect_echo_checks_to_itself(first, directory);
}

TEST(Cli, BadDeckExitsTwoNamesTheKeyAndWritesNothing) {
  exdyn::testing::TempDir directory;
  const std::string out = directory.file("out");
  const auto result =
      exdyn("run " + deck("wave_bar.yaml") + " --set materials.steel.density=-7800 --output " + out);
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find("materials.steel.density"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// Mortar: `quadrature` is the points on each triangle of a piece (1, 3, 6 or 7), any
// other count refused; a rigid wall has no segments to cut by, so mortar there is refused:
// exit 2, the key named, nothing written. A good mortar deck checks and echoes its keys.
TEST(Cli, MortarKeysAreCheckedAndBadOnesExitTwoWritingNothing) {
  exdyn::testing::TempDir directory;
  const std::string out = directory.file("out");
  const auto bad_rule =
      exdyn("run " + deck("contact_patch_mortar.yaml") + " --set contact[0].quadrature=4 --output " + out);
  EXPECT_EQ(bad_rule.status, 2);
  EXPECT_NE(bad_rule.output.find("contact[0].quadrature"), std::string::npos) << bad_rule.output;
  EXPECT_NE(bad_rule.output.find("1, 3, 6 or 7"), std::string::npos) << bad_rule.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const auto wall =
      exdyn("run " + deck("taylor_wall.yaml") + " --set rigid_walls[0].slave_points=mortar --output " + out);
  EXPECT_EQ(wall.status, 2);
  EXPECT_NE(wall.output.find("rigid_walls[0].slave_points"), std::string::npos) << wall.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const auto good = exdyn("check " + deck("contact_patch_mortar.yaml") + " --set contact[0].quadrature=7");
  ASSERT_EQ(good.status, 0) << good.output;
  EXPECT_NE(good.output.find("slave_points: mortar"), std::string::npos) << good.output;
  EXPECT_NE(good.output.find("quadrature: 7"), std::string::npos) << good.output;
  expect_echo_checks_to_itself(good, directory);
}

// Single-surface contact: a `surface` beside a named side, an empty one or one with a
// face that does not exist exit 2, the key named, nothing written; a good one checks
// and echoes `surface:`, and its echo checks to the same text.
TEST(Cli, SurfaceKeysAreCheckedAndBadOnesExitTwoWritingNothing) {
  exdyn::testing::TempDir directory;
  const std::string out = directory.file("out");
  const std::vector<std::array<std::string, 3>> bad{
      {"plate_impact.yaml", "--set contact[0].surface=all", "contact[0].slave"},
      {"u_shape.yaml", "--set 'contact[0].surface=[]'", "contact[0].surface"},
  };
  for (const auto& [file, set, key] : bad) {
    const auto result = exdyn("run " + deck(file) + " " + set + " --output " + out);
    EXPECT_EQ(result.status, 2) << set << ": " << result.output;
    EXPECT_NE(result.output.find(key), std::string::npos) << result.output;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  const auto unknown = exdyn("run " + deck("u_shape.yaml") +
                             " --set 'contact[0].surface=[u.inner_left, u.inside]' --output " + out);
  EXPECT_EQ(unknown.status, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("contact[0].surface[1]"), std::string::npos) << unknown.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const auto good = exdyn("check " + deck("u_shape.yaml"));
  ASSERT_EQ(good.status, 0) << good.output;
  EXPECT_NE(good.output.find("surface: [u.inner_left, u.inner_right, u.inner_base]"), std::string::npos)
      << good.output;
  expect_echo_checks_to_itself(good, directory);
  const auto all = exdyn("check " + deck("u_shape.yaml") + " --set contact[0].surface=all");
  ASSERT_EQ(all.status, 0) << all.output;
  EXPECT_NE(all.output.find("surface: all"), std::string::npos) << all.output;
  expect_echo_checks_to_itself(all, directory);
}

// A mesh part: every kind of bad mesh exits 2, names the file and what is wrong, and
// writes nothing; a good one checks, and its echo checks to the same text.
TEST(Cli, MeshPartsOfBadMeshesExitTwoNamingTheFileAndWriteNothing) {
  exdyn::testing::TempDir directory;
  const std::string meshes = std::string(EXDYN_SOURCE_DIR) + "/tests/mesh/meshes/";
  int decks = 0;
  auto deck_on = [&](const std::string& file, const std::string& volume, const std::string& extra = "") {
    const std::string name = directory.file("mesh_" + std::to_string(++decks) + ".yaml");
    std::ofstream(name)
        << "name: cube\nmaterials:\n  steel: {model: linear_elastic, density: 7800, youngs_modulus: 2.1e11, "
           "poissons_ratio: 0.3}\nparts:\n  - name: cube\n    mesh: {file: "
        << file << ", volume: " << volume << "}\n    material: steel\n"
        << extra << "time:\n  end_time: 1.0e-6\n";
    return name;
  };
  const std::string out = directory.file("out");
  const std::pair<std::string, std::string> cases[] = {
      {deck_on(meshes + "cube_tets.msh", "cube"),
       "cube_tets.msh' has 48 tetrahedra ('Tetrahedron 4', Gmsh type 4)"},
      {deck_on(meshes + "cube_hex27.msh", "cube"),
       "cube_hex27.msh' has 8 27-node hexahedra ('Hexahedron 27', Gmsh type 12)"},
      {deck_on(meshes + "cube_tets.msh", "cube",
               "boundary_conditions:\n  - {faces: [cube.bottom], fix: [x]}\n"),
       "cube_tets.msh' has 48 tetrahedra"},
      {deck_on(std::string(EXDYN_SOURCE_DIR) + "/input/meshes/plate_impact_hex8.msh", "plate_a",
               "boundary_conditions:\n  - {faces: [cube.right], fix: [x]}\n"),
       "boundary_conditions[0].faces[0]: the face 'cube.right': the physical surface 'right' of '"},
  };
  for (const auto& [file, expected] : cases) {
    const auto result = exdyn("run " + file + " --output " + out);
    EXPECT_EQ(result.status, 2) << result.output;
    EXPECT_NE(result.output.find(expected), std::string::npos) << result.output;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  const auto good = exdyn("check " + deck("tube_impact.yaml"));
  ASSERT_EQ(good.status, 0) << good.output;
  EXPECT_NE(good.output.find("mesh: {file: "), std::string::npos) << good.output;
  expect_echo_checks_to_itself(good, directory);
}

TEST(Cli, RunWritesTheThreeFilesAndOneSummaryLineWhenNotATerminal) {
  exdyn::testing::TempDir directory;
  const auto result = exdyn("run " + deck("wave_bar.yaml") + " --output " + directory.path().string());
  ASSERT_EQ(result.status, 0) << result.output;
  for (const char* suffix : {".h5", ".xmf", ".json"})
    EXPECT_TRUE(std::filesystem::exists(directory.file(std::string("wave_bar") + suffix))) << suffix;
  // stdout is a pipe here: no progress line, only the final summary line.
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
  EXPECT_NE(result.output.find("completed"), std::string::npos);
  const auto quiet = exdyn("run " + deck("wave_bar.yaml") + " --quiet --output " + directory.path().string());
  EXPECT_EQ(quiet.status, 0);
  EXPECT_EQ(quiet.output, "");
}

TEST(Cli, SetOverridesTheOutputInterval) {
  exdyn::testing::TempDir directory;
  const auto result = exdyn("run " + deck("wave_bar.yaml") + " --quiet --set output.every=1000 --output " +
                            directory.path().string());
  ASSERT_EQ(result.status, 0) << result.output;
  std::ifstream xmf(directory.file("wave_bar.xmf"));
  const std::string text((std::istreambuf_iterator<char>(xmf)), std::istreambuf_iterator<char>());
  std::size_t grids = 0;
  for (std::size_t at = text.find("<Time "); at != std::string::npos; at = text.find("<Time ", at + 1))
    ++grids;
  EXPECT_EQ(grids, 2u);  // the first and the last step only
}

TEST(Cli, UnstableRunExitsOneNamesTheStepAndLeavesAFailedSummary) {
  exdyn::testing::TempDir directory;
  // Courant 1.5 is beyond the stable limit of 1.0: the energy grows until it overflows.
  const auto result =
      exdyn("run " + deck("wave_bar.yaml") + " --quiet --set time.courant=1.5 --set time.end_time=1e-4" +
            " --output " + directory.path().string());
  EXPECT_EQ(result.status, 1) << result.output;
  EXPECT_NE(result.output.find("at step "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("node"), std::string::npos) << result.output;
  std::ifstream json(directory.file("wave_bar.json"));
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"status\": \"failed\""), std::string::npos) << text;
  EXPECT_TRUE(std::filesystem::exists(directory.file("wave_bar.xmf")));  // the steps written so far
}

// The element kernels' instruction set (common/isa.hpp): --version names it, the
// summary records it, and a name that is unknown or that this CPU cannot run is bad
// input (exit 2, nothing written), from --isa and from EXDYN_ISA alike.
TEST(Cli, InstructionSetIsReportedAndBadNamesExitTwo) {
  const auto version = exdyn("--version");
  EXPECT_NE(version.output.find("a run uses x86-64-v"), std::string::npos) << version.output;
  exdyn::testing::TempDir directory;
  const std::string run = "run " + deck("wave_bar.yaml") + " --quiet --set time.end_time=2e-6 --output " +
                          directory.path().string();
  const auto unknown = exdyn(run + " --isa x86-64-v9");
  EXPECT_EQ(unknown.status, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("--isa: unknown instruction set 'x86-64-v9'"), std::string::npos)
      << unknown.output;
  ::setenv("EXDYN_ISA", "avx9", 1);
  const auto from_environment = exdyn(run);
  ::unsetenv("EXDYN_ISA");
  EXPECT_EQ(from_environment.status, 2) << from_environment.output;
  EXPECT_NE(from_environment.output.find("EXDYN_ISA: unknown instruction set 'avx9'"), std::string::npos)
      << from_environment.output;
  EXPECT_FALSE(std::filesystem::exists(directory.file("wave_bar.json")));
  const auto baseline = exdyn(run + " --isa x86-64-v2");
  ASSERT_EQ(baseline.status, 0) << baseline.output;
  std::ifstream json(directory.file("wave_bar.json"));
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"isa\": \"x86-64-v2\""), std::string::npos) << text;
}

}  // namespace
