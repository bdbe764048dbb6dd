// Reads and validates a deck (../shared/spec/input-deck.md). The only place,
// with project_cases.cpp, that touches the YAML library.
#pragma once

#include <string>
#include <vector>

#include "input/options.hpp"

namespace exdyn::input {

// One `--set KEY=VALUE` override, e.g. {"time.courant", "0.5"} or
// {"parts[0].elements", "[50,1,50]"}. VALUE is parsed as YAML.
struct Override {
  std::string key_path;
  std::string value;
};

// Parses "KEY=VALUE"; throws InputError on a malformed argument.
Override parse_override(const std::string& argument);

// Reads the deck at `path`, applies the overrides in order, validates every key
// and returns the options with every default filled in.
// Throws InputError (file, line, column, key path, what was expected) on bad input.
Deck read_deck(const std::string& path, const std::vector<Override>& overrides = {});

// The same from text in memory (`source_name` is used in messages).
Deck parse_deck(const std::string& text, const std::string& source_name,
                const std::vector<Override>& overrides = {});

// The resolved deck as YAML, every default filled in (`exdyn check`). Reading
// this text back gives the same Deck.
std::string to_yaml(const Deck& deck);

// What a restart may not change (docs/output.md, "Checkpoints"): the key path of the
// first value in which `deck` differs from `saved` (to_yaml of the deck a checkpoint
// was written by), with its two values; empty when they agree everywhere but in
// time.end_time, output and checkpoint, which a restart may change.
std::string restart_difference(const std::string& saved, const Deck& deck);

}  // namespace exdyn::input
