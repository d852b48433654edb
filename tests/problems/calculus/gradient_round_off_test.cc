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

// A coarse finger bent by 90 degrees, K = 3, its base ring held.
GeodesicInput BentFinger(const Mesh& finger) {
  GeodesicInput input = GeodesicInput::Between(
      finger.positions, BendAlongY(finger.positions, 4.0, M_PI / 2), 3);
  input.fixed_vertices = FingerBaseVertices(12, 1);
  return input;
}

TEST(GradientRoundOffTest, TheFloorIsFarBelowAnUnsolvedGradientAndRepeatable) {
  const Mesh finger = MakeFinger(0.5, 4.0, 12, 10, 3);
  const ShellSpace space = testing::MakeSpace(finger);
  const GeodesicInput input = BentFinger(finger);
  const ShellPath linear = LinearPath(input.start, input.end, input.steps);
  const double gradient = PathGradientNorm(space, input, linear, 1);
  const double floor = GradientRoundOff(space, input, linear, 1);
  EXPECT_GT(floor, 0);
  EXPECT_LT(floor, 1e-10 * gradient);
  // The same probes every time, and on any number of threads.
  EXPECT_EQ(GradientRoundOff(space, input, linear, 2), floor);
}

TEST(GradientRoundOffTest, ASliverRaisesTheFloor) {
  const Mesh finger = MakeFinger(0.5, 4.0, 12, 10, 3);
  const ShellSpace space = testing::MakeSpace(finger);
  const GeodesicInput input = BentFinger(finger);
  const ShellPath linear = LinearPath(input.start, input.end, input.steps);
  const double plain = GradientRoundOff(space, input, linear, 1);
  // The apex k of a flap half way up the finger moved to 1e-4 of its
  // distance from the midpoint of edge (i, j), in every shape: triangle
  // (i, j, k) becomes a sliver, stiff across its short height.
  const EdgeFlap& flap =
      space.topology.interior_edges[space.topology.interior_edges.size() / 2];
  ShellPath thin = linear;
  for (Positions& shape : thin) {
    const Eigen::RowVector3d mid =
        0.5 * (shape.row(flap.i) + shape.row(flap.j));
    shape.row(flap.k) = mid + 1e-4 * (shape.row(flap.k) - mid);
  }
  GeodesicInput thin_input = input;
  thin_input.start = thin.front();
  thin_input.end = thin.back();
  EXPECT_GT(GradientRoundOff(space, thin_input, thin, 1), 100 * plain);
}

TEST(GradientRoundOffTest, AnUnreachableTargetIsMetAtTheFloorAndSaysSo) {
  const Mesh finger = MakeFinger(0.5, 4.0, 12, 10, 3);
  const ShellSpace space = testing::MakeSpace(finger);
  const GeodesicInput input = BentFinger(finger);
  SolverSettings settings = testing::TightSettings(1e-15);
  settings.max_iterations = 400;
  const GeodesicResult g = SolveGeodesic(space, input, settings);
  ASSERT_TRUE(g.converged) << g.final_gradient << " " << g.stall;
  EXPECT_TRUE(g.converged_at_round_off);
  EXPECT_FALSE(g.stall.empty());
  EXPECT_GT(g.final_gradient, g.gradient_target);  // the target was not met
  EXPECT_LE(g.final_gradient, g.gradient_round_off);
  EXPECT_EQ(g.gradient_round_off, GradientRoundOff(space, input, g.path, 1));
  // Twin: an ordinary target is met by the criterion itself.
  const GeodesicResult ordinary =
      SolveGeodesic(space, input, testing::TightSettings(1e-8));
  EXPECT_TRUE(ordinary.converged);
  EXPECT_FALSE(ordinary.converged_at_round_off);
  EXPECT_EQ(ordinary.gradient_round_off, 0);
}

}  // namespace
}  // namespace shellspace
