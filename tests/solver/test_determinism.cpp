// Results do not depend on the number of threads (docs/performance.md, "Threads"):
// the plate impact run on 1, 2 and 3 threads writes the same bits in every dataset
// of NAME.h5, and the same energies and contact counts in NAME.json.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "../support/result_file.hpp"
#include "../support/temp_dir.hpp"
#include "common/errors.hpp"
#include "input/deck_reader.hpp"
#include "solver/simulation.hpp"

namespace {

using exdyn::testing::read_dataset;

// Every dataset of a file, by path ("/steps/000064/stress", ...), in name order.
std::vector<std::string> dataset_paths(const std::string& file) {
  std::vector<std::string> paths;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  if (f < 0) return paths;
  struct Visit {
    hid_t file;
    std::vector<std::string>* paths;
  } visit{f, &paths};
  H5Lvisit(
      f, H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t group, const char* name, const H5L_info_t*, void* data) -> herr_t {
        const hid_t object = H5Oopen(group, name, H5P_DEFAULT);
        if (object >= 0) {
          if (H5Iget_type(object) == H5I_DATASET)
            static_cast<Visit*>(data)->paths->push_back(std::string("/") + name);
          H5Oclose(object);
        }
        return 0;
      },
      &visit);
  H5Fclose(f);
  return paths;
}

struct ThreadedRun {
  exdyn::testing::TempDir directory{"exdyn_threads"};
  exdyn::output::RunSummary summary;
  std::string h5;
};

