// libFuzzer target: the mesh import (mesh/imported.hpp) on what the Gmsh library could
// return, generated and broken by the bytes (fuzz_mesh_input.hpp). An InputError is the
// expected answer to a bad mesh; any other exception, a crash, a sanitizer report, a
// hang or a huge allocation is a finding, and so is an accepted mesh whose part breaks
// the import's promises.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string_view>

#include "fuzz_mesh_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::string problem;
  try {
    problem = exdyn::fuzz::check_mesh_input(bytes);
  } catch (const exdyn::InputError&) {
    return 0;  // rejected with a message: the expected outcome for bad input
  } catch (const std::exception& error) {
    std::fprintf(stderr, "fuzz_mesh: exception other than InputError: %s\n", error.what());
    std::abort();
  }
  if (!problem.empty()) {
    std::fprintf(stderr, "fuzz_mesh: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
