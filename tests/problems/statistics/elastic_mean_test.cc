// The far inputs of an elastic mean: the median of the energies W[S_i, s]
// and the inputs far above it, on lists of energies given here.
#include <gtest/gtest.h>

#include <vector>

#include "shellspace/problems/statistics/elastic_mean.h"

namespace shellspace {
namespace {

TEST(ElasticMeanTest, FarInputsAreTheOutliersOfTheMeanEnergies) {
  EXPECT_DOUBLE_EQ(Median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(Median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_EQ(FarInputs({0.05, 0.04, 2.0, 0.06}), std::vector<int>({2}));
  EXPECT_EQ(FarInputs({0.05, 0.04, 0.3, 0.06}), std::vector<int>());
  EXPECT_EQ(FarInputs({0.05, 0.04, 0.3, 0.06}, 5.0), std::vector<int>({2}));
  EXPECT_EQ(FarInputs({0.05, 2.0}), std::vector<int>());  // too few
  EXPECT_EQ(FarInputs({0.0, 0.0, 1.0}), std::vector<int>());  // zero median
}

}  // namespace
}  // namespace shellspace