void run(ThreadedRun& result, const std::vector<std::string>& overrides, int threads,
         const std::string& deck_file = "plate_impact.yaml") {
  std::vector<exdyn::input::Override> parsed;
  for (const auto& o : overrides) parsed.push_back(exdyn::input::parse_override(o));
  const exdyn::input::Deck deck =
      exdyn::input::read_deck(std::string(EXDYN_SOURCE_DIR) + "/input/" + deck_file, parsed);
  exdyn::solver::RunControls controls;
  controls.output_directory = result.directory.path().string();
  controls.threads = threads;
  result.summary = exdyn::solver::run_simulation(deck, controls);
  result.h5 = result.directory.file(deck.name + ".h5");
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

void expect_same_results_on_1_2_3_threads(const std::vector<std::string>& overrides) {
  ThreadedRun one, two, three;
  run(one, overrides, 1);
  run(two, overrides, 2);
  run(three, overrides, 3);
  EXPECT_EQ(one.summary.threads, 1);
  EXPECT_EQ(two.summary.threads, 2);
  EXPECT_EQ(three.summary.threads, 3);
  const std::vector<std::string> paths = dataset_paths(one.h5);
  ASSERT_GT(paths.size(), 50u);  // mesh, time, 7 history rows, 16 steps x 7 fields
  EXPECT_EQ(dataset_paths(two.h5), paths);
  EXPECT_EQ(dataset_paths(three.h5), paths);
  for (const auto& path : paths) {
    const auto reference = read_dataset(one.h5, path).values;
    EXPECT_TRUE(same_bits(read_dataset(two.h5, path).values, reference)) << path << ", 2 threads";
    EXPECT_TRUE(same_bits(read_dataset(three.h5, path).values, reference)) << path << ", 3 threads";
  }
  for (const ThreadedRun* other : {&two, &three}) {
    EXPECT_EQ(std::memcmp(&other->summary.energy, &one.summary.energy, sizeof one.summary.energy), 0);
    EXPECT_EQ(other->summary.contact.projections, one.summary.contact.projections);
    EXPECT_EQ(other->summary.contact.mean_iterations, one.summary.contact.mean_iterations);
    EXPECT_EQ(other->summary.contact.max_penetration_over_h, one.summary.contact.max_penetration_over_h);
  }
}

TEST(Threads, PlateImpactIsTheSameBitsOnOneTwoAndThreeThreads) {
  // hex8 on the regular grid (the paired constant-Jacobian kernels), BFGS, two passes.
  expect_same_results_on_1_2_3_threads({"output.every=16", "time.end_time=1.2e-7"});
}

TEST(Threads, DistortedHex8rPlateImpactIsTheSameBitsOnOneTwoAndThreeThreads) {
  // hex8r on distorted plates (the general kernels), Newton from the previous point.
  expect_same_results_on_1_2_3_threads(
      {"output.every=16", "time.end_time=1.2e-7", "parts[0].formulation=hex8r", "parts[1].formulation=hex8r",
       "parts[0].perturbation={fraction: 0.2, seed: 1}", "parts[1].perturbation={fraction: 0.2, seed: 2}",
       "contact[0].local_search.method=newton", "contact[0].local_search.initial_guess=previous"});
}

TEST(Threads, DistortedHex8IsTheSameBitsOnOneAndTwoThreads) {
  // The general hex8 kernel (unpaired elements).
  ThreadedRun one, two;
  const std::vector<std::string> overrides{"parts[0].perturbation={fraction: 0.2, seed: 3}",
                                           "parts[1].perturbation={fraction: 0.2, seed: 4}",
                                           "time.end_time=1.0e-7", "output.every=50"};
  run(one, overrides, 1);
  run(two, overrides, 2);
  for (const auto& path : dataset_paths(one.h5))
    EXPECT_TRUE(same_bits(read_dataset(two.h5, path).values, read_dataset(one.h5, path).values)) << path;
}

TEST(Threads, LargeContactFacesAreTheSameBitsOnOneAndTwoThreads) {
  // Faces of 65 x 65 and 81 x 81 nodes (cubes of 12.5 and 15.6 um), 39 steps: the
  // contact's motion check and penalty forces run on the threads from 4096 slave
  // nodes on (contact_pass.cpp).
  ThreadedRun one, two;
  const std::vector<std::string> overrides{
      "parts[0].elements=[80,80,2]", "parts[0].box={min: [0, 0, -2.5e-5], max: [1.0e-3, 1.0e-3, 0]}",
      "parts[1].elements=[64,64,2]", "parts[1].box={min: [0, 0, 0], max: [1.0e-3, 1.0e-3, 3.125e-5]}",
      "time.end_time=2.0e-8",        "output.every=4"};
  run(one, overrides, 1, "contact_patch.yaml");
  run(two, overrides, 2, "contact_patch.yaml");
  ASSERT_GT(one.summary.contact.projections, 10000);
  for (const auto& path : dataset_paths(one.h5))
    EXPECT_TRUE(same_bits(read_dataset(two.h5, path).values, read_dataset(one.h5, path).values)) << path;
}

TEST(Threads, ErodingBarIsTheSameBitsOnOneTwoAndThreeThreads) {
  // input/tension_failure.yaml as a bar of 8 x 8 x 24 bricks (3 chunks), finite strain,
  // pulled at 100 m/s until every layer has failed: the damage pass, the failed
  // elements' energy and the eroded elements in the packs.
  const std::vector<std::string> overrides{
      "parts[0].elements=[8, 8, 24]", "parts[0].box={min: [0, 0, 0], max: [0.01, 0.01, 0.03]}",
      "parts[0].kinematics=finite",   "boundary_conditions[3].velocity={z: 100.0}",
      "time={end_time: 6.0e-5}",      "output.every=25"};
  ThreadedRun one, two, three;
  run(one, overrides, 1, "tension_failure.yaml");
  run(two, overrides, 2, "tension_failure.yaml");
  run(three, overrides, 3, "tension_failure.yaml");
  const std::vector<double> status = read_dataset(one.h5, "/steps/000200/status").values;
  EXPECT_EQ(std::count(status.begin(), status.end(), 0.0), 1536);
  const std::vector<double> middle = read_dataset(one.h5, "/steps/000125/status").values;
  const auto eroded = std::count(middle.begin(), middle.end(), 0.0);
  EXPECT_GT(eroded, 0);
  EXPECT_LT(eroded, 1536);
  for (const auto& path : dataset_paths(one.h5)) {
    const auto reference = read_dataset(one.h5, path).values;
    EXPECT_TRUE(same_bits(read_dataset(two.h5, path).values, reference)) << path << ", 2 threads";
    EXPECT_TRUE(same_bits(read_dataset(three.h5, path).values, reference)) << path << ", 3 threads";
  }
}

TEST(Threads, PunchedPlateIsTheSameBitsOnOneTwoAndThreeThreads) {
  // input/punch_through.yaml while the plug is cut out (elements erode from step 52 on):
  // the faces each erosion opens, the searches they start and the contacts that begin
  // inside a face, on the threads of the element pass and the contact pass side by side.
  const std::vector<std::string> overrides{"time.end_time=2.5e-6", "output.every=60"};
  ThreadedRun one, two, three;
  run(one, overrides, 1, "punch_through.yaml");
  run(two, overrides, 2, "punch_through.yaml");
  run(three, overrides, 3, "punch_through.yaml");
  EXPECT_GT(one.summary.energy.eroded_elements, 100);
  for (const auto& path : dataset_paths(one.h5)) {
    const auto reference = read_dataset(one.h5, path).values;
    EXPECT_TRUE(same_bits(read_dataset(two.h5, path).values, reference)) << path << ", 2 threads";
    EXPECT_TRUE(same_bits(read_dataset(three.h5, path).values, reference)) << path << ", 3 threads";
  }
}

TEST(Threads, DistortionErosionIsTheSameBitsOnOneTwoAndThreeThreads) {
  // input/perforation.yaml on a coarse plate to 40 us: time.erode takes the bricks
  // crushed beside the projectile's rim (the marks of the element pass's corner checks).
  const std::vector<std::string> overrides{"parts[1].elements=[16, 16, 4]", "parts[0].elements=[4, 2, 16]",
                                           "time.end_time=4.0e-5", "output.every=40"};
  ThreadedRun one, two, three;
  run(one, overrides, 1, "perforation.yaml");
  run(two, overrides, 2, "perforation.yaml");
  run(three, overrides, 3, "perforation.yaml");
  ASSERT_EQ(one.summary.status, "completed");
  EXPECT_GE(one.summary.energy.eroded_elements, 2);
  for (const auto& path : dataset_paths(one.h5)) {
    const auto reference = read_dataset(one.h5, path).values;
    EXPECT_TRUE(same_bits(read_dataset(two.h5, path).values, reference)) << path << ", 2 threads";
    EXPECT_TRUE(same_bits(read_dataset(three.h5, path).values, reference)) << path << ", 3 threads";
  }
}

TEST(StepsWritten, AStopBetweenOutputStepsWritesTheStressesOfItsStep) {
  // The element pass stores the stresses only at output steps; a step written by a stop
  // computes them again. Here the penetration guard stops the plate impact (at step 2:
  // the penetration is largest as the plates meet): with output.every = 1000 that is
  // no output step, with output.every = 1 it is one. Both must write it with the same bits.
  struct Stopped {
    exdyn::testing::TempDir directory{"exdyn_stop_step"};
    long step = -1;
    std::string h5;
  };
  const auto run_until_the_guard = [](Stopped& result, const std::string& every) {
    std::vector<exdyn::input::Override> parsed;
    for (const std::string o : {"time.end_time=1.2e-7", "guards.max_penetration=4.4e-5", every.c_str()})
      parsed.push_back(exdyn::input::parse_override(o));
    const exdyn::input::Deck deck =
        exdyn::input::read_deck(std::string(EXDYN_SOURCE_DIR) + "/input/plate_impact.yaml", parsed);
    exdyn::solver::RunControls controls;
    controls.output_directory = result.directory.path().string();
    try {
      exdyn::solver::run_simulation(deck, controls);
    } catch (const exdyn::RunFailure& failure) {
      result.step = failure.step();
    }
    result.h5 = result.directory.file(deck.name + ".h5");
  };
  Stopped sparse, every_step;
  run_until_the_guard(sparse, "output.every=1000");
  run_until_the_guard(every_step, "output.every=1");
  ASSERT_GT(sparse.step, 0) << "the guard did not stop the run";
  ASSERT_EQ(every_step.step, sparse.step);
  ASSERT_NE(sparse.step % 1000, 0);
  char group[32];
  std::snprintf(group, sizeof group, "/steps/%06ld", sparse.step);
  for (const char* field : {"stress", "von_mises", "velocity", "displacement", "contact_force"}) {
    const std::string path = std::string(group) + "/" + field;
    const auto expected = read_dataset(every_step.h5, path).values;
    ASSERT_FALSE(expected.empty()) << path;
    EXPECT_TRUE(same_bits(read_dataset(sparse.h5, path).values, expected)) << path;
  }
  // Not the stale stresses of step 0 (u = 0: all zero): the contact has loaded the plates.
  const auto stress = read_dataset(sparse.h5, std::string(group) + "/stress").values;
  EXPECT_TRUE(std::any_of(stress.begin(), stress.end(), [](double s) { return s != 0.0; }));
}

}  // namespace
