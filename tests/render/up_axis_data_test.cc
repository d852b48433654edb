// The automatic choice of the up axis (render/up_axis.h AutoUpAxis) from
// the vertices of boxes made here and of the shared meshes, and from the
// faces of an open surface, which stands on its boundary.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/render/up_axis.h"
#include "tests/testing/render_fixtures.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::Box;
using testing::UnitSquareMesh;

using ::shellspace::testing::LoadData;

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
