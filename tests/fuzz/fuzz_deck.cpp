// libFuzzer target: the deck reader (input/deck_reader.hpp) on arbitrary bytes,
// with "#set KEY=VALUE" lines at the start as --set overrides (fuzz_inputs.hpp).
// An InputError is the expected answer to bad input; any other exception, a
// crash, a sanitizer report, a hang or a huge allocation is a finding, and so is
// a valid deck whose to_yaml does not read back to the same deck.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string_view>

#include "fuzz_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::string problem;
  try {
    problem = exdyn::fuzz::check_deck_input(bytes);
  } catch (const exdyn::InputError&) {
    return 0;  // rejected with a message: the expected outcome for bad input
  } catch (const std::exception& error) {
    std::fprintf(stderr, "fuzz_deck: exception other than InputError: %s\n", error.what());
    std::abort();
  }
  if (!problem.empty()) {
    std::fprintf(stderr, "fuzz_deck: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
