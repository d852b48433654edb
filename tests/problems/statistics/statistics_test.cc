// Tests of the elastic mean, shell PCA, Procrustes PCA, the leave-one-out
// evaluation, and the `mean` / `pca` verbs, on small meshes (the 162-vertex
// spheres and the 121-vertex plates).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/statistics/leave_one_out.h"
#include "shellspace/problems/statistics/procrustes_pca.h"
#include "shellspace/problems/statistics/shell_pca.h"
#include "tests/testing/cli_output.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::DataPath;
using testing::LoadData;
using testing::MakeSpace;
using testing::Number;
using testing::RandomRigidMotion;
using testing::RunCli;
using testing::TempDir;

const char* const kSpheres[] = {
    "sphere/unitSphere1.ply", "sphere/unitSphere1_defX.ply",
    "sphere/unitSphere1_defY.ply", "sphere/unitSphere1_defZ.ply"};

std::vector<Positions> LoadSpheres() {
  std::vector<Positions> shapes;
  for (const char* name : kSpheres) shapes.push_back(LoadData(name).positions);
  return shapes;
}

SolverSettings Tight() {
  SolverSettings settings;
  settings.gradient_tolerance = 1e-10;
  settings.function_tolerance = 1e-14;
  return settings;
}

Positions Noise(int rows, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Positions p(rows, 3);
  for (int i = 0; i < p.size(); ++i) p.data()[i] = scale * normal(rng);
  return p;
}

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
  const ElasticMeanResult plain = ComputeElasticMean(space, copies, Tight());
  EXPECT_LT(plain.energy, 1e-14);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(plain.mean, shape), 1e-8);
  // From a perturbed guess, so that the solver has work to do.
  const Positions initial =
      RandomRigidMotion(shape, 3) + Noise(shape.rows(), 0.03, 4);
  ASSERT_GT(RelativeDistanceUpToRigidMotion(initial, shape), 1e-2);
  const ElasticMeanResult result =
      ComputeElasticMean(space, copies, Tight(), &initial);
  EXPECT_TRUE(result.summary.IsSolutionUsable());
  EXPECT_LT(result.energy, 1e-12);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(result.mean, shape), 1e-6);
  // Reported aligned to the first input.
  EXPECT_LT((result.mean - shape).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(ElasticMeanTest, InvariantUnderRigidMotionsOfTheInputs) {
  const std::vector<Positions> shapes = LoadSpheres();
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  const ElasticMeanResult a = ComputeElasticMean(space, shapes, Tight());
  std::vector<Positions> moved;
  for (size_t i = 0; i < shapes.size(); ++i) {
    moved.push_back(RandomRigidMotion(shapes[i], 10 + i));
  }
  const ElasticMeanResult b = ComputeElasticMean(space, moved, Tight());
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

TEST(ShellPcaTest, MetricIsSemidefiniteWithTheRigidMotionsInItsKernel) {
  const Mesh mesh = LoadData("sphere/unitSphere1_defX.ply");
  const ShellSpace space = MakeSpace(mesh);
  const ShellMetric metric(space, mesh.positions);
  const Positions u = Noise(mesh.num_vertices(), 1.0, 7);
  const double guu = metric.Inner(u, u);
  EXPECT_GT(guu, 0);
  const Positions w = Noise(mesh.num_vertices(), 1.0, 8);
  EXPECT_NEAR(metric.Inner(u, w), metric.Inner(w, u), 1e-10 * guu);
  // Infinitesimal rigid motion x -> omega x x + t.
  const Eigen::RowVector3d omega(0.3, -0.5, 0.8), t(1.0, 2.0, -0.5);
  Positions rigid(mesh.num_vertices(), 3);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    rigid.row(v) = omega.cross(mesh.positions.row(v)) + t;
  }
  EXPECT_LT(metric.Inner(rigid, rigid),
            1e-10 * guu * rigid.squaredNorm() / u.squaredNorm());
}

void ExpectOrthonormalModes(const ShellPcaModel& model, int expected_modes) {
  const int n = static_cast<int>(model.displacements.size());
  ASSERT_EQ(model.eigenvalues.size(), n);
  ASSERT_GE(static_cast<int>(model.modes.size()), expected_modes);
  const double largest = model.eigenvalues(0);
  ASSERT_GT(largest, 0);
  for (int j = 0; j < n; ++j) {
    EXPECT_GE(model.eigenvalues(j), -1e-12 * largest) << j;
    if (j > 0) {
      EXPECT_LE(model.eigenvalues(j), model.eigenvalues(j - 1));
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) {
      EXPECT_NEAR(
          model.gram(i, k),
          model.metric.Inner(model.displacements[i], model.displacements[k]) /
              n,
          1e-12 * largest * n);
    }
  }
  for (size_t j = 0; j < model.modes.size(); ++j) {
    for (size_t k = 0; k < model.modes.size(); ++k) {
      EXPECT_NEAR(model.metric.Inner(model.modes[j], model.modes[k]),
                  j == k ? 1.0 : 0.0, 1e-8)
          << j << " " << k;
    }
  }
  // Every displacement lies in the span of the modes (in the metric).
  for (int i = 0; i < n; ++i) {
    const Positions& v = model.displacements[i];
    const Eigen::VectorXd c =
        ShellModeCoefficients(model, v, static_cast<int>(model.modes.size()));
    Positions projection = Positions::Zero(v.rows(), 3);
    for (int j = 0; j < c.size(); ++j) projection += c(j) * model.modes[j];
    const Positions rest = v - projection;
    EXPECT_LT(model.metric.Inner(rest, rest), 1e-8 * model.metric.Inner(v, v))
        << i;
  }
}

TEST(ShellPcaTest, LogModesAreOrthonormalInTheMetric) {
  const std::vector<Positions> shapes = LoadSpheres();
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  const ElasticMeanResult mean = ComputeElasticMean(space, shapes, Tight());
  ShellPcaOptions options;
  options.steps = 2;
  const ShellPcaModel model =
      ComputeShellPca(space, mean.mean, shapes, options, Tight());
  ExpectOrthonormalModes(model, 3);
  // The LOGs at the mean sum to about zero (first-order optimality), so the
  // last eigenvalue is tiny compared with the first.
  EXPECT_LT(model.eigenvalues(3), 1e-2 * model.eigenvalues(0));
  // All modes: EXP of the projected LOG gives back a training shape.
  for (int i = 0; i < 2; ++i) {
    const Eigen::VectorXd c = ShellModeCoefficients(
        model, model.displacements[i], static_cast<int>(model.modes.size()));
    const Positions back =
        ShellFromCoefficients(space, model, c, options, Tight());
    EXPECT_LT(RelativeDistanceUpToRigidMotion(back, shapes[i]), 1e-3) << i;
    EXPECT_GT(RelativeDistanceUpToRigidMotion(model.mean, shapes[i]), 1e-2);
  }
  // Mode shapes at +-1 are on either side of the mean.
  const Positions plus = ShellModeShape(space, model, 0, 1.0, options, Tight());
  const Positions minus =
      ShellModeShape(space, model, 0, -1.0, options, Tight());
  EXPECT_GT(RelativeDistanceUpToRigidMotion(plus, minus), 1e-3);
  EXPECT_THROW(ShellModeShape(space, model, 10, 1.0, options, Tight()),
               InputError);
}

TEST(ShellPcaTest, PoseOnTheFirstModeCurveIsRecovered) {
  const std::vector<Positions> shapes = LoadSpheres();
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  const ElasticMeanResult mean = ComputeElasticMean(space, shapes, Tight());
  ShellPcaOptions options;
  options.steps = 3;
  options.exp_steps = 3;  // LOG_3 and EXP_3: EXP_3(LOG_3(T)) = T
  const ShellPcaModel model =
      ComputeShellPca(space, mean.mean, shapes, options, Tight());
  ASSERT_GE(model.modes.size(), 3u);
  // T = EXP_3(s_bar, a w_1), a = 0.8 sqrt(lambda_1), in another pose.
  const double a = 0.8 * std::sqrt(model.eigenvalues(0));
  const Positions truth = RandomRigidMotion(
      ShellModeShape(space, model, 0, 0.8, options, Tight()), 5);
  ASSERT_GT(RelativeDistanceUpToRigidMotion(truth, model.mean), 1e-2);
  // LOG_3(s_bar -> T) = a w_1: coefficients (a, 0, 0, ...).
  const Positions v =
      ShellDisplacement(space, model.mean, truth, options, Tight());
  const Eigen::VectorXd c =
      ShellModeCoefficients(model, v, static_cast<int>(model.modes.size()));
  EXPECT_NEAR(c(0), a, 1e-5 * a);
  for (int j = 1; j < c.size(); ++j) EXPECT_LT(std::abs(c(j)), 1e-5 * a) << j;
  // One mode reconstructs T.
  ExpShotReport report;
  const Positions back =
      ShellFromCoefficients(space, model, c.head(1), options, Tight(), &report);
  EXPECT_TRUE(report.ok);
  EXPECT_EQ(report.steps, 3);
  EXPECT_EQ(report.attempts, 1);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(back, truth), 1e-5);
  EXPECT_LT(EvaluateDeformationEnergy(space, truth, back).total,
            1e-8 * EvaluateDeformationEnergy(space, truth, model.mean).total);
}

