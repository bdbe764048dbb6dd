// The cases reader and the CSV of `exdyn project` (library level).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/project_command.hpp"
#include "common/errors.hpp"
#include "contact/local_search.hpp"
#include "input/project_cases.hpp"

namespace exdyn {
namespace {

const std::string bad_cases_dir = std::string(EXDYN_SOURCE_DIR) + "/tests/contact/bad_cases/";
const std::string reference_cases = std::string(EXDYN_SOURCE_DIR) + "/tests/contact/cases/reference.yaml";

std::string error_of(const std::string& file) {
  try {
    input::read_project_cases(bad_cases_dir + file);
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

struct BadFile {
  std::string file;
  std::vector<std::string> must_contain;  // the location, the case and key, what was expected
};

TEST(ProjectCases, MalformedFilesNameTheCaseTheKeyAndWhatWasExpected) {
  const std::vector<BadFile> files{
      {"wrong_node_count.yaml",
       {"wrong_node_count.yaml:9:12:", "cases[1].nodes", "expected 8 points", "got 4"}},
      {"non_numeric.yaml",
       {"non_numeric.yaml:5:", "cases[0].nodes[2][1]", "expected a finite number", "'one'"}},
      {"unknown_segment.yaml",
       {"unknown_segment.yaml:4:14:", "cases[0].segment", "quad9", "did you mean 'quad"}},
      {"missing_point.yaml", {"missing_point.yaml:3:", "cases[0].point", "missing key"}},
      {"unknown_key.yaml",
       {"unknown_key.yaml:6:5:", "cases[0].pointt", "unknown key", "did you mean 'point'"}},
      {"short_point.yaml", {"short_point.yaml:6:12:", "cases[0].point", "expected a list of 3 numbers"}},
      {"bad_initial_guess.yaml", {"cases[0].initial_guess[1]", "expected a finite number"}},
      {"not_yaml.yaml", {"not_yaml.yaml:", "not valid YAML"}},
      {"no_cases.yaml", {"no_cases.yaml:2:1:", "case", "unknown key"}},
  };
  for (const BadFile& bad : files) {
    const std::string message = error_of(bad.file);
    for (const std::string& part : bad.must_contain)
      EXPECT_NE(message.find(part), std::string::npos)
          << bad.file << ": '" << part << "' not in: " << message;
  }
}

TEST(ProjectCases, MissingFileIsAnInputError) {
  EXPECT_THROW(input::read_project_cases(bad_cases_dir + "does_not_exist.yaml"), InputError);
}

TEST(ProjectCases, ReferenceFileReadsEveryCase) {
  const auto cases = input::read_project_cases(reference_cases);
  ASSERT_EQ(cases.size(), 8u);
  EXPECT_EQ(cases[0].id, 1);
  EXPECT_EQ(cases[0].segment, contact::SegmentType::quad8);
  EXPECT_EQ(cases[0].nodes.size(), 8u);
  EXPECT_EQ(cases[4].segment, contact::SegmentType::quad4);
  EXPECT_EQ(cases[4].nodes.size(), 4u);
  EXPECT_DOUBLE_EQ(cases[0].point[2], 0.5);
  EXPECT_FALSE(cases[0].initial_guess);
}

TEST(ProjectCases, OptionalIdAndInitialGuess) {
  const auto cases = input::parse_project_cases(
      "cases:\n  - segment: quad4\n    nodes: [[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]]\n    point: [0.1, 0.2, "
      "1]\n"
      "    initial_guess: [0.5, -0.25]\n",
      "memory");
  ASSERT_EQ(cases.size(), 1u);
  EXPECT_EQ(cases[0].id, 0);
  ASSERT_TRUE(cases[0].initial_guess);
  EXPECT_EQ((*cases[0].initial_guess)[1], -0.25);
}

std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::istringstream fs(line);
    std::string field;
    while (std::getline(fs, field, ',')) fields.push_back(field);
    rows.push_back(fields);
  }
  return rows;
}

std::string run(app::ProjectCommandOptions options) {
  options.timing_seconds = 0.0;
  std::ostringstream out;
  app::run_project_command(options, out);
  return out.str();
}

TEST(ProjectCommand, CsvHasTheContractHeaderAndOneRowPerCaseMethodAndGuess) {
  app::ProjectCommandOptions options;
  options.cases_file = reference_cases;
  options.methods = "all";
  options.initial_guess = "all";
  const auto rows = parse_csv(run(options));
  ASSERT_FALSE(rows.empty());
  const std::vector<std::string> header{"id",        "method",     "initial_guess", "xi1",        "xi2",
                                        "converged", "iterations", "evaluations",   "stationary", "inside",
                                        "distance",  "gap",        "nanoseconds"};
  EXPECT_EQ(rows[0], header);
  ASSERT_EQ(rows.size(), 1u + 8u * 9u * 6u);
  const std::vector<std::string> guesses{"lsp", "center", "corner1", "corner2", "corner3", "corner4"};
  for (std::size_t k = 1; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), 13u) << k;
    const std::size_t index = k - 1;
    EXPECT_EQ(rows[k][1], contact::search_method_names[(index / 6) % 9].second);
    EXPECT_EQ(rows[k][2], guesses[index % 6]);
    EXPECT_TRUE(rows[k][5] == "0" || rows[k][5] == "1");
    EXPECT_TRUE(rows[k][9] == "0" || rows[k][9] == "1");
    EXPECT_TRUE(rows[k][8] == "minimum" || rows[k][8] == "saddle" || rows[k][8] == "maximum" ||
                rows[k][8] == "none");
  }
}

