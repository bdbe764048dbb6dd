// The mesh size check (model/memory_estimate.hpp, docs/input.md "Mesh size"):
// the estimate counts what a run holds, and a deck too large for the machine or
// for 32-bit indices is refused as bad input before its mesh is allocated.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <climits>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "../support/run_exdyn.hpp"
#include "../support/temp_dir.hpp"
#include "common/errors.hpp"
#include "input/deck_reader.hpp"
#include "model/memory_estimate.hpp"
#include "model/model.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define EXDYN_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define EXDYN_TEST_UNDER_ASAN 1
#endif
#endif

namespace exdyn::solver {
namespace {

constexpr std::uint64_t gib = std::uint64_t(1) << 30;

// A deck text of box parts with these element counts (one material, hex8).
std::string deck_text(const std::vector<std::string>& element_lists) {
  std::string text =
      "name: sized\n"
      "materials:\n"
      "  steel: {model: linear_elastic, density: 7800, youngs_modulus: 2.1e11, poissons_ratio: 0.3}\n"
      "parts:\n";
  for (std::size_t p = 0; p < element_lists.size(); ++p)
    text += "  - {name: part" + std::to_string(p) + ", box: {min: [" + std::to_string(2 * p) +
            ", 0, 0], max: [" + std::to_string(2 * p + 1) + ", 1, 1]}, elements: " + element_lists[p] +
            ", material: steel}\n";
  // One step (end_time below the stable step), the step-0 output and the last.
  text += "time: {end_time: 1.0e-9}\n";
  return text;
}

input::Deck deck_of(const std::vector<std::string>& element_lists) {
  return input::parse_deck(deck_text(element_lists), "sized.yaml");
}

TEST(MemoryEstimate, MatchesAHandCountOfNodesAndElements) {
  // 10 x 8 x 6 and 5 x 5 x 5: 11*9*7 + 6*6*6 = 909 nodes, 480 + 125 = 605 elements.
  const MemoryEstimate estimate = estimate_memory(deck_of({"[10, 8, 6]", "[5, 5, 5]"}));
  EXPECT_EQ(estimate.nodes, 909u);
  EXPECT_EQ(estimate.elements, 605u);
  // 42 doubles per node; 8 ids + part + 10 + 14 doubles + 8 int64 per element.
  EXPECT_EQ(bytes_per_node, 336u);
  EXPECT_EQ(bytes_per_element(input::PartOptions{}), 292u);
  EXPECT_DOUBLE_EQ(estimate.bytes, 909.0 * 336.0 + 605.0 * 292.0);
}

TEST(MemoryEstimate, ADistortedPartCountsTheGeneralKernelsReferenceData) {
  input::PartOptions part;
  part.perturbation_fraction = 0.1;
  part.formulation = input::Formulation::hex8;
  EXPECT_EQ(bytes_per_element(part), 212u + 81u * 8u);  // 2x2x2 Gauss points
  part.formulation = input::Formulation::hex8r;
  EXPECT_EQ(bytes_per_element(part), 212u + 59u * 8u);
  part.perturbation_fraction = 0.0;  // a regular box: the parallelepiped kernel, its 4 hourglass matrices
  EXPECT_EQ(bytes_per_element(part), 212u + 34u * 8u);
}

TEST(MemoryEstimate, ASurfaceThatFollowsErosionCountsItsPartsSharedFaces) {
  // input/punch_through.yaml: its plate (24 x 24 x 8 = 4,608 bricks) can fail; the rod cannot.
  const input::Deck deck = input::read_deck(std::string(EXDYN_SOURCE_DIR) + "/input/punch_through.yaml");
  input::Deck kept = deck;
  kept.contact.clear();
  EXPECT_DOUBLE_EQ(estimate_memory(deck).bytes - estimate_memory(kept).bytes, 4608.0 * 3072.0);
}

TEST(MemoryEstimate, CoversTheArraysOfTheBuiltModel) {
  for (const double fraction : {0.0, 0.1}) {  // regular boxes, then distorted (the general kernels)
    SCOPED_TRACE("perturbation fraction " + std::to_string(fraction));
    input::Deck deck = deck_of({"[10, 8, 6]", "[5, 5, 5]"});
    for (auto& part : deck.parts) part.perturbation_fraction = fraction;
    const Model model = build_model(deck);
    ASSERT_EQ(model.mesh.node_count(), 909u);
    ASSERT_EQ(model.mesh.element_count(), 605u);
    // The model is part of the run's memory: the estimate must hold at least its arrays.
    double model_bytes =
        8.0 * double(model.mesh.x_ref.x.capacity() + model.mesh.x_ref.y.capacity() +
                     model.mesh.x_ref.z.capacity() + model.mass.capacity() + model.inverse_mass.capacity());
    model_bytes += 4.0 * double(model.mesh.connectivity.capacity() + model.mesh.element_part.capacity());
    for (const auto& block : model.blocks) model_bytes += 8.0 * double(block.reference.capacity());
    const MemoryEstimate estimate = estimate_memory(deck);
    EXPECT_GT(estimate.bytes, model_bytes);
    EXPECT_LT(estimate.bytes, 8.0 * model_bytes);  // the model is over an eighth of a run
  }
}

TEST(MemoryEstimate, CountsOfIntMaxElementsSaturateWithoutOverflow) {
  const std::string n = std::to_string(INT_MAX);
  const MemoryEstimate estimate =
      estimate_memory(deck_of({"[" + n + ", " + n + ", " + n + "]", "[1, 1, 1]"}));
  EXPECT_EQ(estimate.nodes, std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(estimate.elements, std::numeric_limits<std::uint64_t>::max());
  EXPECT_GT(estimate.bytes, 1e30);  // (2^31)^3 elements
}

TEST(MemoryEstimate, ReadsMemAvailableFromMeminfo) {
  testing::TempDir directory;
  std::ofstream(directory.file("meminfo")) << "MemTotal:       32000000 kB\n"
                                              "MemFree:         1000000 kB\n"
                                              "MemAvailable:   20000000 kB\n";
  EXPECT_EQ(available_memory(directory.file("meminfo")), std::uint64_t(20000000) * 1024);
  std::ofstream(directory.file("old_kernel")) << "MemTotal:       32000000 kB\nMemFree:  1000 kB\n";
  EXPECT_EQ(available_memory(directory.file("old_kernel")), std::nullopt);
  EXPECT_EQ(available_memory(directory.file("missing")), std::nullopt);
  // The machine's, when it has one, is positive.
  if (const auto available = available_memory()) {
    EXPECT_GT(*available, 0u);
  }
}

TEST(MemoryEstimate, ASmallDeckPassesTheCheck) {
  EXPECT_NO_THROW(check_mesh_size(deck_of({"[10, 8, 6]"}), 1 * gib));
  EXPECT_NO_THROW(check_mesh_size(deck_of({"[10, 8, 6]"}), std::nullopt));
  EXPECT_NO_THROW(check_mesh_size(deck_of({"[10, 8, 6]"})));
}

TEST(MemoryEstimate, ADeckLargerThanTheAvailableMemoryIsRefused) {
  // 1000^3 elements: about 586 GiB (1003004332 nodes x 336 B + 1000001000 elements x 292 B), within the
  // 32-bit limits.
  const input::Deck deck = deck_of({"[10, 10, 10]", "[1000, 1000, 1000]"});
  try {
    check_mesh_size(deck, 16 * gib);
    FAIL() << "no InputError";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(error.key_path(), "parts");
    EXPECT_NE(message.find("sized.yaml"), std::string::npos) << message;
    EXPECT_NE(message.find("parts[1] 'part1' 1000 x 1000 x 1000 = 1000000000 elements"), std::string::npos)
        << message;
    EXPECT_NE(message.find("parts[0] 'part0' 10 x 10 x 10 = 1000 elements"), std::string::npos) << message;
    EXPECT_NE(message.find("about 586 GiB of memory"), std::string::npos) << message;
    EXPECT_NE(message.find("16 GiB are available"), std::string::npos) << message;
    EXPECT_EQ(message.find("32-bit"), std::string::npos) << message;
  }
  // Without a known available memory only the index limits apply.
  EXPECT_NO_THROW(check_mesh_size(deck, std::nullopt));
}

// On many ranks the check is this machine's share: 4 of 8 ranks here need half the
// estimate, whatever the parts (a perturbed box and a ball are set up by numbers too).
TEST(MemoryEstimate, OnManyRanksTheCheckIsThisMachinesShare) {
  input::Deck deck = deck_of({"[100, 100, 100]", "[50, 50, 50]"});
  deck.parts[1].perturbation_fraction = 0.1;
  const double share = estimate_memory(deck).bytes * 4.0 / 8.0;
  EXPECT_NO_THROW(check_mesh_size(deck, std::uint64_t(share) + 1, {8, 4}));
  try {
    check_mesh_size(deck, std::uint64_t(share) - 1, {8, 4});
    FAIL() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("the 4 of its 8 ranks on this machine would need about"),
              std::string::npos)
        << error.what();
  }
}

TEST(MemoryEstimate, MoreNodesThan32BitIndicesAreRefusedWhateverTheMemory) {
  // 1700^3 = 4.9e9 elements and nodes: over 2^32 nodes.
  const input::Deck deck = deck_of({"[1700, 1700, 1700]"});
  for (const std::optional<std::uint64_t> available :
       {std::optional<std::uint64_t>(), std::optional<std::uint64_t>(UINT64_MAX)}) {
    try {
      check_mesh_size(deck, available);
      FAIL() << "no InputError";
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("4294967295 nodes"), std::string::npos) << message;
      EXPECT_NE(message.find("32-bit"), std::string::npos) << message;
      EXPECT_NE(message.find("1700 x 1700 x 1700 = 4913000000 elements"), std::string::npos) << message;
    }
  }
}

TEST(MemoryEstimate, BuildModelRefusesBeforeAllocating) {
  // A 10^15-element mesh would need about 437 PiB: reaching the allocator would fail.
  EXPECT_THROW(build_model(deck_of({"[100000, 100000, 100000]"})), InputError);
}

// Through the executable: exit status 2, the message, and no output directory.
TEST(MemoryEstimate, AHugeDeckExitsWithStatus2AndWritesNothing) {
  testing::TempDir directory;
  std::ofstream(directory.file("huge.yaml")) << deck_text({"[100000, 100000, 100000]"});
  const std::string output = directory.file("results");
  const testing::CommandResult result =
      testing::run_exdyn("run " + directory.file("huge.yaml") + " --output " + output);
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("100000 x 100000 x 100000 = 1000000000000000 elements"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("the run would need about"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("available"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(output));

  // The same through --set on a valid deck.
  const testing::CommandResult set =
      testing::run_exdyn("run " + std::string(EXDYN_SOURCE_DIR) + "/input/wave_bar.yaml --output " + output +
                         " --set 'parts[0].elements=[100000,100000,100000]'");
  EXPECT_EQ(set.status, 2) << set.output;
  EXPECT_NE(set.output.find("parts[0]"), std::string::npos) << set.output;
  EXPECT_FALSE(std::filesystem::exists(output));
}

TEST(MemoryEstimate, ADeckOverTheMachinesMemoryExitsWithStatus2) {
  // 1200^3 elements: within the 32-bit limits, about 793 GiB.
  const input::Deck deck = deck_of({"[1200, 1200, 1200]"});
  const std::optional<std::uint64_t> available = available_memory();
  if (!available || double(*available) >= estimate_memory(deck).bytes)
    GTEST_SKIP() << "MemAvailable unknown or larger than the deck's estimate";
  testing::TempDir directory;
  std::ofstream(directory.file("large.yaml")) << deck_text({"[1200, 1200, 1200]"});
  const std::string output = directory.file("results");
  const testing::CommandResult result =
      testing::run_exdyn("run " + directory.file("large.yaml") + " --output " + output);
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("are available (MemAvailable)"), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find("32-bit"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(output));
}

// The estimate against the measured peak memory of real runs: the growth of the
// executable's peak resident set from a 1-element deck to a 48^3 one (about
// 56 MB estimated) is within a factor of 2 of the estimated growth.
TEST(MemoryEstimate, IsWithinAFactorOf2OfTheMeasuredPeakMemoryOfARun) {
#ifdef EXDYN_TEST_UNDER_ASAN
  GTEST_SKIP() << "AddressSanitizer's allocator and shadow memory change the resident set";
#endif
  testing::TempDir directory;
  // Peak resident set (kB on Linux) of the waited-for children so far: the
  // largest child's, so the small run goes first.
  auto run_peak_kb = [&](const std::string& elements) {
    const std::string deck = directory.file("deck" + std::to_string(elements.size()) + ".yaml");
    std::ofstream(deck) << deck_text({elements});
    const testing::CommandResult result =
        testing::run_exdyn("run " + deck + " --quiet --output " + directory.file("out"));
    EXPECT_EQ(result.status, 0) << result.output;
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    return double(usage.ru_maxrss);
  };
  const double small_kb = run_peak_kb("[1, 1, 1]");
  const double large_kb = run_peak_kb("[48, 48, 48]");
  const double measured = 1024.0 * (large_kb - small_kb);
  const double estimated =
      estimate_memory(deck_of({"[48, 48, 48]"})).bytes - estimate_memory(deck_of({"[1, 1, 1]"})).bytes;
  RecordProperty("measured_bytes", std::to_string(measured));
  RecordProperty("estimated_bytes", std::to_string(estimated));
  EXPECT_GT(measured, 0.5 * estimated) << "measured " << measured << " B, estimated " << estimated << " B";
  EXPECT_LT(measured, 2.0 * estimated) << "measured " << measured << " B, estimated " << estimated << " B";
}

}  // namespace
}  // namespace exdyn::solver