TEST(ShellPcaTest, ExpShotSafeguardDoublesTheSteps) {
  const std::vector<Positions> shapes = LoadSpheres();
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  const ElasticMeanResult mean = ComputeElasticMean(space, shapes, Tight());
  ShellPcaOptions options;
  const ShellPcaModel model =
      ComputeShellPca(space, mean.mean, shapes, options, Tight());
  const Positions variation = std::sqrt(model.eigenvalues(0)) * model.modes[0];
  // A discrete geodesic conserves its step energies: EXP_4 of a one-sigma
  // variation passes at once, with a small drift.
  options.exp_steps = 4;
  options.max_exp_steps = 16;
  ExpShotReport report;
  const Positions shot =
      ShootFromMean(space, model.mean, variation, options, Tight(), &report);
  EXPECT_TRUE(report.ok);
  EXPECT_EQ(report.steps, 4);
  EXPECT_EQ(report.attempts, 1);
  EXPECT_LT(report.energy_drift, 0.05);
  EXPECT_GT(RelativeDistanceUpToRigidMotion(shot, model.mean), 1e-2);
  // An impossible drift bound: K = 4, 8, 16 are tried and the last returned,
  // flagged; EXP_16 and EXP_4 of the same variation nearly agree.
  options.max_energy_drift = 1e-12;
  const Positions last =
      ShootFromMean(space, model.mean, variation, options, Tight(), &report);
  EXPECT_FALSE(report.ok);
  EXPECT_EQ(report.steps, 16);
  EXPECT_EQ(report.attempts, 3);
  EXPECT_GT(report.energy_drift, 1e-12);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(last, shot), 0.05);
  // Zero variation: the mean itself, nothing shot.
  const Positions zero =
      ShootFromMean(space, model.mean, Positions::Zero(variation.rows(), 3),
                    options, Tight(), &report);
  EXPECT_TRUE(report.ok);
  EXPECT_EQ(zero, model.mean);
  options.max_exp_steps = 2;
  EXPECT_THROW(ShootFromMean(space, model.mean, variation, options, Tight()),
               InputError);
}

