// Test helper: runs a deck in a temporary directory and reads its results back.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "input/deck_reader.hpp"
#include "result_file.hpp"
#include "solver/simulation.hpp"
#include "temp_dir.hpp"

namespace exdyn::testing {

struct DeckRun {
  TempDir directory{"exdyn_run"};
  input::Deck deck;
  output::RunSummary summary;

  explicit DeckRun(input::Deck d) : deck(std::move(d)) {
    solver::RunControls controls;
    controls.output_directory = directory.path().string();
    summary = solver::run_simulation(deck, controls);
  }
  // file: a deck of input/, or a path from the source directory (scripts/decks/...).
  explicit DeckRun(const std::string& file, const std::vector<input::Override>& overrides = {})
      : DeckRun(input::read_deck(source_path(file), overrides)) {}

  static std::string source_path(const std::string& file) {
    return std::string(EXDYN_SOURCE_DIR) + (file.find('/') == std::string::npos ? "/input/" : "/") + file;
  }
  std::string h5() const { return directory.file(deck.name + ".h5"); }
  // A field of a written step, and of the last one.
  std::vector<double> at(long step, const std::string& field) const {
    return read_dataset(h5(), step_path(step, field)).values;
  }
  std::vector<double> final(const std::string& field) const { return at(summary.steps, field); }
  // /history/NAME
  std::vector<double> history(const std::string& name) const {
    return read_dataset(h5(), "/history/" + name).values;
  }
};

}  // namespace exdyn::testing
