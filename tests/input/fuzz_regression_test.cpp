// The inputs of tests/fuzz/regressions/ (what scripts/fuzz.sh found, once fixed)
// and tests/fuzz/seeds/ (hand-written edge cases) through the readers, the way
// the fuzz targets run them (tests/fuzz/fuzz_inputs.hpp): each is read, keeping
// the reader's promises, or rejected with an InputError; nothing else. This runs
// them in the GCC builds too, where the fuzz targets (clang) are not built.
#include <gtest/gtest.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../fuzz/fuzz_inputs.hpp"
#include "common/errors.hpp"

namespace exdyn::input {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> files_of(const std::string& folder) {
  std::vector<fs::path> files;
  const fs::path path = fs::path(EXDYN_SOURCE_DIR) / "tests" / "fuzz" / folder;
  if (!fs::is_directory(path)) return files;
  for (const fs::directory_entry& entry : fs::directory_iterator(path))
    if (entry.is_regular_file() && entry.path().filename().string().front() != '.')  // not .gitkeep
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

// Runs `check` on every file of the folders; returns how many were read.
template <class Check>
int expect_read_or_rejected(const std::vector<std::string>& folders, Check check, int& rejected) {
  int read = 0;
  for (const std::string& folder : folders)
    for (const fs::path& file : files_of(folder)) {
      SCOPED_TRACE(file.string());
      try {
        const std::string problem = check(read_bytes(file));
        EXPECT_EQ(problem, "");
        ++read;
      } catch (const InputError& error) {
        ++rejected;
        EXPECT_NE(std::string(error.what()), "");
      } catch (const std::exception& error) {
        ADD_FAILURE() << "an exception other than InputError: " << error.what();
      }
    }
  return read;
}

TEST(FuzzRegressions, DeckInputsAreReadOrRejectedWithAnInputError) {
  int rejected = 0;
  const int read =
      expect_read_or_rejected({"regressions/deck", "seeds/deck"}, fuzz::check_deck_input, rejected);
  EXPECT_GT(rejected, 0) << "no inputs under tests/fuzz/{regressions,seeds}/deck";
  EXPECT_GT(read, 0) << "seeds/deck holds valid decks (good_override.yaml, huge_elements.yaml)";
}

TEST(FuzzRegressions, CasesInputsAreReadOrRejectedWithAnInputError) {
  int rejected = 0;
  const int read =
      expect_read_or_rejected({"regressions/cases", "seeds/cases"}, fuzz::check_cases_input, rejected);
  EXPECT_GT(read + rejected, 0) << "no inputs under tests/fuzz/{regressions,seeds}/cases";
  // Past findings: a list or a map as a key stopped the reader with yaml-cpp's
  // "bad conversion" instead of an InputError.
  EXPECT_GE(files_of("regressions/cases").size(), 2u);
}

// The "#set KEY=VALUE" lines at the start of a fuzzed deck are overrides.
TEST(FuzzRegressions, SetLinesAtTheStartOfADeckAreOverrides) {
  const fuzz::DeckInput split =
      fuzz::split_deck_input("#set time.courant=0.5\n#set a=1\nname: x\n#set b=2\n");
  ASSERT_EQ(split.set_arguments.size(), 2u);
  EXPECT_EQ(split.set_arguments[0], "time.courant=0.5");
  EXPECT_EQ(split.set_arguments[1], "a=1");
}

}  // namespace
}  // namespace exdyn::input
