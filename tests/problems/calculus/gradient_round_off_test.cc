// The round-off floor of the path gradient (GradientRoundOff) and the
// geodesic solve that stops there: a gradient target below what double
// precision resolves is met by a stalled solve only when its gradient is
// within that floor, and the result says so.
#include <gtest/gtest.h>

#include <cmath>

#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

// A coarse finger bent by 90 degrees, K = 3, its base ring held, and the
// linear path between the two.
class GradientRoundOffTest : public ::testing::Test {
 protected:
  GradientRoundOffTest()
      : finger_(MakeFinger(0.5, 4.0, 12, 10, 3)),
        space_(testing::MakeSpace(finger_)),
        input_(GeodesicInput::Between(
            finger_.positions, BendAlongY(finger_.positions, 4.0, M_PI / 2),
            3)) {
    input_.fixed_vertices = FingerBaseVertices(12, 1);
    linear_ = LinearPath(input_.start, input_.end, input_.steps);
  }
  const Mesh finger_;
  const ShellSpace space_;
  GeodesicInput input_;
  ShellPath linear_;
};

TEST_F(GradientRoundOffTest,
       TheFloorIsFarBelowAnUnsolvedGradientAndRepeatable) {
  const double gradient = PathGradientNorm(space_, input_, linear_, 1);
  const double floor = GradientRoundOff(space_, input_, linear_, 1);
  EXPECT_GT(floor, 0);
  EXPECT_LT(floor, 1e-10 * gradient);
  // The same probes every time, and on any number of threads.
  EXPECT_EQ(GradientRoundOff(space_, input_, linear_, 2), floor);
}

TEST_F(GradientRoundOffTest, ASliverRaisesTheFloor) {
  const double plain = GradientRoundOff(space_, input_, linear_, 1);
  // The apex k of a flap half way up the finger moved to 1e-4 of its
  // distance from the midpoint of edge (i, j), in every shape: triangle
  // (i, j, k) becomes a sliver, stiff across its short height.
  const EdgeFlap& flap =
      space_.topology.interior_edges[space_.topology.interior_edges.size() / 2];
  ShellPath thin = linear_;
  for (Positions& shape : thin) {
    const Eigen::RowVector3d mid =
        0.5 * (shape.row(flap.i) + shape.row(flap.j));
    shape.row(flap.k) = mid + 1e-4 * (shape.row(flap.k) - mid);
  }
  GeodesicInput thin_input = input_;
  thin_input.start = thin.front();
  thin_input.end = thin.back();
  EXPECT_GT(GradientRoundOff(space_, thin_input, thin, 1), 100 * plain);
}

TEST_F(GradientRoundOffTest, AnUnreachableTargetIsMetAtTheFloorAndSaysSo) {
  SolverSettings settings = testing::TightSettings(1e-15);
  settings.max_iterations = 400;
  const GeodesicResult g = SolveGeodesic(space_, input_, settings);
  ASSERT_TRUE(g.converged) << g.final_gradient << " " << g.stall;
  EXPECT_TRUE(g.converged_at_round_off);
  EXPECT_FALSE(g.stall.empty());
  EXPECT_GT(g.final_gradient, g.gradient_target);  // the target was not met
  EXPECT_LE(g.final_gradient, g.gradient_round_off);
  EXPECT_EQ(g.gradient_round_off, GradientRoundOff(space_, input_, g.path, 1));
  // Twin: an ordinary target is met by the criterion itself.
  const GeodesicResult ordinary =
      SolveGeodesic(space_, input_, testing::TightSettings(1e-8));
  EXPECT_TRUE(ordinary.converged);
  EXPECT_FALSE(ordinary.converged_at_round_off);
  EXPECT_EQ(ordinary.gradient_round_off, 0);
}

}  // namespace
}  // namespace shellspace
