// Stand-alone local search cases for `exdyn project` (../shared/spec/cli.md).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "contact/search_names.hpp"

namespace exdyn::input {

struct ProjectCase {
  long id = 0;
  contact::SegmentType segment = contact::SegmentType::quad4;
  std::vector<std::array<double, 3>> nodes;  // 4 or 8 points, corners then mid-sides
  std::array<double, 3> point{};             // the slave point
  std::optional<std::array<double, 2>> initial_guess;
};

// Reads and validates a cases file; throws InputError naming the case and key.
std::vector<ProjectCase> read_project_cases(const std::string& path);
std::vector<ProjectCase> parse_project_cases(const std::string& text, const std::string& source_name);

}  // namespace exdyn::input
