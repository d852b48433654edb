// The step-energy ratio of a path (max over min of its step energies, the
// measure of uneven steps) on lists of energies given here.
#include <gtest/gtest.h>

#include <cmath>

#include "shellspace/problems/calculus/geodesic.h"

namespace shellspace {
namespace {

TEST(StepEnergyRatioTest, MaxOverMin) {
  EXPECT_EQ(StepEnergyRatio({}), 1.0);
  EXPECT_EQ(StepEnergyRatio({3.0}), 1.0);
  EXPECT_EQ(StepEnergyRatio({1.0, 4.0, 2.0}), 4.0);
  EXPECT_EQ(StepEnergyRatio({0.0, 0.0}), 1.0);
  EXPECT_EQ(StepEnergyRatio({0.0, 1.0}), HUGE_VAL);
}

}  // namespace
}  // namespace shellspace
