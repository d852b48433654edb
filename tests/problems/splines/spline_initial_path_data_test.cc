// A spline's initial paths (spline_initial_path.h): the piecewise geodesic
// is the segments' geodesics, keyframes exact; on keyframes that lie on one
// geodesic it is that geodesic (F_K ~ 0); periodic closure and one-step
// segments; the name parser.
#include "shellspace/problems/splines/spline_initial_path.h"

#include <gtest/gtest.h>

#include <utility>

#include "shellspace/geometry/rigid_alignment.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

// The flat plate and its two rolled versions as keyframes (K small).
class SplineInitialPathTest : public ::testing::Test {
 protected:
  static Positions Plate(const std::string& name) {
    return testing::LoadData("plate/" + name + ".ply").positions;
  }
  // PiecewiseGeodesicPath through keys_[0 .. at.size() - 1] at `at`.
  ShellPath Piecewise(const std::vector<int>& at, int steps, bool periodic,
                      std::vector<GeodesicSegment>* segments,
                      const SolverSettings& settings) const {
    const std::vector<Positions> keys(keys_.begin(),
                                      keys_.begin() + at.size());
    return PiecewiseGeodesicPath(space_, keys, at, steps, periodic, settings,
                                 segments);
  }
  GeodesicResult Geodesic(const Positions& a, const Positions& b,
                          int steps) const {
    return SolveGeodesic(space_, GeodesicInput::Between(a, b, steps), tight_);
  }
  // The (from, to) of each segment.
  static std::vector<std::pair<int, int>> Bounds(
      const std::vector<GeodesicSegment>& segments) {
    std::vector<std::pair<int, int>> bounds;
    for (const GeodesicSegment& g : segments) bounds.emplace_back(g.from, g.to);
    return bounds;
  }
  static double MaxDifference(const Positions& x, const Positions& y) {
    return (x - y).cwiseAbs().maxCoeff();
  }
  const std::vector<Positions> keys_ = {
      Plate("plate121"), Plate("plate121_rolledA"), Plate("plate121_rolledB")};
  const ShellSpace space_ =
      testing::MakeSpace(testing::LoadData("plate/plate121.ply"));
  const SolverSettings tight_ = testing::TightSettings(1e-12);
};

// Each segment is SolveGeodesic's path of that segment, to the bit; the
// keyframes stand at their indices; the report lists the segments.
TEST_F(SplineInitialPathTest, SegmentsAreTheGeodesicsBetweenKeyframes) {
  std::vector<GeodesicSegment> segments;
  const ShellPath path = Piecewise({0, 2, 5}, 5, false, &segments, tight_);
  ASSERT_EQ(path.size(), 6u);
  ASSERT_EQ(Bounds(segments),
            (std::vector<std::pair<int, int>>{{0, 2}, {2, 5}}));
  const GeodesicResult first = Geodesic(keys_[0], keys_[1], 2);
  const GeodesicResult second = Geodesic(keys_[1], keys_[2], 3);
  EXPECT_EQ(MaxDifference(path[1], first.path[1]), 0.0);
  for (int k = 3; k <= 4; ++k) {
    EXPECT_EQ(MaxDifference(path[k], second.path[k - 2]), 0.0) << k;
  }
  EXPECT_EQ(segments[0].path_energy, first.path_energy);
  EXPECT_EQ(segments[1].iterations, second.iterations);
  EXPECT_TRUE(segments[0].converged && segments[1].converged);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(MaxDifference(path[std::vector<int>{0, 2, 5}[i]], keys_[i]), 0.0);
  }
}

