// The LΘA spline (docs/math.md, "Riemannian splines") on the shared plate
// and its two rolled shapes: it passes through its keyframes, gives a
// keyframe back up to its rigid motion, reconstructs a shell from its own
// quantities, gives the same digits on 1 and 3 threads, and rejects bad
// inputs.
#include "shellspace/problems/splines/ltheta_spline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/splines/cubic_spline.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

class LThetaSplineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    plate_ = testing::LoadData("plate/plate121.ply");
    rolled_a_ = testing::LoadData("plate/plate121_rolledA.ply").positions;
    rolled_b_ = testing::LoadData("plate/plate121_rolledB.ply").positions;
    space_ = testing::MakeSpace(plate_);
  }

  static SolverSettings Tight() {
    SolverSettings settings = testing::TightSettings(1e-12);
    settings.num_threads = 1;
    return settings;
  }

  Mesh plate_;
  Positions rolled_a_, rolled_b_;
  ShellSpace space_;
};

// The frames are solved in parallel, each on one thread: 1 and 3 threads
// give the same path to the bit and the same LM iterations.
TEST_F(LThetaSplineTest, ThreadCountDoesNotChangeADigit) {
  const std::vector<Positions> keys = {plate_.positions, rolled_a_, rolled_b_};
  SolverSettings one = SolverSettings{}, three = SolverSettings{};
  one.num_threads = 1;
  three.num_threads = 3;
  LThetaSplineReport report_one, report_three;
  const ShellPath a =
      LThetaSpline(space_, keys, {0, 2, 5}, 6, false, one, &report_one);
  const ShellPath b =
      LThetaSpline(space_, keys, {0, 2, 5}, 6, false, three, &report_three);
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) EXPECT_TRUE(a[k] == b[k]) << k;
  EXPECT_EQ(report_one.lm_iterations(), report_three.lm_iterations());
  EXPECT_GT(report_one.lm_iterations(), 4);
}

TEST_F(LThetaSplineTest, PassesThroughItsKeyframes) {
  const std::vector<Positions> keys = {plate_.positions, rolled_a_, rolled_b_};
  LThetaSplineReport report;
  const ShellPath path = LThetaSpline(space_, keys, {0, 2, 5}, 6, false,
                                      SolverSettings{}, &report);
  ASSERT_EQ(path.size(), 7u);
  EXPECT_TRUE(path[0] == keys[0]);
  EXPECT_TRUE(path[2] == keys[1]);
  EXPECT_TRUE(path[5] == keys[2]);
  EXPECT_EQ(report.solved_frames, (std::vector<int>{1, 3, 4, 6}));
  int iterations = 0;  // Ceres' records, less each solve's iteration 0
  for (const auto& summary : report.summaries) {
    EXPECT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
    iterations += static_cast<int>(summary.iterations.size()) - 1;
  }
  EXPECT_GT(iterations, 4);
  EXPECT_EQ(report.lm_iterations(), iterations);
  EXPECT_TRUE(report.unconverged_frames().empty());
  // One LM iteration per frame: every solved frame is named unconverged.
  SolverSettings one_iteration;
  one_iteration.max_iterations = 1;
  LThetaSplineReport capped;
  LThetaSpline(space_, keys, {0, 2, 5}, 6, false, one_iteration, &capped);
  EXPECT_EQ(capped.unconverged_frames(), (std::vector<int>{1, 3, 4, 6}));
  EXPECT_EQ(capped.lm_iterations(), 4);
  // Inner frames are genuine shells between their neighbouring keyframes a,
  // b: a copy of neither, and nearer to one of them than they are apart.
  const std::vector<std::array<int, 3>> frames = {
      {1, 0, 1}, {3, 1, 2}, {4, 1, 2}};
  for (const auto& [k, a, b] : frames) {
    const double to_a = RelativeDistanceUpToRigidMotion(path[k], keys[a]);
    const double to_b = RelativeDistanceUpToRigidMotion(path[k], keys[b]);
    EXPECT_GT(std::min(to_a, to_b), 1e-2) << k;
    EXPECT_LT(std::min(to_a, to_b),
              RelativeDistanceUpToRigidMotion(keys[a], keys[b]))
        << k;
  }

  const ShellPath closed =
      LThetaSpline(space_, keys, {0, 2, 4}, 6, true, SolverSettings{});
  ASSERT_EQ(closed.size(), 7u);
  EXPECT_TRUE(closed[0] == keys[0]);
  EXPECT_TRUE(closed[2] == keys[1]);
  EXPECT_TRUE(closed[4] == keys[2]);
  EXPECT_TRUE(closed[6] == closed[0]);
}

