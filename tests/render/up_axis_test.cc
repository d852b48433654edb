// Tests of the up axis (render/up_axis.h): parsing, the rotation that takes
// each axis to +y, the camera frame it gives (camera.h ViewFrame) and the
// automatic choice from the vertices.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/render/camera.h"
#include "shellspace/render/up_axis.h"
#include "shellspace/render/view.h"
#include "tests/testing/render_fixtures.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::Box;
using testing::UnitSquareMesh;

using ::shellspace::testing::LoadData;

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

TEST(UpAxisTest, AutoPicksTheLongAxisWithItsPlusEndUp) {
  EXPECT_EQ(AutoUpAxis(Box(1, 1, 5).positions), UpAxis::kPlusZ);
  EXPECT_EQ(AutoUpAxis(Box(1, 5, 1).positions), UpAxis::kPlusY);
  EXPECT_EQ(AutoUpAxis(Box(5, 1, 1).positions), UpAxis::kPlusX);
  // Moved and mirrored, the same axis (without faces the sign is never
  // chosen).
  Positions mirrored = Box(1, 1, 5).positions;
  mirrored.col(2) = -mirrored.col(2).array() - 100;
  EXPECT_EQ(AutoUpAxis(mirrored), UpAxis::kPlusZ);
  // No clear long axis: +y.
  EXPECT_EQ(AutoUpAxis(Box(1, 1, 1).positions), UpAxis::kPlusY);
  EXPECT_EQ(AutoUpAxis(UnitSquareMesh().positions), UpAxis::kPlusY);
  EXPECT_EQ(AutoUpAxis(Box(3, 3, 1).positions), UpAxis::kPlusY);
  EXPECT_EQ(AutoUpAxis(Positions(0, 3)), UpAxis::kPlusY);
  // A tilted long axis snaps to its nearest coordinate axis.
  Positions tilted(2, 3);
  tilted << 0, 0, 0, 0.3, 1, -0.2;
  EXPECT_EQ(AutoUpAxis(tilted), UpAxis::kPlusY);
  // The shared meshes: the cactus stands along z, the faces lie along x,
  // the finger along x.
  EXPECT_EQ(AutoUpAxis(LoadData("cactus/cactus0.ply").positions),
            UpAxis::kPlusZ);
  EXPECT_EQ(AutoUpAxis(LoadData("faces/neutral.ply").positions),
            UpAxis::kPlusX);
  EXPECT_EQ(AutoUpAxis(LoadData("finger/finger0.ply").positions),
            UpAxis::kPlusX);
  Positions bad = Box(1, 1, 5).positions;
  bad(3, 1) = std::nan("");
  EXPECT_THROW(AutoUpAxis(bad), InputError);
}

// An open surface stands on its boundary: the faces (open at the neck)
// come out upright, -x, while their vertices alone give +x; the closed
// cactus keeps +z.
TEST(UpAxisTest, AutoStandsAnOpenSurfaceOnItsBoundary) {
  for (const char* pose : {"faces/neutral.ply", "faces/smile.ply",
                           "faces/disgust.ply", "faces/surprise.ply"}) {
    const Mesh face = LoadData(pose);
    EXPECT_EQ(AutoUpAxis(face.positions, &face.faces), UpAxis::kMinusX)
        << pose;
    // Mirrored along x, the boundary moves to the other end: +x.
    Mesh mirrored = face;
    mirrored.positions.col(0) *= -1;
    mirrored.faces.col(1).swap(mirrored.faces.col(2));
    EXPECT_EQ(AutoUpAxis(mirrored.positions, &mirrored.faces),
              UpAxis::kPlusX)
        << pose;
  }
  const Mesh cactus = LoadData("cactus/cactus0.ply");
  EXPECT_EQ(AutoUpAxis(cactus.positions, &cactus.faces), UpAxis::kPlusZ);
  // A tube along z, closed at the top by a fan and open at the bottom:
  // +z; turned upside down: -z.
  const int n = 8, rings = 6;
  Mesh tube;
  tube.positions.resize(n * rings, 3);
  for (int r = 0; r < rings; ++r) {
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      tube.positions.row(r * n + i) << std::cos(a), std::sin(a), 2.0 * r;
    }
  }
  std::vector<Eigen::Vector3i> faces;
  for (int r = 0; r + 1 < rings; ++r) {
    for (int i = 0; i < n; ++i) {
      const int a = r * n + i, b = r * n + (i + 1) % n;
      faces.emplace_back(a, b, b + n);
      faces.emplace_back(a, b + n, a + n);
    }
  }
  // Close the top with a fan around an apex: the only boundary is at z = 0.
  tube.positions.conservativeResize(n * rings + 1, 3);
  tube.positions.row(n * rings) << 0, 0, 2.0 * rings - 1;
  for (int i = 0; i < n; ++i) {
    faces.emplace_back((rings - 1) * n + i, (rings - 1) * n + (i + 1) % n,
                       n * rings);
  }
  tube.faces.resize(static_cast<int>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) {
    tube.faces.row(static_cast<int>(f)) = faces[f].transpose();
  }
  EXPECT_EQ(AutoUpAxis(tube.positions, &tube.faces), UpAxis::kPlusZ);
  Mesh flipped = tube;
  flipped.positions.col(2) *= -1;
  EXPECT_EQ(AutoUpAxis(flipped.positions, &flipped.faces), UpAxis::kMinusZ);
}

}  // namespace
}  // namespace shellspace
