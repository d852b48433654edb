// Rigid motions: Kabsch recovers a known motion, the inverse undoes it, and
// a fraction of a motion turns by that fraction of the angle about the same
// axis and moves its centre by that fraction of the way.
#include "shellspace/geometry/rigid_alignment.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace shellspace {
namespace {

Positions Scatter() {
  Positions x(5, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 3, 0.5, -1, 0.25;
  return x;
}

RigidMotion Known() {
  RigidMotion m;
  m.rotation = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, -0.5).normalized())
                   .toRotationMatrix();
  m.translation << 0.3, -2.0, 5.0;
  return m;
}

TEST(RigidAlignmentTest, KabschRecoversAKnownMotion) {
  const RigidMotion fitted =
      FitRigidMotion(Scatter(), Known().Apply(Scatter()));
  EXPECT_LT((fitted.rotation - Known().rotation).norm(), 1e-12);
  EXPECT_LT((fitted.translation - Known().translation).norm(), 1e-12);
}

TEST(RigidAlignmentTest, TheInverseUndoesTheMotion) {
  const Positions back = Known().Inverse().Apply(Known().Apply(Scatter()));
  EXPECT_LT((back - Scatter()).norm(), 1e-13);
  // Twin: the motion applied twice is not the identity.
  EXPECT_GT((Known().Apply(Known().Apply(Scatter())) - Scatter()).norm(), 1);
}

TEST(RigidAlignmentTest, AFractionTurnsByThatFractionAndMovesTheCentre) {
  const Eigen::RowVector3d centre(0.2, 0.4, 0.7);
  const RigidMotion whole = Known();
  EXPECT_LT(
      (whole.Fraction(1, centre).Apply(Scatter()) - whole.Apply(Scatter()))
          .norm(),
      1e-13);
  EXPECT_LT((whole.Fraction(0, centre).Apply(Scatter()) - Scatter()).norm(),
            1e-15);
  for (const double tau : {0.125, 0.5, 0.75}) {
    const RigidMotion part = whole.Fraction(tau, centre);
    const Eigen::AngleAxisd turn(part.rotation);
    EXPECT_NEAR(turn.angle(), tau * 1.1, 1e-13) << tau;
    EXPECT_LT((turn.axis() - Eigen::Vector3d(1, 2, -0.5).normalized()).norm(),
              1e-12)
        << tau;
    // The centre travels the straight line to its image.
    Positions c(1, 3);
    c.row(0) = centre;
    const Eigen::RowVector3d expected =
        centre + tau * (whole.Apply(c).row(0) - centre);
    EXPECT_LT((part.Apply(c).row(0) - expected).norm(), 1e-13) << tau;
  }
}

}  // namespace
}  // namespace shellspace
