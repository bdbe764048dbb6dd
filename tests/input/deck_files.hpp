// Paths of the test decks under tests/input/, and reading them as text.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

namespace exdyn::input::testing {

inline std::string test_deck_path(const std::string& relative) {
  return std::string(EXDYN_SOURCE_DIR) + "/tests/input/" + relative;
}

inline std::string read_text(const std::string& path) {
  std::ifstream file(path);
  std::ostringstream content;
  content << file.rdbuf();
  return content.str();
}

}  // namespace exdyn::input::testing
