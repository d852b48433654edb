// The geodesic workflow solves to the end shape rigidly aligned onto the
// start and carries the path back to the user's end: a rigid motion of the
// end leaves the path energy, the iterations and every shape up to rigid
// motion as they were, and the path ends exactly at the end given.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/workflows/geodesic.h"

namespace shellspace {
namespace {

// A coarse finger (12 around, 10 rings) bent by 90 degrees, K = 4.
workflows::GeodesicOptions BentFinger() {
  workflows::GeodesicOptions options;
  options.start = MakeFinger(0.5, 4.0, 12, 10, 3);
  options.topology = Topology::Build(options.start);
  options.end = BendAlongY(options.start.positions, 4.0, M_PI / 2);
  options.steps = 4;
  options.material.material.eta =
      EtaFromRelative(kDefaultRelativeEta, options.start);
  options.settings = UserSolverSettings(1e-8, 200, 1, /*quiet=*/true, "test");
  return options;
}

RigidMotion Turn(double radians) {
  RigidMotion motion;
  motion.rotation =
      Eigen::AngleAxisd(radians, Eigen::Vector3d(0.3, -1, 0.5).normalized())
          .toRotationMatrix();
  motion.translation << 2, -1, 3;
  return motion;
}

TEST(GeodesicRigidMotionTest, ARigidMotionOfTheEndMovesThePathOnly) {
  workflows::GeodesicOptions plain = BentFinger();
  const workflows::GeodesicResult a = workflows::RunGeodesic(plain);
  ASSERT_TRUE(a.geodesic().converged);

  workflows::GeodesicOptions moved = BentFinger();
  moved.end = Turn(2.5).Apply(plain.end);  // 143 degrees
  const workflows::GeodesicResult b = workflows::RunGeodesic(moved);
  ASSERT_TRUE(b.geodesic().converged);
  // The solve saw both ends in one frame: its initial path had no rigid
  // motion to remove (the checks of that path, such as triangles turning
  // over between shapes, then compare shapes in one frame).
  EXPECT_LT(a.geodesic().init.rotation_degrees, 1e-6);
  EXPECT_LT(b.geodesic().init.rotation_degrees, 1e-6);

  EXPECT_NEAR(b.path_energy(), a.path_energy(), 1e-9 * a.path_energy());
  EXPECT_EQ(b.geodesic().iterations, a.geodesic().iterations);
  EXPECT_EQ(b.path().front(), moved.start.positions);
  EXPECT_EQ(b.path().back(), moved.end);  // bit for bit
  for (int k = 1; k < 4; ++k) {
    EXPECT_LT(RelativeDistanceUpToRigidMotion(b.path()[k], a.path()[k]), 1e-7)
        << k;
    // Twin: the comparison tells neighbouring shapes apart.
    EXPECT_GT(RelativeDistanceUpToRigidMotion(b.path()[k], a.path()[k + 1]),
              1e-3)
        << k;
  }
  // The motion is spread over the steps: shape k is turned by about k/K of
  // the 143 degrees against the start (plus the bend's own share).
  const double step_turn =
      Eigen::AngleAxisd(FitRigidMotion(a.path()[1], b.path()[1]).rotation)
          .angle();
  EXPECT_NEAR(step_turn, 2.5 / 4, 0.15);
}

TEST(GeodesicRigidMotionTest, WithAMaskTheEndIsNotMoved) {
  // The fixed vertices pin the frame: the solve runs to the end as given
  // (a pure translation of the end is a real deformation there).
  workflows::GeodesicOptions options = BentFinger();
  options.fixed_vertices = FingerBaseVertices(12, 1);
  const workflows::GeodesicResult pinned = workflows::RunGeodesic(options);
  ASSERT_TRUE(pinned.geodesic().converged);
  EXPECT_EQ(pinned.path().back(), options.end);
  for (const int v : options.fixed_vertices) {
    for (int k = 0; k <= 4; ++k) {
      EXPECT_LT(
          (pinned.path()[k].row(v) - options.start.positions.row(v)).norm(),
          1e-12)
          << v << " " << k;
    }
  }
}

}  // namespace
}  // namespace shellspace
