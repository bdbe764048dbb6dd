// Small text helpers for input messages: "did you mean" suggestions, lists, and
// numbers written so that they read back to the same double.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace exdyn::input {

// Optimal string alignment distance: insertions, deletions, substitutions and
// swaps of two neighbours each cost 1 ("densty" -> "density" is 1, "bgfs" -> "bfgs" is 1).
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate nearest to `word`, if it is close enough to be a likely typo:
// at most one edit per three characters of the longer word (at least one), and
// not a rewrite of every character.
std::optional<std::string> nearest_name(std::string_view word, const std::vector<std::string>& candidates);

// "; did you mean 'density'?" when a candidate is close, else "; <list_intro> a, b, c".
std::string suggestion(std::string_view word, const std::vector<std::string>& candidates,
                       std::string_view list_intro);

std::string join(const std::vector<std::string>& words, std::string_view separator);

// Shortest text that reads back to exactly `value` (std::to_chars), e.g. 0.3, 2.1e+11.
std::string format_number(double value);

}  // namespace exdyn::input
