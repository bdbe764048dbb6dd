// `--set KEY=VALUE`: parsed, applied to the YAML tree in order, then validated.
#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "deck_files.hpp"
#include "input/deck_reader.hpp"

namespace exdyn::input {
namespace {

using testing::test_deck_path;

Deck plate_with(const std::vector<std::string>& arguments) {
  std::vector<Override> overrides;
  for (const std::string& argument : arguments) overrides.push_back(parse_override(argument));
  return read_deck(test_deck_path("decks/plate_impact.yaml"), overrides);
}

Deck minimal_with(const std::vector<std::string>& arguments) {
  std::vector<Override> overrides;
  for (const std::string& argument : arguments) overrides.push_back(parse_override(argument));
  return read_deck(test_deck_path("decks/minimal.yaml"), overrides);
}

// The InputError thrown by `action`, or a test failure.
template <class Action>
InputError error_of(Action action) {
  try {
    action();
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("no error");
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ParseOverride, SplitsAtTheFirstEqualsSign) {
  const Override item = parse_override("parts[0].elements=[50,1,50]");
  EXPECT_EQ(item.key_path, "parts[0].elements");
  EXPECT_EQ(item.value, "[50,1,50]");
  const Override spaced = parse_override(" output.directory = a=b ");
  EXPECT_EQ(spaced.key_path, "output.directory");
  EXPECT_EQ(spaced.value, "a=b");
}

TEST(ParseOverride, ArgumentWithoutEqualsSignIsRejected) {
  const InputError error = error_of([] { parse_override("time.courant"); });
  EXPECT_EQ(error.location().file, "<command line>");
  EXPECT_TRUE(contains(error.what(), "--set time.courant")) << error.what();
  EXPECT_TRUE(contains(error.what(), "expected KEY=VALUE")) << error.what();
}

TEST(ParseOverride, EmptyKeyOrValueIsRejected) {
  EXPECT_THROW(parse_override("=0.5"), InputError);
  EXPECT_THROW(parse_override("time.courant="), InputError);
}

TEST(ParseOverride, MalformedKeyPathsAreRejected) {
  for (const char* argument : {"time..courant=1", "parts[x].elements=1", "parts[0.elements=1", ".time=1",
                               "time.=1", "parts]0[=1", "parts[0]x=1"}) {
    const InputError error = error_of([&] { parse_override(argument); });
    EXPECT_TRUE(contains(error.what(), "--set ")) << argument << ": " << error.what();
  }
}

TEST(Override, ScalarReplacesAValue) {
  const Deck deck = plate_with({"time.courant=0.5"});
  EXPECT_EQ(deck.time.courant, 0.5);
}

TEST(Override, ListReplacesAList) {
  const Deck deck = plate_with({"parts[0].elements=[50,1,50]"});
  EXPECT_EQ(deck.parts[0].elements, (std::array<int, 3>{50, 1, 50}));
  EXPECT_EQ(deck.parts[1].elements, (std::array<int, 3>{100, 1, 100}));
}

TEST(Override, ListIndexReachesIntoAList) {
  const Deck deck = plate_with({"parts[1].initial_velocity[0]=-2.5", "contact[0].local_search.method=dfp",
                                "boundary_conditions[1].fix=[x, z]"});
  EXPECT_EQ(deck.parts[1].initial_velocity, (Vec3{-2.5, 0.0, 0.0}));
  EXPECT_EQ(deck.contact[0].local_search.method, contact::SearchMethod::dfp);
  EXPECT_EQ(deck.boundary_conditions[1].fix, (std::array<bool, 3>{true, false, true}));
}

TEST(Override, MissingKeyInAnExistingMapIsCreated) {
  const Deck deck = minimal_with({"time.dt=1e-9", "parts[0].formulation=hex8r"});
  EXPECT_EQ(deck.time.dt, 1e-9);
  EXPECT_EQ(deck.parts[0].formulation, Formulation::hex8r);
}

TEST(Override, MissingSectionIsCreated) {
  const Deck deck = minimal_with({"output.every=5", "output.fields=[stress]"});
  EXPECT_EQ(deck.output.every, 5);
  EXPECT_EQ(deck.output.fields, std::vector<OutputField>{OutputField::stress});
}

TEST(Override, LaterOverridesWin) {
  EXPECT_EQ(plate_with({"time.courant=0.5", "time.courant=0.25"}).time.courant, 0.25);
}

TEST(Override, MaterialsAreAddressedByName) {
  EXPECT_EQ(plate_with({"materials.steel.density=7850"}).materials[0].density, 7850.0);
}

TEST(Override, CreatedDtConflictsWithAnExplicitCourant) {
  const InputError error = error_of([] { plate_with({"time.dt=1e-9"}); });
  EXPECT_EQ(error.key_path(), "time.dt");
  EXPECT_EQ(error.location().file, "<command line>");
  EXPECT_TRUE(contains(error.what(), "not both")) << error.what();
  EXPECT_TRUE(contains(error.what(), "--set time.dt=1e-9")) << error.what();
}

TEST(Override, InvalidValueNamesTheKeyPathAndTheOverride) {
  const InputError error = error_of([] { plate_with({"time.courant=-1"}); });
  EXPECT_EQ(error.key_path(), "time.courant");
  EXPECT_EQ(error.location().file, "<command line>");
  EXPECT_EQ(error.location().line, 0);
  EXPECT_TRUE(contains(error.what(), "expected a number > 0, got -1")) << error.what();
  EXPECT_TRUE(contains(error.what(), "--set time.courant=-1")) << error.what();
}

TEST(Override, InvalidEntryOfAnOverriddenListNamesItsIndex) {
  const InputError error = error_of([] { plate_with({"parts[0].elements=[50,0,50]"}); });
  EXPECT_EQ(error.key_path(), "parts[0].elements[1]");
  EXPECT_EQ(error.location().file, "<command line>");
}

TEST(Override, TypoInACreatedKeyIsAnUnknownKey) {
  const InputError error = error_of([] { plate_with({"time.courrant=0.5"}); });
  EXPECT_EQ(error.key_path(), "time.courrant");
  EXPECT_TRUE(contains(error.what(), "did you mean 'courant'?")) << error.what();
  EXPECT_TRUE(contains(error.what(), "--set time.courrant=0.5")) << error.what();
}

TEST(Override, IndexOutOfRangeIsRejected) {
  const InputError error = error_of([] { plate_with({"parts[3].elements=[1,1,1]"}); });
  EXPECT_EQ(error.location().file, "<command line>");
  EXPECT_TRUE(contains(error.what(), "--set parts[3].elements: index 3 is out of range: parts has 2 entries"))
      << error.what();
}

TEST(Override, PathThroughAScalarIsRejected) {
  const InputError error = error_of([] { plate_with({"time.courant.value=1"}); });
  EXPECT_TRUE(contains(error.what(), "--set time.courant.value: time.courant is the value 0.125, not a map"))
      << error.what();
}

TEST(Override, KeyIntoAListIsRejected) {
  const InputError error = error_of([] { plate_with({"parts.name=x"}); });
  EXPECT_TRUE(contains(error.what(), "--set parts.name: parts is a list of 2 entries")) << error.what();
  EXPECT_TRUE(contains(error.what(), "parts[0]")) << error.what();
}

TEST(Override, IndexIntoAMapOrAMissingListIsRejected) {
  EXPECT_TRUE(contains(error_of([] { plate_with({"time[0]=1"}); }).what(), "not a list"));
  EXPECT_TRUE(
      contains(error_of([] { minimal_with({"contact[0].name=x"}); }).what(), "contact is not in the deck"));
}

TEST(Override, ValueThatIsNotYamlIsRejected) {
  const InputError error = error_of([] { plate_with({"parts[0].elements=[1, 2"}); });
  EXPECT_TRUE(contains(error.what(), "--set parts[0].elements")) << error.what();
}

}  // namespace
}  // namespace exdyn::input
