// libFuzzer target: the restart checkpoint reader (output/checkpoint_file.hpp) on
// arbitrary bytes, twice: as they are, and with every checksum made right, so that the
// fuzzer also reaches what lies behind the checksums (the sections' framing and lengths,
// the written position, the deck a restart compares). An InputError is the expected
// answer to bad input; any other exception, a crash, a sanitizer report, a hang or a
// huge allocation is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "input/deck_reader.hpp"
#include "output/checkpoint_file.hpp"

namespace {

const char* const deck_text = R"(name: fuzz
materials: {steel: {model: linear_elastic, density: 7850, youngs_modulus: 2.1e11, poissons_ratio: 0.3}}
parts: [{name: block, box: {min: [0, 0, 0], max: [1, 1, 1]}, elements: [1, 1, 1], material: steel}]
time: {end_time: 1.0e-5}
)";

// Rewrites each section's hash and the trailer of bytes framed as a checkpoint; leaves
// bytes that are not framed so (too short, no head) as they are.
std::vector<unsigned char> with_checksums(std::vector<unsigned char> b) {
  const std::size_t n = b.size(), trailer = 32;
  if (n < 12 + trailer || std::memcmp(b.data(), "EXDYNCKP", 8) != 0) return b;
  const std::size_t end = n - trailer;
  std::vector<unsigned char> headers;
  std::uint64_t count = 0;
  std::size_t at = 12;
  while (end - at >= 4) {
    std::uint32_t name = 0;
    std::memcpy(&name, b.data() + at, 4);
    if (name == 0 || name > 256 || end - at - 4 < std::size_t(name) + 16) break;
    std::uint64_t length = 0;
    std::memcpy(&length, b.data() + at + 4 + name, 8);
    if (length > end - at - 4 - name - 16) break;
    const std::uint64_t hash = exdyn::output::hash_bytes(b.data() + at + 4 + name + 16, length);
    std::memcpy(b.data() + at + 4 + name + 8, &hash, 8);
    headers.insert(headers.end(), b.begin() + long(at + 4), b.begin() + long(at + 4 + name + 16));
    at += 4 + name + 16 + length;
    ++count;
  }
  const std::uint64_t total = n, hash = exdyn::output::hash_bytes(headers.data(), headers.size());
  std::memcpy(b.data() + end, "EXDYNEND", 8);
  std::memcpy(b.data() + end + 8, &count, 8);
  std::memcpy(b.data() + end + 16, &total, 8);
  std::memcpy(b.data() + end + 24, &hash, 8);
  return b;
}

// What a restart reads of a checkpoint before it reads the state.
void read(std::vector<unsigned char> bytes) {
  static const exdyn::input::Deck deck = exdyn::input::parse_deck(deck_text, "fuzz.yaml");
  try {
    const exdyn::output::CheckpointReader reader(std::move(bytes), "fuzz.restart");
    (void)exdyn::output::read_position(reader);
    if (reader.has("next_step")) (void)reader.value<long>("next_step");
    if (reader.has("state/displacement.x")) (void)reader.values<double>("state/displacement.x", 8);
    if (reader.has("deck")) {
      try {
        (void)exdyn::input::restart_difference(reader.text("deck"), deck);
      } catch (const exdyn::InputError&) {
        throw;
      } catch (const std::exception&) {
        // A deck text that is not YAML: the restart refuses it as "cannot be read".
      }
    }
  } catch (const exdyn::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<unsigned char> bytes(data, data + size);
  try {
    read(bytes);
    read(with_checksums(bytes));
  } catch (const std::exception& error) {
    std::fprintf(stderr, "fuzz_checkpoint: exception other than InputError: %s\n", error.what());
    std::abort();
  }
  return 0;
}