// TryShootFromMean of a shot that must fail: it returns false without an
// exception and leaves the shape empty; its report for further checks.
ExpShotReport ExpectFailedShot(const ShellSpace& space, const Positions& mean,
                               const Positions& variation,
                               const ShellPcaOptions& options) {
  ExpShotReport status;
  Positions shot;
  bool solved = true;
  EXPECT_NO_THROW(solved = TryShootFromMean(space, mean, variation, options,
                                            Tight(), &shot, &status));
  EXPECT_FALSE(solved);
  EXPECT_EQ(shot.size(), 0);
  return status;
}

// Shot options starting at EXP_4 and doubling up to EXP_16.
ShellPcaOptions ShotsFrom4To16() {
  ShellPcaOptions options;
  options.exp_steps = 4;
  options.max_exp_steps = 16;
  return options;
}

TEST(ShellPcaTest, ExpShotWithoutSolutionStopsAndNamesTheStep) {
  // A variation 8 (x^2, y^2, z^2) of the unit sphere (a stretch to ~8 times
  // its size, uneven): an early EXP step has no solution (for K = 16 the
  // second: the first is reached by the continuation in the load), for
  // K = 4, 8, 16. Every attempt stops at its first unsolved step (a fast
  // failure, not K - 1 steps shot from non-solutions), and the last one
  // throws, naming the step.
  const Positions sphere = LoadData(kSpheres[0]).positions;
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  const Positions variation = 8.0 * sphere.array().square().matrix();
  const ShellPcaOptions options = ShotsFrom4To16();
  ExpShotReport report;
  try {
    ShootFromMean(space, sphere, variation, options, Tight(), &report);
    ADD_FAILURE() << "the shot should have thrown";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("step 3 of EXP_16 has no solution"),
              std::string::npos)
        << message;
  }
  EXPECT_FALSE(report.ok);
  EXPECT_EQ(report.attempts, 3);
  EXPECT_EQ(report.steps, 16);
  // The status twin: false, the same message, no exception, no shape.
  const ExpShotReport status =
      ExpectFailedShot(space, sphere, variation, options);
  EXPECT_NE(status.failure.find("step 3 of EXP_16 has no solution"),
            std::string::npos)
      << status.failure;
  EXPECT_EQ(status.attempts, 3);
}

