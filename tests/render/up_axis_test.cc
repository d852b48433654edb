// Tests of the up axis (render/up_axis.h): parsing, the rotation that takes
// each axis to +y and the camera frame it gives (camera.h ViewFrame).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "shellspace/render/camera.h"
#include "shellspace/render/up_axis.h"
#include "shellspace/render/view.h"

namespace shellspace {
namespace {

TEST(UpAxisTest, ParsesTheSignedAxesAndAuto) {
  EXPECT_EQ(ParseUpAxis("auto"), UpAxis::kAuto);
  EXPECT_EQ(ParseUpAxis("x"), UpAxis::kPlusX);
  EXPECT_EQ(ParseUpAxis("+Y"), UpAxis::kPlusY);
  EXPECT_EQ(ParseUpAxis(" -z "), UpAxis::kMinusZ);
  EXPECT_EQ(ParseUpAxis("-x"), UpAxis::kMinusX);
  for (UpAxis axis : {UpAxis::kAuto, UpAxis::kPlusX, UpAxis::kMinusX,
                      UpAxis::kPlusY, UpAxis::kMinusY, UpAxis::kPlusZ,
                      UpAxis::kMinusZ}) {
    EXPECT_EQ(ParseUpAxis(UpAxisName(axis)), axis) << UpAxisName(axis);
  }
  for (const char* bad : {"", "w", "xy", "--x", "up", "+-y", "1"}) {
    EXPECT_THROW(ParseUpAxis(bad), InputError) << bad;
  }
}

TEST(UpAxisTest, RotationTakesTheAxisToPlusY) {
  for (UpAxis axis : {UpAxis::kPlusX, UpAxis::kMinusX, UpAxis::kPlusY,
                      UpAxis::kMinusY, UpAxis::kPlusZ, UpAxis::kMinusZ}) {
    const Eigen::Matrix3d r = UpRotation(axis);
    EXPECT_TRUE((r * UpDirection(axis)).isApprox(Eigen::Vector3d::UnitY()))
        << UpAxisName(axis);
    EXPECT_DOUBLE_EQ(r.determinant(), 1) << UpAxisName(axis);
    EXPECT_TRUE((r * r.transpose()).isIdentity(0)) << UpAxisName(axis);
  }
  EXPECT_TRUE(UpRotation(UpAxis::kPlusY).isIdentity(0));
  // +x and -x keep +z towards a front viewer.
  EXPECT_EQ(UpRotation(UpAxis::kPlusX) * Eigen::Vector3d::UnitZ(),
            Eigen::Vector3d::UnitZ());
  EXPECT_THROW(UpRotation(UpAxis::kAuto), std::invalid_argument);
}

TEST(UpAxisTest, ViewFrameOfZUpLooksAlongPlusY) {
  Eigen::Vector3d right, up, forward;
  ViewFrame(ParseView("front"), UpAxis::kPlusZ, &right, &up, &forward);
  EXPECT_EQ(forward, Eigen::Vector3d::UnitY());
  EXPECT_EQ(up, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(right, Eigen::Vector3d::UnitX());
  // The azimuth turns about the up axis: side looks along -x.
  ViewFrame(ParseView("side"), UpAxis::kPlusZ, &right, &up, &forward);
  EXPECT_TRUE(forward.isApprox(-Eigen::Vector3d::UnitX()));
  EXPECT_TRUE(up.isApprox(Eigen::Vector3d::UnitZ()));
  // And kPlusY is the plain view frame, bit for bit.
  Eigen::Vector3d r0, u0, f0;
  ViewFrame(ViewAngles{37, -21}, &r0, &u0, &f0);
  ViewFrame(ViewAngles{37, -21}, UpAxis::kPlusY, &right, &up, &forward);
  EXPECT_EQ(right, r0);
  EXPECT_EQ(up, u0);
  EXPECT_EQ(forward, f0);
}

}  // namespace
}  // namespace shellspace
