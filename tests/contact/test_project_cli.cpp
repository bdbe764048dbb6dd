// `exdyn project` through the executable: exit status and messages.
#include <gtest/gtest.h>

#include <string>

#include "../support/run_exdyn.hpp"

namespace {

exdyn::testing::CommandResult run(const std::string& arguments) {
  return exdyn::testing::run_exdyn(arguments);
}

const std::string source = EXDYN_SOURCE_DIR;

TEST(ProjectCli, MalformedCasesFileExitsTwoNamingTheCaseAndKey) {
  const std::array<std::pair<const char*, const char*>, 4> files{{
      {"wrong_node_count.yaml", "cases[1].nodes"},
      {"non_numeric.yaml", "cases[0].nodes[2][1]"},
      {"unknown_segment.yaml", "cases[0].segment"},
      {"unknown_key.yaml", "cases[0].pointt"},
  }};
  for (const auto& [file, key] : files) {
    const auto o = run("project " + source + "/tests/contact/bad_cases/" + file);
    EXPECT_EQ(o.status, 2) << file << ": " << o.output;
    EXPECT_NE(o.output.find(key), std::string::npos) << file << ": " << o.output;
    EXPECT_NE(o.output.find(file), std::string::npos) << file << ": " << o.output;
  }
}

TEST(ProjectCli, UnknownMethodExitsTwo) {
  const auto o = run("project " + source + "/tests/contact/cases/reference.yaml --method newtn");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("newtn"), std::string::npos) << o.output;
}

TEST(ProjectCli, ReferenceCasesPrintTheCsv) {
  const auto o =
      run("project " + source + "/tests/contact/cases/reference.yaml --method all --initial-guess all");
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_EQ(
      o.output.rfind("id,method,initial_guess,xi1,xi2,converged,iterations,evaluations,stationary,inside,"
                     "distance,gap,nanoseconds\n",
                     0),
      0u);
  std::size_t lines = 0;
  for (char ch : o.output) lines += ch == '\n';
  EXPECT_EQ(lines, 1u + 8u * 9u * 6u);
}

}  // namespace
