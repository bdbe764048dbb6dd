// Random edits of a valid deck are either read (and then survive the to_yaml
// round trip) or rejected with an InputError that has a position: never another
// exception, never a crash. A deterministic stand-in until the fuzzer exists.
#include <gtest/gtest.h>

#include <random>

#include "common/errors.hpp"
#include "deck_files.hpp"
#include "input/deck_reader.hpp"

namespace exdyn::input {
namespace {

TEST(DeckReaderRobustness, EditedDecksAreReadOrRejectedWithAPosition) {
  const std::string original = testing::read_text(testing::test_deck_path("decks/plate_impact.yaml"));
  const std::string alphabet = "[]{}:,-#&*!|>'\"%@` \n\t0123456789.eE+abxyz~?";
  std::mt19937 random(20261121);
  int read = 0;
  int rejected = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    std::string text = original;
    const int edits = 1 + static_cast<int>(random() % 4);
    for (int edit = 0; edit < edits && !text.empty(); ++edit) {
      const std::size_t position = random() % text.size();
      const char character = alphabet[random() % alphabet.size()];
      switch (random() % 3) {
        case 0:
          text.erase(position, 1 + random() % 3);
          break;
        case 1:
          text.insert(position, 1, character);
          break;
        default:
          text[position] = character;
          break;
      }
    }
    try {
      const Deck deck = parse_deck(text, "edited.yaml");
      ++read;
      ASSERT_EQ(parse_deck(to_yaml(deck), "edited.yaml"), deck) << text;
    } catch (const InputError& error) {
      ++rejected;
      // Only an empty document has no line to point at.
      if (error.location().line == 0) {
        EXPECT_NE(std::string(error.what()).find("empty"), std::string::npos) << error.what() << "\n" << text;
      }
    }
  }
  // Both outcomes must occur, or the edits test nothing.
  EXPECT_GT(read, 50);
  EXPECT_GT(rejected, 500);
}

}  // namespace
}  // namespace exdyn::input
