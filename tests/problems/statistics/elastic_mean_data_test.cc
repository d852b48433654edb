// Tests of the elastic mean on the shared spheres and plates: the mean of
// copies is the shape, it is invariant under rigid motions of the inputs,
// the Newton finish reaches a tight gradient and the LM mean, bad inputs
// are rejected.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "tests/testing/statistics_fixtures.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::GaussianNoise;
using testing::kSpheres;
using testing::LoadData;
using testing::LoadSpheres;
using testing::MakeSpace;
using testing::RandomRigidMotion;
using testing::StatisticsSettings;

// max-norm of sum_i D_2 W[S_i, s] relative to the largest single term.
double RelativeMeanGradient(const ShellSpace& space,
                            const std::vector<Positions>& shapes,
                            const Positions& s) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(s.size());
  double scale = 0;
  for (const Positions& shape : shapes) {
    const Eigen::VectorXd g =
        EnergyGradient(space, shape, s, ShellSide::kDeformed);
    sum += g;
    scale = std::max(scale, g.cwiseAbs().maxCoeff());
  }
  return sum.cwiseAbs().maxCoeff() / scale;
}

TEST(ElasticMeanTest, MeanOfCopiesIsTheShape) {
  const Mesh mesh = LoadData("sphere/unitSphere1_defX.ply");
  const ShellSpace space = MakeSpace(mesh);
  const Positions& shape = mesh.positions;
  const std::vector<Positions> copies = {shape, RandomRigidMotion(shape, 1),
                                         RandomRigidMotion(shape, 2)};
  // From the default guess (the aligned average: the shape itself).
  const ElasticMeanResult plain =
      ComputeElasticMean(space, copies, StatisticsSettings());
  EXPECT_LT(plain.energy, 1e-14);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(plain.mean, shape), 1e-8);
  // From a perturbed guess, so that the solver has work to do.
  const Positions initial =
      RandomRigidMotion(shape, 3) + GaussianNoise(shape.rows(), 0.03, 4);
  ASSERT_GT(RelativeDistanceUpToRigidMotion(initial, shape), 1e-2);
  const ElasticMeanResult result =
      ComputeElasticMean(space, copies, StatisticsSettings(), &initial);
  EXPECT_TRUE(result.summary.IsSolutionUsable());
  EXPECT_LT(result.energy, 1e-12);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(result.mean, shape), 1e-6);
  // Reported aligned to the first input.
  EXPECT_LT((result.mean - shape).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(ElasticMeanTest, InvariantUnderRigidMotionsOfTheInputs) {
  const std::vector<Positions> shapes = LoadSpheres();
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  const ElasticMeanResult a =
      ComputeElasticMean(space, shapes, StatisticsSettings());
  std::vector<Positions> moved;
  for (size_t i = 0; i < shapes.size(); ++i) {
    moved.push_back(RandomRigidMotion(shapes[i], 10 + i));
  }
  const ElasticMeanResult b =
      ComputeElasticMean(space, moved, StatisticsSettings());
  ASSERT_GT(a.energy, 1e-4);  // the inputs differ: a non-trivial mean
  EXPECT_NEAR(a.energy, b.energy, 1e-9 * a.energy);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(a.mean, b.mean), 1e-6);
  // b is reported in the pose of the moved first input.
  EXPECT_LT((AlignRigidly(a.mean, moved[0]) - b.mean).cwiseAbs().maxCoeff(),
            1e-5);
  // A stationary point that beats the initial guess, and not an input.
  EXPECT_LT(RelativeMeanGradient(space, shapes, a.mean), 1e-6);
  double at_average = 0;
  const Positions average = AlignedVertexAverage(shapes);
  for (const Positions& s : shapes) {
    at_average += EvaluateDeformationEnergy(space, s, average).total;
  }
  EXPECT_LT(a.energy, at_average);
  for (const Positions& s : shapes) {
    EXPECT_GT(RelativeDistanceUpToRigidMotion(a.mean, s), 1e-3);
  }
}

TEST(ElasticMeanTest, NewtonFinishReachesATightGradientAndTheLmMean) {
  const std::vector<Positions> shapes = LoadSpheres();
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  SolverSettings settings;
  settings.gradient_tolerance = 1e-11;
  settings.max_iterations = 1000;
  const ElasticMeanResult newton = ComputeElasticMean(space, shapes, settings);
  // LM hands over at 1e-4 relative; Newton takes it to the target.
  EXPECT_TRUE(newton.converged);
  EXPECT_FALSE(newton.newton_fell_back);
  EXPECT_GE(newton.newton_iterations, 1);
  EXPECT_LE(newton.newton_iterations, 6);  // quadratic convergence
  EXPECT_LE(newton.gradient_norm,
            1e-11 * std::max(1.0, newton.initial_gradient_norm));
  // The reported gradient is the true one at the (aligned) mean.
  EXPECT_LT(RelativeMeanGradient(space, shapes, newton.mean), 1e-9);
  EXPECT_NEAR(
      newton.gradient_norm,
      ElasticMeanGradient(space, shapes, newton.mean).cwiseAbs().maxCoeff(),
      1e-12);

  // LM alone, to the same target, finds the same mean.
  ElasticMeanOptions lm_only;
  lm_only.newton = false;
  const ElasticMeanResult lm =
      ComputeElasticMean(space, shapes, settings, nullptr, lm_only);
  EXPECT_EQ(lm.newton_iterations, 0);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(lm.mean, newton.mean), 1e-6);
  EXPECT_NEAR(lm.energy, newton.energy, 1e-10 * newton.energy);
  EXPECT_LE(newton.energy, lm.energy + 1e-12 * lm.energy);
  // LM stopped early, then Newton: fewer LM iterations than LM alone.
  EXPECT_LT(newton.lm_iterations, lm.lm_iterations);
}

TEST(ElasticMeanTest, RejectsBadInputs) {
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  EXPECT_THROW(ComputeElasticMean(space, {}, SolverSettings{}), InputError);
  const Positions plate = LoadData("plate/plate121.ply").positions;
  EXPECT_THROW(ComputeElasticMean(space, {plate}, SolverSettings{}),
               InputError);
}

}  // namespace
}  // namespace shellspace
