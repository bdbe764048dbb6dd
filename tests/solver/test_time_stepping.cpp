#include <gtest/gtest.h>

#include "model/model.hpp"

namespace {

TEST(TimeStepping, EndTimeOfAWholeNumberOfStepsGivesThatNumber) {
  exdyn::input::TimeOptions time;
  time.courant = 0.125;
  const double critical = 2.5e-5 / 6020.1811;
  time.end_time = 448 * 0.125 * critical * (1 + 1e-14);
  EXPECT_EQ(exdyn::solver::time_stepping(time, critical).steps, 448);
  time.end_time = 448 * 0.125 * critical * (1 - 1e-14);
  EXPECT_EQ(exdyn::solver::time_stepping(time, critical).steps, 448);
}

TEST(TimeStepping, OtherwiseTheRunEndsAtOrPastEndTime) {
  exdyn::input::TimeOptions time;
  time.dt = 1e-3;
  time.end_time = 0.0105;
  const auto stepping = exdyn::solver::time_stepping(time, 1.0);
  EXPECT_EQ(stepping.steps, 11);
  EXPECT_EQ(stepping.dt, 1e-3);
}

TEST(TimeStepping, CourantScalesTheCriticalStep) {
  exdyn::input::TimeOptions time;
  time.courant = 0.5;
  time.end_time = 1.0;
  EXPECT_DOUBLE_EQ(exdyn::solver::time_stepping(time, 0.1).dt, 0.05);
}

}  // namespace