// A stop request (settings.stop, e.g. --time_limit) ends a shot before its
// next EXP step: false, "stopped on request", one attempt, no retry with
// more steps; without the request the same shot succeeds.
TEST(ShellPcaTest, ExpShotStopsOnRequest) {
  const Positions sphere = LoadData(kSpheres[0]).positions;
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  const Positions variation = 0.05 * sphere.array().square().matrix();
  const ShellPcaOptions options = ShotsFrom4To16();
  SolverSettings settings = Tight();
  Positions shot;
  ExpShotReport status;
  ASSERT_TRUE(TryShootFromMean(space, sphere, variation, options, settings,
                               &shot, &status));
  settings.stop = [] { return true; };
  Positions stopped;
  EXPECT_FALSE(TryShootFromMean(space, sphere, variation, options, settings,
                                &stopped, &status));
  EXPECT_NE(status.failure.find("stopped on request"), std::string::npos)
      << status.failure;
  EXPECT_EQ(status.attempts, 1);
  EXPECT_EQ(stopped.size(), 0);
}

TEST(ShellPcaTest, ExpShotThroughADegenerateTriangleIsAStatus) {
  // A variation that takes every vertex of the sphere to its centroid in
  // the first linear step s_1 = s_bar + v/4 (one attempt: max K = 4): the
  // shot meets degenerate triangles at step 1 and says so by a false return
  // naming the step and the element, not by an exception from the energy.
  const Positions sphere = LoadData(kSpheres[0]).positions;
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  const Eigen::RowVector3d centroid = sphere.colwise().mean();
  const Positions variation = -4.0 * (sphere.rowwise() - centroid);
  ShellPcaOptions options;
  options.exp_steps = 4;
  options.max_exp_steps = 4;
  const ExpShotReport status =
      ExpectFailedShot(space, sphere, variation, options);
  EXPECT_FALSE(status.ok);
  EXPECT_EQ(status.attempts, 1);
  EXPECT_NE(status.failure.find("step 1 of EXP_4 meets a degenerate"),
            std::string::npos)
      << status.failure;
  // The throwing form carries the same message.
  try {
    ShootFromMean(space, sphere, variation, options, Tight());
    ADD_FAILURE() << "the shot should have thrown";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), status.failure);
  }
}

