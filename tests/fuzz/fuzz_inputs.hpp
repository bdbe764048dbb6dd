// What the fuzz targets (tests/fuzz/fuzz_*.cpp) and the regression test
// (tests/input/fuzz_regression_test.cpp) do with one input, so that a file of
// tests/fuzz/regressions/ is checked the same way by both.
//
// An input is either read or rejected with an InputError: that is the contract.
// Any other exception propagates to the caller (a finding). A read input must
// also keep the readers' promises; the returned text names a broken one (empty:
// all kept).
#pragma once

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.hpp"
#include "input/deck_reader.hpp"
#include "input/project_cases.hpp"

namespace exdyn::fuzz {

inline constexpr const char* fuzz_source_name = "fuzz.yaml";

// Deck inputs may start with lines "#set KEY=VALUE" (YAML comments, so the deck
// reads the same without them): each becomes a `--set` override, so that the
// override parser and the tree edits are fuzzed too.
struct DeckInput {
  std::vector<std::string> set_arguments;
  std::string text;
};

inline DeckInput split_deck_input(std::string_view bytes) {
  DeckInput result;
  constexpr std::string_view prefix = "#set ";
  std::size_t position = 0;
  while (bytes.substr(position, prefix.size()) == prefix) {
    const std::size_t end = bytes.find('\n', position);
    const std::size_t line_end = end == std::string_view::npos ? bytes.size() : end;
    result.set_arguments.emplace_back(
        bytes.substr(position + prefix.size(), line_end - position - prefix.size()));
    position = end == std::string_view::npos ? bytes.size() : end + 1;
  }
  result.text = std::string(bytes);  // the #set lines stay: they are comments
  return result;
}

// Reads a deck; if it is valid, checks that to_yaml reads back to the same Deck
// (deck_reader.hpp's promise). Throws InputError when the input is rejected.
inline std::string check_deck_input(std::string_view bytes) {
  const DeckInput split = split_deck_input(bytes);
  std::vector<input::Override> overrides;
  for (const std::string& argument : split.set_arguments)
    overrides.push_back(input::parse_override(argument));
  const input::Deck deck = input::parse_deck(split.text, fuzz_source_name, overrides);
  const std::string resolved = input::to_yaml(deck);
  try {
    if (!(input::parse_deck(resolved, fuzz_source_name) == deck))
      return "to_yaml of the deck reads back to a different deck:\n" + resolved;
  } catch (const InputError& error) {
    return "to_yaml of the deck does not read back: " + std::string(error.what()) + "\n" + resolved;
  }
  return {};
}

// Reads a cases file; if it is valid, checks what project_cases.hpp promises:
// 4 points for quad4, 8 for quad8, every coordinate finite. Throws InputError
// when the input is rejected.
inline std::string check_cases_input(std::string_view bytes) {
  const std::vector<input::ProjectCase> cases =
      input::parse_project_cases(std::string(bytes), fuzz_source_name);
  for (const input::ProjectCase& c : cases) {
    const std::size_t expected = c.segment == contact::SegmentType::quad4 ? 4 : 8;
    if (c.nodes.size() != expected)
      return "case " + std::to_string(c.id) + " has " + std::to_string(c.nodes.size()) + " nodes";
    bool finite = std::isfinite(c.point[0]) && std::isfinite(c.point[1]) && std::isfinite(c.point[2]);
    for (const auto& node : c.nodes)
      for (const double value : node) finite = finite && std::isfinite(value);
    if (c.initial_guess)
      finite = finite && std::isfinite((*c.initial_guess)[0]) && std::isfinite((*c.initial_guess)[1]);
    if (!finite) return "case " + std::to_string(c.id) + " has a non-finite value";
  }
  return {};
}

}  // namespace exdyn::fuzz
