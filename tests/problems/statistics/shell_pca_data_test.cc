// Tests of shell PCA, Procrustes PCA and the leave-one-out evaluation on
// small meshes (the 162-vertex spheres and the 121-vertex plates): the
// metric and its kernel, orthonormal modes, a pose on the first mode's
// curve recovered, the EXP shots of the mode shapes (their safeguard,
// failures, stops and degenerate triangles as statuses), warm LOG paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/statistics/leave_one_out.h"
#include "shellspace/problems/statistics/procrustes_pca.h"
#include "shellspace/problems/statistics/shell_pca.h"
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

TEST(ShellPcaTest, MetricIsSemidefiniteWithTheRigidMotionsInItsKernel) {
  const Mesh mesh = LoadData("sphere/unitSphere1_defX.ply");
  const ShellSpace space = MakeSpace(mesh);
  const ShellMetric metric(space, mesh.positions);
  const Positions u = GaussianNoise(mesh.num_vertices(), 1.0, 7);
  const double guu = metric.Inner(u, u);
  EXPECT_GT(guu, 0);
  const Positions w = GaussianNoise(mesh.num_vertices(), 1.0, 8);
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
  const ElasticMeanResult mean =
      ComputeElasticMean(space, shapes, StatisticsSettings());
  ShellPcaOptions options;
  options.steps = 2;
  const ShellPcaModel model =
      ComputeShellPca(space, mean.mean, shapes, options, StatisticsSettings());
  ExpectOrthonormalModes(model, 3);
  // The LOGs at the mean sum to about zero (first-order optimality), so the
  // last eigenvalue is tiny compared with the first.
  EXPECT_LT(model.eigenvalues(3), 1e-2 * model.eigenvalues(0));
  // All modes: EXP of the projected LOG gives back a training shape.
  for (int i = 0; i < 2; ++i) {
    const Eigen::VectorXd c = ShellModeCoefficients(
        model, model.displacements[i], static_cast<int>(model.modes.size()));
    const Positions back =
        ShellFromCoefficients(space, model, c, options, StatisticsSettings());
    EXPECT_LT(RelativeDistanceUpToRigidMotion(back, shapes[i]), 1e-3) << i;
    EXPECT_GT(RelativeDistanceUpToRigidMotion(model.mean, shapes[i]), 1e-2);
  }
  // Mode shapes at +-1 are on either side of the mean.
  const Positions plus =
      ShellModeShape(space, model, 0, 1.0, options, StatisticsSettings());
  const Positions minus =
      ShellModeShape(space, model, 0, -1.0, options, StatisticsSettings());
  EXPECT_GT(RelativeDistanceUpToRigidMotion(plus, minus), 1e-3);
  EXPECT_THROW(
      ShellModeShape(space, model, 10, 1.0, options, StatisticsSettings()),
      InputError);
}

