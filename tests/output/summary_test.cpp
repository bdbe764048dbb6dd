// write_summary: NAME.json has every key of ../shared/spec/output.md's example.
#include "output/summary.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace exdyn::output {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

class SummaryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ =
        fs::temp_directory_path() / ("exdyn_summary_" + std::to_string(::getpid()) + "_" +
                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(directory_);
  }
  Json read(const fs::path& path) const {
    std::ifstream in(path);
    return Json::parse(in);
  }
  fs::path directory_;
};

RunSummary example() {
  RunSummary s;
  s.name = "plate_impact";
  s.status = "completed";
  s.message = "";
  s.exdyn_version = "0.1.0";
  s.threads = 2;
  s.nodes = 40804;
  s.elements = 20000;
  s.steps = 448;
  s.dt = 5.19e-10;
  s.end_time = 2.3255e-7;
  s.wall_seconds = 12.5;
  s.element_cycles_per_second = 716800.0;
  s.phase_seconds = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0};
  s.energy = {10.0, 9.5, 0.05};
  static_cast<ContactFigures&>(s.contact) = {1000, 3.5, 12, 2, 1, 0.01, 1.5e9, 3};
  return s;
}

TEST_F(SummaryTest, EveryKeyOfTheSpecIsWrittenInItsOrder) {
  const fs::path path = directory_ / "plate_impact.json";
  write_summary(path.string(), example());  // also creates the directory
  const Json j = read(path);

  std::vector<std::string> keys;
  for (const auto& item : j.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"name", "status", "message", "exdyn_version", "threads", "mesh",
                                            "steps", "dt", "end_time", "wall_seconds",
                                            "element_cycles_per_second", "phase_seconds", "energy", "contact",
                                            "mpi", "guards", "isa", "dt_min", "warnings"}));
  EXPECT_EQ(j["name"], "plate_impact");
  EXPECT_EQ(j["status"], "completed");
  EXPECT_EQ(j["message"], "");
  EXPECT_EQ(j["exdyn_version"], "0.1.0");
  EXPECT_EQ(j["threads"], 2);
  EXPECT_EQ(j["mesh"], (Json{{"nodes", 40804}, {"elements", 20000}}));
  EXPECT_TRUE(j["steps"].is_number_integer());
  EXPECT_EQ(j["steps"], 448);
  EXPECT_EQ(j["dt"].get<double>(), 5.19e-10);
  EXPECT_EQ(j["end_time"].get<double>(), 2.3255e-7);
  EXPECT_EQ(j["wall_seconds"].get<double>(), 12.5);
  EXPECT_EQ(j["element_cycles_per_second"].get<double>(), 716800.0);
  EXPECT_EQ(j["phase_seconds"], (Json{{"element_forces", 1.0},
                                      {"contact_global_search", 2.0},
                                      {"contact_local_search", 3.0},
                                      {"contact_forces", 4.0},
                                      {"time_integration", 5.0},
                                      {"output", 6.0},
                                      {"guards", 7.0},
                                      {"contact_segmentation", 8.0}}));  // the spec's six, then ours
  EXPECT_EQ(j["energy"], (Json{{"initial_total", 10.0},
                               {"final_total", 9.5},
                               {"max_relative_error", 0.05},
                               {"internal", 0.0},
                               {"hourglass", 0.0},
                               {"plastic_work", 0.0},
                               {"eroded", 0.0},
                               {"eroded_elements", 0}}));  // the spec's three, then ours
  EXPECT_EQ(j["contact"], (Json{{"projections", 1000},
                                {"mean_iterations", 3.5},
                                {"max_iterations", 12},
                                {"not_converged", 2},
                                {"saddle_points", 1},
                                {"max_penetration_over_h", 0.01},
                                {"penalty_stiffness", 1.5e9},
                                {"fallbacks", 3},
                                {"pairs", Json::object()},
                                {"rigid_walls", Json::object()}}));  // the spec's keys, then ours
  EXPECT_EQ(j["mpi"], (Json{{"ranks", 1},  // the spec's key, then ours (docs/output.md)
                            {"shared_nodes", 0},
                            {"messages_per_step", 0},
                            {"bytes_per_step", 0.0},
                            {"contact_nodes", 0},
                            {"exchange_seconds", 0.0},
                            {"partition", "bisection"},
                            {"edge_cut", 0},
                            {"weigh", "elements"},
                            {"setup", "whole"},
                            {"per_rank",
                             {{"peak_resident_mb", Json::array()},
                              {"contact_nodes", Json::array()},
                              {"contact_points", Json::array()},
                              {"contact_segments", Json::array()},
                              {"ghost_segments", Json::array()},
                              {"ghost_nodes", Json::array()},
                              {"contact_messages_per_step", Json::array()},
                              {"contact_bytes_per_step", Json::array()},
                              {"force_messages_per_step", Json::array()},
                              {"force_bytes_per_step", Json::array()},
                              {"wait_seconds", Json::array()},
                              {"element_seconds", Json::array()},
                              {"contact_seconds", Json::array()}}}}));
  for (const char* integer :
       {"projections", "max_iterations", "not_converged", "saddle_points", "fallbacks"}) {
    EXPECT_TRUE(j["contact"][integer].is_number_integer()) << integer;
  }
  EXPECT_FALSE(fs::exists(directory_ / "plate_impact.json.tmp"));
}

TEST_F(SummaryTest, FailedRunKeepsItsMessageAndNonFiniteNumbersBecomeNull) {
  RunSummary s = example();
  s.status = "failed";
  s.message = "element 17 inverted at step 212 (t = 1.1e-7)\n\"quoted\" \xff";  // \xff: not UTF-8
  s.energy.final_total = std::numeric_limits<double>::quiet_NaN();
  s.energy.max_relative_error = std::numeric_limits<double>::infinity();
  s.element_cycles_per_second = -std::numeric_limits<double>::infinity();
  const fs::path path = directory_ / "failed.json";
  write_summary(path.string(), s);
  const Json j = read(path);
  EXPECT_EQ(j["status"], "failed");
  EXPECT_EQ(
      j["message"].get<std::string>().rfind("element 17 inverted at step 212 (t = 1.1e-7)\n\"quoted\" ", 0),
      0u);
  EXPECT_TRUE(j["energy"]["final_total"].is_null());
  EXPECT_TRUE(j["energy"]["max_relative_error"].is_null());
  EXPECT_TRUE(j["element_cycles_per_second"].is_null());
  EXPECT_EQ(j["energy"]["initial_total"].get<double>(), 10.0);
}

TEST_F(SummaryTest, ExistingSummaryIsReplaced) {
  fs::create_directories(directory_);
  const fs::path path = directory_ / "run.json";
  std::ofstream(path) << "old, longer content that is not JSON at all ..........................";
  write_summary(path.string(), example());
  EXPECT_EQ(read(path)["name"], "plate_impact");
  EXPECT_FALSE(fs::exists(directory_ / "run.json.tmp"));
}

TEST_F(SummaryTest, UnwritableLocationThrowsNamingThePath) {
  fs::create_directories(directory_ / "run.json");  // a directory where the file should go
  const std::string path = (directory_ / "run.json").string();
  try {
    write_summary(path, example());
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(directory_ / "run.json.tmp"));
}

}  // namespace
}  // namespace exdyn::output
