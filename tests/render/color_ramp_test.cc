// Tests of the colour ramp (render/color_ramp.h): its stops, linear
// interpolation between them, clamping, and lightness rising along it.
#include <gtest/gtest.h>

#include <cmath>

#include "shellspace/render/color_ramp.h"

namespace shellspace {
namespace {

TEST(ColorRampTest, StopsAndClamping) {
  EXPECT_TRUE(RampColor(0).isApprox(Eigen::Vector3d(0.36, 0.30, 0.62)));
  EXPECT_TRUE(RampColor(1).isApprox(Eigen::Vector3d(0.99, 0.90, 0.15)));
  EXPECT_TRUE(RampColor(0.5).isApprox(Eigen::Vector3d(0.18, 0.66, 0.62)));
  EXPECT_TRUE(RampColor(0.125).isApprox(
      0.5 * (RampColor(0) + RampColor(0.25))));
  EXPECT_EQ(RampColor(-3), RampColor(0));
  EXPECT_EQ(RampColor(7), RampColor(1));
  EXPECT_EQ(RampColor(std::nan("")), RampColor(0));
  // Lightness rises along the ramp.
  auto luminance = [](const Eigen::Vector3d& c) {
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
  };
  for (int k = 0; k < 20; ++k) {
    EXPECT_LT(luminance(RampColor(k / 20.0)), luminance(RampColor((k + 1) / 20.0)));
  }
}

}  // namespace
}  // namespace shellspace
