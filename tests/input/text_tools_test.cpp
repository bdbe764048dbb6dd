#include "input/text_tools.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace exdyn::input {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(edit_distance("density", "density"), 0u);
  EXPECT_EQ(edit_distance("densty", "density"), 1u);
  EXPECT_EQ(edit_distance("bgfs", "bfgs"), 1u);
  EXPECT_EQ(edit_distance("hex20", "hex8"), 2u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

TEST(NearestName, SuggestsOnlyCloseNames) {
  const std::vector<std::string> keys{"end_time", "courant", "dt"};
  EXPECT_EQ(nearest_name("courrant", keys), "courant");
  EXPECT_EQ(nearest_name("endtime", keys), "end_time");
  EXPECT_FALSE(nearest_name("frequency", keys).has_value());
  EXPECT_EQ(suggestion("frequency", keys, "the keys are"), "; the keys are end_time, courant, dt");
  EXPECT_EQ(suggestion("dtt", keys, "the keys are"), "; did you mean 'dt'?");
}

TEST(FormatNumber, ReadsBackToTheSameDouble) {
  for (const double value :
       {0.3, 2.1e11, 1.0 / 3.0, 2.32551069659978e-7, -0.0025, 1e-300, std::numeric_limits<double>::max()}) {
    const std::string text = format_number(value);
    EXPECT_EQ(std::stod(text), value) << text;
  }
  EXPECT_EQ(format_number(0.3), "0.3");
  EXPECT_EQ(format_number(7800.0), "7800");
}

}  // namespace
}  // namespace exdyn::input