TEST(ShellPcaTest, PoseOnTheFirstModeCurveIsRecovered) {
  const std::vector<Positions> shapes = LoadSpheres();
  const ShellSpace space = MakeSpace(LoadData(kSpheres[0]));
  const ElasticMeanResult mean =
      ComputeElasticMean(space, shapes, StatisticsSettings());
  ShellPcaOptions options;
  options.steps = 3;
  options.exp_steps = 3;  // LOG_3 and EXP_3: EXP_3(LOG_3(T)) = T
  const ShellPcaModel model =
      ComputeShellPca(space, mean.mean, shapes, options, StatisticsSettings());
  ASSERT_GE(model.modes.size(), 3u);
  // T = EXP_3(s_bar, a w_1), a = 0.8 sqrt(lambda_1), in another pose.
  const double a = 0.8 * std::sqrt(model.eigenvalues(0));
  const Positions truth = RandomRigidMotion(
      ShellModeShape(space, model, 0, 0.8, options, StatisticsSettings()), 5);
  ASSERT_GT(RelativeDistanceUpToRigidMotion(truth, model.mean), 1e-2);
  // LOG_3(s_bar -> T) = a w_1: coefficients (a, 0, 0, ...).
  const Positions v = ShellDisplacement(space, model.mean, truth, options,
                                        StatisticsSettings());
  const Eigen::VectorXd c =
      ShellModeCoefficients(model, v, static_cast<int>(model.modes.size()));
  EXPECT_NEAR(c(0), a, 1e-5 * a);
  for (int j = 1; j < c.size(); ++j) EXPECT_LT(std::abs(c(j)), 1e-5 * a) << j;
  // One mode reconstructs T.
  ExpShotReport report;
  const Positions back = ShellFromCoefficients(space, model, c.head(1), options,
                                               StatisticsSettings(), &report);
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
  const ElasticMeanResult mean =
      ComputeElasticMean(space, shapes, StatisticsSettings());
  ShellPcaOptions options;
  const ShellPcaModel model =
      ComputeShellPca(space, mean.mean, shapes, options, StatisticsSettings());
  const Positions variation = std::sqrt(model.eigenvalues(0)) * model.modes[0];
  // A discrete geodesic conserves its step energies: EXP_4 of a one-sigma
  // variation passes at once, with a small drift.
  options.exp_steps = 4;
  options.max_exp_steps = 16;
  ExpShotReport report;
  const Positions shot = ShootFromMean(space, model.mean, variation, options,
                                       StatisticsSettings(), &report);
  EXPECT_TRUE(report.ok);
  EXPECT_EQ(report.steps, 4);
  EXPECT_EQ(report.attempts, 1);
  EXPECT_LT(report.energy_drift, 0.05);
  EXPECT_GT(RelativeDistanceUpToRigidMotion(shot, model.mean), 1e-2);
  // An impossible drift bound: K = 4, 8, 16 are tried and the last returned,
  // flagged; EXP_16 and EXP_4 of the same variation nearly agree.
  options.max_energy_drift = 1e-12;
  const Positions last = ShootFromMean(space, model.mean, variation, options,
                                       StatisticsSettings(), &report);
  EXPECT_FALSE(report.ok);
  EXPECT_EQ(report.steps, 16);
  EXPECT_EQ(report.attempts, 3);
  EXPECT_GT(report.energy_drift, 1e-12);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(last, shot), 0.05);
  // Zero variation: the mean itself, nothing shot.
  const Positions zero =
      ShootFromMean(space, model.mean, Positions::Zero(variation.rows(), 3),
                    options, StatisticsSettings(), &report);
  EXPECT_TRUE(report.ok);
  EXPECT_EQ(zero, model.mean);
  options.max_exp_steps = 2;
  EXPECT_THROW(ShootFromMean(space, model.mean, variation, options,
                             StatisticsSettings()),
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
  EXPECT_NO_THROW(solved =
                      TryShootFromMean(space, mean, variation, options,
                                       StatisticsSettings(), &shot, &status));
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
    ShootFromMean(space, sphere, variation, options, StatisticsSettings(),
                  &report);
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
  SolverSettings settings = StatisticsSettings();
  Positions shot;
  ExpShotReport status;
  ASSERT_TRUE(TryShootFromMean(space, sphere, variation, options, settings,
                               &shot, &status));
  settings.stop = StopToken([] { return true; });
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
    ShootFromMean(space, sphere, variation, options, StatisticsSettings());
    ADD_FAILURE() << "the shot should have thrown";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), status.failure);
  }
}

TEST(ShellPcaTest, DifferenceModesAreOrthonormalOnPlates) {
  std::vector<Positions> shapes;
  for (const char* name : {"plate/plate121.ply", "plate/plate121_rolledA.ply",
                           "plate/plate121_rolledB.ply"}) {
    shapes.push_back(LoadData(name).positions);
  }
  const ShellSpace space = MakeSpace(LoadData("plate/plate121.ply"));
  const ElasticMeanResult mean =
      ComputeElasticMean(space, shapes, StatisticsSettings());
  ShellPcaOptions options;
  options.displacement = DisplacementKind::kAlignedDifference;
  const ShellPcaModel model =
      ComputeShellPca(space, mean.mean, shapes, options, StatisticsSettings());
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
  options.initial_mean =
      ComputeElasticMean(space, shapes, StatisticsSettings()).mean;
  const LeaveOneOutTable warm =
      EvaluateLeaveOneOut(space, shapes, options, StatisticsSettings());
  options.warm_logs = false;
  const LeaveOneOutTable cold =
      EvaluateLeaveOneOut(space, shapes, options, StatisticsSettings());
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
  ShellDisplacement(space, shapes[0], shapes[1], options, StatisticsSettings(),
                    nullptr, &old_log);
  const ShellPath& old = old_log.path;
  ASSERT_EQ(old.size(), 4u);
  const Positions start = shapes[0] + GaussianNoise(shapes[0].rows(), 1e-3, 3);
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
  const Positions cold = ShellDisplacement(
      space, start, end, options, StatisticsSettings(), nullptr, &cold_log);
  const Positions warm = ShellDisplacement(
      space, start, end, options, StatisticsSettings(), &old, &warm_log);
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

}  // namespace
}  // namespace shellspace
