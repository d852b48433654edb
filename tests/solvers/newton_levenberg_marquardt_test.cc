// The Newton engine's Levenberg-Marquardt globalisation
// (solvers/newton_solver.h) on small closed-form problems
// (tests/testing/newton_problems.h): Rosenbrock's valley on the
// Gauss-Newton model, the hand-over at a contracting step, rejected rising
// steps that raise lambda, the gradient deciding below the merit's
// round-off, the rejection limit and the stop hook.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "shellspace/solvers/newton_solver.h"
#include "shellspace/solvers/reusable_cholesky.h"
#include "tests/testing/newton_problems.h"

namespace shellspace {
namespace {

using testing::Callbacks;
using testing::FunctionProblem;
using testing::Hyperbolas;
using testing::Minimize;
using testing::MonotoneMerits;
using testing::ScaledSaddle;

// Rosenbrock's function as least squares, f = 1/2 |r|^2 with r = (10 (x_2 -
// x_1^2), 1 - x_1): gradient J^T r, model matrix the Gauss-Newton J^T J
// (J = [[-20 x_1, 10], [-1, 0]]), minimiser (1, 1) with r = 0 there, so
// Gauss-Newton converges fast near it. `wrong_j11` replaces dr_1/dx_1 in
// the model matrix only (a deliberately wrong derivative).
Callbacks RosenbrockLeastSquares(double wrong_j11_factor = 1) {
  Callbacks c;
  const auto r = [](const Eigen::VectorXd& x) {
    return Eigen::Vector2d(10 * (x(1) - x(0) * x(0)), 1 - x(0));
  };
  const auto jac = [](const Eigen::VectorXd& x, double factor) {
    Eigen::Matrix2d j;
    j << -20 * x(0) * factor, 10, -1, 0;
    return j;
  };
  c.merit = [r](const Eigen::VectorXd& x) { return 0.5 * r(x).squaredNorm(); };
  c.residual = [r, jac](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(jac(x, 1).transpose() * r(x));
  };
  c.jacobian = [jac, wrong_j11_factor](const Eigen::VectorXd& x) {
    const Eigen::Matrix2d j = jac(x, wrong_j11_factor);
    return Eigen::MatrixXd(j.transpose() * j);
  };
  return c;
}

NewtonSettings LevenbergMarquardt(double tolerance, int max_steps) {
  NewtonSettings s = Minimize(tolerance, max_steps);
  s.globalisation = NewtonSettings::Globalisation::kLevenbergMarquardt;
  return s;
}

// Accepted LM steps from Rosenbrock's start (-1.2, 1) until |x - (1, 1)| <=
// 1e-10 (max_steps + 1 if never), merits checked to be monotone.
int LevenbergMarquardtStepsOnRosenbrock(const Callbacks& c, int max_steps) {
  FunctionProblem problem(c, Eigen::Vector2d(-1.2, 1), true);
  ReusableCholesky cholesky;
  SolveNewton(&problem, &cholesky, LevenbergMarquardt(0, max_steps));
  EXPECT_TRUE(MonotoneMerits(c, problem.iterates));
  for (size_t k = 0; k < problem.iterates.size(); ++k) {
    if ((problem.iterates[k] - Eigen::Vector2d(1, 1)).norm() <= 1e-10) {
      return static_cast<int>(k);
    }
  }
  return max_steps + 1;
}

// The engine's Levenberg-Marquardt on the Gauss-Newton matrix solves
// Rosenbrock's valley with monotone merits in few steps (Ceres' LM needs
// about as many); the twin, whose model has dr_1/dx_1 off by a factor 1.5,
// still descends (LM accepts only decreasing steps) but is counted by the
// same helper as not converging within the bound.
TEST(NewtonSolverTest, LevenbergMarquardtSolvesRosenbrockOnTheGaussNewtonModel) {
  const int steps = LevenbergMarquardtStepsOnRosenbrock(RosenbrockLeastSquares(), 200);
  std::cout << "LM steps to 1e-10: " << steps << "\n";
  EXPECT_LE(steps, 40);
  const int wrong =
      LevenbergMarquardtStepsOnRosenbrock(RosenbrockLeastSquares(1.5), 200);
  std::cout << "with a wrong model: " << wrong << "\n";
  EXPECT_GT(wrong, 40);
}

// The hand-over rule ends LM at its first accepted step that divides the
// gradient's max norm by the set factor (here on Rosenbrock's valley, where
// Gauss-Newton's steps contract the gradient by less far from the
// minimiser and by more near it). The contractions are read from the
// iterates with the problem's own gradient; the twin without the rule runs
// to convergence through the same steps.
std::vector<double> GradientMaxNorms(const Callbacks& c,
                                     const std::vector<Eigen::VectorXd>& xs) {
  std::vector<double> norms;
  for (const Eigen::VectorXd& x : xs) {
    norms.push_back(c.residual(x).cwiseAbs().maxCoeff());
  }
  return norms;
}

TEST(NewtonSolverTest, HandOverEndsLevenbergMarquardtAtAContractingStep) {
  const Callbacks c = RosenbrockLeastSquares();
  const double factor = 10;
  NewtonSettings s = LevenbergMarquardt(1e-12, 200);
  s.hand_over_contraction = factor;
  FunctionProblem problem(c, Eigen::Vector2d(-1.2, 1), true);
  ReusableCholesky cholesky;
  const NewtonReport r = SolveNewton(&problem, &cholesky, s);
  EXPECT_EQ(r.stop, NewtonStop::kHandedOver);
  EXPECT_EQ(r.stop_reason, "gradient contracting: handed over");
  EXPECT_FALSE(r.converged);
  const std::vector<double> g = GradientMaxNorms(c, problem.iterates);
  ASSERT_GE(g.size(), 3u);  // a few steps before the contracting one
  for (size_t k = 1; k + 1 < g.size(); ++k) EXPECT_GT(g[k] * factor, g[k - 1]);
  EXPECT_LE(g.back() * factor, g[g.size() - 2]);
  // Without the rule: the same first steps, on to convergence.
  FunctionProblem all(c, Eigen::Vector2d(-1.2, 1), true);
  ReusableCholesky cholesky2;
  const NewtonReport full =
      SolveNewton(&all, &cholesky2, LevenbergMarquardt(1e-12, 200));
  EXPECT_TRUE(full.converged) << full.stop_reason;
  ASSERT_GT(all.iterates.size(), problem.iterates.size());
  for (size_t k = 0; k < problem.iterates.size(); ++k) {
    EXPECT_EQ(all.iterates[k], problem.iterates[k]) << k;
  }
}

// On the hyperbolas from (3, -2.5, 2), where the Newton step raises f, and
// with the exact (there positive definite but misleading) Hessian as the
// model: every accepted step lowers f, rejected steps raise lambda (the
// largest lambda tried exceeds the initial one), and it converges.
TEST(NewtonSolverTest, LevenbergMarquardtRejectsRisingStepsAndRaisesLambda) {
  const Callbacks c = Hyperbolas();
  FunctionProblem problem(c, Eigen::Vector3d(3, -2.5, 2), true);
  ReusableCholesky cholesky;
  NewtonSettings s = LevenbergMarquardt(1e-12, 100);
  s.lm_initial = 1e-8;
  s.accept_smaller_max_norm = true;  // the last steps change f below round-off
  const NewtonReport r = SolveNewton(&problem, &cholesky, s);
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_TRUE(MonotoneMerits(c, problem.iterates));
  EXPECT_GT(r.max_shift, 1e-8);
  EXPECT_EQ(r.shifted_steps, r.steps);
  EXPECT_GT(problem.trial_points.size(), problem.iterates.size() - 1);
  EXPECT_LT(problem.x().cwiseAbs().maxCoeff(), 1e-11);
}

// Below round-off the residual decides in LM too (as in the trust region):
// on a saddle scaled by 1e-6 every damped step from (0, 1e-3) towards the
// valleys x_1 = +-1 lowers f by about 1e-12 (below merit_round_off = 1e-10
// of f = 1, so does the model's predicted decrease) with a ratio near 1 --
// a ratio rule would take it -- but raises the gradient: no step is taken,
// and LM gives up after its rejection limit. The twin, the same saddle
// unscaled, moves by the ratio and converges to a valley.
TEST(NewtonSolverTest, LevenbergMarquardtBelowRoundOffTheGradientDecides) {
  NewtonSettings settings = LevenbergMarquardt(1e-20, 60);
  settings.merit_round_off = 1e-10;
  settings.lm_max_rejections = 8;
  Eigen::VectorXd x0(2);
  x0 << 0, 1e-3;
  FunctionProblem flat(ScaledSaddle(1e-6), x0, true);
  ReusableCholesky cholesky;
  const NewtonReport stayed = SolveNewton(&flat, &cholesky, settings);
  EXPECT_FALSE(stayed.converged);
  EXPECT_EQ(stayed.stop, NewtonStop::kLineSearchFailed);
  EXPECT_EQ(flat.iterates.size(), 1u);  // no step taken
  // Its trials did lower f, by less than its round-off and not by nothing.
  const double f0 = ScaledSaddle(1e-6).merit(x0);
  int lower = 0;
  for (double f : flat.trial_merits) {
    if (f < f0) {
      ++lower;
      EXPECT_GT(f0 - f, 1e-15);
      EXPECT_LT(f0 - f, 1e-10);
    }
  }
  EXPECT_GE(lower, 1);

  settings.tolerance = 1e-11;
  FunctionProblem steep(ScaledSaddle(1), x0, true);
  ReusableCholesky cholesky2;
  const NewtonReport moved = SolveNewton(&steep, &cholesky2, settings);
  EXPECT_TRUE(moved.converged) << moved.stop_reason;
  EXPECT_NEAR(std::abs(steep.x()[1]), 1, 1e-10);
}

// lm_max_rejections rejected steps in a row end the solve with
// kLineSearchFailed: with the gradient's sign flipped every model step goes
// uphill; 1 + lm_max_rejections trials, each raising f, none accepted.
TEST(NewtonSolverTest, LevenbergMarquardtGivesUpAfterTheRejectionLimit) {
  Callbacks c = Hyperbolas();
  // The gradient's sign flipped: every model step points uphill.
  const auto gradient = c.residual;
  c.residual = [gradient](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(-gradient(x));
  };
  FunctionProblem problem(c, Eigen::Vector3d(3, -2.5, 2), true);
  ReusableCholesky cholesky;
  NewtonSettings s = LevenbergMarquardt(1e-12, 100);
  s.lm_max_rejections = 5;
  const NewtonReport r = SolveNewton(&problem, &cholesky, s);
  EXPECT_EQ(r.stop, NewtonStop::kLineSearchFailed);
  EXPECT_EQ(r.steps, 0);
  ASSERT_EQ(problem.trial_merits.size(), 6u);
  for (double m : problem.trial_merits) EXPECT_GT(m, c.merit(problem.x()));
}

// The stop hook ends an LM solve at the current point too: polled before
// every iteration and every retry, the third poll stops after two accepted
// steps, which are those of the same solve capped at two steps.
TEST(NewtonSolverTest, LevenbergMarquardtStopsOnRequest) {
  const Callbacks c = RosenbrockLeastSquares();
  FunctionProblem capped(c, Eigen::Vector2d(-1.2, 1), true);
  ReusableCholesky cholesky;
  const NewtonReport two =
      SolveNewton(&capped, &cholesky, LevenbergMarquardt(0, 2));
  ASSERT_EQ(two.steps, 2);
  FunctionProblem stopped(c, Eigen::Vector2d(-1.2, 1), true);
  NewtonSettings s = LevenbergMarquardt(0, 100);
  int polls = 0;
  s.stop = StopToken([&polls] { return ++polls == 3; });
  ReusableCholesky cholesky2;
  const NewtonReport r = SolveNewton(&stopped, &cholesky2, s);
  EXPECT_EQ(r.stop, NewtonStop::kStopped);
  EXPECT_FALSE(r.converged);
  EXPECT_LE(r.steps, 2);
  EXPECT_EQ(stopped.iterates.back(),
            capped.iterates[std::min<size_t>(r.steps, 2)]);
}

}  // namespace
}  // namespace shellspace