TEST_F(LThetaSplineTest,
       UniformlyScaledFlatSheetKeepsSplineLengthsAndStaysFlat) {
  // Keyframes: the plate scaled by 1, 1.2, 1.44 at 0, 2, 4. Every length
  // follows the natural spline through (0, 1), (2, 1.2), (4, 1.44) times its
  // rest length (1.09625 at k = 1), every area the spline through the
  // squares (1.20185 at k = 1, not exactly 1.09625^2 = 1.20176): the frames
  // are a slight compromise between the two, in the plane of the sheet.
  const Positions& p = plate_.positions;
  const std::vector<Positions> keys = {p, 1.2 * p, 1.44 * p};
  const ShellPath path =
      LThetaSpline(space_, keys, {0, 2, 4}, 4, false, Tight());
  const Eigen::MatrixXd scales = InterpolateCubicSplineAtSteps(
      {0, 2, 4}, (Eigen::MatrixXd(3, 1) << 1, 1.2, 1.44).finished(), 4,
      SplineEnds::kNatural);
  EXPECT_NEAR(scales(1, 0), 1.09625, 1e-14);
  const LThetaQuantities rest = ComputeLThetaQuantities(space_, p);
  for (int k : {1, 3}) {
    const LThetaQuantities q = ComputeLThetaQuantities(space_, path[k]);
    const Eigen::ArrayXd ratio = q.lengths.array() / rest.lengths.array();
    EXPECT_NEAR(ratio.mean(), scales(k, 0), 1e-4) << k;
    EXPECT_LT((ratio - scales(k, 0)).abs().maxCoeff(), 2e-4) << k;
    // Flat: the plate lies in z = 0 and every frame stays in a plane.
    EXPECT_LT(path[k].col(2).cwiseAbs().maxCoeff(), 1e-12) << k;
    EXPECT_LT(q.dihedrals.cwiseAbs().maxCoeff(), 1e-12) << k;
  }
}

TEST_F(LThetaSplineTest, RigidMotionsOfAKeyframeGiveThatKeyframe) {
  // All keyframes are rigid motions of the rolled plate: every quantity's
  // spline is constant and each frame is the rolled plate up to rigid motion,
  // placed between its neighbours.
  const std::vector<Positions> keys = {
      rolled_a_, testing::RandomRigidMotion(rolled_a_, 3),
      testing::RandomRigidMotion(rolled_a_, 5)};
  for (bool periodic : {false, true}) {
    const ShellPath path =
        LThetaSpline(space_, keys, {0, 3, 5}, 7, periodic, Tight());
    for (int k = 0; k <= 7; ++k) {
      EXPECT_LT(RelativeDistanceUpToRigidMotion(path[k], rolled_a_), 1e-8)
          << "frame " << k << (periodic ? " periodic" : "");
    }
    // The rigid placement moves between the keyframes: frame 4 is neither
    // where keyframe 1 nor where keyframe 2 is.
    EXPECT_GT((path[4] - keys[1]).cwiseAbs().maxCoeff(), 1e-2);
    EXPECT_GT((path[4] - keys[2]).cwiseAbs().maxCoeff(), 1e-2);
  }
}

TEST_F(LThetaSplineTest, ReconstructingAShellsOwnQuantitiesGivesItBack) {
  const LThetaQuantities own = ComputeLThetaQuantities(space_, rolled_a_);
  const LThetaWeights weights = LThetaResidualWeights(space_, plate_.positions);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> noise(-0.02, 0.02);
  Positions perturbed = rolled_a_;
  for (int i = 0; i < perturbed.size(); ++i) perturbed.data()[i] += noise(rng);
  ASSERT_GT(RelativeDistanceUpToRigidMotion(perturbed, rolled_a_), 1e-2);
  ceres::Solver::Summary summary;
  const Positions back =
      ReconstructFromLTheta(space_, own, weights, perturbed, Tight(), &summary);
  EXPECT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
  EXPECT_LT(summary.final_cost, 1e-16);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(back, rolled_a_), 1e-8);
  // From the flat plate the quantities of the rolled plate also lead back to
  // it (the signed dihedral targets fix the rolling direction).
  const Positions from_flat = ReconstructFromLTheta(
      space_, own, weights, plate_.positions, Tight(), &summary);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(from_flat, rolled_a_), 1e-6)
      << summary.BriefReport();
}

TEST_F(LThetaSplineTest, RejectsBadInputs) {
  const std::vector<Positions> keys = {plate_.positions, rolled_a_};
  const SolverSettings settings;
  EXPECT_THROW(LThetaSpline(space_, keys, {0}, 4, false, settings), InputError);
  EXPECT_THROW(LThetaSpline(space_, keys, {2, 1}, 4, false, settings),
               InputError);
  EXPECT_THROW(LThetaSpline(space_, keys, {0, 5}, 4, false, settings),
               InputError);
  EXPECT_THROW(LThetaSpline(space_, keys, {0, 4}, 4, true, settings),
               InputError);
  EXPECT_THROW(LThetaSpline(space_, keys, {0, 1}, 0, false, settings),
               InputError);
  const std::vector<Positions> wrong = {plate_.positions,
                                        rolled_a_.topRows(100)};
  EXPECT_THROW(LThetaSpline(space_, wrong, {0, 4}, 4, false, settings),
               InputError);
}

}  // namespace
}  // namespace shellspace