// Keyframes taken from one geodesic (K = 4 at 0, 2, 4): the piecewise
// geodesic is that geodesic again (each half of a geodesic is the geodesic
// of its ends), so its spline energy is ~ 0, while the piecewise linear
// path's is not.
TEST_F(SplineInitialPathTest, KeyframesOnAGeodesicGiveItsSplineEnergyZero) {
  const GeodesicResult g = Geodesic(keys_[0], keys_[1], 4);
  const std::vector<Positions> keys = {g.path[0], g.path[2], g.path[4]};
  const ShellPath path =
      PiecewiseGeodesicPath(space_, keys, {0, 2, 4}, 4, false, tight_);
  for (int k : {1, 3}) {
    EXPECT_LT(RelativeDistanceUpToRigidMotion(path[k], g.path[k]), 1e-5) << k;
  }
  SplineSpec spec;
  spec.steps = 4;
  spec.initial = path;
  spec.is_free = {0, 1, 0, 1, 0};
  const SplineObjective objective(space_, spec, tight_);
  const double f_geodesic = objective.SplineEnergyOf(path);
  const double f_linear =
      objective.SplineEnergyOf(PiecewiseLinearPath(keys, {0, 2, 4}, 4, false));
  EXPECT_LT(f_geodesic, 1e-8 * g.path_energy);
  EXPECT_GT(f_linear, 1e4 * f_geodesic);
}

// Periodic (K = 5 at 0, 2, 3): three segments, the last from 3 across K to
// 0 + 5; K shapes; a one-step segment (2 -> 3) is its two keyframes.
TEST_F(SplineInitialPathTest, PeriodicClosureAndOneStepSegments) {
  std::vector<GeodesicSegment> segments;
  const ShellPath path = Piecewise({0, 2, 3}, 5, true, &segments, tight_);
  ASSERT_EQ(path.size(), 5u);
  ASSERT_EQ(Bounds(segments),
            (std::vector<std::pair<int, int>>{{0, 2}, {2, 3}, {3, 5}}));
  const GeodesicResult closing = Geodesic(keys_[2], keys_[0], 2);
  EXPECT_EQ(MaxDifference(path[4], closing.path[1]), 0.0);
  EXPECT_EQ(MaxDifference(path[0], keys_[0]), 0.0);
  EXPECT_EQ(MaxDifference(path[3], keys_[2]), 0.0);
}

// A stop request before the first segment leaves the piecewise linear path
// and reports no segment.
TEST_F(SplineInitialPathTest, AStopRequestKeepsTheLinearPath) {
  SolverSettings stopped = tight_;
  stopped.stop = StopToken([] { return true; });
  std::vector<GeodesicSegment> segments;
  const ShellPath path = Piecewise({0, 2, 4}, 4, false, &segments, stopped);
  EXPECT_TRUE(segments.empty());
  const ShellPath linear = PiecewiseLinearPath(keys_, {0, 2, 4}, 4, false);
  for (int k = 0; k <= 4; ++k) {
    EXPECT_EQ(MaxDifference(path[k], linear[k]), 0.0) << k;
  }
}

TEST_F(SplineInitialPathTest, NamesAndKeyframeChecks) {
  EXPECT_EQ(ParseSplineInit("ltheta"), SplineInit::kLTheta);
  EXPECT_EQ(ParseSplineInit("geodesic"), SplineInit::kGeodesic);
  EXPECT_THROW(ParseSplineInit("linear"), InputError);
  for (SplineInit init : {SplineInit::kLTheta, SplineInit::kGeodesic}) {
    EXPECT_EQ(ParseSplineInit(SplineInitName(init)), init);
  }
  // Not ending at K, and K = 1: SolveSpline's refusals.
  EXPECT_THROW(Piecewise({0, 2}, 3, false, nullptr, tight_), InputError);
  EXPECT_THROW(Piecewise({0, 1}, 1, false, nullptr, tight_), InputError);
  // MakeSplineInitialPath: the geodesic choice fills the segments only.
  const std::vector<Positions> ends = {keys_[0], keys_[1]};
  const SplineInitialPath initial = MakeSplineInitialPath(
      SplineInit::kGeodesic, space_, ends, {0, 2}, 2, false, tight_);
  EXPECT_EQ(initial.segments.size(), 1u);
  EXPECT_TRUE(initial.ltheta.solved_frames.empty());
  EXPECT_EQ(initial.path.size(), 3u);
}

}  // namespace
}  // namespace shellspace