TEST(ElasticMeanTest, FarInputsAreTheOutliersOfTheMeanEnergies) {
  EXPECT_DOUBLE_EQ(Median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(Median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_EQ(FarInputs({0.05, 0.04, 2.0, 0.06}), std::vector<int>({2}));
  EXPECT_EQ(FarInputs({0.05, 0.04, 0.3, 0.06}), std::vector<int>());
  EXPECT_EQ(FarInputs({0.05, 0.04, 0.3, 0.06}, 5.0), std::vector<int>({2}));
  EXPECT_EQ(FarInputs({0.05, 2.0}), std::vector<int>());  // too few
  EXPECT_EQ(FarInputs({0.0, 0.0, 1.0}), std::vector<int>());  // zero median
}

TEST(ShellPcaTest, DifferenceModesAreOrthonormalOnPlates) {
  std::vector<Positions> shapes;
  for (const char* name : {"plate/plate121.ply", "plate/plate121_rolledA.ply",
                           "plate/plate121_rolledB.ply"}) {
    shapes.push_back(LoadData(name).positions);
  }
  const ShellSpace space = MakeSpace(LoadData("plate/plate121.ply"));
  const ElasticMeanResult mean = ComputeElasticMean(space, shapes, Tight());
  ShellPcaOptions options;
  options.displacement = DisplacementKind::kAlignedDifference;
  const ShellPcaModel model =
      ComputeShellPca(space, mean.mean, shapes, options, Tight());
  ExpectOrthonormalModes(model, 2);
}

TEST(ProcrustesPcaTest, ModesAreOrthonormalAndInvariantUnderRigidMotions) {
  const std::vector<Positions> shapes = LoadSpheres();
  const ProcrustesPcaModel model = ComputeProcrustesPca(shapes);
  ASSERT_GE(model.modes.size(), 3u);
  for (size_t j = 0; j < model.modes.size(); ++j) {
    for (size_t k = 0; k < model.modes.size(); ++k) {
      EXPECT_NEAR(model.modes[j].cwiseProduct(model.modes[k]).sum(),
                  j == k ? 1.0 : 0.0, 1e-10);
    }
  }
  for (int j = 0; j < model.eigenvalues.size(); ++j) {
    EXPECT_GE(model.eigenvalues(j), -1e-12 * model.eigenvalues(0));
  }
  // All modes reconstruct a training shape (up to rigid motion).
  const Positions back = ProcrustesReconstruct(
      model, shapes[2], static_cast<int>(model.modes.size()));
  EXPECT_LT(RelativeDistanceUpToRigidMotion(back, shapes[2]), 1e-8);
  std::vector<Positions> moved;
  for (size_t i = 0; i < shapes.size(); ++i) {
    moved.push_back(RandomRigidMotion(shapes[i], 20 + i));
  }
  const ProcrustesPcaModel other = ComputeProcrustesPca(moved);
  EXPECT_LT((model.eigenvalues - other.eigenvalues).cwiseAbs().maxCoeff(),
            1e-9 * model.eigenvalues(0));
  EXPECT_LT(RelativeDistanceUpToRigidMotion(model.mean, other.mean), 1e-8);
}

TEST(LeaveOneOutTest, TableOnTheSpheres) {
  const std::vector<Positions> shapes = LoadSpheres();
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  LeaveOneOutOptions options;
  options.max_modes = 2;
  const LeaveOneOutTable table =
      EvaluateLeaveOneOut(space, shapes, options, SolverSettings{});
  ASSERT_EQ(table.rows.size(), 3u);
  ASSERT_EQ(table.folds.size(), 4u);
  for (const LeaveOneOutRow& row : table.rows) {
    EXPECT_TRUE(std::isfinite(row.shell_vertex_error));
    EXPECT_TRUE(std::isfinite(row.shell_energy));
    EXPECT_GT(row.procrustes_vertex_error, 0);
    EXPECT_GT(row.shell_energy, 0);
    // Every shot passes here: the shell averages run over all folds, and
    // the Procrustes averages over the shell's folds are the plain ones.
    EXPECT_EQ(row.shell_failed, 0);
    double shell_energy = 0;
    for (const LeaveOneOutFold& fold : table.folds) {
      shell_energy += fold.shell_energy[row.modes] / table.folds.size();
    }
    EXPECT_NEAR(row.shell_energy, shell_energy, 1e-14 * shell_energy);
    EXPECT_DOUBLE_EQ(row.procrustes_energy_shell_folds, row.procrustes_energy);
  }
  // 3 training shapes per fold: 3 eigenvalues.
  for (const LeaveOneOutFold& fold : table.folds) {
    EXPECT_GT(fold.shell_energy[0], 0);
    EXPECT_EQ(fold.shell_eigenvalues.size(), 3);
    EXPECT_TRUE(fold.mean_converged);
    ASSERT_EQ(fold.shell_shots.size(), 3u);
    for (const ExpShotReport& shot : fold.shell_shots) EXPECT_TRUE(shot.ok);
  }
  options.held_out = {7};
  EXPECT_THROW(EvaluateLeaveOneOut(space, shapes, options, SolverSettings{}),
               InputError);
  EXPECT_THROW(EvaluateLeaveOneOut(space, {shapes[0], shapes[1]},
                                   LeaveOneOutOptions{}, SolverSettings{}),
               InputError);
}

TEST(LeaveOneOutTest, WarmLogsGiveTheSameTable) {
  // Folds whose LOGs start from the LOG paths at the mean of all shapes
  // (the default with an initial mean) reach the same geodesics as LOGs
  // from the linear path: the same table up to solver tolerance.
  const std::vector<Positions> shapes = LoadSpheres();
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  LeaveOneOutOptions options;
  options.max_modes = 2;
  options.held_out = {0, 2};
  options.initial_mean = ComputeElasticMean(space, shapes, Tight()).mean;
  const LeaveOneOutTable warm =
      EvaluateLeaveOneOut(space, shapes, options, Tight());
  options.warm_logs = false;
  const LeaveOneOutTable cold =
      EvaluateLeaveOneOut(space, shapes, options, Tight());
  for (int f = 0; f < 2; ++f) {
    const LeaveOneOutFold& a = warm.folds[f];
    const LeaveOneOutFold& b = cold.folds[f];
    EXPECT_LE(a.log_iterations, b.log_iterations);
    EXPECT_LT((a.shell_eigenvalues - b.shell_eigenvalues).cwiseAbs().maxCoeff(),
              1e-6 * b.shell_eigenvalues(0));
    for (int m = 0; m <= 2; ++m) {
      EXPECT_NEAR(a.shell_energy[m], b.shell_energy[m],
                  1e-5 * b.shell_energy[m]);
      EXPECT_NEAR(a.shell_vertex_error[m], b.shell_vertex_error[m],
                  1e-5 * b.shell_vertex_error[m]);
    }
  }
}

TEST(ShellPcaTest, WarmLogPathHasTheNewEndsAndIgnoresRigidMotions) {
  const std::vector<Positions> shapes = LoadSpheres();
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  ShellPcaOptions options;
  options.steps = 3;
  // An old LOG_3 path from shapes[0] to shapes[1]; new ends: a perturbed
  // start and a rigidly moved end.
  GeodesicResult old_log;
  ShellDisplacement(space, shapes[0], shapes[1], options, Tight(), nullptr,
                    &old_log);
  const ShellPath& old = old_log.path;
  ASSERT_EQ(old.size(), 4u);
  const Positions start = shapes[0] + Noise(shapes[0].rows(), 1e-3, 3);
  const Positions end = RandomRigidMotion(shapes[1], 7);
  const ShellPath path = WarmLogPath(old, start, end);
  ASSERT_EQ(path.size(), 4u);
  EXPECT_EQ(path.front(), start);
  EXPECT_EQ(path.back(), end);
  // Moving the old path rigidly as a whole changes nothing.
  ShellPath moved = old;
  for (Positions& p : moved) p = RandomRigidMotion(p, 11);
  const ShellPath again = WarmLogPath(moved, start, end);
  for (int k = 1; k < 3; ++k) {
    EXPECT_LT((again[k] - path[k]).cwiseAbs().maxCoeff(), 1e-10) << k;
    // and the inner shapes keep the old path's shape.
    EXPECT_LT(RelativeDistanceUpToRigidMotion(path[k], old[k]), 2e-3) << k;
  }
  // A LOG solved from it lands on the geodesic from the linear path. The
  // inner shapes' rigid gauge is pinned at the initial path, so s_1 and
  // LOG = K (s_1 - s_0) may differ by a small rigid motion, which the
  // metric nearly ignores (infinitesimal rigid motions are its kernel).
  GeodesicResult cold_log, warm_log;
  const Positions cold = ShellDisplacement(space, start, end, options,
                                           Tight(), nullptr, &cold_log);
  const Positions warm =
      ShellDisplacement(space, start, end, options, Tight(), &old, &warm_log);
  for (int k = 1; k < 3; ++k) {
    EXPECT_LT(
        RelativeDistanceUpToRigidMotion(warm_log.path[k], cold_log.path[k]),
        1e-7)
        << k;
  }
  // The warm start is the better start: a smaller gradient to begin from,
  // and no more iterations (3 and 3 with the squared forcing).
  EXPECT_LT(warm_log.initial_gradient, 0.5 * cold_log.initial_gradient);
  EXPECT_LE(warm_log.iterations, cold_log.iterations);
  const ShellMetric metric(space, start);
  EXPECT_LT(metric.Norm(warm - cold), 1e-4 * metric.Norm(cold));
  EXPECT_THROW(WarmLogPath({shapes[0]}, start, end), InputError);
}

std::string SphereList(int count) {
  std::string list;
  for (int i = 0; i < count; ++i) {
    list += (i ? "," : "") + DataPath(kSpheres[i]);
  }
  return list;
}

TEST(StatisticsCliTest, MeanWritesTheShapeAndJson) {
  const std::string out = TempDir() + "/M.ply";
  std::string stdout_text, stderr_text;
  ASSERT_EQ(RunCli("mean --inputs " + SphereList(3) + " --output " + out +
                       " --json --quiet",
                   &stdout_text, &stderr_text),
            0)
      << stderr_text;
  EXPECT_TRUE(std::filesystem::exists(out));
  EXPECT_NE(stdout_text.find("\"energy\""), std::string::npos);
  // The written shape is the library's elastic mean, with the CLI's default
  // material: eta = kDefaultRelativeEta (1e-4) x the area of the first input.
  std::vector<Positions> shapes = LoadSpheres();
  shapes.resize(3);
  const Mesh first = LoadData(kSpheres[0]);
  ShellMaterial material;
  material.eta = kDefaultRelativeEta * SurfaceArea(first);
  EXPECT_NEAR(Number(stdout_text, "eta"), material.eta, 1e-15 * material.eta);
  const ElasticMeanResult mean =
      ComputeElasticMean(MakeSpace(first, material), shapes, SolverSettings{});
  EXPECT_LT(RelativeDistanceUpToRigidMotion(ReadMesh(out).positions, mean.mean),
            1e-6);
}

// Runs `pca` with two modes of the four spheres into `dir`, with `options`;
// returns its exit status.
int RunPcaOfSpheres(const std::string& dir, const std::string& options,
                    std::string* stdout_text, std::string* stderr_text) {
  return RunCli("pca --inputs " + SphereList(4) + " --modes 2 --output " + dir +
                    " " + options,
                stdout_text, stderr_text);
}

TEST(StatisticsCliTest, PcaWritesModesAndLeaveOneOutTable) {
  const std::string dir = TempDir() + "/pca";
  std::string stdout_text, stderr_text;
  ASSERT_EQ(RunPcaOfSpheres(dir, "--baseline procrustes --loo --json --quiet",
                            &stdout_text, &stderr_text),
            0)
      << stderr_text;
  for (const char* name :
       {"mean.ply", "mode_1_minus.ply", "mode_1_plus.ply", "mode_2_plus.ply",
        "procrustes_mean.ply", "procrustes_mode_2_minus.ply", "pca.json"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + name)) << name;
  }
  EXPECT_NE(stdout_text.find("\"eigenvalues\""), std::string::npos);
  EXPECT_NE(stdout_text.find("\"leave_one_out\""), std::string::npos);
  EXPECT_NE(stdout_text.find("\"procrustes_vertex_error\""), std::string::npos);
  EXPECT_NE(stdout_text.find("\"log_iterations\""), std::string::npos);
}

TEST(StatisticsCliTest, MeanWarnsAboutAFarInput) {
  // The four spheres twice over and one blown up to twice its size: the big
  // one is far (W[S, mean] more than 10 times the median), the others are
  // not.
  const std::string big = TempDir() + "/big.ply";
  Mesh sphere = LoadData(kSpheres[1]);
  sphere.positions *= 2.0;
  WriteMesh(sphere, big);
  const std::string out = TempDir() + "/far_mean.ply";
  std::string stdout_text, stderr_text;
  ASSERT_EQ(RunCli("mean --inputs " + SphereList(4) + "," + SphereList(4) +
                       "," + big +
                       " --output " + out + " --json",
                   &stdout_text, &stderr_text),
            0)
      << stderr_text;
  EXPECT_NE(stderr_text.find("warning: input " + big + " is far"),
            std::string::npos)
      << stderr_text;
  EXPECT_NE(stdout_text.find("\"far_inputs\": [\"" + big + "\"]"),
            std::string::npos)
      << stdout_text;
  ASSERT_EQ(RunCli("mean --inputs " + SphereList(4) + " --output " + out +
                       " --json",
                   &stdout_text, &stderr_text),
            0);
  EXPECT_EQ(stderr_text.find("warning"), std::string::npos) << stderr_text;
  EXPECT_NE(stdout_text.find("\"far_inputs\": []"), std::string::npos);
}

TEST(StatisticsCliTest, PcaSkipsModeShapesWithoutAnExpSolution) {
  // At 40 standard deviations the EXP shots of the sphere modes break down
  // (no solution of a step near the extrapolation, for K = 4, 8, 16): those
  // shapes are not written, listed in the JSON, and the rest is written.
  const std::string dir = TempDir() + "/pca_far";
  std::string stdout_text, stderr_text;
  ASSERT_EQ(RunPcaOfSpheres(dir, "--amplitude 40 --eta 0.01 --json",
                            &stdout_text, &stderr_text),
            0)
      << stderr_text;
  const auto begin = stdout_text.find("\"failed_mode_shapes\": [");
  ASSERT_NE(begin, std::string::npos) << stdout_text;
  const std::string failed =
      stdout_text.substr(begin, stdout_text.find(']', begin) - begin);
  EXPECT_NE(failed.find(".ply"), std::string::npos) << failed;  // some
  for (const char* name : {"mode_1_minus.ply", "mode_1_plus.ply",
                           "mode_2_minus.ply", "mode_2_plus.ply"}) {
    const bool listed = failed.find(name) != std::string::npos;
    EXPECT_EQ(std::filesystem::exists(dir + "/" + name), !listed) << name;
    EXPECT_EQ(stderr_text.find(std::string(name) + " not written") !=
                  std::string::npos,
              listed)
        << name;
  }
  EXPECT_TRUE(std::filesystem::exists(dir + "/mean.ply"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/pca.json"));
}

TEST(StatisticsCliTest, BadInputsFailWithOneLineAndNoOutput) {
  const std::string base = TempDir();
  struct Case {
    std::string args, expected;
  };
  const std::vector<Case> cases = {
      {"mean --inputs " + DataPath(kSpheres[0]) + "," +
           DataPath("plate/plate121.ply") + " --output " + base + "/a.ply",
       "plate121"},
      {"mean --inputs " + DataPath(kSpheres[0]) + ",missing.ply --output " +
           base + "/b.ply",
       "missing.ply"},
      {"mean --output " + base + "/c.ply", "--inputs"},
      {"pca --inputs " + SphereList(4) + " --modes 0 --output " + base + "/d",
       "--modes"},
      {"pca --inputs " + SphereList(3) + " --modes 3 --output " + base + "/e",
       "--modes"},
      {"pca --inputs " + SphereList(3) +
           " --modes 1 --baseline linear "
           "--output " +
           base + "/f",
       "--baseline"},
      {"pca --inputs " + SphereList(2) + " --modes 1 --loo --output " + base +
           "/g",
       "at least 3"},
      {"pca --inputs " + SphereList(3) + " --modes 1 --exp_steps 0 --output " +
           base + "/h",
       "--exp_steps"},
      {"mean --inputs " + SphereList(3) + " --threads 0 --output " + base +
           "/i.ply",
       "--threads"},
  };
  for (const Case& c : cases) {
    std::string stdout_text, stderr_text;
    EXPECT_EQ(RunCli(c.args + " --quiet", &stdout_text, &stderr_text), 1)
        << c.args;
    EXPECT_NE(stderr_text.find(c.expected), std::string::npos) << c.args << "\n"
                                                               << stderr_text;
    EXPECT_EQ(std::count(stderr_text.begin(), stderr_text.end(), '\n'), 1)
        << stderr_text;
  }
  for (const char* name :
       {"a.ply", "b.ply", "c.ply", "d", "e", "f", "g", "h", "i.ply"}) {
    EXPECT_FALSE(std::filesystem::exists(base + "/" + name)) << name;
  }
}

}  // namespace
}  // namespace shellspace