TEST(ProjectCommand, CsvValuesRoundTripTheLibraryResultWith17Digits) {
  app::ProjectCommandOptions options;
  options.cases_file = reference_cases;
  options.methods = "newton,robust";
  options.initial_guess = "0.25,-0.5";
  const auto rows = parse_csv(run(options));
  ASSERT_EQ(rows.size(), 1u + 8u * 2u);
  const auto cases = input::read_project_cases(reference_cases);
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto& c = cases[(k - 1) / 2];
    contact::Segment s;
    s.type = c.segment;
    for (std::size_t i = 0; i < c.nodes.size(); ++i)
      s.nodes[i] = {c.nodes[i][0], c.nodes[i][1], c.nodes[i][2]};
    contact::ProjectionSettings st;
    st.method = (k - 1) % 2 == 0 ? contact::SearchMethod::newton : contact::SearchMethod::robust;
    const auto r = contact::project(s, {c.point[0], c.point[1], c.point[2]}, {0.25, -0.5}, st);
    EXPECT_EQ(rows[k][0], std::to_string(c.id));
    EXPECT_EQ(rows[k][2], "0.25;-0.5");
    EXPECT_EQ(std::stod(rows[k][3]), r.xi[0]);
    EXPECT_EQ(std::stod(rows[k][4]), r.xi[1]);
    EXPECT_EQ(std::stod(rows[k][10]), r.distance);
    EXPECT_EQ(std::stod(rows[k][11]), r.gap);
    EXPECT_EQ(std::stoi(rows[k][6]), r.iterations);
    EXPECT_EQ(std::stoi(rows[k][7]), r.evaluations);
    EXPECT_EQ(rows[k][8], contact::name(r.stationary));
  }
}

TEST(ProjectCommand, CaseInitialGuessIsUsedWhenNoneIsGiven) {
  const auto path = std::filesystem::temp_directory_path() / "exdyn_contact_case_guess.yaml";
  {
    std::ofstream file(path);
    file << "cases:\n  - id: 9\n    segment: quad4\n    nodes: [[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]]\n"
            "    point: [0.1, 0.2, 1]\n    initial_guess: [0.5, -0.25]\n  - id: 10\n    segment: quad4\n"
            "    nodes: [[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]]\n    point: [0.1, 0.2, 1]\n";
  }
  app::ProjectCommandOptions options;
  options.cases_file = path.string();
  const auto rows = parse_csv(run(options));
  std::filesystem::remove(path);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1][1], "bfgs");
  EXPECT_EQ(rows[1][2], "0.5;-0.25");
  EXPECT_EQ(rows[2][2], "lsp");
}

TEST(ProjectCommand, BadOptionsAreInputErrors) {
  app::ProjectCommandOptions options;
  options.cases_file = reference_cases;
  options.methods = "newton,bfsg";
  EXPECT_THROW(run(options), InputError);
  options.methods = "newton";
  options.initial_guess = "middle";
  EXPECT_THROW(run(options), InputError);
  options.initial_guess = "1,x";
  EXPECT_THROW(run(options), InputError);
  options.initial_guess = "lsp";
  options.tolerance = 0.0;
  EXPECT_THROW(run(options), InputError);
  options.tolerance = 1e-10;
  options.max_iterations = 0;
  EXPECT_THROW(run(options), InputError);
}

TEST(ProjectCommand, NanosecondsAreMeasured) {
  app::ProjectCommandOptions options;
  options.cases_file = reference_cases;
  options.methods = "newton";
  options.timing_seconds = 1e-4;
  std::ostringstream out;
  app::run_project_command(options, out);
  const auto rows = parse_csv(out.str());
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double ns = std::stod(rows[k][12]);
    EXPECT_GT(ns, 0.0);
    EXPECT_LT(ns, 1e6);
  }
}

}  // namespace
}  // namespace exdyn
